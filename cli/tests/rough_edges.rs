//! The command line's rough edges: tiny numbers in messages and outputs, long runs
//! (a progress bar on a terminal, Ctrl-C that still writes the outputs), and `--threads`
//! far beyond the cores.

use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::time::Duration;

fn springwater(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args(args)
        .output()
        .unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("springwater-edges-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn critical_timestep_messages_keep_significant_digits_for_tiny_numbers() {
    for flag in [["--mass", "1e-30"], ["--viscosity", "1e30"]] {
        let out = springwater(&["simulate", flag[0], flag[1]]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(!err.contains("0.0000"), "{flag:?}: {err}");
        // "use dt < X (for example Y)": both positive, Y below X.
        let after = |key: &str| -> f32 {
            let rest = &err[err.find(key).unwrap() + key.len()..];
            let end = rest.find([' ', ')', ',']).unwrap();
            rest[..end].parse().unwrap()
        };
        let (limit, example) = (after("use dt < "), after("for example "));
        assert!(limit > 0.0 && example > 0.0 && example < limit, "{err}");
    }
    // Everyday values keep their four decimals.
    let err =
        String::from_utf8_lossy(&springwater(&["simulate", "--dt", "0.5"]).stderr).into_owned();
    assert!(err.contains("critical timestep 0.4358"), "{err}");
}

/// True if `field` is the shortest round-trip form of its value, plain or with an exponent,
/// whichever is shorter.
fn shortest(field: &str) -> bool {
    let v: f32 = field.parse().unwrap();
    let (plain, exponent) = (format!("{v}"), format!("{v:e}"));
    let best = plain.len().min(exponent.len());
    (field == plain || field == exponent) && field.len() == best
}

#[test]
fn tiny_floats_print_in_exponent_notation_where_that_is_shorter() {
    let csv = scratch("tiny.csv");
    let out = springwater(&[
        "simulate",
        "--size",
        "40x40",
        "--steps",
        "6",
        "--drop",
        "20,20,1,2",
        "--floater",
        "30,30,1,1",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let fields: Vec<&str> = text
        .lines()
        .skip(1)
        .flat_map(|l| l.split(',').skip(2))
        .collect();
    assert!(
        fields.iter().all(|f| shortest(f)),
        "a field is not in its shortest form"
    );
    // The ripple has not reached the far nodes: their heights are tiny, in exponent form.
    assert!(
        fields.iter().any(|f| f.contains("e-")),
        "no tiny value in the CSV"
    );
    assert!(
        fields.iter().all(|f| f.len() <= 15),
        "a field longer than 15 characters"
    );
    let report = String::from_utf8(out.stdout).unwrap();
    let floater = report.lines().find(|l| l.starts_with("floater 0")).unwrap();
    let numbers: Vec<&str> = floater
        .split(' ')
        .filter(|t| t.parse::<f32>().is_ok())
        .skip(1)
        .collect();
    assert_eq!(numbers.len(), 6, "{floater}");
    assert!(numbers.iter().all(|f| shortest(f)), "{floater}");
}

#[test]
fn threads_far_beyond_the_cores_are_capped_with_a_warning_and_change_nothing() {
    let (a, b) = (scratch("t1.csv"), scratch("t1000.csv"));
    let run = |threads: &str, csv: &PathBuf| {
        let started = std::time::Instant::now();
        let out = springwater(&[
            "simulate",
            "--size",
            "64x64",
            "--steps",
            "200",
            "--drop",
            "32,32,1,3",
            "--threads",
            threads,
            "--csv",
            csv.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        (String::from_utf8(out.stderr).unwrap(), started.elapsed())
    };
    let (quiet, _) = run("1", &a);
    assert_eq!(quiet, "");
    let (warning, took) = run("1000", &b);
    let cores = std::thread::available_parallelism().unwrap().get();
    if cores < 1000 {
        assert_eq!(warning.lines().count(), 1, "{warning}");
        assert!(
            warning.contains("warning: --threads 1000")
                && warning.contains(&format!("using {cores}")),
            "{warning}"
        );
    }
    assert!(
        took < Duration::from_secs(2),
        "200 steps of 64x64 took {took:?}"
    );
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}

#[test]
fn no_progress_bar_when_stderr_is_not_a_terminal() {
    let out = springwater(&["simulate", "--size", "32x32", "--steps", "3000"]);
    assert!(out.status.success());
    assert_eq!(String::from_utf8_lossy(&out.stderr), "");
}

#[test]
fn a_long_run_shows_a_progress_bar_on_a_terminal() {
    // `script` (util-linux) runs the command on a pseudo-terminal.
    let command = format!(
        "{} simulate --size 64x64 --steps 20000",
        env!("CARGO_BIN_EXE_springwater")
    );
    let out = match Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .stdin(Stdio::null())
        .output()
    {
        Ok(out) => out,
        Err(e) => {
            println!("skipped: cannot run `script` for a terminal ({e})");
            return;
        }
    };
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    assert!(text.contains("/20000 steps"), "no progress bar: {text}");
    assert!(text.contains("steps       20000"), "{text}");
}

#[test]
fn ctrl_c_writes_the_outputs_at_the_step_reached_and_says_so() {
    let (csv, save) = (scratch("interrupted.csv"), scratch("interrupted.snap"));
    let child = Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args([
            "simulate",
            "--size",
            "48x48",
            "--steps",
            "1000000000",
            "--drop",
            "24,24,1,3",
            "--csv",
            csv.to_str().unwrap(),
            "--save",
            save.to_str().unwrap(),
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    let (report, err) = (
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    );
    assert_eq!(out.status.code(), Some(130), "{report}{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("interrupted after") && err.contains("of 1000000000 steps"),
        "{err}"
    );
    let reached: u64 = report
        .lines()
        .find_map(|l| l.strip_prefix("steps"))
        .and_then(|l| l.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    assert!(reached > 0 && reached < 1_000_000_000, "{report}");
    assert!(err.contains(&format!("after {reached} of")), "{err}");
    // The CSV and the snapshot are the state at that step: a fresh run of `reached` steps.
    let again = scratch("again.csv");
    let steps = reached.to_string();
    let out = springwater(&[
        "simulate",
        "--size",
        "48x48",
        "--steps",
        &steps,
        "--drop",
        "24,24,1,3",
        "--csv",
        again.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    assert_eq!(std::fs::read(&csv).unwrap(), std::fs::read(&again).unwrap());
    let from_snapshot = scratch("from-snapshot.csv");
    let out = springwater(&[
        "simulate",
        "--load",
        save.to_str().unwrap(),
        "--steps",
        "0",
        "--csv",
        from_snapshot.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        std::fs::read(&csv).unwrap(),
        std::fs::read(&from_snapshot).unwrap()
    );
}

#[test]
fn obj_files_print_tiny_floats_in_their_shortest_form_too() {
    // `export` and bake's OBJs share the writer; the same six steps as above leave tiny
    // heights far from the drop.
    let obj = scratch("tiny.obj");
    let out = springwater(&[
        "export",
        "--size",
        "40x40",
        "--steps",
        "6",
        "--drop",
        "20,20,1,2",
        "--eye",
        "20,30,-20",
        "--depth",
        "4",
        "--obj",
        obj.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&obj).unwrap();
    let fields: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("v ") || l.starts_with("vn ") || l.starts_with("vt "))
        .flat_map(|l| l.split(' ').skip(1))
        .collect();
    assert!(fields.len() > 3 * 1600);
    assert!(
        fields.iter().all(|f| shortest(f)),
        "a number is not in its shortest form"
    );
    assert!(
        fields.iter().any(|f| f.contains("e-")),
        "no tiny value in the OBJ"
    );
}
