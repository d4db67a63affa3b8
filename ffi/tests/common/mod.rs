//! What the C and C# client tests share: the release build they run on, and fingerprints
//! of float values in the order the clients print them.

use springwater::{Floater, Params, Shape, Surface};

/// A test whose tool is not installed says why and passes, unless
/// `SPRINGWATER_REQUIRE_TOOLS` is set (as CI does, having installed every tool), where it
/// fails: the one convention of every test that needs a program besides cargo.
pub fn tool_missing(why: &str) {
    assert!(
        std::env::var_os("SPRINGWATER_REQUIRE_TOOLS").is_none(),
        "SPRINGWATER_REQUIRE_TOOLS is set but {why}"
    );
    println!("skipped: {why}");
}
use std::path::PathBuf;
use std::process::{Command, Output};

/// Builds `packages` in release for `target` (the host without one) by a nested `cargo
/// build` into their own target directory, `target/ffi-c/` (cargo holds the test's own
/// target directory while the tests run, and does not build a library's `staticlib` and
/// `cdylib` for its tests; it keeps them up to date with the sources), and returns the
/// directory of the libraries and programs.
pub fn build_release(packages: &[&str], target: Option<&str>) -> PathBuf {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf();
    let dir = root.join("target").join("ffi-c");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut build = Command::new(cargo);
    build
        .current_dir(&root)
        .args(["build", "--release", "--quiet"])
        .args(packages.iter().flat_map(|p| ["-p", p]))
        .arg("--target-dir")
        .arg(&dir);
    if let Some(target) = target {
        build.args(["--target", target]);
    }
    let out = build.output().expect("cargo runs");
    assert_ok(&out, &format!("building {}", packages.join(", ")));
    match target {
        Some(target) => dir.join(target).join("release"),
        None => dir.join("release"),
    }
}

/// Fails with the program's output unless it succeeded.
pub fn assert_ok(out: &Output, what: &str) {
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// FNV-1a over the little-endian bits of `values`.
pub fn fnv(values: impl Iterator<Item = f32>) -> u64 {
    values.fold(0xcbf2_9ce4_8422_2325u64, |h, v| {
        v.to_bits()
            .to_le_bytes()
            .iter()
            .fold(h, |h, &b| (h ^ b as u64).wrapping_mul(0x0100_0000_01b3))
    })
}

/// A body's fields in the order the clients fingerprint them: radius, half extents (the
/// other shapes' read as 0), mass, drag, position, velocity, push, water force,
/// orientation (x, y, z, w), angular velocity, push torque, water torque.
pub fn floater_floats(f: &Floater) -> Vec<f32> {
    let (radius, half_extents) = match f.shape {
        Shape::Sphere { radius } => (radius, [0.0; 3]),
        Shape::Box { half_extents } => (0.0, half_extents.to_array()),
        _ => (0.0, [0.0; 3]),
    };
    let mut floats = vec![radius];
    floats.extend(half_extents);
    floats.extend([f.mass, f.drag]);
    for v in [f.position, f.velocity, f.push, f.water_force] {
        floats.extend(v.to_array());
    }
    floats.extend(f.orientation.to_array());
    for v in [f.angular_velocity, f.push_torque, f.water_torque] {
        floats.extend(v.to_array());
    }
    floats
}

/// What the C and C# clients print for their built-in box, through the Rust API: a 6 × 1.5
/// × 3 box at half the water's density heeled 15° about x (sin and cos of 7.5° as
/// literals) on a 48 × 48 pool, after ten seconds of 60 Hz frames: its orientation's and
/// height's bits.
pub fn righted_box() -> Vec<(&'static str, String)> {
    let mut s = Surface::new(Params::with_size(48, 48)).unwrap();
    let e = glam::Vec3::new(3.0, 0.75, 1.5);
    let mass = 0.5 * s.buoyancy().density * 8.0 * e.x * e.y * e.z;
    let mut body = Floater::cuboid(e, mass, [24.0, 0.0, 24.0]);
    body.orientation = glam::Quat::from_xyzw(0.130_526_19, 0.0, 0.0, 0.991_444_9);
    let id = s.add_floater(body).unwrap();
    for _ in 0..600 {
        s.advance(1.0 / 60.0).unwrap();
    }
    let f = s.floater(id).unwrap();
    let bits: Vec<String> = f
        .orientation
        .to_array()
        .iter()
        .map(|v| format!("{:08x}", v.to_bits()))
        .collect();
    vec![
        ("righted_orientation", bits.join(" ")),
        (
            "righted_position",
            format!("{:08x}", f.position.y.to_bits()),
        ),
    ]
}
