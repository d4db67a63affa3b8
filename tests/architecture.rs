//! The house rules of ARCHITECTURE.md, checked on the sources of every crate in the
//! workspace: where `unsafe` may live, no source file over 800 lines, and no import circle
//! between sibling modules.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The crates' source folders, from the workspace root.
const CRATES: [&str; 5] = [
    "src",
    "cli/src",
    "ffi/src",
    "bevy/src",
    "examples/rapier/src",
];

/// The only places an `unsafe` block, function or impl may stand (ARCHITECTURE.md, "Where
/// `unsafe` lives"): a folder ends in `/`. The C ABI's exported functions are declared
/// `unsafe extern "C" fn` wherever they are (a C caller's pointers are the reason); that
/// declaration is the only `unsafe` allowed outside these places.
const UNSAFE_PLACES: [&str; 5] = [
    "src/simd/",                 // the lane layer: intrinsics, one file per instruction set
    "src/jobs.rs",               // disjoint parts of one buffer for tasks running at once
    "src/forces/engine/access/", // the engine's unchecked row access and each band's parts
    "ffi/src/ptr.rs",            // the C ABI's pointer and length checks
    "ffi/src/jobs.rs",           // a C host's job-system callbacks
];

const MAX_LINES: usize = 800;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under `dir`, as paths relative to the workspace root.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(root().join(dir))
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let rel = path.strip_prefix(root()).unwrap().to_path_buf();
        if path.is_dir() {
            rust_files(&rel, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(rel);
        }
    }
}

/// A file's code without its comments (line comments and doc comments; the crate uses no
/// block comments in code) and without string literals' contents.
fn code(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let mut in_str = false;
        let mut prev = ' ';
        let mut chars = line.chars().peekable();
        while let Some(c) = chars.next() {
            if !in_str && c == '/' && chars.peek() == Some(&'/') {
                break;
            }
            if c == '"' && prev != '\\' && prev != '\'' {
                in_str = !in_str;
                out.push(c);
            } else if !in_str {
                out.push(c);
            }
            prev = c;
        }
        out.push('\n');
    }
    out
}

fn slash(p: &Path) -> String {
    p.to_string_lossy().replace('\\', "/")
}

