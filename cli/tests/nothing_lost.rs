//! "Nothing is lost" (`docs/reliability.md`): a run that fails, is refused or is stopped
//! leaves the files that were there exactly as they were, never removes a path it did not
//! create (a device node, a user's file, its own `--load` input) and leaves no partial
//! file.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::*;

/// A fresh, empty directory for one test.
fn fresh(name: &str) -> PathBuf {
    common::fresh("lost", name)
}

/// A drop that makes the first step non-finite: a run that fails after its outputs were
/// started.
const BLOW_UP: [&str; 2] = ["--drop", "8,8,3e38,2"];

#[test]
fn a_failing_simulate_keeps_the_existing_csv_and_snapshot() {
    let dir = fresh("simulate-fails");
    let (csv, snap) = (dir.join("out.csv"), dir.join("out.snap"));
    std::fs::write(&csv, "the user's data\n").unwrap();
    std::fs::write(&snap, "not a snapshot, the user's").unwrap();
    let mut args = vec![
        "simulate",
        "--size",
        "16x16",
        "--csv",
        s(&csv),
        "--save",
        s(&snap),
    ];
    args.extend(BLOW_UP);
    let err = refused(&args);
    assert!(err.contains("non-finite"), "{err}");
    assert_eq!(std::fs::read(&csv).unwrap(), b"the user's data\n");
    assert_eq!(std::fs::read(&snap).unwrap(), b"not a snapshot, the user's");
    assert_eq!(names(&dir), ["out.csv", "out.snap"]);
}

#[test]
fn load_and_save_to_one_file_keeps_it_until_the_new_one_is_complete() {
    let dir = fresh("load-save");
    let snap = dir.join("s.snap");
    ok(&line(
        "simulate --size 16x16 --steps 5 --drop 8,8,1,2 --save @",
        &[&snap],
    ));
    let before = std::fs::read(&snap).unwrap();
    let mut args = vec![
        "simulate",
        "--load",
        s(&snap),
        "--save",
        s(&snap),
        "--steps",
        "10",
    ];
    args.extend(BLOW_UP);
    refused(&args);
    assert!(
        std::fs::read(&snap).unwrap() == before,
        "the snapshot changed"
    );
    assert_eq!(names(&dir), ["s.snap"]);
    // And succeeding, it is replaced by the continued state, with the file's mode.
    ok(&line(
        "simulate --load @ --save @ --steps 10",
        &[&snap, &snap],
    ));
    let after = std::fs::read(&snap).unwrap();
    assert_eq!(after.len(), before.len());
    assert!(after != before);
    assert_eq!(names(&dir), ["s.snap"]);
}

#[test]
fn a_failing_render_keeps_the_existing_gif_and_png_frames() {
    let dir = fresh("render-fails");
    let (gif, pngs) = (dir.join("water.gif"), dir.join("frames"));
    ok(&line(
        "render --size 16x16 --frames 2 --width 32 --height 24 --out @ --png @",
        &[&gif, &pngs],
    ));
    let before = (std::fs::read(&gif).unwrap(), names(&pngs));
    let mut args = vec![
        "render",
        "--size",
        "16x16",
        "--frames",
        "2",
        "--out",
        s(&gif),
        "--png",
        s(&pngs),
    ];
    args.extend(BLOW_UP);
    refused(&args);
    assert!((std::fs::read(&gif).unwrap(), names(&pngs)) == before);
    assert_eq!(names(&dir), ["frames", "water.gif"]);
}

#[test]
fn a_failing_rebake_keeps_the_earlier_caches() {
    let dir = fresh("rebake-fails");
    for out in ["water.glb", "water.pc2", "seq"] {
        let path = dir.join(out);
        ok(&line(
            "bake --size 16x16 --drop 8,8,1,2 --frames 3 --out @",
            &[&path],
        ));
        let snapshot = |p: &Path| -> Vec<(String, Vec<u8>)> {
            let mut files: Vec<PathBuf> = if p.is_dir() {
                names(p).iter().map(|n| p.join(n)).collect()
            } else {
                vec![p.to_path_buf(), p.with_extension("obj")]
            };
            files.retain(|f| f.exists());
            files
                .iter()
                .map(|f| (f.display().to_string(), std::fs::read(f).unwrap()))
                .collect()
        };
        let before = snapshot(&path);
        let mut args = vec![
            "bake",
            "--size",
            "16x16",
            "--frames",
            "3",
            "--out",
            s(&path),
        ];
        args.extend(BLOW_UP);
        refused(&args);
        assert!(snapshot(&path) == before, "{out} changed");
    }
    assert_eq!(names(&dir), ["seq", "water.glb", "water.obj", "water.pc2"]);
}

