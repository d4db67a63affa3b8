//! The public API changes only on purpose: this test lists every public item of the
//! library (modules, types, functions, constants, fields, variants, methods, trait
//! implementations) from rustdoc's JSON output and compares the list with the checked-in
//! `tests/public-api.txt`.
//!
//! After an intended change, regenerate the list with
//! `SPRINGWATER_BLESS=1 cargo test --test public_api` and review its diff.
//!
//! rustdoc's JSON output needs a nightly toolchain (`cargo +nightly rustdoc … --output-format
//! json`); the test fails if there is none, unless `SPRINGWATER_SKIP_PUBLIC_API=1` says to
//! skip it. Items behind `#[doc(hidden)]` (the `internals` feature: scalar twins,
//! comparison kernels, the engine's schedule) are not listed: they carry no promise.

use serde_json::Value;
use std::collections::BTreeSet;
use std::path::Path;
use std::process::Command;

/// Features documented: everything a user can turn on, except `internals`.
const FEATURES: &str = "parallel,render,serde";

#[test]
fn the_public_api_is_the_checked_in_list() {
    if std::env::var_os("SPRINGWATER_SKIP_PUBLIC_API").is_some() {
        eprintln!("skipped: SPRINGWATER_SKIP_PUBLIC_API is set");
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
        "`cargo +nightly rustdoc --output-format json` failed: a nightly toolchain is needed \
         (or set SPRINGWATER_SKIP_PUBLIC_API=1)"
    );
    let json = std::fs::read_to_string(target.join("doc").join("springwater.json")).unwrap();
    let doc: Value = serde_json::from_str(&json).unwrap();
    let mut api = BTreeSet::new();
    let root_id = doc["root"].to_string();
    walk(&doc, &root_id, "springwater", &mut api);
    let listed: String = api.iter().map(|l| format!("{l}\n")).collect();

    let file = root.join("tests").join("public-api.txt");
    if std::env::var_os("SPRINGWATER_BLESS").is_some() {
        std::fs::write(&file, &listed).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&file).unwrap_or_default();
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

/// Records the item `id` as `path`, and what it contains.
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
            out.insert(format!("struct {path}"));
            if let Some(fields) = body["kind"]["plain"]["fields"].as_array() {
                for f in fields {
                    let name = doc["index"][&f.to_string()]["name"].as_str().unwrap_or("_");
                    out.insert(format!("field {path}::{name}"));
                }
            }
            impls(doc, &body["impls"], path, out);
        }
        "enum" => {
            out.insert(format!("enum {path}"));
            for v in body["variants"].as_array().unwrap() {
                let name = doc["index"][&v.to_string()]["name"].as_str().unwrap();
                out.insert(format!("variant {path}::{name}"));
            }
            impls(doc, &body["impls"], path, out);
        }
        "trait" => {
            out.insert(format!("trait {path}"));
            for i in body["items"].as_array().unwrap() {
                let name = doc["index"][&i.to_string()]["name"].as_str().unwrap();
                out.insert(format!("trait-item {path}::{name}"));
            }
            for i in body["implementations"].as_array().unwrap() {
                let imp = &doc["index"][&i.to_string()]["inner"]["impl"];
                out.insert(format!("impl {path} for {}", type_name(&imp["for"])));
            }
        }
        other => {
            out.insert(format!("{other} {path}"));
        }
    }
}

/// Inherent methods and constants, and the traits implemented (not auto or blanket ones).
fn impls(doc: &Value, ids: &Value, path: &str, out: &mut BTreeSet<String>) {
    for i in ids.as_array().into_iter().flatten() {
        let imp = &doc["index"][&i.to_string()]["inner"]["impl"];
        if imp["is_synthetic"] == true || !imp["blanket_impl"].is_null() {
            continue;
        }
        if imp["trait"].is_null() {
            for m in imp["items"].as_array().unwrap() {
                let m = &doc["index"][&m.to_string()];
                let Some(name) = m["name"].as_str() else {
                    continue;
                };
                let full = format!("{path}::{name}");
                let kind = m["inner"]
                    .as_object()
                    .and_then(|o| o.keys().next().cloned());
                out.insert(format!("{} {full}", kind.unwrap_or_default()));
            }
        } else {
            let name = imp["trait"]["path"].as_str().unwrap_or("?");
            let name = name.rsplit("::").next().unwrap();
            out.insert(format!("impl {name} for {path}"));
        }
    }
}

/// A short name for the type an implementation is for.
fn type_name(ty: &Value) -> String {
    if let Some(p) = ty.get("resolved_path") {
        return p["path"].as_str().unwrap_or("?").to_string();
    }
    if let Some(p) = ty.get("primitive") {
        return p.as_str().unwrap_or("?").to_string();
    }
    if let Some(t) = ty.get("tuple") {
        let parts: Vec<String> = t.as_array().unwrap().iter().map(type_name).collect();
        return format!("({})", parts.join(", "));
    }
    if let Some(s) = ty.get("slice") {
        return format!("[{}]", type_name(s));
    }
    if let Some(r) = ty.get("borrowed_ref") {
        return format!("&mut {}", type_name(&r["type"]));
    }
    if ty.get("generic").is_some() {
        return ty["generic"].as_str().unwrap_or("?").to_string();
    }
    "?".to_string()
}
