//! `springwater export`: the OBJ `cli/README.md` describes, and one-line errors for bad
//! flags.

use std::process::Command;

fn springwater(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args(args)
        .output()
        .unwrap()
}

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("springwater-export-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn writes_one_v_vn_vt_per_node_and_ccw_lod_faces() {
    let path = temp("frame.obj");
    let out = springwater(&[
        "export",
        "--size",
        "70x45",
        "--steps",
        "10",
        "--drop",
        "35,22,1,3",
        "--eye",
        "5,8,5",
        "--depth",
        "3",
        "--ior",
        "1.5",
        "--obj",
        path.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&path).unwrap();
    let nodes = 70 * 45;
    let lines = |tag: &'static str| {
        text.lines()
            .filter(move |l| l.split(' ').next() == Some(tag))
    };
    let v: Vec<[f32; 3]> = lines("v")
        .map(|l| {
            let f: Vec<f32> = l.split(' ').skip(1).map(|s| s.parse().unwrap()).collect();
            [f[0], f[1], f[2]]
        })
        .collect();
    assert_eq!(v.len(), nodes);
    assert_eq!(lines("vn").count(), nodes);
    assert_eq!(lines("vt").count(), nodes);
    // Row-major: node (col, row) starts at (col, 0, row); with pinned borders row 0 is exact.
    assert_eq!(v[3], [3.0, 0.0, 0.0]);
    assert_eq!(v[70], [0.0, 0.0, 1.0]);
    for l in lines("vn").chain(lines("vt")) {
        assert!(
            l.split(' ')
                .skip(1)
                .all(|s| s.parse::<f32>().unwrap().is_finite()),
            "{l}"
        );
    }
    let mut area2 = 0i64;
    let faces: Vec<[usize; 3]> = lines("f")
        .map(|l| {
            let idx: Vec<usize> = l
                .split(' ')
                .skip(1)
                .map(|corner| {
                    let parts: Vec<&str> = corner.split('/').collect();
                    assert_eq!(parts.len(), 3, "f a/a/a: {l}");
                    assert!(
                        parts[0] == parts[1] && parts[1] == parts[2],
                        "same index for v/vt/vn: {l}"
                    );
                    parts[0].parse().unwrap()
                })
                .collect();
            [idx[0], idx[1], idx[2]]
        })
        .collect();
    assert!(
        !faces.is_empty() && faces.len() < 2 * 69 * 44,
        "LOD drops far-away detail"
    );
    for f in &faces {
        let p: Vec<(i64, i64)> = f
            .iter()
            .map(|&i| {
                assert!((1..=nodes).contains(&i), "1-based index in range");
                (((i - 1) % 70) as i64, ((i - 1) / 70) as i64)
            })
            .collect();
        let up = (p[1].1 - p[0].1) * (p[2].0 - p[0].0) - (p[1].0 - p[0].0) * (p[2].1 - p[0].1);
        assert!(up > 0, "counter-clockwise from +y");
        area2 += up;
    }
    assert_eq!(area2, 2 * 69 * 44, "the faces cover the grid once");
    std::fs::remove_file(&path).ok();
}

#[test]
fn bad_flags_give_one_line_errors() {
    let obj = temp("bad.obj");
    let obj = obj.to_str().unwrap();
    let cases: &[&[&str]] = &[
        &["export", "--depth", "3", "--obj", obj],
        &["export", "--eye", "1,2,3", "--obj", obj],
        &["export", "--eye", "1,2,3", "--depth", "3"],
        &["export", "--eye", "1,2", "--depth", "3", "--obj", obj],
        &["export", "--eye", "1,x,3", "--depth", "3", "--obj", obj],
        &["export", "--eye", "1,inf,3", "--depth", "3", "--obj", obj],
        &["export", "--eye", "1,2,3", "--depth", "-1", "--obj", obj],
        &[
            "export", "--eye", "1,2,3", "--depth", "3", "--ior", "0.5", "--obj", obj,
        ],
        &[
            "export", "--eye", "1,2,3", "--depth", "3", "--levels", "9", "--obj", obj,
        ],
        &[
            "export",
            "--eye",
            "1,2,3",
            "--depth",
            "3",
            "--patch-cells",
            "6",
            "--obj",
            obj,
        ],
        &[
            "export",
            "--eye",
            "1,2,3",
            "--depth",
            "3",
            "--obj",
            "/nonexistent-dir/x.obj",
        ],
        &[
            "export", "--eye", "1,2,3", "--depth", "3", "--obj", obj, "--size", "1x5",
        ],
        &[
            "export", "--eye", "1,2,3", "--depth", "3", "--obj", obj, "--bogus",
        ],
    ];
    for args in cases {
        let out = springwater(args);
        assert!(!out.status.success(), "{args:?} should fail");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{args:?}: one line, got {err:?}");
        assert!(err.starts_with("springwater: error: "), "{err}");
    }
}