#[test]
fn unsafe_lives_only_in_its_places() {
    let mut files = Vec::new();
    for dir in CRATES {
        rust_files(Path::new(dir), &mut files);
    }
    // Every place is still there (a moved file must move in the list too).
    for place in UNSAFE_PLACES {
        assert!(root().join(place).exists(), "{place} is listed but missing");
    }
    let mut found = Vec::new();
    for file in &files {
        let name = slash(file);
        if UNSAFE_PLACES
            .iter()
            .any(|p| name == *p || (p.ends_with('/') && name.starts_with(p)))
        {
            continue;
        }
        let text = code(&std::fs::read_to_string(root().join(file)).unwrap());
        for (n, line) in text.lines().enumerate() {
            // (String contents are blanked here: `extern "C"` reads `extern ""`.)
            let declaration =
                name.starts_with("ffi/src/") && line.contains("unsafe extern \"\" fn");
            let words: Vec<&str> = line
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .collect();
            if words.contains(&"unsafe") && !declaration {
                found.push(format!("{name}:{}: {}", n + 1, line.trim()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "`unsafe` outside {UNSAFE_PLACES:?}:\n{}",
        found.join("\n")
    );
}

#[test]
fn no_source_file_is_over_800_lines() {
    let mut files = Vec::new();
    for dir in CRATES {
        rust_files(Path::new(dir), &mut files);
    }
    let long: Vec<String> = files
        .iter()
        .filter_map(|f| {
            let lines = std::fs::read_to_string(root().join(f))
                .unwrap()
                .lines()
                .count();
            (lines > MAX_LINES).then(|| format!("{}: {lines} lines", slash(f)))
        })
        .collect();
    assert!(
        long.is_empty(),
        "over {MAX_LINES} lines:\n{}",
        long.join("\n")
    );
}

/// A module path inside one crate, `[]` for the crate root.
type Module = Vec<String>;

/// The module a file defines: `src/surface/step.rs` is `[surface, step]`,
/// `src/surface/mod.rs` is `[surface]`.
fn module_of(src: &Path, file: &Path) -> Module {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// The module paths a file's code names with `crate::` or `super::` (groups in braces
/// opened one level), resolved against the crate's modules: the longest prefix that is a
/// module.
fn references(here: &Module, text: &str, modules: &BTreeSet<Module>) -> BTreeSet<Module> {
    // Only the file's own code: an inline test module at its end names its parent with
    // `super::`, which is not an edge between files.
    let text = text.split("#[cfg(test)]\nmod ").next().unwrap();
    let mut paths = Vec::new();
    for start in ["crate::", "super::"] {
        for (at, _) in text.match_indices(start) {
            let before = text[..at].chars().last().unwrap_or(' ');
            if before.is_alphanumeric() || before == '_' || before == ':' {
                continue;
            }
            let mut base: Module = if start == "crate::" {
                Vec::new()
            } else {
                here[..here.len().saturating_sub(1)].to_vec()
            };
            let rest = &text[at + start.len()..];
            let mut rest = rest;
            while let Some(r) = rest.strip_prefix("super::") {
                base.pop();
                rest = r;
            }
            let tail: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':' || *c == '{')
                .collect();
            if let Some(group) = tail
                .strip_suffix('{')
                .or_else(|| tail.ends_with("::{").then(|| tail.trim_end_matches('{')))
            {
                // `crate::a::{b, c::d}`: the group's first segments.
                let prefix: Module = group
                    .split("::")
                    .filter(|s| !s.is_empty())
                    .map(str::to_owned)
                    .collect();
                let close = rest.find('}').unwrap_or(rest.len());
                let open = rest.find('{').unwrap_or(0);
                for item in rest[open + 1..close].split(',') {
                    let mut p = base.clone();
                    p.extend(prefix.iter().cloned());
                    p.extend(
                        item.trim()
                            .split("::")
                            .map(|s| s.trim().to_owned())
                            .filter(|s| !s.is_empty()),
                    );
                    paths.push(p);
                }
            } else {
                let mut p = base.clone();
                p.extend(
                    tail.split("::")
                        .filter(|s| !s.is_empty())
                        .map(str::to_owned),
                );
                paths.push(p);
            }
        }
    }
    paths
        .into_iter()
        .filter_map(|p| {
            (0..=p.len())
                .rev()
                .map(|k| p[..k].to_vec())
                .find(|m| modules.contains(m))
        })
        .collect()
}

/// Where `a` and `b` meet: the two children of their deepest common module that contain
/// them, or `None` when one contains the other (a module and its own parts).
fn siblings(a: &Module, b: &Module) -> Option<(Module, Module)> {
    let common = a.iter().zip(b).take_while(|(x, y)| x == y).count();
    (common < a.len() && common < b.len()).then(|| (a[..=common].to_vec(), b[..=common].to_vec()))
}

#[test]
fn sibling_modules_never_import_each_other_in_a_circle() {
    let mut circles = Vec::new();
    for dir in CRATES {
        let src = Path::new(dir);
        let mut files = Vec::new();
        rust_files(src, &mut files);
        let modules: BTreeSet<Module> = files.iter().map(|f| module_of(src, f)).collect();
        // Edges between siblings: `a → b` when code in `a` (or below it) names `b` (or
        // something below it).
        let mut edges: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
        for file in &files {
            let here = module_of(src, file);
            let text = code(&std::fs::read_to_string(root().join(file)).unwrap());
            for target in references(&here, &text, &modules) {
                if let Some((from, to)) = siblings(&here, &target) {
                    edges.entry(from).or_default().insert(to);
                }
            }
        }
        // A circle is an edge `a → b` with a path back from `b` to `a`.
        let reaches = |from: &Module, to: &Module| {
            let mut seen = BTreeSet::new();
            let mut stack = vec![from.clone()];
            while let Some(m) = stack.pop() {
                if &m == to {
                    return true;
                }
                if seen.insert(m.clone()) {
                    stack.extend(edges.get(&m).into_iter().flatten().cloned());
                }
            }
            false
        };
        for (a, targets) in &edges {
            for b in targets {
                if a < b && reaches(b, a) {
                    circles.push(format!("{dir}: {} <-> {}", a.join("::"), b.join("::")));
                }
            }
        }
    }
    assert!(
        circles.is_empty(),
        "import circles between sibling modules:\n{}",
        circles.join("\n")
    );
}

/// The fields of `struct name` in `text` (the lines between its `{` and the closing `}` at
/// the start of a line), as written.
fn fields_of<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
    let start = text
        .find(&format!("struct {name} {{"))
        .unwrap_or_else(|| panic!("struct {name} not found"));
    let body = &text[start..];
    let end = body.find("\n}").expect("the struct ends");
    body[..end]
        .lines()
        .skip(1)
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("//") && !l.starts_with('#'))
        .collect()
}

#[test]
fn surface_and_its_subsystems_keep_their_fields_to_themselves() {
    // `Surface` is a coordinator: its fields are private to `surface/`, and the bodies'
    // subsystem's to `surface/bodies/`; every other module goes through their methods.
    for (file, name) in [
        ("src/surface/mod.rs", "Surface"),
        ("src/surface/bodies/mod.rs", "BodySet"),
    ] {
        let text = std::fs::read_to_string(root().join(file)).unwrap();
        let fields = fields_of(&text, name);
        assert!(fields.len() >= 4, "{name}: found {fields:?}");
        let open: Vec<_> = fields.iter().filter(|f| f.starts_with("pub")).collect();
        assert!(
            open.is_empty(),
            "{name} has fields open outside its module: {open:?}"
        );
    }
    // The check itself: a field marked `pub(crate)` is seen.
    let sample = "pub struct S {\n    /// a\n    pub(crate) a: u8,\n    b: u8,\n}\n";
    assert_eq!(fields_of(sample, "S"), ["pub(crate) a: u8,", "b: u8,"]);
}
