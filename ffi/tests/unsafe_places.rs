//! Where the C ABI's `unsafe` code may live: `src/ptr.rs` (the pointer and length checks,
//! which state the safety argument once) and `src/jobs.rs` (the host's job-system
//! callbacks). Every other file calls their safe helpers. The exported functions are
//! `unsafe extern "C" fn`s, as C's raw pointers ask; the crate denies
//! `unsafe_op_in_unsafe_fn`, so their bodies, too, can do nothing unsafe outside an
//! `unsafe` block, which this test would find.

use std::path::{Path, PathBuf};

/// The files allowed `unsafe` blocks and `unsafe impl`s, relative to `src/`.
const ALLOWED: &[&str] = &["ptr.rs", "jobs.rs"];

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The places in `text` where unsafe code starts: `unsafe {` (however spaced, also across
/// a line break), `unsafe impl`, and an `unsafe fn` that is not an exported `extern "C"`
/// one. Line comments are left out, so prose may name the keyword.
fn unsafe_places(text: &str) -> Vec<String> {
    let code: Vec<&str> = text
        .lines()
        .map(|line| line.find("//").map_or(line, |at| &line[..at]))
        .collect();
    let code = code.join("\n");
    let mut places = Vec::new();
    for (at, _) in code.match_indices("unsafe") {
        let before = code[..at].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest = code[at + "unsafe".len()..].trim_start();
        let what = if rest.starts_with('{') {
            "unsafe {"
        } else if rest.starts_with("impl") {
            "unsafe impl"
        } else if rest.starts_with("fn") {
            "unsafe fn"
        } else {
            continue;
        };
        let line = code[..at].matches('\n').count() + 1;
        places.push(format!("line {line}: {what}"));
    }
    places
}

#[test]
fn unsafe_code_is_only_in_the_pointer_module_and_the_job_system() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    files.sort();
    assert!(files.len() >= 15, "the C ABI's sources are not in {src:?}");

    let mut outside = Vec::new();
    // What the scan saw: unsafe code in the allowed files, and the exported functions.
    let (mut allowed, mut exported) = (0, 0);
    for file in &files {
        let name = file
            .strip_prefix(&src)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let text = std::fs::read_to_string(file).unwrap();
        exported += text.matches("unsafe extern \"C\" fn").count();
        let places = unsafe_places(&text);
        if ALLOWED.contains(&name.as_str()) {
            assert!(
                !places.is_empty(),
                "src/{name} has no unsafe code any more: take it off the allowed list"
            );
            allowed += places.len();
        } else {
            outside.extend(places.into_iter().map(|p| format!("src/{name} {p}")));
        }
    }
    assert!(allowed >= 10, "only {allowed} unsafe places in {ALLOWED:?}");
    assert!(
        exported >= 50,
        "only {exported} exported `unsafe extern \"C\" fn`s"
    );
    assert!(
        outside.is_empty(),
        "unsafe code outside {ALLOWED:?} (use the safe helpers of src/ptr.rs):\n{}",
        outside.join("\n")
    );

    let lib = std::fs::read_to_string(src.join("lib.rs")).unwrap();
    assert!(
        lib.contains("#![deny(unsafe_op_in_unsafe_fn)]"),
        "src/lib.rs must deny unsafe_op_in_unsafe_fn, or an exported function's body could \
         dereference a pointer without an `unsafe` block this test sees"
    );
}

#[test]
fn the_scan_finds_each_kind_of_unsafe_code_and_skips_prose() {
    let text = "fn a() {\n    let x = unsafe { *p };\n}\n// unsafe { in a comment }\n\
                unsafe impl Send for A {}\nunsafe fn b() {}\n\
                pub unsafe extern \"C\" fn c() {}\nlet y = unsafe\n{ 1 };\nnot_unsafe { }\n";
    assert_eq!(
        unsafe_places(text),
        [
            "line 2: unsafe {",
            "line 5: unsafe impl",
            "line 6: unsafe fn",
            "line 8: unsafe {"
        ]
    );
}
