//! The CLI refuses every bad input named in `cli/README.md` and `docs/reliability.md`
//! with one line on stderr and a non-zero exit, and `--save` / `--load` continue a run
//! bitwise.

use std::path::PathBuf;
use std::process::{Command, Output};

fn springwater(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("springwater-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Asserts a refusal: non-zero exit, exactly one line on stderr, naming `needle`.
fn refused(args: &[&str], needle: &str) {
    let out = springwater(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} succeeded");
    assert_ne!(out.status.code(), Some(101), "{args:?} panicked: {stderr}");
    assert_eq!(
        stderr.lines().count(),
        1,
        "{args:?}: stderr is not one line:\n{stderr}"
    );
    assert!(stderr.ends_with('\n'));
    assert!(
        stderr.contains(needle),
        "{args:?}: '{needle}' not in: {stderr}"
    );
}

#[test]
fn bad_grids_are_refused() {
    refused(&["simulate", "--size", "0x10"], "too small");
    refused(&["simulate", "--size", "1x10"], "too small");
    refused(&["simulate", "--size", "10x1"], "too small");
    refused(&["simulate", "--size", "100000x100000"], "too large");
    refused(
        &["simulate", "--size", "18446744073709551615x3"],
        "too large",
    );
    refused(&["simulate", "--size", "10"], "COLSxROWS");
    refused(&["simulate", "--size", "-3x4"], "--size");
    refused(&["bench", "--size", "1x1"], "too small");
}

#[test]
fn non_finite_and_negative_parameters_are_refused() {
    for flag in ["--mass", "--stiffness", "--spacing", "--dt"] {
        for value in ["NaN", "inf", "-1", "0"] {
            refused(&["simulate", "--steps", "1", flag, value], &flag[2..]);
        }
    }
    for value in ["NaN", "-inf", "-0.5"] {
        refused(&["simulate", "--viscosity", value], "viscosity");
    }
    refused(&["simulate", "--rest-ratio", "1.5"], "rest-ratio");
    refused(&["simulate", "--rest-ratio", "nan"], "rest-ratio");
    refused(&["simulate", "--spacing", "1e30"], "spacing");
    refused(&["simulate", "--drop", "5,5,nan,2"], "--drop");
    refused(&["simulate", "--drop", "5,5,1,-2"], "--drop");
    refused(&["simulate", "--drop", "5,5,1,inf"], "--drop");
}

#[test]
fn timestep_at_or_past_the_critical_one_is_refused() {
    refused(&["simulate", "--dt", "0.44"], "critical timestep");
    refused(
        &["simulate", "--dt", "0.6", "--mass", "4"],
        "critical timestep",
    );
    refused(
        &["simulate", "--dt", "0.4", "--viscosity", "8"],
        "critical timestep",
    );
}

#[test]
fn malformed_flags_are_refused() {
    refused(&["simulate", "--bogus"], "unknown flag --bogus");
    refused(&["simulate", "-x"], "unknown flag -x");
    refused(&["simulate", "stray"], "unexpected argument");
    refused(&["simulate", "--steps"], "--steps needs a value");
    refused(&["simulate", "--steps", "ten"], "not a valid whole number");
    refused(&["simulate", "--steps", "-5"], "--steps");
    refused(&["simulate", "--mass", "heavy"], "not a valid number");
    refused(&["simulate", "--drop", "1,2,3"], "4 comma-separated");
    refused(&["simulate", "--boundary", "open"], "--boundary");
    refused(&["simulate", "--threads", "0"], "--threads");
    refused(&["simulate", "--csv"], "--csv needs a value");
    refused(&["simulate", "--save"], "--save needs a value");
    refused(&["simulate", "--load"], "--load needs a value");
    refused(&["frobnicate"], "unknown command");
    refused(&["--version-of-nothing"], "unknown flag");
}

#[test]
fn unwritable_and_unreadable_files_are_refused_before_any_work() {
    let missing_dir = "/nonexistent-springwater-dir/out";
    refused(
        &["simulate", "--steps", "1000000000", "--csv", missing_dir],
        "cannot write",
    );
    refused(
        &["simulate", "--steps", "1000000000", "--save", missing_dir],
        "cannot write",
    );
    refused(
        &["simulate", "--load", "/nonexistent-springwater-dir/in.snap"],
        "cannot read",
    );
}

#[test]
fn damaged_snapshots_are_refused() {
    let good = scratch("good.snap");
    let out = springwater(&[
        "simulate",
        "--size",
        "9x7",
        "--steps",
        "3",
        "--save",
        good.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(&good).unwrap();

    let truncated = scratch("truncated.snap");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    refused(
        &["simulate", "--load", truncated.to_str().unwrap()],
        "truncated",
    );

    let corrupted = scratch("corrupted.snap");
    let mut b = bytes.clone();
    b[200] ^= 1;
    std::fs::write(&corrupted, &b).unwrap();
    refused(
        &["simulate", "--load", corrupted.to_str().unwrap()],
        "checksum",
    );

    let version = scratch("version.snap");
    let mut b = bytes.clone();
    b[8] = 9;
    std::fs::write(&version, &b).unwrap();
    refused(
        &["simulate", "--load", version.to_str().unwrap()],
        "version 9",
    );

    let junk = scratch("junk.snap");
    let mut b = bytes.clone();
    b.extend_from_slice(b"junk appended");
    std::fs::write(&junk, &b).unwrap();
    refused(
        &["simulate", "--load", junk.to_str().unwrap()],
        "trailing data",
    );

    let text = scratch("text.snap");
    std::fs::write(&text, "col,row,x,y,z\n").unwrap();
    refused(
        &["simulate", "--load", text.to_str().unwrap()],
        "not a springwater snapshot",
    );

    // Model flags conflict with the snapshot's model.
    for flag in [
        ["--mass", "3"],
        ["--size", "9x7"],
        ["--dt", "0.3"],
        ["--boundary", "free"],
    ] {
        let args = [
            "simulate",
            "--load",
            good.to_str().unwrap(),
            flag[0],
            flag[1],
        ];
        refused(&args, "cannot be combined with --load");
    }
}

#[test]
fn load_and_continue_equals_one_run() {
    let snap = scratch("split.snap");
    let (split, whole) = (scratch("split.csv"), scratch("whole.csv"));
    let model = [
        "--size",
        "21x17",
        "--drop",
        "10,8,1.5,2.5",
        "--drop",
        "3.5,4,-0.5,1",
        "--viscosity",
        "0",
    ];
    let run = |extra: &[&str]| {
        let mut args = vec!["simulate"];
        args.extend_from_slice(extra);
        let out = springwater(&args);
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let mut first = model.to_vec();
    first.extend([
        "--steps",
        "37",
        "--threads",
        "1",
        "--save",
        snap.to_str().unwrap(),
    ]);
    run(&first);
    let resumed = run(&[
        "--load",
        snap.to_str().unwrap(),
        "--steps",
        "63",
        "--threads",
        "2",
        "--csv",
        split.to_str().unwrap(),
    ]);
    let mut all = model.to_vec();
    all.extend(["--steps", "100", "--csv", whole.to_str().unwrap()]);
    run(&all);
    assert!(resumed.contains("steps       100"), "{resumed}");
    let (a, b) = (
        std::fs::read_to_string(&split).unwrap(),
        std::fs::read_to_string(&whole).unwrap(),
    );
    assert_eq!(a.lines().count(), 21 * 17 + 1);
    assert_eq!(a, b, "load + 63 steps differs from 100 steps in one go");
    // And the surface did move, so the comparison means something.
    assert!(a.lines().skip(1).any(|l| !l.ends_with(",0")));
}

#[test]
fn drop_adds_to_a_loaded_snapshot() {
    let snap = scratch("drop.snap");
    let (with, without) = (scratch("with.csv"), scratch("without.csv"));
    let s = snap.to_str().unwrap();
    assert!(
        springwater(&["simulate", "--size", "9x9", "--steps", "2", "--save", s])
            .status
            .success()
    );
    assert!(springwater(&[
        "simulate",
        "--load",
        s,
        "--steps",
        "0",
        "--csv",
        without.to_str().unwrap()
    ])
    .status
    .success());
    let out = springwater(&[
        "simulate",
        "--load",
        s,
        "--steps",
        "0",
        "--drop",
        "4,4,0.5,1",
        "--csv",
        with.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let line = |p: &PathBuf| {
        std::fs::read_to_string(p)
            .unwrap()
            .lines()
            .nth(1 + 4 * 9 + 4)
            .unwrap()
            .to_string()
    };
    assert_eq!(line(&without), "4,4,4,0,4");
    assert_eq!(line(&with), "4,4,4,0.5,4");
}

#[test]
fn a_run_that_goes_non_finite_fails_in_one_line_and_leaves_no_outputs() {
    let (snap, csv) = (scratch("nonfinite.snap"), scratch("nonfinite.csv"));
    let args = [
        "simulate",
        "--size",
        "20x20",
        "--drop",
        "10,10,1e30,2",
        "--steps",
        "5",
        "--save",
        snap.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
    ];
    refused(&args, "non-finite");
    assert!(!snap.exists() && !csv.exists());
}

#[test]
fn open_water_and_floater_flags_are_checked() {
    refused(&["simulate", "--boundary", "absorbing:0"], "--boundary");
    refused(
        &["simulate", "--size", "40x40", "--boundary", "absorbing:20"],
        "--boundary absorbing:20: a 40x40 grid takes an absorbing frame 1 to 19 cells wide",
    );
    refused(&["simulate", "--boundary", "absorbing:x"], "WIDTH");
    refused(&["simulate", "--boundary", "absorbent"], "--boundary");
    refused(&["simulate", "--floater", "1,2,3"], "--floater");
    refused(&["simulate", "--floater", "10,10,0,2"], "floater mass");
    refused(&["simulate", "--floater", "10,10,1,nan"], "--floater");
    refused(&["render", "--floaters", "-1"], "--floaters");
}

#[test]
fn simulate_prints_one_line_per_floater_in_the_order_given() {
    let out = springwater(&[
        "simulate",
        "--size",
        "80x80",
        "--boundary",
        "absorbing:16",
        "--steps",
        "200",
        "--floater",
        "40,40,8,2",
        "--floater",
        "20.5,30,1,1",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().filter(|l| l.starts_with("floater ")).collect();
    assert_eq!(lines.len(), 2, "{text}");
    for (k, (line, x)) in lines.iter().zip([40.0f32, 20.5]).enumerate() {
        let words: Vec<&str> = line.split(' ').collect();
        assert_eq!(
            words[..3],
            ["floater", &*k.to_string(), "position"],
            "{line}"
        );
        assert_eq!(words[6], "velocity", "{line}");
        let v: Vec<f32> = [3, 4, 5, 7, 8, 9]
            .map(|i| words[i].parse().unwrap())
            .to_vec();
        assert!((v[0] - x).abs() < 0.5, "{line}: the ball drifted");
        assert!(v.iter().all(|c| c.is_finite()), "{line}");
    }
    // The numbers are the library's, bit for bit: velocities in world units per second.
    let p = springwater::Params::with_size(80, 80)
        .with_boundary(springwater::Boundary::Absorbing { width: 16 });
    let mut s = springwater::Surface::new(p).unwrap();
    for [x, z, mass, radius] in [[40.0, 40.0, 8.0, 2.0], [20.5, 30.0, 1.0, 1.0]] {
        s.add_floater(springwater::Floater::sphere(radius, mass, [x, 0.0, z]))
            .unwrap();
    }
    s.step_n(200).unwrap();
    for (line, (_, f)) in lines.iter().zip(s.floaters()) {
        let words: Vec<f32> = line
            .split(' ')
            .filter_map(|w| w.parse().ok())
            .skip(1)
            .collect();
        let expected = [f.position.to_array(), f.velocity.to_array()].concat();
        assert_eq!(words, expected, "{line}");
    }
}

/// A reader that has gone away (`springwater simulate … | head -1`) is no error: no panic,
/// a successful exit, and the files the command was asked for are still written.
#[test]
fn a_reader_that_has_gone_away_is_no_error() {
    let csv = scratch("closed-stdout.csv");
    let _ = std::fs::remove_file(&csv);
    let csv_arg = csv.to_str().unwrap();
    let runs: [&[&str]; 3] = [
        &[
            "simulate", "--size", "16x16", "--steps", "5", "--csv", csv_arg,
        ],
        &["bench", "--size", "16x16", "--steps", "2", "--repeats", "1"],
        &["--help"],
    ];
    for args in runs {
        // The pipe's reader is closed before the command starts: every write to stdout
        // fails (EPIPE), from the first.
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let out = Command::new(env!("CARGO_BIN_EXE_springwater"))
            .args(args)
            .stdout(writer)
            .output()
            .expect("the binary runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            out.status.success(),
            "{args:?}: {:?}, stderr: {stderr}",
            out.status
        );
        assert!(stderr.is_empty(), "{args:?}: stderr: {stderr}");
        assert!(
            out.stdout.is_empty(),
            "stdout went to the pipe, not to the test"
        );
    }
    let lines = std::fs::read_to_string(&csv).unwrap().lines().count();
    assert_eq!(
        lines,
        1 + 16 * 16,
        "the CSV is a header and one line per node"
    );
}

/// A stdout that fails otherwise (a full disk) is reported in one line with exit code 2,
/// and the files already asked for are complete: they are written before the report.
#[cfg(target_os = "linux")]
#[test]
fn a_stdout_that_fails_is_reported_after_the_files_are_written() {
    let (csv, snap) = (scratch("full-stdout.csv"), scratch("full-stdout.snap"));
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args(["simulate", "--size", "16x16", "--steps", "5"])
        .args([
            "--csv",
            csv.to_str().unwrap(),
            "--save",
            snap.to_str().unwrap(),
        ])
        .stdout(full)
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("cannot write to standard output"),
        "{stderr}"
    );
    let lines = std::fs::read_to_string(&csv).unwrap().lines().count();
    assert_eq!(lines, 1 + 16 * 16);
    let resumed = springwater(&["simulate", "--load", snap.to_str().unwrap(), "--steps", "1"]);
    assert!(resumed.status.success(), "the snapshot loads");
}
