//! `springwater bake` (`cli/README.md`): every format against `simulate --csv` after the same
//! steps, the glTF checked by the Khronos validator, and the caches opened in Blender.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::*;

/// A real client's test that cannot run here says why; where CI installed the clients
/// (`SPRINGWATER_REQUIRE_TOOLS` set), not running one is a failure.
fn skipped(why: &str) {
    assert!(
        std::env::var_os("SPRINGWATER_REQUIRE_TOOLS").is_none(),
        "SPRINGWATER_REQUIRE_TOOLS is set but {why}"
    );
    println!("skipped: {why}");
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("springwater-bake-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The model every test bakes: a drop and a floater on a small pool. At 60 fps a frame
/// is one step of the default timestep (24 units of model time a second), so frame k is
/// `simulate --steps k`.
const MODEL: [&str; 8] = [
    "--size",
    "33x21",
    "--drop",
    "16,10,1,3",
    "--floater",
    "10,12,2,1.5",
    "--fps",
    "60",
];
const NODES: usize = 33 * 21;

fn bake(out: &Path, frames: usize) -> String {
    let frames = frames.to_string();
    let mut args = vec!["bake", "--frames", &frames, "--out", out.to_str().unwrap()];
    args.extend(MODEL.iter().filter(|&&a| a != "--fps" && a != "60"));
    args.extend(["--fps", "60"]);
    ok(&args)
}

/// `simulate --csv` after `steps` steps of the same model: the x, y, z of every node, and
/// the first floater's summary line.
fn simulate(steps: usize) -> (Vec<[f32; 3]>, String) {
    let csv = scratch(&format!("steps{steps}.csv"));
    let steps = steps.to_string();
    let report = ok(&[
        "simulate",
        "--size",
        "33x21",
        "--drop",
        "16,10,1,3",
        "--floater",
        "10,12,2,1.5",
        "--steps",
        &steps,
        "--csv",
        csv.to_str().unwrap(),
    ]);
    let nodes = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<f32> = l.split(',').skip(2).map(|s| s.parse().unwrap()).collect();
            [f[0], f[1], f[2]]
        })
        .collect();
    let floater = report
        .lines()
        .find(|l| l.starts_with("floater 0 "))
        .unwrap()
        .to_owned();
    (nodes, floater)
}

fn f32s(bytes: &[u8], big_endian: bool) -> Vec<f32> {
    bytes
        .chunks_exact(4)
        .map(|c| {
            let c = [c[0], c[1], c[2], c[3]];
            if big_endian {
                f32::from_be_bytes(c)
            } else {
                f32::from_le_bytes(c)
            }
        })
        .collect()
}

fn obj_positions(path: &Path) -> Vec<[f32; 3]> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| {
            let f: Vec<f32> = l[2..].split(' ').map(|s| s.parse().unwrap()).collect();
            [f[0], f[1], f[2]]
        })
        .collect()
}

#[test]
fn point_caches_hold_frames_1_to_n_bit_for_bit() {
    let (frame3, _) = simulate(3);
    let (rest, _) = simulate(0);
    for (name, big) in [("water.mdd", true), ("water.pc2", false)] {
        let path = scratch(name);
        bake(&path, 5);
        let bytes = std::fs::read(&path).unwrap();
        let header = if big {
            assert_eq!(i32::from_be_bytes(bytes[0..4].try_into().unwrap()), 5);
            assert_eq!(
                i32::from_be_bytes(bytes[4..8].try_into().unwrap()),
                NODES as i32
            );
            let times = f32s(&bytes[8..28], true);
            assert_eq!(times, [1.0, 2.0, 3.0, 4.0, 5.0].map(|k| k / 60.0));
            28
        } else {
            assert_eq!(&bytes[..12], b"POINTCACHE2\0");
            let ints = |at: usize| i32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
            assert_eq!((ints(12), ints(16), ints(28)), (1, NODES as i32, 5));
            assert_eq!(f32s(&bytes[20..28], false), [1.0, 1.0]);
            32
        };
        assert_eq!(bytes.len(), header + 5 * NODES * 12);
        // Sample 2 is frame 3, the state after 3 steps.
        let sample = f32s(
            &bytes[header + 2 * NODES * 12..header + 3 * NODES * 12],
            big,
        );
        let sample: Vec<[f32; 3]> = sample.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        assert_eq!(sample, frame3, "{name}: frame 3");
        assert_ne!(frame3, rest);
        // The rest mesh beside it is frame 0, same vertex order.
        assert_eq!(
            obj_positions(&path.with_extension("obj")),
            rest,
            "{name}: rest OBJ"
        );
    }
}

