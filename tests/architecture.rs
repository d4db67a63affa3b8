//! The house rules of ARCHITECTURE.md, checked on the sources of every crate in the
//! workspace: where `unsafe` may live, no source file over 800 lines (of any language, in
//! the whole repository), and no circle
//! between sibling modules, of imports or of calls between one type's `impl` blocks in
//! different files. Each check asserts that it found what it scans (files, lines, edges),
//! so a broken path or pattern fails instead of passing on nothing; the circle check also
//! runs on the fixtures of `tests/fixtures/architecture/`, one with a known circle.

use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;
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

/// Every file below `dir` whose extension `keep` accepts, as paths relative to the
/// workspace root, but what builds, tools and packages put there (`target/`,
/// `node_modules/`, hidden folders).
fn files(dir: &Path, keep: &dyn Fn(&str) -> bool, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(root().join(dir))
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let rel = path.strip_prefix(root()).unwrap().to_path_buf();
        let name = path.file_name().unwrap().to_string_lossy();
        if path.is_dir() {
            if !(name.starts_with('.') || name == "target" || name == "node_modules") {
                files(&rel, keep, out);
            }
        } else if path.extension().is_some_and(|e| keep(&e.to_string_lossy())) {
            out.push(rel);
        }
    }
}

/// Every `.rs` file under `dir`, as paths relative to the workspace root.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    files(dir, &|e| e == "rs", out);
}

