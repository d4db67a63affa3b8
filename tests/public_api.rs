//! The public API changes only on purpose: this test lists every public item of the
//! library from rustdoc's JSON output, with its signature (modules, types with their
//! generics, functions and methods with their parameters and return types, constants and
//! fields with their types, variants with their fields, the traits implemented and the
//! auto traits, `Send` and `Sync` among them; `#[non_exhaustive]`, `#[deprecated]` and
//! `#[repr(C)]`), and compares the list with the checked-in
//! `tests/public-api.txt`. A changed parameter, a field's new type or a type that stops
//! being `Send` fails it as surely as a removed function.
//!
//! After an intended change, regenerate the list with
//! `SPRINGWATER_BLESS=1 cargo test --test public_api` and review its diff.
//!
//! rustdoc's JSON output needs a nightly toolchain (`cargo +nightly rustdoc … --output-format
//! json`); without one the test says so and passes, unless `SPRINGWATER_REQUIRE_TOOLS` is
//! set (as CI does), where it fails. Items behind `#[doc(hidden)]` (the `internals` feature: scalar twins,
//! comparison kernels, the engine's schedule) are not listed: they carry no promise.

use serde_json::Value;
use std::collections::BTreeSet;
use std::path::Path;
use std::process::Command;

/// The auto traits a user can name on stable Rust.
const AUTO_TRAITS: [&str; 5] = ["Send", "Sync", "Unpin", "UnwindSafe", "RefUnwindSafe"];

/// Features documented: everything a user can turn on, except `internals`.
const FEATURES: &str = "parallel,render,serde";

