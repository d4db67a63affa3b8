//! The command line explains itself: `--help` and `--version`, refusals before any work
//! (each answered at once, where running first would take hours), and messages that name
//! the flag, the value in its shortest form and the valid range.

mod common;
use common::*;

fn scratch(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("springwater-explains-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).to_str().unwrap().to_owned()
}

#[test]
fn every_command_answers_help_on_stdout_with_its_flags_and_defaults() {
    let cases: [(&str, &[&str]); 5] = [
        (
            "simulate",
            &[
                "--steps",
                "--csv FILE",
                "--save FILE",
                "--load FILE",
                "--follow-shift",
                "(100)",
            ],
        ),
        (
            "bake",
            &[
                "--out",
                "--frames N",
                "(48)",
                "--fps F",
                "(24)",
                "--rain RATE",
            ],
        ),
        (
            "render",
            &[
                "--out FILE.gif",
                "--png DIR",
                "(72)",
                "--width W",
                "pixels",
                "--boats N",
            ],
        ),
        (
            "export",
            &["--eye X,Y,Z", "--depth D", "--obj FILE", "(1.333)"],
        ),
        ("bench", &["--repeats N", "(5)", "--compare LIST"]),
    ];
    for (command, needles) in cases {
        for ask in [
            vec![command, "--help"],
            vec![command, "-h"],
            vec!["help", command],
            vec![command, "--size", "9x9", "--help"],
        ] {
            let out = springwater(&ask);
            let text = String::from_utf8(out.stdout).unwrap();
            assert_eq!(out.status.code(), Some(0), "{ask:?}");
            assert!(out.stderr.is_empty(), "{ask:?}");
            for needle in needles {
                assert!(text.contains(needle), "{ask:?} lacks {needle}:\n{text}");
            }
            // The model flags, with the command's own default step count.
            assert!(
                text.contains("--size COLSxROWS") && text.contains("(128x128)"),
                "{ask:?}"
            );
        }
    }
    assert!(ok(&["bake", "--help"]).contains("--steps N            steps to run (0)"));
    assert!(ok(&["render", "--help"]).contains("--steps N            steps to run (60)"));
    for ask in [&["--help"][..], &["-h"], &[], &["help"]] {
        let text = ok(ask);
        for command in ["render", "simulate", "bench", "export", "bake"] {
            assert!(text.contains(command), "{ask:?}");
        }
    }
    refused(&["help", "nothing"]);
}

#[test]
fn version_prints_the_version() {
    for ask in ["--version", "-V"] {
        let out = springwater(&[ask]);
        assert_eq!(out.status.code(), Some(0));
        let text = String::from_utf8(out.stdout).unwrap();
        assert_eq!(text, format!("springwater {}\n", env!("CARGO_PKG_VERSION")));
    }
}

#[test]
fn rain_rates_are_bounded_before_any_step() {
    let err = refused(&["bake", "--rain", "1e9", "--out", &scratch("rain.glb")]);
    assert!(
        err.contains("--rain 1e9") && err.contains("at most 983039 drops per second"),
        "{err}"
    );
    let err = refused(&["render", "--rain", "1e30", "--out", &scratch("rain.gif")]);
    assert!(err.contains("--rain 1e30"), "{err}");
    // The bound scales with the grid and the step rate; under it, rain falls.
    let err = refused(&[
        "bake",
        "--size",
        "16x16",
        "--rain",
        "20000",
        "--out",
        &scratch("r.glb"),
    ]);
    assert!(err.contains("at most 15359 drops per second"), "{err}");
    ok(&[
        "bake",
        "--size",
        "16x16",
        "--rain",
        "15000",
        "--frames",
        "2",
        "--out",
        &scratch("r.glb"),
    ]);
}

#[test]
fn what_can_be_checked_before_the_first_step_is() {
    // A shift past the window's range, after four billion steps.
    let err = refused(&line(
        "simulate --steps 4000000000 --follow-shift 20000000,0",
        &[],
    ));
    assert!(
        err.contains("DC 20000000 is out of range") && err.contains("-15728640 to 15728640"),
        "{err}"
    );
    // A whole number past i32 is out of range, not "not a whole number".
    let err = refused(&["simulate", "--follow-shift", "2147483648,0"]);
    assert!(err.contains("2147483648 is out of range"), "{err}");
    assert!(!err.contains("not a valid"), "{err}");
    // A .glb past 4 GiB, after four billion warm-up steps.
    let glb = scratch("huge.glb");
    let err = refused(&line(
        "bake --size 1024x1024 --steps 4000000000 --frames 200 --out @",
        &[&glb],
    ));
    assert!(err.contains("at most 4 GiB"), "{err}");
    // The count it suggests: one more is refused too, and that many frames of position and
    // normal offsets (24 bytes a node) stay under 4 GiB.
    let most: u64 = err
        .split("bake at most ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(most * 1024 * 1024 * 24 < 1 << 32, "{err}");
    let more = (most + 1).to_string();
    let err = refused(&line(
        "bake --size 1024x1024 --steps 4000000000 --frames @ --out @",
        &[&more, &glb],
    ));
    assert!(err.contains("at most 4 GiB"), "{err}");
    // Frames shorter than a step would all repeat the one before.
    let err = refused(&["bake", "--fps", "1e30", "--out", &scratch("fast.glb")]);
    assert!(
        err.contains("--fps 1e30") && err.contains("use --fps 60 or less"),
        "{err}"
    );
    // A GIF's frame rate has a range.
    let err = refused(&["render", "--fps", "1e30", "--out", &scratch("fast.gif")]);
    assert!(
        err.contains("--fps must be between 0.0016 and 50") && err.contains("got 1e30"),
        "{err}"
    );
    // A name that says another format.
    let err = refused(&["render", "--out", &scratch("x.png")]);
    assert!(err.contains("does not end in .gif"), "{err}");
    // Two balls where one was asked for: --follow has its own.
    let err = refused(&["render", "--follow", "--wake", "--out", &scratch("x.gif")]);
    assert!(
        err.contains("--follow and --wake cannot be combined"),
        "{err}"
    );
}

#[test]
fn messages_name_the_flag_and_the_value_as_typed() {
    let obj = scratch("x.obj");
    let export = ["export", "--eye", "1,2,3", "--depth", "2", "--obj", &obj];
    let err = refused(&[&export[..], &["--first-range", "-1"]].concat());
    assert!(
        err.contains("--first-range -1:") && !err.contains("first_range"),
        "{err}"
    );
    let err = refused(&[
        "render",
        "--out",
        &scratch("x.gif"),
        "--eye",
        "0,0,0",
        "--look-at",
        "0,0,0",
    ]);
    assert!(
        err.contains("--look-at: a point away from the eye") && !err.contains("look_at"),
        "{err}"
    );
    // The default absorbing frame on a tiny grid: no width the user never gave.
    let err = refused(&line("simulate --size 3x3 --boundary absorbing", &[]));
    assert!(
        err.contains("too small for an absorbing frame") && !err.contains("32"),
        "{err}"
    );
    // A limit, not a formula.
    let err = refused(&line("simulate --size 10x10 --boundary absorbing:40", &[]));
    assert!(
        err.contains("frame 1 to 4 cells wide") && !err.contains("min(cols"),
        "{err}"
    );
    let err = refused(&["simulate", "--spacing", "1e30"]);
    assert!(
        err.contains("--spacing 1e30") && err.contains("use --spacing 7.8740157e12 or less"),
        "{err}"
    );
    // Values in their shortest form.
    let err = refused(&["bake", "--ior", "-0.1", "--out", &scratch("x.glb")]);
    assert!(
        err.contains("--ior -0.1:") && !err.contains("0.1000000"),
        "{err}"
    );
    let err = refused(&["render", "--fov", "1e30", "--out", &scratch("x.gif")]);
    assert!(
        err.contains("--fov 1e30") && !err.contains("1000000015"),
        "{err}"
    );
    let err = refused(&["bake", "--depth", "-0.1", "--out", &scratch("x.glb")]);
    assert!(err.contains("got -0.1"), "{err}");
}

#[test]
fn reports_count_in_the_singular_and_plural_and_print_short_numbers() {
    let report = ok(&[
        "bake",
        "--size",
        "9x9",
        "--frames",
        "1",
        "--drop",
        "4,4,1,1",
        "--out",
        &scratch("one.glb"),
    ]);
    assert!(report.starts_with("baked 1 frame at 24 fps"), "{report}");
    let dir = scratch("one-dir");
    let report = ok(&line(
        "bake --size 9x9 --frames 1 --fps 60 --drop 4,4,1,1 --out @",
        &[&dir],
    ));
    assert!(
        report.contains(": 1 step of 0.4") && report.contains("wrote 1 OBJ file to"),
        "{report}"
    );
    let report = ok(&[
        "render",
        "--size",
        "9x9",
        "--frames",
        "1",
        "--width",
        "16",
        "--height",
        "16",
        "--out",
        &scratch("one.gif"),
    ]);
    assert!(report.starts_with("rendered 1 frame of"), "{report}");
    assert!(report.contains("(rate 7.2, seed 1)"), "{report}");
}

#[test]
fn a_kernel_compared_twice_is_timed_once() {
    let report = ok(&line(
        "bench --size 16x16 --steps 2 --repeats 1 --compare naive,naive",
        &[],
    ));
    assert_eq!(
        report.lines().filter(|l| l.starts_with("naive")).count(),
        1,
        "{report}"
    );
}
