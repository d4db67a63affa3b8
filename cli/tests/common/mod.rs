//! Running the binary from the tests: its output, a deadline, and the two outcomes most
//! tests look for (success, or a one-line refusal).
#![allow(dead_code)] // each test file uses its own part

use std::ffi::OsStr;
use std::fmt::Debug;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// `springwater args`, waited for.
pub fn springwater<S: AsRef<OsStr> + Debug>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args(args)
        .output()
        .unwrap()
}

/// `springwater args`; a run still going after `seconds` is killed and the test fails (a
/// refusal that comes only after the work would otherwise hang the test).
pub fn within<S: AsRef<OsStr> + Debug>(args: &[S], seconds: u64) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(seconds);
    while child.try_wait().unwrap().is_none() {
        if Instant::now() > deadline {
            child.kill().unwrap();
            let _ = child.wait();
            panic!("{args:?} still ran after {seconds} s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// Runs a command that must succeed; returns its stdout.
pub fn ok<S: AsRef<OsStr> + Debug>(args: &[S]) -> String {
    let out = springwater(args);
    assert!(
        out.status.success(),
        "springwater {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Runs a command that must be refused: exit 2, one line on stderr (returned), nothing on
/// stdout, within 20 s.
pub fn refused<S: AsRef<OsStr> + Debug>(args: &[S]) -> String {
    let out = within(args, 20);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?}");
    err
}

/// The words of `line`, each `@` replaced by the next of `paths` (paths may hold spaces).
pub fn line(line: &str, paths: &[&dyn AsRef<Path>]) -> Vec<String> {
    let mut paths = paths.iter();
    line.split_whitespace()
        .map(|w| match w {
            "@" => {
                let path = paths.next().expect("a path for every @");
                path.as_ref().display().to_string()
            }
            w => w.to_owned(),
        })
        .collect()
}

/// A fresh, empty directory for one test: `name` under a folder of this process's named
/// after the test file (`group`).
pub fn fresh(group: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir()
        .join(format!("springwater-{group}-{}", std::process::id()))
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A path as a command-line argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The names in `dir`, sorted.
pub fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Writes a grey 8-bit PNG of `width` × `height` pixels at `path`, row by row (so a large
/// one is never whole in memory): row `r` is `row(r)`.
pub fn grey_png(path: &Path, width: u32, height: u32, row: impl Fn(u32) -> Vec<u8>) {
    let file = std::fs::File::create(path).unwrap();
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), width, height);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fastest);
    let mut writer = encoder
        .write_header()
        .unwrap()
        .into_stream_writer()
        .unwrap();
    for r in 0..height {
        std::io::Write::write_all(&mut writer, &row(r)).unwrap();
    }
    writer.finish().unwrap();
}
