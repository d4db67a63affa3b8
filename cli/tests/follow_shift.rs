//! `springwater simulate --follow-shift DC,DR` (`cli/README.md`): after the steps the
//! window moves by whole cells; the CSV's x, z are world positions, so every node of the
//! overlap appears with the same x, y, z as the unshifted run's node at
//! `col + DC, row + DR`, and the strip that came in is calm.

use std::collections::HashMap;
use std::process::Command;

fn springwater(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args(args)
        .output()
        .unwrap()
}

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("springwater-follow-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// `(col, row) -> [x, y, z]` as printed (the text, so the comparison is of the bits).
fn read_csv(path: &std::path::Path) -> HashMap<(i64, i64), [String; 3]> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("col,row,x,y,z"));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let key = (f[0].parse().unwrap(), f[1].parse().unwrap());
            (key, [f[2], f[3], f[4]].map(str::to_owned))
        })
        .collect()
}

fn simulate(extra: &[&str], csv: &std::path::Path) {
    let mut args = vec![
        "simulate",
        "--size",
        "60x50",
        "--steps",
        "15",
        "--boundary",
        "absorbing:6",
        "--drop",
        "30,25,1,2",
        "--csv",
        csv.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let out = springwater(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn the_overlap_keeps_its_world_positions_and_the_strip_is_calm() {
    let (plain, shifted) = (temp("plain.csv"), temp("shifted.csv"));
    simulate(&[], &plain);
    let (dc, dr) = (7i64, -4i64);
    simulate(&["--follow-shift", "7,-4"], &shifted);
    let (a, b) = (read_csv(&plain), read_csv(&shifted));
    assert_eq!(a.len(), 60 * 50);
    assert_eq!(b.len(), 60 * 50);
    let mut overlap = 0;
    for r in 1..49i64 {
        for c in 1..59i64 {
            let node = &b[&(c, r)];
            match a.get(&(c + dc, r + dr)) {
                Some(world) => {
                    assert_eq!(node, world, "node ({c}, {r})");
                    overlap += 1;
                }
                None => {
                    let rest = [(c + dc).to_string(), "0".into(), (r + dr).to_string()];
                    assert_eq!(node, &rest, "incoming node ({c}, {r})");
                }
            }
        }
    }
    assert!(overlap > 2000, "{overlap}");
}

#[test]
fn a_snapshot_after_a_shift_continues_as_the_shifted_window() {
    let (csv, snap, csv2) = (temp("a.csv"), temp("a.snap"), temp("b.csv"));
    simulate(
        &["--follow-shift", "-3,5", "--save", snap.to_str().unwrap()],
        &csv,
    );
    // Loaded with no more steps, it writes the same CSV.
    let out = springwater(&[
        "simulate",
        "--load",
        snap.to_str().unwrap(),
        "--steps",
        "0",
        "--csv",
        csv2.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(&csv).unwrap(),
        std::fs::read_to_string(&csv2).unwrap()
    );
}

#[test]
fn bad_follow_shifts_are_one_line_errors() {
    for bad in ["7", "1,2,3", "a,1", "1.5,0", "99999999999,0", "16000000,0"] {
        let out = springwater(&["simulate", "--size", "8x8", "--follow-shift", bad]);
        assert!(!out.status.success(), "--follow-shift {bad} was accepted");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains("--follow-shift"), "{err}");
    }
}

#[test]
fn render_follow_draws_a_ball_crossing_open_water() {
    let dir = temp("frames");
    let out = springwater(&[
        "render",
        "--size",
        "96x64",
        "--boundary",
        "absorbing:12",
        "--follow",
        "--frames",
        "40",
        "--width",
        "80",
        "--height",
        "60",
        "--png",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let frames = std::fs::read_dir(&dir).unwrap().count();
    assert_eq!(frames, 40);
    // The ball crosses 2.5 cells per unit of model time along +x, one cell a step of 0.4:
    // 60 warm-up steps and 39 frames of 3 are 177 cells, and the window follows all of it
    // but the 16 cells from the ball's start to the window's middle and its dead zone.
    let report = String::from_utf8_lossy(&out.stdout);
    let line = report
        .lines()
        .find(|l| l.starts_with("window"))
        .unwrap_or_else(|| panic!("no window line in\n{report}"));
    let numbers: Vec<i64> = line
        .split_whitespace()
        .filter_map(|w| w.parse().ok())
        .collect();
    assert!(numbers[0] >= 150 && numbers[1] == 0, "{line}");
    // The last frame differs from the first (the water and its wake moved with the ball).
    let first = std::fs::read(dir.join("frame_0000.png")).unwrap();
    let last = std::fs::read(dir.join("frame_0039.png")).unwrap();
    assert_ne!(first, last);
}