#[test]
fn a_directory_gets_one_obj_per_frame() {
    let dir = scratch("frames");
    let _ = std::fs::remove_dir_all(&dir);
    bake(&dir, 4);
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "water_0001.obj",
            "water_0002.obj",
            "water_0003.obj",
            "water_0004.obj"
        ]
    );
    let (frame2, _) = simulate(2);
    assert_eq!(obj_positions(&dir.join("water_0002.obj")), frame2);
    // A full-detail mesh: two triangles per cell.
    let text = std::fs::read_to_string(dir.join("water_0002.obj")).unwrap();
    assert_eq!(
        text.lines().filter(|l| l.starts_with("f ")).count(),
        2 * 32 * 20
    );
    assert_eq!(text.lines().filter(|l| l.starts_with("vt ")).count(), NODES);
}

#[test]
fn glb_has_one_target_per_frame_and_a_floater_node() {
    let path = scratch("water.glb");
    bake(&path, 6);
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    assert_eq!(u32_at(4), 2);
    assert_eq!(u32_at(8), bytes.len());
    let json_len = u32_at(12);
    assert_eq!(&bytes[16..20], b"JSON");
    let json = std::str::from_utf8(&bytes[20..20 + json_len]).unwrap();
    assert_eq!(json.matches(r#"{"POSITION":"#).count(), 1 + 6);
    assert!(json.contains(r#""name":"floater 0""#));
    assert!(json.contains(r#""path":"weights""#));
    assert!(json.contains(r#""path":"translation""#));
    let bin = 20 + json_len;
    assert_eq!(&bytes[bin + 4..bin + 8], b"BIN\0");
    assert_eq!(u32_at(bin) + bin + 8, bytes.len());
    // The base mesh is frame 0, at the start of the binary chunk.
    let (rest, _) = simulate(0);
    let base = f32s(&bytes[bin + 8..bin + 8 + NODES * 12], false);
    let base: Vec<[f32; 3]> = base.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    assert_eq!(base, rest);
    assert!(
        !scratch("water.glb.part").exists(),
        "the temporary file is removed"
    );
}

#[test]
fn bad_outputs_fail_in_one_line_before_any_frame() {
    let cases = [
        ("/nonexistent-dir/water.glb", "cannot write"),
        ("/nonexistent-dir/water.pc2", "cannot write"),
        ("/nonexistent-dir/water.mdd", "cannot write"),
        ("water.abc", "not a format bake writes"),
    ];
    for (out, needle) in cases {
        let o = springwater(&["bake", "--size", "9x9", "--frames", "2", "--out", out]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{out}: {err}");
        assert_eq!(err.lines().count(), 1, "{out}: {err}");
        assert!(err.contains(needle), "{out}: {err}");
        assert!(!err.contains("panicked"), "{out}: {err}");
    }
    // A directory that cannot be created (under a file).
    let file = scratch("a-file");
    std::fs::write(&file, "x").unwrap();
    let under = file.join("frames");
    let o = springwater(&["bake", "--size", "9x9", "--out", under.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    for bad in [
        &["--frames", "0"][..],
        &["--fps", "0"],
        &["--fps", "nan"],
        &["--out"],
        &["--load", "x.snap", "--size", "9x9"],
    ] {
        let mut args = vec!["bake", "--out", "x.glb"];
        args.extend(bad);
        let o = springwater(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{bad:?}: {err}");
    }
    assert!(!Path::new("x.glb").exists());
}

#[test]
fn a_full_disk_is_an_error_not_a_panic_and_the_device_stays() {
    // /dev/full accepts the open and fails every write. A cache named through a link to
    // it is written in place, as a stream (a device has no earlier content to keep).
    if !Path::new("/dev/full").exists() {
        println!("skipped: no /dev/full here");
        return;
    }
    let dir = scratch("full");
    std::fs::create_dir_all(&dir).unwrap();
    let link = dir.join("full.pc2");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink("/dev/full", &link).unwrap();
    let err = refused(&[
        "bake",
        "--size",
        "9x9",
        "--frames",
        "3",
        "--out",
        link.to_str().unwrap(),
    ]);
    assert!(err.contains("No space left"), "{err}");
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(Path::new("/dev/full").exists());
    // The rest OBJ, a regular file, was discarded with the failed run.
    assert!(!dir.join("full.obj").exists());
}

/// Runs `blender -b` on tests/blender/check_bake.py; false (after saying why) if there is
/// no Blender here.
fn blender(args: &[&str]) -> bool {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/blender/check_bake.py");
    let out = match Command::new("blender")
        .args([
            "-b",
            "--factory-startup",
            "--python-exit-code",
            "1",
            "--python",
        ])
        .arg(&script)
        .arg("--")
        .args(args)
        .output()
    {
        Ok(out) => out,
        Err(e) => {
            skipped(&format!(
                "cannot run blender ({e}); install it with apt-get install blender python3-numpy"
            ));
            return false;
        }
    };
    let stdout = String::from_utf8_lossy(&out.stdout);
    println!("{stdout}");
    assert!(
        out.status.success() && stdout.contains("BAKE OK"),
        "blender {args:?}:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    true
}

#[test]
fn blender_imports_the_glb_and_the_point_caches_at_the_simulated_positions() {
    let frame = 7;
    let (nodes, floater) = simulate(frame);
    let csv = scratch("blender.csv");
    let mut text = String::from("col,row,x,y,z\n");
    for (i, [x, y, z]) in nodes.iter().enumerate() {
        text += &format!("{},{},{x},{y},{z}\n", i % 33, i / 33);
    }
    std::fs::write(&csv, text).unwrap();
    // "floater 0 position X Y Z velocity …"
    let centre: Vec<&str> = floater.split(' ').skip(3).take(3).collect();
    let centre = centre.join(",");
    let common = [
        "--fps",
        "60",
        "--frame",
        "7",
        "--csv",
        csv.to_str().unwrap(),
    ];

    let glb = scratch("blender.glb");
    bake(&glb, 10);
    let mut args = vec!["--glb", glb.to_str().unwrap(), "--floater", &centre];
    args.extend(common);
    if !blender(&args) {
        return;
    }
    for name in ["blender.mdd", "blender.pc2"] {
        let cache = scratch(name);
        bake(&cache, 10);
        let obj = cache.with_extension("obj");
        let mut args = vec![
            "--obj",
            obj.to_str().unwrap(),
            "--cache",
            cache.to_str().unwrap(),
        ];
        args.extend(common);
        blender(&args);
    }
}

#[test]
fn the_khronos_validator_finds_no_error_and_no_warning() {
    // `npm install --prefix cli/tests/gltf gltf-validator` puts it where this looks.
    let here = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gltf");
    if !here.join("node_modules/gltf-validator").exists() {
        skipped(
            "gltf-validator is not installed (npm install --prefix cli/tests/gltf gltf-validator)",
        );
        return;
    }
    let glb = scratch("validate.glb");
    bake(&glb, 12);
    // With an eye: the LOD triangles.
    let lod = scratch("validate-lod.glb");
    ok(&[
        "bake",
        "--size",
        "100x70",
        "--frames",
        "3",
        "--eye",
        "5,10,5",
        "--drop",
        "50,35,1,4",
        "--out",
        lod.to_str().unwrap(),
    ]);
    for file in [&glb, &lod] {
        let out = match Command::new("node")
            .arg(here.join("validate.js"))
            .arg(file)
            .env("NODE_PATH", here.join("node_modules"))
            .output()
        {
            Ok(out) => out,
            Err(e) => {
                skipped(&format!("cannot run node ({e})"));
                return;
            }
        };
        let report = String::from_utf8_lossy(&out.stdout);
        println!("{}: {report}", file.display());
        assert!(out.status.success(), "{}: {report}", file.display());
        assert!(report.contains("errors 0 warnings 0"), "{report}");
    }
}

#[test]
fn a_bake_continues_from_a_snapshot() {
    let snap = scratch("start.snap");
    ok(&[
        "simulate",
        "--size",
        "33x21",
        "--drop",
        "16,10,1,3",
        "--steps",
        "4",
        "--save",
        snap.to_str().unwrap(),
    ]);
    let cache = scratch("loaded.pc2");
    ok(&[
        "bake",
        "--load",
        snap.to_str().unwrap(),
        "--frames",
        "3",
        "--fps",
        "60",
        "--out",
        cache.to_str().unwrap(),
    ]);
    let csv = scratch("loaded.csv");
    ok(&[
        "simulate",
        "--load",
        snap.to_str().unwrap(),
        "--steps",
        "3",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    let want: Vec<f32> = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .skip(1)
        .flat_map(|l| {
            l.split(',')
                .skip(2)
                .map(|s| s.parse::<f32>().unwrap())
                .collect::<Vec<_>>()
        })
        .collect();
    let bytes = std::fs::read(&cache).unwrap();
    let last = &bytes[32 + 2 * NODES * 12..];
    assert_eq!(f32s(last, false), want, "frame 3 after the snapshot");
}

#[test]
fn ctrl_c_stops_a_bake_and_leaves_the_earlier_cache_as_it_was() {
    let dir = scratch("interrupted");
    std::fs::create_dir_all(&dir).unwrap();
    let cache = dir.join("interrupted.pc2");
    ok(&line(
        "bake --size 5x5 --drop 2,2,1,1 --frames 2 --out @",
        &[&cache],
    ));
    let before = (
        std::fs::read(&cache).unwrap(),
        std::fs::read(cache.with_extension("obj")).unwrap(),
    );
    let child = Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args([
            "bake",
            "--size",
            "5x5",
            "--drop",
            "2,2,1,1",
            "--frames",
            "900000",
            // 1200 steps a frame: a few thousand frames a second, a few MB a second.
            "--fps",
            "0.05",
            "--out",
            cache.to_str().unwrap(),
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("stopped by Ctrl-C"), "{err}");
    let after = (
        std::fs::read(&cache).unwrap(),
        std::fs::read(cache.with_extension("obj")).unwrap(),
    );
    assert!(after == before, "the earlier cache changed");
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        2,
        "a partial file was left"
    );
}

#[test]
fn a_frame_is_the_steps_advance_takes() {
    // At 24 fps and the default time scale a frame is 2.5 steps: the clock takes 2 and 3
    // in turn, the bake says how many in all, and `simulate` with that many steps lands
    // on the same bits.
    let dir = scratch("fps24");
    let report = ok(&[
        "bake",
        "--size",
        "17x17",
        "--drop",
        "8,8,1,2",
        "--frames",
        "2",
        "--fps",
        "24",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let words: Vec<&str> = report.split_whitespace().collect();
    let at = words.iter().position(|&w| w == "steps").unwrap();
    let (steps, dt): (usize, &str) = (words[at - 1].parse().unwrap(), words[at + 2]);
    assert_eq!((steps, dt), (5, "0.4"), "{report}");
    let csv = scratch("fps24.csv");
    let steps = steps.to_string();
    ok(&[
        "simulate",
        "--size",
        "17x17",
        "--drop",
        "8,8,1,2",
        "--steps",
        &steps,
        "--dt",
        dt,
        "--csv",
        csv.to_str().unwrap(),
    ]);
    let want: Vec<[f32; 3]> = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<f32> = l.split(',').skip(2).map(|s| s.parse().unwrap()).collect();
            [f[0], f[1], f[2]]
        })
        .collect();
    assert_eq!(obj_positions(&dir.join("water_0002.obj")), want);
}

#[test]
fn a_long_frame_takes_all_its_steps() {
    // At 2 fps a frame is 30 steps, past the game's default cap of 16 steps per `advance`:
    // a bake takes them all (the cap is for stalls in a game, not for a cache).
    let dir = scratch("fps2");
    let report = ok(&[
        "bake",
        "--size",
        "9x9",
        "--drop",
        "4,4,1,2",
        "--frames",
        "2",
        "--fps",
        "2",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(report.contains(" 60 steps of 0.4 "), "{report}");
    let csv = scratch("fps2.csv");
    ok(&[
        "simulate",
        "--size",
        "9x9",
        "--drop",
        "4,4,1,2",
        "--steps",
        "60",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    let want: Vec<[f32; 3]> = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<f32> = l.split(',').skip(2).map(|s| s.parse().unwrap()).collect();
            [f[0], f[1], f[2]]
        })
        .collect();
    assert_eq!(obj_positions(&dir.join("water_0002.obj")), want);

    // A frame longer than `advance` may ever step is refused before anything is written.
    let tiny = scratch("fps-tiny");
    let err = refused(&line(
        "bake --size 9x9 --frames 2 --fps 0.0001 --out @",
        &[&tiny],
    ));
    assert!(err.contains("use --fps 0.0060006 or more"), "{err}");
    // The longer timestep that would fit is past the critical one: not offered.
    assert!(!err.contains("--dt"), "{err}");
    assert!(!tiny.exists());
    // With a tiny timestep, a longer one is the remedy too.
    let err = refused(&line("bake --size 9x9 --dt 1e-6 --out @", &[&tiny]));
    assert!(err.contains("--dt 1.0001e-4 or more"), "{err}");
    assert!(!tiny.exists());
}

#[test]
fn frames_of_thousands_of_steps_take_every_step_they_mean() {
    // 100 s frames are 6,000 steps of 0.4 each; the f32 nearest 0.4 is a hair longer, and
    // that rounding must not cost the second frame a step.
    let dir = scratch("fps-hundredth");
    let report = ok(&line(
        "bake --size 9x9 --drop 4,4,1,2 --frames 2 --fps 0.01 --out @",
        &[&dir],
    ));
    assert!(report.contains(" 12000 steps of 0.4 "), "{report}");
}

#[test]
fn rain_a_wake_open_water_and_threads_bake_the_same_bits_on_one_thread_and_two() {
    // Every disturbance and the absorbing frame go through bake, and the thread count
    // changes nothing (the engine's promise, through the command line).
    let bake = |threads: &str, name: &str| {
        let dir = scratch(name);
        let report = ok(&[
            "bake",
            "--size",
            "33x25",
            "--boundary",
            "absorbing",
            "--rain",
            "720",
            "--seed",
            "5",
            "--wake",
            "--floater",
            "16,12,5,1.5",
            "--threads",
            threads,
            "--frames",
            "6",
            "--out",
            dir.to_str().unwrap(),
        ]);
        assert!(report.contains("baked 6 frames"), "{report}");
        (1..=6)
            .map(|k| obj_positions(&dir.join(format!("water_{k:04}.obj"))))
            .collect::<Vec<_>>()
    };
    let one = bake("1", "disturbed-1");
    assert_eq!(one, bake("2", "disturbed-2"));
    assert!(one.iter().flatten().flatten().all(|v| v.is_finite()));
    let moved = |a: &[[f32; 3]], b: &[[f32; 3]]| a.iter().zip(b).filter(|(p, q)| p != q).count();
    // The rain and the wake keep the water moving from frame to frame.
    for k in 1..6 {
        assert!(moved(&one[k - 1], &one[k]) > 100, "frame {k} to {}", k + 1);
    }
}

#[test]
fn ctrl_c_during_the_warm_up_steps_stops_the_bake_too() {
    let dir = scratch("interrupted-warm-up");
    std::fs::create_dir_all(&dir).unwrap();
    let cache = dir.join("interrupted-warm-up.mdd");
    let child = Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args([
            "bake",
            "--size",
            "5x5",
            "--drop",
            "2,2,1,1",
            "--steps",
            "4000000000",
            "--frames",
            "3",
            "--out",
            cache.to_str().unwrap(),
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    // Before the warm-up listened, the run went on: give it 20 s, then fail (not hang).
    let mut child = child;
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(20);
    while child.try_wait().unwrap().is_none() {
        if std::time::Instant::now() > deadline {
            child.kill().unwrap();
            panic!("the bake did not stop at Ctrl-C during its warm-up steps");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("stopped by Ctrl-C"), "{err}");
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "a file was left"
    );
}