/// A file's code without its comments (line comments and doc comments; the crate uses no
/// block comments in code) and without string literals' contents (a string may go on over
/// a line break; its quotes stay).
fn code(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut in_str = false;
    for line in text.lines() {
        let mut escaped = false;
        let mut prev = ' ';
        let mut chars = line.chars().peekable();
        while let Some(c) = chars.next() {
            if in_str {
                if escaped {
                    escaped = false;
                } else if c == '\\' {
                    escaped = true;
                } else if c == '"' {
                    in_str = false;
                    out.push(c);
                }
            } else if c == '/' && chars.peek() == Some(&'/') {
                break;
            } else {
                // `'"'` and `'\"'` are characters, not the start of a string.
                in_str = c == '"' && prev != '\'' && prev != '\\';
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
    // What the scan saw: `unsafe` lines in the places, and the C ABI's declarations.
    let (mut in_places, mut declarations) = (0, 0);
    for file in &files {
        let name = slash(file);
        let place = UNSAFE_PLACES
            .iter()
            .any(|p| name == *p || (p.ends_with('/') && name.starts_with(p)));
        let text = code(&std::fs::read_to_string(root().join(file)).unwrap());
        for (n, line) in text.lines().enumerate() {
            // (String contents are blanked here: `extern "C"` reads `extern ""`.)
            let declaration =
                name.starts_with("ffi/src/") && line.contains("unsafe extern \"\" fn");
            let words: Vec<&str> = line
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .collect();
            if !words.contains(&"unsafe") {
                continue;
            }
            if place {
                in_places += 1;
            } else if declaration {
                declarations += 1;
            } else {
                found.push(format!("{name}:{}: {}", n + 1, line.trim()));
            }
        }
    }
    // A broken path or a scan that sees nothing cannot pass.
    assert!(files.len() >= 100, "only {} files scanned", files.len());
    assert!(
        in_places >= 100,
        "only {in_places} `unsafe` lines in the places"
    );
    assert!(
        declarations >= 50,
        "only {declarations} exported C functions"
    );
    assert!(
        found.is_empty(),
        "`unsafe` outside {UNSAFE_PLACES:?}:\n{}",
        found.join("\n")
    );
}

/// What a person writes, by extension: the workspace's Rust, the C and C# clients of the
/// C ABI, the web package's JavaScript and TypeScript, the scripts.
const SOURCE_EXTENSIONS: [&str; 10] = ["rs", "c", "h", "cpp", "cs", "js", "mjs", "ts", "py", "sh"];

/// Written by a tool, not by hand (`ffi/tests/header.rs` keeps it current).
const GENERATED: [&str; 1] = ["ffi/include/springwater.h"];

/// Every hand-written source file below `dir` (see [`files`] for what is passed over).
fn source_files(dir: &Path, out: &mut Vec<PathBuf>) {
    files(dir, &|e| SOURCE_EXTENSIONS.contains(&e), out);
    out.retain(|f| !GENERATED.contains(&slash(f).as_str()));
}

#[test]
fn no_source_file_is_over_800_lines() {
    let mut files = Vec::new();
    source_files(Path::new(""), &mut files);
    let lengths: Vec<(String, usize)> = files
        .iter()
        .map(|f| {
            let text = std::fs::read_to_string(root().join(f)).unwrap();
            (slash(f), text.lines().count())
        })
        .collect();
    // A broken path or a count that sees nothing cannot pass: the library, the tests, the
    // C and C# clients and the web package are all in it.
    let total: usize = lengths.iter().map(|(_, n)| n).sum();
    assert!(lengths.len() >= 200, "only {} files", lengths.len());
    assert!(total >= 50_000, "only {total} lines in all");
    for seen in [
        "src/surface/mod.rs",
        "tests/architecture.rs",
        "ffi/tests/c/client.c",
    ] {
        assert!(lengths.iter().any(|(f, _)| f == seen), "{seen} not scanned");
    }
    for seen in [".cs", ".js", ".py", ".sh"] {
        assert!(
            lengths.iter().any(|(f, _)| f.ends_with(seen)),
            "no {seen} file scanned"
        );
    }
    let long: Vec<String> = lengths
        .iter()
        .filter(|(_, lines)| *lines > MAX_LINES)
        .map(|(f, lines)| format!("{f}: {lines} lines"))
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

/// One file of a crate as the circle check reads it.
struct Source {
    name: String,
    module: Module,
    /// The file's own code (`code`), without an inline test module at its end: that module
    /// names its parent with `super::`, which is not an edge between files.
    code: String,
}

/// The `.rs` files under `dir` (a crate's `src/`, or a fixture), read.
fn sources(dir: &str) -> Vec<Source> {
    let src = Path::new(dir);
    let mut files = Vec::new();
    rust_files(src, &mut files);
    files
        .iter()
        .map(|file| {
            let text = code(&std::fs::read_to_string(root().join(file)).unwrap());
            Source {
                name: slash(file),
                module: module_of(src, file),
                code: text.split("#[cfg(test)]\nmod ").next().unwrap().to_owned(),
            }
        })
        .collect()
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The identifiers of `text` with their byte offsets (numbers too; they match no name).
fn identifiers(text: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut start = None;
    for (at, c) in text.char_indices().chain([(text.len(), ' ')]) {
        match (start, is_ident(c)) {
            (None, true) => start = Some(at),
            (Some(s), false) => {
                out.push((s, &text[s..at]));
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// The byte just past the `}` that closes the `{` at `open`.
fn closing(text: &str, open: usize) -> usize {
    let mut depth = 0usize;
    for (at, c) in text[open..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return open + at + 1;
                }
            }
            _ => {}
        }
    }
    text.len()
}

/// A file's inherent `impl` blocks (`impl Surface {`, `impl<'a, V: Vector> Band<'a, V>
/// where … {`; not `impl Trait for Type`): the type's name and the block's byte range,
/// braces included.
fn inherent_impls(code: &str) -> Vec<(String, Range<usize>)> {
    let mut impls = Vec::new();
    for (at, word) in identifiers(code) {
        let Some(open) = (word == "impl")
            .then(|| code[at..].find(['{', ';']).map(|k| at + k))
            .flatten()
            .filter(|&open| code[open..].starts_with('{'))
        else {
            continue;
        };
        // The header without the impl's own generics: `Band<'a, V> where …`.
        let mut header = code[at + "impl".len()..open].trim_start();
        if header.starts_with('<') {
            let mut depth = 0;
            let end = header
                .char_indices()
                .find(|&(_, c)| {
                    depth += (c == '<') as i32 - (c == '>') as i32;
                    depth == 0
                })
                .map_or(header.len(), |(k, _)| k + 1);
            header = header[end..].trim_start();
        }
        let head = header.split(" where").next().unwrap();
        if identifiers(head).iter().any(|&(_, w)| w == "for") {
            continue;
        }
        let path = head.split(['<', ' ', '\n']).next().unwrap();
        let name = path.rsplit("::").next().unwrap();
        if !name.is_empty() {
            impls.push((name.to_owned(), open..closing(code, open)));
        }
    }
    impls
}

/// The methods an `impl` block defines: each `fn` at the block's own depth.
fn methods_in(block: &str) -> Vec<&str> {
    let mut depth = 0usize;
    let mut methods = Vec::new();
    let words = identifiers(block);
    let mut next = 0;
    for (at, c) in block.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth = depth.saturating_sub(1),
            _ => {}
        }
        while next < words.len() && words[next].0 <= at {
            if words[next].0 == at && depth == 1 && words[next].1 == "fn" {
                if let Some(&(_, name)) = words.get(next + 1) {
                    methods.push(name);
                }
            }
            next += 1;
        }
    }
    methods
}

/// `LodParams` → `lod_params`.
fn snake(name: &str) -> String {
    let mut out = String::new();
    for (k, c) in name.chars().enumerate() {
        if c.is_uppercase() && k > 0 {
            out.push('_');
        }
        out.extend(c.to_lowercase());
    }
    out
}

/// The names that hold a `ty` in a file's code (`words` its identifiers): the type's name
/// in snake case (`surface`), and every name declared with the type (`water: &mut Surface`,
/// `s: &'a Surface`, `let mut s = Surface::new(…)`).
fn holders_of<'a>(code: &'a str, words: &[(usize, &str)], ty: &str) -> BTreeSet<&'a str> {
    let mut names = BTreeSet::new();
    for &(at, word) in words {
        if word != ty {
            continue;
        }
        let before = &code[..at];
        let Some(mark) = before.rfind([':', '=']) else {
            continue;
        };
        // Between the mark and the type only `&`, `mut` and a lifetime.
        let between: String = before[mark + 1..]
            .replace('&', " ")
            .split_whitespace()
            .filter(|w| *w != "mut")
            .collect();
        let lifetime = between
            .strip_prefix('\'')
            .is_some_and(|l| l.chars().all(is_ident));
        if !(between.is_empty() || lifetime) {
            continue;
        }
        // `name:` (not a path's `::`), `name =` (not `==`, `<=`, `+=`, …).
        let head = before[..mark].trim_end();
        if head.ends_with(|c: char| ":=!<>+-*/%&|^".contains(c)) {
            continue;
        }
        let start = head.trim_end_matches(is_ident).len();
        if start < head.len() {
            names.insert(&code[start..head.len()]);
        }
    }
    names
}

/// Why one module depends on another: a file's import, or a method call.
type Evidence = BTreeMap<(Module, Module), BTreeSet<String>>;

/// What the circle check found in one crate.
#[derive(Default)]
struct Graph {
    files: usize,
    /// Edges between sibling modules, with what makes each.
    edges: Evidence,
    /// Edges from `crate::` and `super::` paths, before siblings are taken.
    imports: usize,
    /// Types whose inherent `impl` blocks stand in more than one file, with their methods.
    split_types: BTreeMap<String, usize>,
    /// Calls, in one file, of a method of such a type that another file's `impl` defines.
    calls: usize,
}

/// The crate's module graph: `a → b` between siblings when code in `a` (or below it)
/// names `b` (or something below it) by a `crate::` or `super::` path, or calls a method
/// that an `impl` block in `b` (or below it) defines.
///
/// A method call is tied to its type by its receiver, as far as a text scan can: a type's
/// inherent `impl` blocks in several files (`impl Surface` across `surface/`) define
/// methods; a call `self.m(` or `Self::m(` inside an `impl` of that type, `T::m(`, or
/// `x.m(` where `x` is the type's name in snake case (`surface.m(`, `self.surface.m(`) or
/// a name the file declares with the type (`water: &mut Surface`, `let s = Surface::new(`)
/// is a call of the type's method. A call on any other receiver (`self.bodies[k].m(`, a
/// chain's result) is not seen: a method's name alone says too little (`contains`, `len`
/// are also std's).
fn graph(sources: &[Source]) -> Graph {
    let mut g = Graph {
        files: sources.len(),
        ..Graph::default()
    };
    let modules: BTreeSet<Module> = sources.iter().map(|s| s.module.clone()).collect();
    let add = |g: &mut Graph, here: &Module, target: &Module, why: String| {
        if let Some(pair) = siblings(here, target) {
            g.edges.entry(pair).or_default().insert(why);
        }
    };
    for s in sources {
        for target in references(&s.module, &s.code, &modules) {
            g.imports += 1;
            let why = format!("{} names crate::{}", s.name, target.join("::"));
            add(&mut g, &s.module, &target, why);
        }
    }

    // Each file's inherent impl blocks, and the methods of the types split over files:
    // (type, method) → the files that define it.
    let impls: Vec<Vec<(String, Range<usize>)>> =
        sources.iter().map(|s| inherent_impls(&s.code)).collect();
    let mut files_of: BTreeMap<&str, BTreeSet<usize>> = BTreeMap::new();
    for (k, blocks) in impls.iter().enumerate() {
        for (name, _) in blocks {
            files_of.entry(name).or_default().insert(k);
        }
    }
    let mut defined: BTreeMap<(&str, &str), BTreeSet<usize>> = BTreeMap::new();
    for (k, blocks) in impls.iter().enumerate() {
        for (name, range) in blocks {
            if files_of[name.as_str()].len() > 1 {
                for m in methods_in(&sources[k].code[range.clone()]) {
                    defined.entry((name, m)).or_default().insert(k);
                }
            }
        }
    }
    for (name, _) in defined.keys() {
        *g.split_types.entry(name.to_string()).or_default() += 1;
    }
    let split: Vec<(String, String)> = g
        .split_types
        .keys()
        .map(|ty| (ty.clone(), snake(ty)))
        .collect();
    for (k, s) in sources.iter().enumerate() {
        let words = identifiers(&s.code);
        let mut holders: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
        for (ty, snake) in &split {
            let mut names = holders_of(&s.code, &words, ty);
            names.insert(snake);
            holders.insert(ty, names);
        }
        for (i, &(at, m)) in words.iter().enumerate() {
            let after = s.code[at + m.len()..].trim_start();
            if !(after.starts_with('(') || after.starts_with("::<")) {
                continue;
            }
            let before = s.code[..at].trim_end();
            let (dot, path) = (before.ends_with('.'), before.ends_with("::"));
            if !(dot || path) || i == 0 {
                continue;
            }
            let (prev_at, prev) = words[i - 1];
            let adjacent = s.code[prev_at + prev.len()..at]
                .chars()
                .all(|c| c.is_whitespace() || c == '.' || c == ':');
            let inside = |ty: &str| {
                impls[k]
                    .iter()
                    .any(|(name, r)| name == ty && r.contains(&at))
            };
            for (ty, m) in defined.keys().filter(|(_, name)| *name == m) {
                let by_path = path && (prev == *ty || (prev == "Self" && inside(ty)));
                let by_value =
                    dot && ((prev == "self" && inside(ty)) || holders[ty].contains(prev));
                if !(adjacent && (by_path || by_value)) {
                    continue;
                }
                for &there in &defined[&(*ty, *m)] {
                    if there != k {
                        g.calls += 1;
                        let why = format!("{} calls {ty}::{m} of {}", s.name, sources[there].name);
                        add(&mut g, &s.module, &sources[there].module, why);
                    }
                }
            }
        }
    }
    g
}

/// The circles of a graph: each edge `a → b` with a path back from `b` to `a`, with what
/// makes every edge around it.
fn circles(edges: &Evidence) -> Vec<String> {
    let mut next: BTreeMap<&Module, Vec<&Module>> = BTreeMap::new();
    for (a, b) in edges.keys() {
        next.entry(a).or_default().push(b);
    }
    // The shortest path from `from` to `to`, if any.
    let path = |from: &Module, to: &Module| -> Option<Vec<Module>> {
        let mut came: BTreeMap<Module, Module> = BTreeMap::new();
        let mut queue = std::collections::VecDeque::from([from.clone()]);
        while let Some(m) = queue.pop_front() {
            if &m == to {
                let mut p = vec![m];
                while let Some(b) = came.get(p.last().unwrap()) {
                    p.push(b.clone());
                }
                p.reverse();
                return Some(p);
            }
            for n in next.get(&m).into_iter().flatten() {
                if !came.contains_key(*n) && *n != from {
                    came.insert((*n).clone(), m.clone());
                    queue.push_back((*n).clone());
                }
            }
        }
        None
    };
    let mut found = Vec::new();
    for (a, b) in edges.keys() {
        if a >= b {
            continue;
        }
        let Some(back) = path(b, a) else { continue };
        let name = |m: &Module| m.join("::");
        let mut text = format!("{} <-> {}", name(a), name(b));
        let mut around = vec![a.clone()];
        around.extend(back);
        for step in around.windows(2) {
            let why = &edges[&(step[0].clone(), step[1].clone())];
            text += &format!("\n  {} -> {}:", name(&step[0]), name(&step[1]));
            for w in why.iter().take(6) {
                text += &format!("\n    {w}");
            }
            if why.len() > 6 {
                text += &format!("\n    (and {} more)", why.len() - 6);
            }
        }
        found.push(text);
    }
    found
}

#[test]
fn sibling_modules_never_depend_on_each_other_in_a_circle() {
    let mut found = Vec::new();
    let (mut files, mut imports) = (0, 0);
    for dir in CRATES {
        let g = graph(&sources(dir));
        // The scan found what it scans: a broken path or pattern cannot pass.
        assert!(g.files >= 2, "{dir}: {} files", g.files);
        (files, imports) = (files + g.files, imports + g.imports);
        println!(
            "{dir}: {} files, {} imports, {} method calls across files of {:?}, {} edges",
            g.files,
            g.imports,
            g.calls,
            g.split_types,
            g.edges.len()
        );
        if dir == "src" {
            assert!(
                g.files >= 60 && g.edges.len() >= 40,
                "src: {} edges",
                g.edges.len()
            );
            let surface = g.split_types.get("Surface").copied().unwrap_or(0);
            assert!(
                surface >= 60,
                "src: {surface} methods of Surface's split impls"
            );
            assert!(g.calls >= 50, "src: {} method calls across files", g.calls);
        }
        found.extend(circles(&g.edges).into_iter().map(|c| format!("{dir}: {c}")));
    }
    assert!(
        files >= 100 && imports >= 300,
        "{files} files, {imports} imports"
    );
    assert!(
        found.is_empty(),
        "circles between sibling modules (imports or method calls):\n{}",
        found.join("\n")
    );
}

/// The check on fixtures: two files of one `impl Pond` that call each other's methods
/// are a circle, though neither imports the other; calls one way only are none.
#[test]
fn method_calls_between_impl_blocks_in_two_files_are_a_circle() {
    let g = graph(&sources("tests/fixtures/architecture/circle"));
    assert_eq!(g.files, 4);
    let edges: Vec<_> = g.edges.values().flatten().collect();
    assert!(
        !edges.iter().any(|w| w.contains(" names ")),
        "no file names a sibling by a path: {edges:#?}"
    );
    assert_eq!(g.split_types.get("Pond"), Some(&5));
    let found = circles(&g.edges);
    assert_eq!(found.len(), 1, "{found:#?}");
    let circle = &found[0];
    assert!(circle.starts_with("fill <-> level\n"), "{circle}");
    for why in [
        "fill.rs calls Pond::drain_to of",
        "level.rs calls Pond::top_up of",
    ] {
        assert!(circle.contains(why), "{circle}");
    }
    // `pond.top_up(` (the type's name as receiver) and `tank.rise(` (a name declared
    // `&mut Pond`) count; `self.marks.len(` (a `Vec`, whatever the method's name) does not.
    for why in [
        "gauge.rs calls Pond::top_up of",
        "gauge.rs calls Pond::rise of",
    ] {
        assert!(edges.iter().any(|w| w.contains(why)), "{why}: {edges:#?}");
    }
    assert!(
        !edges.iter().any(|w| w.contains("gauge.rs calls Pond::len")),
        "{edges:#?}"
    );

    // `Self::pour(` and `Pond::pour_twice(` (paths) count.
    let g = graph(&sources("tests/fixtures/architecture/clean"));
    assert_eq!(g.files, 3);
    assert_eq!(g.calls, 2, "{:?}", g.edges);
    assert_eq!(g.edges.len(), 1, "{:?}", g.edges);
    assert!(circles(&g.edges).is_empty());
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