/// A device node made in `dir` (`mknod`), or `None` (with the reason printed) where this
/// user may not make one.
fn device(dir: &Path, name: &str, major: u32, minor: u32) -> Option<PathBuf> {
    let path = dir.join(name);
    let made = Command::new("mknod")
        .args([s(&path), "c", &major.to_string(), &minor.to_string()])
        .output();
    match made {
        Ok(o) if o.status.success() => Some(path),
        Ok(o) => {
            println!(
                "skipped: mknod is not permitted here: {}",
                String::from_utf8_lossy(&o.stderr).trim()
            );
            None
        }
        Err(e) => {
            println!("skipped: no mknod here: {e}");
            None
        }
    }
}

fn is_char_device(path: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_char_device())
}

#[test]
fn a_device_is_written_in_place_and_never_removed() {
    let dir = fresh("devices");
    // A full device (/dev/full: 1,7) fails every write: an error, and the node stays.
    let Some(full) = device(&dir, "full", 1, 7) else {
        return;
    };
    for (args, needle) in [
        (
            vec![
                "render",
                "--size",
                "16x16",
                "--frames",
                "2",
                "--out",
                s(&full),
            ],
            "No space left",
        ),
        (
            vec!["simulate", "--size", "16x16", "--csv", s(&full)],
            "No space left",
        ),
        (
            vec![
                "export",
                "--size",
                "16x16",
                "--eye",
                "1,9,1",
                "--depth",
                "2",
                "--obj",
                s(&full),
            ],
            "No space left",
        ),
        // Without an extension bake would write a directory of frames there.
        (
            vec![
                "bake",
                "--size",
                "16x16",
                "--frames",
                "2",
                "--out",
                s(&full),
            ],
            "not a directory",
        ),
    ] {
        let err = refused(&args);
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(is_char_device(&full), "{args:?} removed the device");
    }
    // /dev/null (1,3) takes the output and stays a device.
    let Some(null) = device(&dir, "null", 1, 3) else {
        return;
    };
    ok(&line(
        "render --size 16x16 --frames 2 --width 32 --height 24 --out @",
        &[&null],
    ));
    ok(&line(
        "simulate --size 16x16 --csv @ --save @",
        &[&null, &null],
    ));
    assert!(is_char_device(&null));
    assert_eq!(names(&dir), ["full", "null"]);
}

#[test]
fn a_fifo_is_written_as_a_stream() {
    let dir = fresh("fifo");
    let fifo = dir.join("pipe");
    let made = Command::new("mkfifo").arg(s(&fifo)).status();
    if !made.is_ok_and(|s| s.success()) {
        println!("skipped: mkfifo failed here");
        return;
    }
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read_to_string(fifo).unwrap())
    };
    ok(&line("simulate --size 3x3 --steps 1 --csv @", &[&fifo]));
    let text = reader.join().unwrap();
    assert!(text.starts_with("col,row,x,y,z\n"), "{text}");
    assert_eq!(text.lines().count(), 10);
    assert_eq!(names(&dir), ["pipe"]);
}

/// Starts `springwater args` with its output piped.
fn start<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

fn kill(child: &Child, signal: &str) {
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
}