/// `simulate --csv` under `SPRINGWATER_SIMD=level`: its CSV, and its summary's simd line.
fn simulate_at(level: &str, csv: &std::path::Path) -> (Vec<u8>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_springwater"))
        .env("SPRINGWATER_SIMD", level)
        .args(["simulate", "--size", "45x33", "--steps", "40"])
        .args(["--drop", "20,15,1.5,3", "--csv", csv.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success(), "{level}: {out:?}");
    let summary = String::from_utf8(out.stdout).unwrap();
    let simd = summary
        .lines()
        .find(|l| l.starts_with("simd"))
        .unwrap_or_else(|| panic!("{level}: no simd line in {summary}"))
        .to_string();
    (std::fs::read(csv).unwrap(), simd)
}

#[test]
fn every_level_forced_through_the_environment_writes_the_same_csv() {
    let csv = temp("levels.csv");
    let (scalar, line) = simulate_at("scalar", &csv);
    assert!(line.starts_with("simd        scalar"), "{line}");
    for level in ["sse2", "avx2", "avx512"] {
        let (got, line) = simulate_at(level, &csv);
        // A level the CPU lacks is clamped; the summary names the one that ran.
        let ran = level
            .parse::<springwater::SimdLevel>()
            .unwrap()
            .clamped()
            .to_string();
        assert!(line.starts_with(&format!("simd        {ran} ")), "{line}");
        assert!(got == scalar, "{level} (ran {ran}) differs from scalar");
    }
}

#[test]
fn bench_names_the_level_first_and_an_unknown_level_is_refused() {
    // `bench`'s first line with `SPRINGWATER_SIMD` set to `simd`, or unset.
    let bench = |simd: Option<&str>| {
        let mut command = Command::new(env!("CARGO_BIN_EXE_springwater"));
        match simd {
            Some(value) => command.env("SPRINGWATER_SIMD", value),
            None => command.env_remove("SPRINGWATER_SIMD"),
        };
        let out = command
            .args(["bench", "--size", "32x32", "--steps", "3", "--repeats", "1"])
            .args(["--compare", "none"])
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
        let stdout = String::from_utf8(out.stdout).unwrap();
        stdout.lines().next().unwrap().to_string()
    };
    let sse2 = bench(Some("sse2"));
    assert!(sse2.starts_with("bench simd=sse2 "), "{sse2}");
    // Set but empty is as if unset: the widest level the CPU has.
    let level = |line: String| line.split_whitespace().nth(1).unwrap().to_string();
    assert_eq!(level(bench(Some(""))), level(bench(None)));

    let out = Command::new(env!("CARGO_BIN_EXE_springwater"))
        .env("SPRINGWATER_SIMD", "avx3")
        .args(["simulate", "--size", "8x8", "--steps", "1"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("avx3") && stderr.contains("avx512") && stderr.contains("portable"),
        "{stderr}"
    );
}

/// `--drop COL,ROW,HEIGHT,RADIUS` stays in grid steps whatever the spacing (the command
/// line's contract), while the library takes world units: at spacing 0.5 the crest is on
/// node (6, 4) and one radius (2 cells) away the height is 1/e of it.
#[test]
fn drop_flags_stay_in_grid_steps_at_any_spacing() {
    let path = temp("drop.csv");
    let out = springwater(&[
        "simulate",
        "--size",
        "13x9",
        "--spacing",
        "0.5",
        "--steps",
        "0",
        "--drop",
        "6,4,1,2",
        "--csv",
        path.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(&path).unwrap();
    let height = |col: usize, row: usize| -> f32 {
        let line = csv
            .lines()
            .find(|l| l.starts_with(&format!("{col},{row},")))
            .unwrap();
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(
            fields[2].parse::<f32>().unwrap(),
            col as f32 * 0.5,
            "x in world units"
        );
        fields[3].parse().unwrap()
    };
    assert_eq!(height(6, 4), 1.0);
    assert!((height(8, 4) - (-1.0f32).exp()).abs() < 1e-6);
    assert!((height(6, 2) - (-1.0f32).exp()).abs() < 1e-6);
}
