//! What a surface costs in memory: the peak resident memory `simulate` reports for a
//! 2048 × 2048 pool, per node. Positions and velocities, double-buffered for the
//! transactional step, are 48 bytes a node; pending forces and the pinned flags add 13;
//! uniform springs keep no tables, and uniform mass and viscosity (the absorbing frame's
//! ramp included) keep a few rows, not one value per node. Measured: 62.1 bytes per node.

use std::process::Command;

#[test]
fn a_2048_square_pool_takes_at_most_64_bytes_per_node() {
    let out = Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args(["simulate", "--size", "2048x2048", "--steps", "2"])
        .output()
        .expect("the binary runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report = String::from_utf8(out.stdout).unwrap();
    let Some(line) = report.lines().find(|l| l.starts_with("memory")) else {
        eprintln!("skipped: this system does not report peak memory (no /proc/self/status)");
        return;
    };
    // "memory      303.0 MB peak (72.3 bytes per node)"
    let per_node: f64 = line
        .split('(')
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("cannot read {line:?}"));
    println!("{line}");
    assert!(per_node <= 64.0, "{line}");
    assert!(
        per_node >= 48.0,
        "below the double-buffered state itself: {line}"
    );
}
