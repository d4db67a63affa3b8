//! C clients of `include/springwater.h`, compiled with the system C compiler against the
//! static and dynamic libraries this crate builds:
//!
//! * `tests/c/client.c`: a frame loop over the whole API, a job system on the host's own
//!   threads, floating bodies on an absorbing (open water) surface (`client_floaters.h`,
//!   a part it includes), and every kind of bad input; its printed values must equal what
//!   the Rust API computes for the same frames.
//! * `tests/c/rigid.c`: rigid bodies: a heeled box rights itself as a built-in body and
//!   in the client's own explicit integrator driven by `sw_surface_body_forces`, a hull
//!   mesh, a client of the version 1 `SwFloater`, bad input; the library's boat, its mesh
//!   read back, floating through rain and a wake (`sw_surface_advance_with`).
//! * Both run plainly, under AddressSanitizer, and under Valgrind's memcheck where it is
//!   installed (`tests/c/check.h` holds their shared checks).
//! * ffi/README.md's C example, linked against the dynamic library;
//! * the header compiled as C++ (`tests/c/header.cpp`), linked and run.
//!
//! Needs `cc` (and `c++`) on the PATH: without a C compiler the tests say so and pass,
//! unless `SPRINGWATER_REQUIRE_TOOLS` is set, where they fail.

mod common;

use common::{assert_ok, build_release, floater_floats, fnv, righted_box, tool_missing};
use springwater::mesh::{compute_normals, LodMesh, LodParams, Normals};
use springwater::refraction::{refract, Refraction, RefractionParams};
use springwater::{Boundary, Buoyancy, Floater, FloaterId, Params, Surface};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The static and dynamic libraries, built in release into `target/ffi-c/`.
fn lib_dir() -> PathBuf {
    static BUILT: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    BUILT.get_or_init(|| build_libraries(None)).clone()
}

/// Builds the libraries for `target` (the host without one) and returns their directory.
fn build_libraries(target: Option<&str>) -> PathBuf {
    build_release(&["springwater-ffi"], target)
}