/// Waits at most 20 s (then fails rather than hangs) and returns the exit code and stderr.
fn finish(mut child: Child) -> (Option<i32>, String) {
    let deadline = Instant::now() + Duration::from_secs(20);
    while child.try_wait().unwrap().is_none() {
        if Instant::now() > deadline {
            child.kill().unwrap();
            panic!("the run did not stop");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn sigterm_and_sighup_stop_a_bake_and_leave_the_earlier_cache_byte_for_byte() {
    for (signal, code, name) in [("-TERM", 143, "SIGTERM"), ("-HUP", 129, "SIGHUP")] {
        let dir = fresh(&format!("bake{signal}"));
        let cache = dir.join("water.pc2");
        let obj = dir.join("water.obj");
        ok(&line(
            "bake --size 64x64 --drop 32,32,1,3 --frames 4 --out @",
            &[&cache],
        ));
        let before = (std::fs::read(&cache).unwrap(), std::fs::read(&obj).unwrap());
        // Some minutes of frames: stopped after a second.
        let child = start(&line(
            "bake --size 256x256 --drop 32,32,1,3 --frames 100000 --out @",
            &[&cache],
        ));
        std::thread::sleep(Duration::from_millis(1000));
        let asked = Instant::now();
        kill(&child, signal);
        let (status, err) = finish(child);
        assert!(
            asked.elapsed() < Duration::from_secs(2),
            "{name} took {:?}",
            asked.elapsed()
        );
        assert_eq!(status, Some(code), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(name), "{err}");
        assert!((std::fs::read(&cache).unwrap(), std::fs::read(&obj).unwrap()) == before);
        assert_eq!(
            names(&dir),
            ["water.obj", "water.pc2"],
            "a partial file was left"
        );
    }
}

#[test]
fn every_long_loop_hears_sigterm_within_a_second() {
    // The warm-up, the frames with rain, and render's drawing.
    let dir = fresh("loops");
    let out = dir.join("x.glb");
    let cache = dir.join("x.pc2");
    let gif = dir.join("x.gif");
    let runs: [Vec<&str>; 3] = [
        vec![
            "bake",
            "--size",
            "64x64",
            "--steps",
            "4000000000",
            "--out",
            s(&out),
        ],
        vec![
            "bake",
            "--size",
            "512x512",
            "--rain",
            "100000",
            "--frames",
            "1000000",
            "--out",
            s(&cache),
        ],
        vec![
            "render",
            "--size",
            "256x256",
            "--frames",
            "100000",
            "--out",
            s(&gif),
        ],
    ];
    for args in runs {
        let child = start(&args);
        std::thread::sleep(Duration::from_millis(800));
        let asked = Instant::now();
        kill(&child, "-TERM");
        let (status, err) = finish(child);
        assert!(
            asked.elapsed() < Duration::from_secs(1),
            "{args:?}: {:?}",
            asked.elapsed()
        );
        assert_eq!(status, Some(143), "{args:?}: {err}");
        assert!(names(&dir).is_empty(), "{args:?} left {:?}", names(&dir));
    }
}

#[test]
fn ctrl_c_twice_never_leaves_an_empty_or_partial_snapshot() {
    let dir = fresh("ctrl-c-twice");
    let snap = dir.join("s.snap");
    let csv = dir.join("s.csv");
    ok(&line("simulate --size 16x16 --steps 3 --save @", &[&snap]));
    let before = std::fs::read(&snap).unwrap();
    // A large grid: writing its CSV and snapshot takes a while, so the second Ctrl-C may
    // come while they are written, or before (the steps), or after (then both are new).
    let child = start(&line(
        "simulate --size 1024x1024 --steps 1000000 --csv @ --save @",
        &[&csv, &snap],
    ));
    std::thread::sleep(Duration::from_millis(1000));
    kill(&child, "-INT");
    std::thread::sleep(Duration::from_millis(30));
    kill(&child, "-INT");
    let (status, err) = finish(child);
    assert_eq!(status, Some(130), "{err}");
    let after = std::fs::read(&snap).unwrap();
    if after != before {
        // Then it is a whole snapshot of the new run, and the CSV is complete too.
        ok(&line("simulate --load @ --steps 0", &[&snap]));
        let text = std::fs::read_to_string(&csv).unwrap();
        assert_eq!(text.lines().count(), 1 + 1024 * 1024);
    }
    for name in names(&dir) {
        assert!(name == "s.snap" || name == "s.csv", "left {name}");
    }
}

#[test]
fn a_directory_bake_replaces_the_whole_sequence() {
    let dir = fresh("sequence");
    let seq = dir.join("frames");
    ok(&line(
        "bake --size 9x9 --drop 4,4,1,1 --frames 10 --out @",
        &[&seq],
    ));
    std::fs::write(seq.join("notes.txt"), "the user's").unwrap();
    ok(&line(
        "bake --size 9x9 --drop 4,4,1,1 --frames 3 --out @",
        &[&seq],
    ));
    assert_eq!(
        names(&seq),
        [
            "notes.txt",
            "water_0001.obj",
            "water_0002.obj",
            "water_0003.obj"
        ]
    );
    // The same for render's PNG frames.
    let png = dir.join("png");
    let small = ["--size", "9x9", "--width", "16", "--height", "16"];
    let mut args = vec!["render", "--frames", "5", "--png", s(&png)];
    args.extend(small);
    ok(&args);
    let mut args = vec!["render", "--frames", "2", "--png", s(&png)];
    args.extend(small);
    ok(&args);
    assert_eq!(names(&png), ["frame_0000.png", "frame_0001.png"]);
}

#[test]
fn frame_names_past_9999_sort_in_frame_order() {
    let dir = fresh("long-sequence");
    ok(&line(
        "bake --size 2x2 --fps 60 --frames 10001 --out @",
        &[&dir],
    ));
    let all = names(&dir);
    assert_eq!(all.len(), 10001);
    assert_eq!(all[0], "water_00001.obj");
    assert_eq!(all[10000], "water_10001.obj");
    let numbers: Vec<usize> = all.iter().map(|n| n[6..11].parse().unwrap()).collect();
    assert!(numbers.windows(2).all(|w| w[1] == w[0] + 1));
}

#[test]
fn a_point_cache_does_not_overwrite_an_unrelated_obj() {
    let dir = fresh("rest-obj");
    let (cache, obj) = (dir.join("model.pc2"), dir.join("model.obj"));
    std::fs::write(&obj, "# the user's model\nv 0 0 0\n").unwrap();
    let err = refused(&line("bake --size 9x9 --frames 2 --out @", &[&cache]));
    assert!(
        err.contains("model.obj") && err.contains("not written by bake"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(&obj).unwrap(),
        "# the user's model\nv 0 0 0\n"
    );
    assert_eq!(names(&dir), ["model.obj"]);
    // Its own rest mesh it replaces.
    std::fs::remove_file(&obj).unwrap();
    ok(&line("bake --size 9x9 --frames 2 --out @", &[&cache]));
    ok(&line("bake --size 9x9 --frames 3 --out @", &[&cache]));
}

#[test]
fn an_empty_out_writes_nothing_anywhere() {
    let dir = fresh("empty-out");
    for command in ["bake", "render"] {
        let out = Command::new(env!("CARGO_BIN_EXE_springwater"))
            .args([command, "--size", "9x9", "--out", ""])
            .current_dir(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains("--out: the path is empty"), "{err}");
    }
    for flag in ["--csv", "--save"] {
        let err = refused(&["simulate", flag, ""]);
        assert!(err.contains("the path is empty"), "{err}");
    }
    assert!(names(&dir).is_empty());
}

#[test]
fn a_snapshot_with_trailing_data_is_refused() {
    let dir = fresh("trailing");
    let snap = dir.join("s.snap");
    ok(&line("simulate --size 8x8 --steps 2 --save @", &[&snap]));
    let mut bytes = std::fs::read(&snap).unwrap();
    bytes.extend_from_slice(b"junk");
    std::fs::write(&snap, &bytes).unwrap();
    let err = refused(&line("simulate --load @ --steps 1", &[&snap]));
    assert!(err.contains("trailing data"), "{err}");
}

#[test]
fn outputs_that_collide_are_refused_before_any_step() {
    let dir = fresh("collide");
    let same = dir.join("same");
    let err = refused(&line(
        "simulate --steps 4000000000 --csv @ --save @",
        &[&same, &same],
    ));
    assert!(
        err.contains("--csv") && err.contains("--save") && err.contains("same file"),
        "{err}"
    );
    // Through another spelling of the same path.
    let other = dir.join(".").join("same");
    let err = refused(&line(
        "simulate --steps 4000000000 --csv @ --save @",
        &[&same, &other],
    ));
    assert!(err.contains("same file"), "{err}");
    // The CSV may not replace the snapshot it loads.
    ok(&line("simulate --size 8x8 --steps 1 --save @", &[&same]));
    let err = refused(&line("simulate --load @ --csv @", &[&same, &same]));
    assert!(err.contains("same file"), "{err}");
    assert_eq!(names(&dir), ["same"]);
}

#[test]
fn a_link_stays_a_link_and_a_replaced_file_keeps_its_mode() {
    use std::os::unix::fs::PermissionsExt;
    let dir = fresh("link");
    let (real, link) = (dir.join("real.csv"), dir.join("link.csv"));
    std::fs::write(&real, "old\n").unwrap();
    std::fs::set_permissions(&real, std::fs::Permissions::from_mode(0o640)).unwrap();
    std::os::unix::fs::symlink("real.csv", &link).unwrap();
    ok(&line("simulate --size 3x3 --steps 1 --csv @", &[&link]));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    let text = std::fs::read_to_string(&real).unwrap();
    assert!(text.starts_with("col,row,x,y,z\n"), "{text}");
    let mode = std::fs::metadata(&real).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o640);
    assert_eq!(names(&dir), ["link.csv", "real.csv"]);
}

#[test]
fn stdout_as_a_path_takes_the_csv() {
    let out = springwater(&[
        "simulate",
        "--size",
        "3x3",
        "--steps",
        "1",
        "--csv",
        "/dev/stdout",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("col,row,x,y,z\n0,0,0,0,0\n"), "{text}");
    assert!(text.contains("wrote /dev/stdout"), "{text}");
}