#[test]
fn the_public_api_is_the_checked_in_list() {
    let nightly = Command::new("cargo")
        .args(["+nightly", "--version"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !nightly {
        // A test whose tool is missing passes saying so, unless CI requires every tool.
        let why = "no nightly toolchain (rustup toolchain install nightly)";
        assert!(
            std::env::var_os("SPRINGWATER_REQUIRE_TOOLS").is_none(),
            "SPRINGWATER_REQUIRE_TOOLS is set but {why}"
        );
        println!("skipped: {why}");
        return;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let target = root.join("target").join("public-api");
    let status = Command::new("cargo")
        .current_dir(root)
        .args([
            "+nightly",
            "rustdoc",
            "-p",
            "springwater",
            "--lib",
            "--quiet",
            "--no-default-features",
        ])
        .args(["--features", FEATURES, "--target-dir"])
        .arg(&target)
        .args(["--", "-Z", "unstable-options", "--output-format", "json"])
        .env_remove("RUSTFLAGS")
        .env_remove("RUSTDOCFLAGS")
        .status()
        .expect("cargo runs");
    assert!(
        status.success(),
        "`cargo +nightly rustdoc --output-format json` failed"
    );
    let json = std::fs::read_to_string(target.join("doc").join("springwater.json")).unwrap();
    let doc: Value = serde_json::from_str(&json).unwrap();
    let mut api = BTreeSet::new();
    let root_id = doc["root"].to_string();
    walk(&doc, &root_id, "springwater", &mut api);
    let listed: String = api.iter().map(|l| format!("{l}\n")).collect();
    // A walk that found (almost) nothing cannot pass, nor be blessed.
    let functions = api
        .iter()
        .filter(|l| l.contains("fn springwater::"))
        .count();
    assert!(
        api.len() >= 800 && functions >= 200,
        "rustdoc's JSON gave only {} items, {functions} functions: has its format changed?",
        api.len()
    );

    let file = root.join("tests").join("public-api.txt");
    if std::env::var_os("SPRINGWATER_BLESS").is_some() {
        std::fs::write(&file, &listed).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&file)
        .unwrap_or_else(|e| panic!("{}: {e} (bless it first)", file.display()));
    let expected: BTreeSet<&str> = expected.lines().collect();
    let found: BTreeSet<&str> = listed.lines().collect();
    let added: Vec<_> = found.difference(&expected).collect();
    let removed: Vec<_> = expected.difference(&found).collect();
    assert!(
        added.is_empty() && removed.is_empty(),
        "the public API changed; if on purpose, run with SPRINGWATER_BLESS=1 and add a \
         migration note to CHANGELOG.md. (This walker was written for rustdoc JSON format \
         57; this nightly wrote {}: if the lists differ only in form, adapt `walk`.)\n\
         added: {added:#?}\nremoved: {removed:#?}",
        doc["format_version"]
    );
}

/// Records the item `id` as `path`, with its signature, and what it contains.
fn walk(doc: &Value, id: &str, path: &str, out: &mut BTreeSet<String>) {
    let Some(item) = doc["index"].get(id) else {
        // A re-export of another crate's item.
        out.insert(format!("use {path}"));
        return;
    };
    let inner = &item["inner"];
    let Some((kind, body)) = inner.as_object().and_then(|o| o.iter().next()) else {
        return;
    };
    attributes(item, path, out);
    let name_of = |id: &Value| {
        doc["index"][&id.to_string()]["name"]
            .as_str()
            .unwrap_or("_")
    };
    match kind.as_str() {
        "module" => {
            out.insert(format!("mod {path}"));
            for child in body["items"].as_array().unwrap() {
                let child = child.to_string();
                let c = &doc["index"][&child];
                match c["inner"].get("use") {
                    Some(u) if u["is_glob"] == true => {
                        out.insert(format!("use {path}::{}::*", u["source"]));
                    }
                    Some(u) => {
                        let name = u["name"].as_str().unwrap();
                        let target = u["id"].to_string();
                        walk(doc, &target, &format!("{path}::{name}"), out);
                    }
                    None => {
                        let name = c["name"].as_str().unwrap_or("_");
                        walk(doc, &child, &format!("{path}::{name}"), out);
                    }
                }
            }
        }
        "struct" => {
            let g = generics(&body["generics"]);
            let kind = &body["kind"];
            if let Some(fields) = kind["tuple"].as_array() {
                let parts: Vec<String> = fields
                    .iter()
                    .map(|f| match f.is_null() {
                        true => "_".into(),
                        false => format!("pub {}", field_type(doc, f)),
                    })
                    .collect();
                out.insert(format!("struct {path}{g}({})", parts.join(", ")));
            } else {
                out.insert(format!("struct {path}{g}"));
            }
            for f in kind["plain"]["fields"].as_array().into_iter().flatten() {
                out.insert(format!(
                    "field {path}::{}: {}",
                    name_of(f),
                    field_type(doc, f)
                ));
            }
            if kind["plain"]["has_stripped_fields"] == true {
                out.insert(format!("field {path}::.. (private fields)"));
            }
            impls(doc, &body["impls"], path, out);
        }
        "enum" => {
            out.insert(format!("enum {path}{}", generics(&body["generics"])));
            for v in body["variants"].as_array().unwrap() {
                let var = &doc["index"][&v.to_string()];
                let vk = &var["inner"]["variant"]["kind"];
                let shape = if let Some(fields) = vk["tuple"].as_array() {
                    let parts: Vec<String> = fields.iter().map(|f| field_type(doc, f)).collect();
                    format!("({})", parts.join(", "))
                } else if let Some(fields) = vk["struct"]["fields"].as_array() {
                    let parts: Vec<String> = fields
                        .iter()
                        .map(|f| format!("{}: {}", name_of(f), field_type(doc, f)))
                        .collect();
                    format!(" {{ {} }}", parts.join(", "))
                } else {
                    String::new()
                };
                out.insert(format!("variant {path}::{}{shape}", name_of(v)));
            }
            impls(doc, &body["impls"], path, out);
        }
        "trait" => {
            out.insert(format!("trait {path}{}", generics(&body["generics"])));
            for i in body["items"].as_array().unwrap() {
                let it = &doc["index"][&i.to_string()];
                let (q, sig) = match it["inner"].get("function") {
                    Some(f) => (qualifiers(f), function(f)),
                    None => Default::default(),
                };
                out.insert(format!("trait-item {q}{path}::{}{sig}", name_of(i)));
            }
            for i in body["implementations"].as_array().unwrap() {
                let imp = &doc["index"][&i.to_string()]["inner"]["impl"];
                out.insert(format!("impl {path} for {}", ty(&imp["for"])));
            }
        }
        "function" => {
            out.insert(format!("{}fn {path}{}", qualifiers(body), function(body)));
        }
        "constant" | "static" => {
            out.insert(format!("{kind} {path}: {}", ty(&body["type"])));
        }
        "type_alias" => {
            let g = generics(&body["generics"]);
            out.insert(format!("type {path}{g} = {}", ty(&body["type"])));
        }
        other => {
            out.insert(format!("{other} {path}"));
        }
    }
}

/// The type of the struct field or variant field `id`.
fn field_type(doc: &Value, id: &Value) -> String {
    ty(&doc["index"][&id.to_string()]["inner"]["struct_field"])
}

/// Inherent methods and constants with their signatures, the traits implemented (not
/// blanket ones) and the auto traits (`Send`, `Sync`, `Unpin`, `UnwindSafe`, …), whose
/// loss would break users as surely as a changed signature.
fn impls(doc: &Value, ids: &Value, path: &str, out: &mut BTreeSet<String>) {
    for i in ids.as_array().into_iter().flatten() {
        let imp = &doc["index"][&i.to_string()]["inner"]["impl"];
        if !imp["blanket_impl"].is_null() {
            continue;
        }
        let not = if imp["is_negative"] == true { "!" } else { "" };
        if imp["is_synthetic"] == true {
            // The stable auto traits only: rustdoc also lists unstable ones (`Freeze`, …)
            // that come and go with the nightly.
            let name = trait_path(&imp["trait"]);
            if AUTO_TRAITS.contains(&name.as_str()) {
                out.insert(format!("auto impl {not}{name} for {path}"));
            }
        } else if imp["trait"].is_null() {
            for m in imp["items"].as_array().unwrap() {
                let m = &doc["index"][&m.to_string()];
                let Some(name) = m["name"].as_str() else {
                    continue;
                };
                let full = format!("{path}::{name}");
                attributes(m, &full, out);
                match m["inner"].as_object().and_then(|o| o.iter().next()) {
                    Some((k, f)) if k == "function" => {
                        out.insert(format!("{}fn {full}{}", qualifiers(f), function(f)));
                    }
                    Some((k, c)) if k == "assoc_const" => {
                        out.insert(format!("const {full}: {}", ty(&c["type"])));
                    }
                    Some((k, _)) => {
                        out.insert(format!("{k} {full}"));
                    }
                    None => {}
                }
            }
        } else {
            // Listed with the type they mention, such as `From<Id> for u64` under `Id`.
            let target = ty(&imp["for"]);
            let named = target.split('<').next();
            let target = match path.rsplit("::").next() == named {
                true => path.to_string(),
                false => target,
            };
            out.insert(format!(
                "impl {not}{} for {target}",
                trait_path(&imp["trait"])
            ));
        }
    }
}

/// The attributes that are part of an item's promise: `#[non_exhaustive]` (a field or
/// variant may come), `#[deprecated]`, and a C layout (`#[repr(C)]`).
fn attributes(item: &Value, path: &str, out: &mut BTreeSet<String>) {
    for a in item["attrs"].as_array().into_iter().flatten() {
        if a == "non_exhaustive" {
            out.insert(format!("#[non_exhaustive] {path}"));
        }
        if a["repr"]["kind"] == "c" {
            out.insert(format!("#[repr(C)] {path}"));
        }
    }
    if !item["deprecation"].is_null() {
        out.insert(format!("#[deprecated] {path}"));
    }
}

/// A function's qualifiers, written before `fn`: `const `, `unsafe `, `extern "C" `.
fn qualifiers(f: &Value) -> String {
    let h = &f["header"];
    let mut q = String::new();
    for (flag, word) in [("is_const", "const "), ("is_unsafe", "unsafe ")] {
        if h[flag] == true {
            q.push_str(word);
        }
    }
    if h["abi"] != "Rust" {
        q.push_str(&format!("extern {} ", h["abi"]));
    }
    q
}

/// A function's generics, parameters and return type.
fn function(f: &Value) -> String {
    let inputs: Vec<String> = f["sig"]["inputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let (name, t) = (p[0].as_str().unwrap_or("_"), &p[1]);
            match (name, ty(t).as_str()) {
                ("self", "Self") => "self".into(),
                ("self", "&Self") => "&self".into(),
                ("self", "&mut Self") => "&mut self".into(),
                (_, t) => format!("{name}: {t}"),
            }
        })
        .collect();
    let output = match f["sig"]["output"].is_null() {
        true => String::new(),
        false => format!(" -> {}", ty(&f["sig"]["output"])),
    };
    let g = generics(&f["generics"]);
    let w = where_clause(&f["generics"]);
    format!("{g}({}){output}{w}", inputs.join(", "))
}

/// `<T: Bound, 'a, const N: usize>`, without the parameters `impl Trait` arguments make.
fn generics(g: &Value) -> String {
    let params: Vec<String> = g["params"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|p| {
            let name = p["name"].as_str().unwrap_or("_");
            let kind = &p["kind"];
            if let Some(t) = kind.get("type") {
                if t["is_synthetic"] == true {
                    return None;
                }
                let b = bounds(&t["bounds"]);
                Some(match b.is_empty() {
                    true => name.to_string(),
                    false => format!("{name}: {b}"),
                })
            } else if let Some(c) = kind.get("const") {
                Some(format!("const {name}: {}", ty(&c["type"])))
            } else {
                Some(name.to_string())
            }
        })
        .collect();
    match params.is_empty() {
        true => String::new(),
        false => format!("<{}>", params.join(", ")),
    }
}

/// ` where T: Bound, …`, or nothing.
fn where_clause(g: &Value) -> String {
    let preds: Vec<String> = g["where_predicates"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|p| {
            let b = p.get("bound_predicate")?;
            Some(format!("{}: {}", ty(&b["type"]), bounds(&b["bounds"])))
        })
        .collect();
    match preds.is_empty() {
        true => String::new(),
        false => format!(" where {}", preds.join(", ")),
    }
}

/// `A + ?Sized + 'a`.
fn bounds(b: &Value) -> String {
    let parts: Vec<String> = b
        .as_array()
        .into_iter()
        .flatten()
        .map(|b| {
            if let Some(t) = b.get("trait_bound") {
                let maybe = if t["modifier"] == "maybe" { "?" } else { "" };
                format!("{maybe}{}", trait_path(&t["trait"]))
            } else {
                b["outlives"].as_str().unwrap_or("?").to_string()
            }
        })
        .collect();
    parts.join(" + ")
}

/// A trait or type path with its generic arguments: `From<Error>`, `Fn(usize) -> bool`.
fn trait_path(p: &Value) -> String {
    let name = p["path"].as_str().unwrap_or("?");
    let name = name.rsplit("::").next().unwrap();
    format!("{name}{}", args(&p["args"]))
}

/// `<T, 'a, Item = U>` or `(A, B) -> C`, or nothing.
fn args(a: &Value) -> String {
    if let Some(ab) = a.get("angle_bracketed") {
        let mut parts: Vec<String> = ab["args"]
            .as_array()
            .into_iter()
            .flatten()
            .map(|x| {
                if let Some(t) = x.get("type") {
                    ty(t)
                } else if let Some(l) = x.get("lifetime") {
                    l.as_str().unwrap_or("'_").to_string()
                } else {
                    x["const"]["expr"].as_str().unwrap_or("_").to_string()
                }
            })
            .collect();
        for c in ab["constraints"].as_array().into_iter().flatten() {
            let binding = &c["binding"];
            let value = match binding.get("equality") {
                Some(e) => format!(" = {}", ty(&e["type"])),
                None => format!(": {}", bounds(&binding["constraint"])),
            };
            parts.push(format!("{}{value}", c["name"].as_str().unwrap_or("?")));
        }
        return match parts.is_empty() {
            true => String::new(),
            false => format!("<{}>", parts.join(", ")),
        };
    }
    if let Some(p) = a.get("parenthesized") {
        let inputs: Vec<String> = p["inputs"].as_array().unwrap().iter().map(ty).collect();
        let output = match p["output"].is_null() {
            true => String::new(),
            false => format!(" -> {}", ty(&p["output"])),
        };
        return format!("({}){output}", inputs.join(", "));
    }
    String::new()
}

/// A type as Rust source writes it (paths shortened to their last segment).
fn ty(t: &Value) -> String {
    if let Some(p) = t.get("resolved_path") {
        return trait_path(p);
    }
    if let Some(p) = t.get("primitive").or(t.get("generic")) {
        return p.as_str().unwrap_or("?").to_string();
    }
    if let Some(parts) = t.get("tuple") {
        let parts: Vec<String> = parts.as_array().unwrap().iter().map(ty).collect();
        return format!("({})", parts.join(", "));
    }
    if let Some(s) = t.get("slice") {
        return format!("[{}]", ty(s));
    }
    if let Some(a) = t.get("array") {
        return format!("[{}; {}]", ty(&a["type"]), a["len"].as_str().unwrap_or("_"));
    }
    if let Some(r) = t.get("borrowed_ref") {
        let life = match r["lifetime"].as_str() {
            Some(l) => format!("{l} "),
            None => String::new(),
        };
        let m = if r["is_mutable"] == true { "mut " } else { "" };
        return format!("&{life}{m}{}", ty(&r["type"]));
    }
    if let Some(r) = t.get("raw_pointer") {
        let m = if r["is_mutable"] == true {
            "mut"
        } else {
            "const"
        };
        return format!("*{m} {}", ty(&r["type"]));
    }
    if let Some(b) = t.get("impl_trait") {
        return format!("impl {}", bounds(b));
    }
    if let Some(d) = t.get("dyn_trait") {
        let mut parts: Vec<String> = d["traits"]
            .as_array()
            .into_iter()
            .flatten()
            .map(|p| trait_path(&p["trait"]))
            .collect();
        if let Some(l) = d["lifetime"].as_str() {
            parts.push(l.to_string());
        }
        return format!("dyn {}", parts.join(" + "));
    }
    if let Some(q) = t.get("qualified_path") {
        let name = q["name"].as_str().unwrap_or("?");
        return match q["trait"].is_null() {
            true => format!("{}::{name}", ty(&q["self_type"])),
            false => format!(
                "<{} as {}>::{name}",
                ty(&q["self_type"]),
                trait_path(&q["trait"])
            ),
        };
    }
    if t.get("function_pointer").is_some() {
        return "fn(..)".to_string();
    }
    if t.get("infer").is_some() {
        return "_".to_string();
    }
    format!("{t}")
}