fn crate_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A scratch directory for the compiled clients.
fn out_dir() -> PathBuf {
    let dir = lib_dir().join("c-clients");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// What a program linked against the static library needs besides it.
const NATIVE_LIBS: &[&str] = &[
    "-lgcc_s",
    "-lutil",
    "-lrt",
    "-lpthread",
    "-lm",
    "-ldl",
    "-lc",
];

/// Whether the C tests cannot run here: no C compiler (see [`tool_missing`]).
fn skip() -> bool {
    if have("cc") {
        return false;
    }
    tool_missing("cc, a C compiler, is not installed (apt-get install gcc)");
    true
}

fn have(tool: &str) -> bool {
    Command::new(tool)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Compiles `source` into `exe` with the static library and `extra` flags.
fn compile_static(source: &Path, exe: &Path, extra: &[&str]) {
    compile_static_with("cc", &lib_dir(), source, exe, extra);
}

/// Compiles `source` into `exe` with the C compiler `cc`, the static library in `lib_dir`
/// and `extra` flags.
fn compile_static_with(cc: &str, lib_dir: &Path, source: &Path, exe: &Path, extra: &[&str]) {
    let lib = lib_dir.join("libspringwater_ffi.a");
    assert!(lib.exists(), "{} was not built", lib.display());
    let out = Command::new(cc)
        .args([
            "-std=c11",
            "-O1",
            "-g",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-pedantic",
        ])
        .args(extra)
        .arg("-I")
        .arg(crate_dir().join("include"))
        .arg(source)
        .arg(&lib)
        .args(NATIVE_LIBS)
        .arg("-o")
        .arg(exe)
        .output()
        .unwrap_or_else(|e| panic!("{cc} runs (install a C compiler): {e}"));
    assert_ok(&out, "compiling");
}

/// `key value` lines of the client's output.
fn values(out: &Output) -> HashMap<String, String> {
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| l.split_once(' '))
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
}

fn floaters_fingerprint(s: &Surface) -> String {
    format!(
        "{:016x}",
        fnv(s.floaters().flat_map(|(_, f)| floater_floats(f)))
    )
}

/// The C client's floating bodies on open water, through the Rust API.
fn expected_floaters() -> Vec<(&'static str, String)> {
    let p = Params::with_size(32, 28).with_boundary(Boundary::Absorbing { width: 6 });
    let mut s = Surface::new(p).unwrap();
    let calm = Buoyancy::default();
    s.set_buoyancy(Buoyancy {
        gravity: 69.12,
        density: 1.1,
    })
    .unwrap();
    let mut ball = Floater::sphere(2.0, 10.0, [12.0, 1.0, 14.0]);
    ball.velocity = glam::Vec3::new(1.2, 0.0, -0.48);
    let a = s.add_floater(ball).unwrap();
    let b = s
        .add_floater(Floater::cuboid([1.5, 0.5, 2.0], 4.0, [20.0, 0.5, 10.0]))
        .unwrap();
    let spare = s
        .add_floater(Floater::sphere(1.0, 1.0, [8.0, 0.0, 8.0]))
        .unwrap();
    s.remove_floater(spare).unwrap();
    assert_eq!(
        (a, b, spare),
        (
            FloaterId::from_raw(0),
            FloaterId::from_raw(1),
            FloaterId::from_raw(2)
        )
    );
    s.drop_at(16.0, 14.0, 0.5, 2.0).unwrap();
    for frame in 0..40 {
        if frame == 10 {
            s.push_floater(a, [288.0, 0.0, 115.2]).unwrap();
        }
        s.advance(1.0 / 60.0).unwrap();
    }
    let mut boxy = s.floater(b).unwrap().clone();
    boxy.velocity.x = 2.4;
    boxy.drag = 24.0;
    s.set_floater(b, boxy).unwrap();
    s.step_n(20).unwrap();
    let floaters = floaters_fingerprint(&s);
    let [x, y, z] = s.positions();
    let positions = fnv((0..s.node_count()).flat_map(|i| [x[i], y[i], z[i]]));
    let snapshot_bytes = s.to_bytes().len();
    s.step_n(2500).unwrap();
    vec![
        (
            "floater_drag",
            format!("{:08x}", Floater::DEFAULT_DRAG.to_bits()),
        ),
        (
            "buoyancy",
            format!(
                "{:08x} {:08x}",
                calm.gravity.to_bits(),
                calm.density.to_bits()
            ),
        ),
        ("floaters", floaters),
        ("open_positions", format!("{positions:016x}")),
        ("open_snapshot_bytes", snapshot_bytes.to_string()),
        ("settled", floaters_fingerprint(&s)),
    ]
}

/// What the C client prints, computed through the Rust API for the same frames.
fn expected() -> HashMap<&'static str, String> {
    let mut s = Surface::new(Params::with_size(48, 40)).unwrap();
    s.drop_at(20.0, 15.0, 1.0, 3.0).unwrap();
    for frame in 0..30 {
        if frame == 10 {
            s.add_force_at(10.5, 12.25, [0.0, -2.0, 0.0]).unwrap();
        }
        s.advance(1.0 / 60.0).unwrap();
    }
    let view = s.mesh_view();
    let n = s.node_count();
    let [x, y, z] = s.positions();
    let positions = fnv((0..n).flat_map(|i| [x[i], y[i], z[i]]));
    let mut normals = Normals::new();
    compute_normals(&view, &mut normals);
    let normal_bits = fnv((0..n).flat_map(|i| [normals.x[i], normals.y[i], normals.z[i]]));
    let mut uv = Refraction::default();
    let eye = glam::Vec3::new(24.0, 30.0, -20.0);
    refract(&view, &normals, eye, &RefractionParams::default(), &mut uv).unwrap();
    let uvs = fnv((0..n).flat_map(|i| [uv.u[i], uv.v[i]]));
    let height = s.height_at(20.5, 15.25).unwrap();
    let normal = s.normal_at(20.5, 15.25).unwrap();
    let velocity = s.velocity_at(20.5, 15.25).unwrap();
    let mut lod = LodMesh::new(
        LodParams::default()
            .with_patch_cells(8)
            .with_levels(3)
            .with_first_range(12.0),
    )
    .unwrap();
    lod.update(&view, glam::Vec3::new(0.0, 10.0, 0.0));
    // The client's rollback run: six frames with a drop each from the saved state.
    let mut rolled = s.clone();
    for f in 0..6 {
        rolled.drop_at(4.0 + f as f32, 5.0, 0.25, 2.0).unwrap();
        rolled.advance(1.0 / 60.0).unwrap();
    }
    HashMap::from([
        ("rollback_hash", format!("{:016x}", rolled.state_hash())),
        ("positions", format!("{positions:016x}")),
        ("normals", format!("{normal_bits:016x}")),
        ("uvs", format!("{uvs:016x}")),
        ("height", format!("{:08x}", height.to_bits())),
        (
            "normal",
            format!(
                "{:08x} {:08x} {:08x}",
                normal.x.to_bits(),
                normal.y.to_bits(),
                normal.z.to_bits()
            ),
        ),
        ("velocity", format!("{:08x}", velocity.y.to_bits())),
        ("lod_indices", lod.indices().len().to_string()),
        ("snapshot_bytes", s.to_bytes().len().to_string()),
        ("simd", s.simd_level().name().to_string()),
        ("checks", "passed".to_string()),
        ("version", env!("CARGO_PKG_VERSION").to_string()),
    ])
    .into_iter()
    .chain(expected_floaters())
    .collect()
}

/// Checks the client's values against the Rust API's, except the keys in `ignore`.
fn check_client_output(out: &Output, how: &str, ignore: &[&str]) {
    assert_ok(out, how);
    let got = values(out);
    for (key, want) in expected() {
        if ignore.contains(&key) {
            continue;
        }
        assert_eq!(
            got.get(key),
            Some(&want),
            "{how}: the C client's `{key}` differs from the Rust API's"
        );
    }
}

/// How a client program runs: plainly, under AddressSanitizer (with UndefinedBehavior-
/// Sanitizer), or under Valgrind's memcheck.
#[derive(Clone, Copy, PartialEq)]
enum Run {
    Plain,
    Sanitized,
    Valgrind,
}

/// Compiles `tests/c/{name}.c` against the static library and runs it as `run` says; None
/// (after saying why) when Valgrind is not installed.
fn run_client(name: &str, run: Run) -> Option<Output> {
    if run == Run::Valgrind && !have("valgrind") {
        eprintln!("skipped: valgrind is not installed");
        return None;
    }
    let source = crate_dir().join("tests/c").join(format!("{name}.c"));
    let suffix = match run {
        Run::Plain => "",
        Run::Sanitized => "-asan",
        Run::Valgrind => "-valgrind",
    };
    let exe = out_dir().join(format!("{name}{suffix}"));
    let sanitize: &[&str] = match run {
        Run::Sanitized => &["-fsanitize=address,undefined", "-fno-omit-frame-pointer"],
        _ => &[],
    };
    compile_static(&source, &exe, sanitize);
    let mut command = match run {
        Run::Valgrind => {
            let mut valgrind = Command::new("valgrind");
            valgrind.args([
                "--quiet",
                "--error-exitcode=99",
                "--leak-check=full",
                "--errors-for-leak-kinds=definite",
            ]);
            valgrind.arg(&exe);
            valgrind
        }
        _ => Command::new(&exe),
    };
    if run == Run::Sanitized {
        command
            .env(
                "ASAN_OPTIONS",
                "detect_leaks=1:abort_on_error=0:exitcode=97",
            )
            .env("UBSAN_OPTIONS", "halt_on_error=1:exitcode=98");
    }
    Some(command.output().unwrap())
}

#[test]
fn the_c_client_runs_its_frame_loop_and_refuses_every_bad_input() {
    if skip() {
        return;
    }
    let out = run_client("client", Run::Plain).unwrap();
    check_client_output(&out, "the C client", &[]);
}

#[test]
fn the_c_client_is_clean_under_address_sanitizer() {
    if skip() {
        return;
    }
    let out = run_client("client", Run::Sanitized).unwrap();
    check_client_output(&out, "the C client under AddressSanitizer", &[]);
}

#[test]
fn the_c_client_is_clean_under_valgrind() {
    if skip() {
        return;
    }
    // Valgrind's CPU has no AVX-512: the level that ran may differ, the bits may not.
    if let Some(out) = run_client("client", Run::Valgrind) {
        check_client_output(&out, "the C client under valgrind", &["simd"]);
    }
}

/// Checks the rigid-body client's values against the Rust API's.
fn check_rigid_output(out: &Output, how: &str) {
    assert_ok(out, how);
    let got = values(out);
    let passed = ("rigid_checks", "passed".to_string());
    for (key, want) in righted_box().into_iter().chain([passed]) {
        assert_eq!(
            got.get(key),
            Some(&want),
            "{how}: the rigid-body client's `{key}` differs from the Rust API's"
        );
    }
}

/// `tests/c/rigid.c` floats a box heeled 15° and rights it, as a built-in body and in its
/// own explicit 60 Hz integrator driven by `sw_surface_body_forces`, as a hull mesh, and
/// through a version 1 `SwFloater`; its built-in box ends in the Rust API's bits. It also
/// floats the library's boat through rain and a wake.
#[test]
fn the_rigid_body_client_rights_its_boxes() {
    if skip() {
        return;
    }
    let out = run_client("rigid", Run::Plain).unwrap();
    check_rigid_output(&out, "the rigid-body client");
}

#[test]
fn the_rigid_body_client_is_clean_under_address_sanitizer() {
    if skip() {
        return;
    }
    let out = run_client("rigid", Run::Sanitized).unwrap();
    check_rigid_output(&out, "the rigid-body client under AddressSanitizer");
}

#[test]
fn the_rigid_body_client_is_clean_under_valgrind() {
    if skip() {
        return;
    }
    if let Some(out) = run_client("rigid", Run::Valgrind) {
        check_rigid_output(&out, "the rigid-body client under valgrind");
    }
}

/// The C client built for another architecture, run under its emulator, prints what the
/// Rust API computes here: the same bits across architectures, through the C ABI; on
/// AArch64 it reports the NEON level, detected and running. Runs
/// when `SPRINGWATER_C_TARGET` names a Rust target, with `SPRINGWATER_C_CC` its C
/// compiler and `SPRINGWATER_C_RUNNER` the command that runs its programs (cargo needs that
/// target's linker too), for example on x86-64 Debian:
///
/// ```text
/// SPRINGWATER_C_TARGET=aarch64-unknown-linux-gnu SPRINGWATER_C_CC=aarch64-linux-gnu-gcc \
/// SPRINGWATER_C_RUNNER="qemu-aarch64 -L /usr/aarch64-linux-gnu" \
/// CARGO_TARGET_AARCH64_UNKNOWN_LINUX_GNU_LINKER=aarch64-linux-gnu-gcc \
///   cargo test --release -p springwater-ffi --test c_client cross
/// ```
#[test]
fn the_c_client_cross_built_prints_the_same_values() {
    let Some(target) = std::env::var_os("SPRINGWATER_C_TARGET") else {
        eprintln!("skipped: SPRINGWATER_C_TARGET is not set");
        return;
    };
    let target = target.to_str().expect("a target name");
    let var = |name: &str| {
        std::env::var(name).unwrap_or_else(|_| panic!("SPRINGWATER_C_TARGET needs {name}"))
    };
    let (cc, runner) = (var("SPRINGWATER_C_CC"), var("SPRINGWATER_C_RUNNER"));
    let dir = build_libraries(Some(target));
    let exe = dir.join("client");
    compile_static_with(&cc, &dir, &crate_dir().join("tests/c/client.c"), &exe, &[]);
    let mut words = runner.split_whitespace();
    let out = Command::new(words.next().expect("a runner command"))
        .args(words)
        .arg(&exe)
        // The level the client reports must be the one its CPU picks, not a forced one.
        .env_remove("SPRINGWATER_SIMD")
        .output()
        .unwrap();
    // The level is the other CPU's; the values must be the same bits.
    let how = format!("the C client on {target}");
    check_client_output(&out, &how, &["simd"]);
    // And the level is that architecture's: NEON, which every AArch64 CPU has, both
    // detected (`sw_simd_level_detect`) and running the surface (`sw_surface_simd_level`).
    if target.starts_with("aarch64") {
        let got = values(&out);
        for key in ["simd_detect", "simd"] {
            assert_eq!(
                got.get(key).map(String::as_str),
                Some("neon"),
                "{how}: `{key}` is not NEON"
            );
        }
    }
}

/// The README's C example, extracted from the README, linked against the dynamic library.
#[test]
fn the_readme_c_example_builds_against_the_dynamic_library_and_runs() {
    if skip() {
        return;
    }
    let readme = std::fs::read_to_string(crate_dir().join("README.md")).unwrap();
    let start = readme.find("```c\n").expect("the README has a C example") + "```c\n".len();
    let end = start + readme[start..].find("```").unwrap();
    let source = out_dir().join("readme_example.c");
    std::fs::write(&source, &readme[start..end]).unwrap();
    let exe = out_dir().join("readme_example");
    let dir = lib_dir();
    let out = Command::new("cc")
        .args(["-std=c11", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg("-I")
        .arg(crate_dir().join("include"))
        .arg(&source)
        .arg("-L")
        .arg(&dir)
        .arg(format!("-Wl,-rpath,{}", dir.display()))
        .args(["-lspringwater_ffi", "-o"])
        .arg(&exe)
        .output()
        .expect("cc runs");
    assert_ok(&out, "compiling the README's C example");
    let run = Command::new(&exe).output().unwrap();
    assert_ok(&run, "the README's C example");
    assert!(!run.stdout.is_empty());
}

/// `tests/c/header.cpp` includes the header as C++ and uses every kind of declaration
/// (the rigid bodies' structs, handles and calls among them): compiled, linked against
/// the static library and run.
#[test]
fn the_header_compiles_as_cpp() {
    if skip() {
        return;
    }
    let exe = out_dir().join("header-cpp");
    let out = Command::new("c++")
        .args(["-std=c++11", "-Wall", "-Wextra", "-Werror", "-I"])
        .arg(crate_dir().join("include"))
        .arg(crate_dir().join("tests/c/header.cpp"))
        .arg(lib_dir().join("libspringwater_ffi.a"))
        .args(NATIVE_LIBS)
        .arg("-o")
        .arg(&exe)
        .output()
        .expect("c++ runs");
    assert_ok(&out, "compiling the header as C++");
    let run = Command::new(&exe).output().unwrap();
    assert_ok(&run, "the C++ program");
}
