//! The second round of hostile cases (issue 46): what a lying file, a machine short of
//! memory, a colliding or dangling output path and a limit found only after the work did to
//! the command line, each now refused at once with one line (or done as asked).

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::*;

/// A fresh, empty directory for one test.
fn fresh(name: &str) -> PathBuf {
    common::fresh("hostile", name)
}

/// A PNG whose header claims `width` × `height` RGB pixels, with an empty image stream.
fn lying_png(path: &Path, width: u32, height: u32) {
    let file = std::fs::File::create(path).unwrap();
    let mut encoder = png::Encoder::new(file, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    // An empty zlib stream: the header is all there is.
    let empty = [0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01];
    writer.write_chunk(png::chunk::IDAT, &empty).unwrap();
}

/// `springwater args` in a shell whose address space is limited to `kib` KiB (`ulimit -v`);
/// None where there is no `sh`.
fn under_ulimit(kib: u64, args: &[&str]) -> Option<std::process::Output> {
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {kib} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_springwater"))
        .args(args)
        .output()
        .ok()
}

/// A refusal under a memory limit: exit 2 and one line on stderr, no abort.
fn refused_under(kib: u64, args: &[&str]) -> Option<String> {
    let out = under_ulimit(kib, args)?;
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(
        out.status.code(),
        Some(2),
        "{args:?}: {:?} {err}",
        out.status
    );
    assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    Some(err)
}

#[test]
fn a_png_whose_header_lies_is_refused_from_its_header() {
    let dir = fresh("lying-png");
    let lie = dir.join("lie.png");
    lying_png(&lie, 60000, 60000);
    assert!(std::fs::metadata(&lie).unwrap().len() < 200);
    let gif = dir.join("out.gif");
    let args = [
        "render",
        "--size",
        "16x16",
        "--frames",
        "1",
        "--bottom",
        s(&lie),
        "--out",
        s(&gif),
    ];
    // Under a limit smaller than the 10.8 GB the header claims: refused, not aborted.
    let err = refused_under(4_000_000, &args).unwrap_or_else(|| refused(&args));
    assert!(err.contains("60000") && err.contains("16384"), "{err}");
    assert_eq!(names(&dir), ["lie.png"]);
}

#[test]
fn a_png_wider_than_the_renderer_takes_is_refused_before_decoding() {
    let dir = fresh("wide-png");
    let wide = dir.join("wide.png");
    // A real image, 16385 × 2 grey pixels.
    common::grey_png(&wide, 16385, 2, |_| vec![128u8; 16385]);
    let gif = dir.join("out.gif");
    let err = refused(&[
        "render",
        "--size",
        "16x16",
        "--frames",
        "1",
        "--bottom",
        s(&wide),
        "--out",
        s(&gif),
    ]);
    assert!(
        err.contains("--bottom") && err.contains("16385") && err.contains("16384"),
        "{err}"
    );
}

#[test]
fn a_decompression_bomb_is_refused_before_decoding() {
    let dir = fresh("bomb");
    let bomb = dir.join("bomb.png");
    // 16384 × 16384 grey pixels, all the same: a few hundred KB that decode to 4 GB of
    // texture.
    common::grey_png(&bomb, 16384, 16384, |_| vec![7u8; 16384]);
    assert!(std::fs::metadata(&bomb).unwrap().len() < 4 << 20);
    let gif = dir.join("out.gif");
    let args = [
        "render",
        "--size",
        "16x16",
        "--frames",
        "1",
        "--bottom",
        s(&bomb),
        "--out",
        s(&gif),
    ];
    let Some(err) = refused_under(2_000_000, &args) else {
        return;
    };
    assert!(err.contains("--bottom") && err.contains("memory"), "{err}");
    assert_eq!(names(&dir), ["bomb.png"]);
}

#[test]
fn bench_and_render_past_the_memory_there_is_are_refused_not_aborted() {
    let dir = fresh("memory");
    let gif = dir.join("max.gif");
    // 2 GB of address space; a 4096 × 4096 grid takes 1 GB a surface.
    let Some(err) = refused_under(
        2_000_000,
        &[
            "bench",
            "--size",
            "4096x4096",
            "--steps",
            "1",
            "--repeats",
            "1",
        ],
    ) else {
        return;
    };
    assert!(err.contains("memory") && err.contains("--size"), "{err}");
    let err = refused_under(
        2_000_000,
        &[
            "render",
            "--size",
            "4096x4096",
            "--frames",
            "1",
            "--steps",
            "0",
            "--substeps",
            "0",
            "--out",
            s(&gif),
        ],
    )
    .unwrap();
    assert!(err.contains("memory") && err.contains("--size"), "{err}");
    assert!(names(&dir).is_empty(), "{:?}", names(&dir));
}

#[test]
fn a_snapshot_too_large_to_load_is_refused_before_it_is_read() {
    // `bake --load` of a real 2048 x 2048 snapshot (323 MB) under an 800 MB limit aborted
    // while loading ("memory allocation of 16777216 bytes failed", exit 134): loading holds
    // the file, the decoded snapshot and the surface at once, more than the bake needs
    // after it. The file's length bounds its grid, so that memory is asked for before the
    // file is read; a sparse file of that length (nothing on disk) shows it.
    let dir = fresh("load-memory");
    let snap = dir.join("big.snap");
    let file = std::fs::File::create(&snap).unwrap();
    file.set_len(196 + 77 * 2048 * 2048).unwrap();
    let out = dir.join("big.pc2");
    let bake = [
        "bake",
        "--load",
        s(&snap),
        "--frames",
        "1",
        "--out",
        s(&out),
    ];
    let Some(err) = refused_under(800_000, &bake) else {
        return;
    };
    assert!(err.contains("--load") && err.contains("memory"), "{err}");
    let simulate = ["simulate", "--load", s(&snap), "--steps", "1"];
    let err = refused_under(800_000, &simulate).unwrap();
    assert!(err.contains("--load") && err.contains("memory"), "{err}");
    assert_eq!(names(&dir), ["big.snap"]);
}

#[test]
fn two_outputs_of_render_on_one_path_are_refused_before_any_work() {
    let dir = fresh("same-path");
    let same = dir.join("same.gif");
    let err = refused(&[
        "render",
        "--size",
        "16x16",
        "--frames",
        "2",
        "--out",
        s(&same),
        "--png",
        s(&same),
    ]);
    assert!(err.contains("--out") && err.contains("--png"), "{err}");
    assert!(names(&dir).is_empty(), "{:?}", names(&dir));
    // Through a symbolic link too.
    #[cfg(unix)]
    {
        let link = dir.join("link.gif");
        std::os::unix::fs::symlink("same.gif", &link).unwrap();
        let err = refused(&[
            "render",
            "--size",
            "16x16",
            "--frames",
            "2",
            "--out",
            s(&link),
            "--png",
            s(&same),
        ]);
        assert!(err.contains("same file"), "{err}");
        assert_eq!(names(&dir), ["link.gif"]);
    }
}

#[cfg(unix)]
#[test]
fn a_point_cache_and_its_rest_mesh_on_one_path_are_refused() {
    let dir = fresh("same-rest");
    let (pc2, obj) = (dir.join("out.pc2"), dir.join("out.obj"));
    std::os::unix::fs::symlink("both", &pc2).unwrap();
    std::os::unix::fs::symlink("both", &obj).unwrap();
    let err = refused(&["bake", "--size", "8x8", "--frames", "2", "--out", s(&pc2)]);
    assert!(err.contains("same file"), "{err}");
    assert_eq!(names(&dir), ["out.obj", "out.pc2"]);
}

#[cfg(unix)]
#[test]
fn a_dangling_link_is_written_through() {
    let dir = fresh("dangling");
    let glb = dir.join("out.glb");
    std::os::unix::fs::symlink("missing.glb", &glb).unwrap();
    ok(&["bake", "--size", "8x8", "--frames", "2", "--out", s(&glb)]);
    assert!(std::fs::symlink_metadata(&glb)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::metadata(dir.join("missing.glb"))
        .unwrap()
        .is_file());
    // The rest OBJ beside a point cache, and the cache, both through links.
    let (pc2, obj) = (dir.join("out.pc2"), dir.join("out.obj"));
    std::os::unix::fs::symlink("cache.pc2", &pc2).unwrap();
    std::os::unix::fs::symlink("rest.obj", &obj).unwrap();
    ok(&["bake", "--size", "8x8", "--frames", "2", "--out", s(&pc2)]);
    for (link, target) in [(&pc2, "cache.pc2"), (&obj, "rest.obj")] {
        assert!(std::fs::symlink_metadata(link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert!(std::fs::metadata(dir.join(target)).unwrap().is_file());
    }
    assert_eq!(
        names(&dir),
        [
            "cache.pc2",
            "missing.glb",
            "out.glb",
            "out.obj",
            "out.pc2",
            "rest.obj"
        ]
    );
    // A link whose target's directory does not exist: one line naming the path.
    let lost = dir.join("lost.glb");
    std::os::unix::fs::symlink("nowhere/x.glb", &lost).unwrap();
    let err = refused(&["bake", "--size", "8x8", "--frames", "2", "--out", s(&lost)]);
    assert!(
        err.contains("lost.glb")
            && err.contains("does not exist")
            && !err.contains("springwater-tmp"),
        "{err}"
    );
}

#[test]
fn a_glb_too_large_is_refused_before_the_grid_is_built() {
    let dir = fresh("glb-limit");
    let glb = dir.join("max.glb");
    // 1 GB of address space: too little for the 4 GB grid, plenty for the refusal.
    let args = [
        "bake",
        "--size",
        "8192x8192",
        "--frames",
        "1",
        "--out",
        s(&glb),
    ];
    let err = refused_under(1_000_000, &args).unwrap_or_else(|| refused(&args));
    assert!(err.contains("4 GiB") && err.contains(".pc2"), "{err}");
    assert!(names(&dir).is_empty());
}

#[test]
fn floaters_on_a_wide_grid_are_sized_to_what_the_water_carries() {
    let dir = fresh("wide-floaters");
    let gif = dir.join("out.gif");
    let report = ok(&[
        "render",
        "--size",
        "1400x1400",
        "--floaters",
        "1",
        "--frames",
        "1",
        "--steps",
        "0",
        "--substeps",
        "0",
        "--width",
        "16",
        "--height",
        "16",
        "--out",
        s(&gif),
    ]);
    assert!(report.contains("floaters     1 ball"), "{report}");
}
#[test]
fn names_as_long_as_the_system_allows_are_written() {
    let dir = fresh("long-names");
    // 255 bytes, the most a file name may have on common file systems.
    let glb = dir.join(format!("{}.glb", "g".repeat(251)));
    ok(&["bake", "--size", "8x8", "--frames", "2", "--out", s(&glb)]);
    let pc2 = dir.join(format!("{}.pc2", "p".repeat(251)));
    ok(&["bake", "--size", "8x8", "--frames", "2", "--out", s(&pc2)]);
    let csv = dir.join(format!("{}.csv", "c".repeat(251)));
    ok(&[
        "simulate",
        "--size",
        "8x8",
        "--steps",
        "2",
        "--csv",
        s(&csv),
    ]);
    let obj = pc2.with_extension("obj");
    let mut want: Vec<String> = [&glb, &pc2, &obj, &csv]
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    want.sort();
    assert_eq!(names(&dir), want);
}

/// A snapshot of a calm 8 × 8 pool whose step counter and model time are changed.
fn snapshot_with(path: &Path, steps: u64, model_time: f64) {
    let surface = springwater::Surface::new(springwater::Params::with_size(8, 8)).unwrap();
    let mut snap = surface.snapshot();
    snap.steps = steps;
    snap.model_time = model_time;
    let bytes = springwater::Surface::from_snapshot(snap)
        .unwrap()
        .to_bytes();
    std::fs::write(path, bytes).unwrap();
}

#[test]
fn impossible_snapshot_counts_and_endless_runs_are_refused() {
    let dir = fresh("counts");
    // A step counter that more steps would wrap: refused, not "steps 2" after 3 steps.
    let snap = dir.join("late.snap");
    snapshot_with(&snap, u64::MAX - 1, 0.0);
    let err = refused(&["simulate", "--load", s(&snap), "--steps", "3"]);
    assert!(err.contains("--steps 1 or fewer"), "{err}");
    let report = ok(&["simulate", "--load", s(&snap), "--steps", "1"]);
    assert!(report.contains(&u64::MAX.to_string()), "{report}");
    // A model time of 1e308 is printed in a few characters, not three hundred digits.
    let old = dir.join("old.snap");
    snapshot_with(&old, 5, 1e308);
    let report = ok(&["simulate", "--load", s(&old), "--steps", "0"]);
    let line = report.lines().find(|l| l.starts_with("steps")).unwrap();
    assert!(line.len() < 80 && line.contains("1.000e308"), "{line}");
    // --steps and bench --repeats have a cap like --frames and --substeps.
    let err = refused(&[
        "simulate",
        "--size",
        "8x8",
        "--steps",
        "18446744073709551615",
    ]);
    assert!(
        err.contains("--steps") && err.contains("10000000000"),
        "{err}"
    );
    let err = refused(&[
        "bench",
        "--size",
        "8x8",
        "--repeats",
        "18446744073709551615",
    ]);
    assert!(err.contains("--repeats") && err.contains("10000"), "{err}");
}

#[test]
fn a_snapshot_whose_clock_owes_ages_is_refused_before_the_bake() {
    let dir = fresh("owed");
    let snap = dir.join("owed.snap");
    let surface = springwater::Surface::new(springwater::Params::with_size(8, 8)).unwrap();
    let mut state = surface.snapshot();
    state.owed_time = 1e300;
    let bytes = springwater::Surface::from_snapshot(state)
        .unwrap()
        .to_bytes();
    std::fs::write(&snap, bytes).unwrap();
    let glb = dir.join("out.glb");
    let err = refused(&[
        "bake",
        "--load",
        s(&snap),
        "--frames",
        "2",
        "--out",
        s(&glb),
    ]);
    // Not advice the user cannot take (--dt is refused next to --load).
    assert!(
        err.contains("--load") && err.contains("owes") && !err.contains("--dt"),
        "{err}"
    );
    assert_eq!(names(&dir), ["owed.snap"]);
}

#[test]
fn messages_name_what_the_user_gave() {
    // An empty --load names the flag, not "cannot read : No such file".
    let err = refused(&["simulate", "--load", ""]);
    assert!(err.contains("--load") && err.contains("empty"), "{err}");
    // A count too large for the machine is still a count, refused for want of room.
    let err = refused(&[
        "render",
        "--boats",
        "18446744073709551615",
        "--out",
        "x.gif",
    ]);
    assert!(
        err.contains("room for") && !err.contains("not a valid"),
        "{err}"
    );
    let err = refused(&["render", "--boats", "-1", "--out", "x.gif"]);
    assert!(err.contains("0 or more"), "{err}");
    // A directory the system will not write in: the error names the user's path only.
    if std::path::Path::new("/sys").is_dir() {
        let err = refused(&["simulate", "--size", "8x8", "--csv", "/sys/out.csv"]);
        assert!(
            err.contains("/sys/out.csv") && !err.contains("springwater-tmp"),
            "{err}"
        );
    }
}

#[test]
fn the_spacing_suggested_is_one_that_is_taken() {
    for size in ["16x16", "128x128", "3x1000"] {
        let err = refused(&["simulate", "--size", size, "--spacing", "6.6666667e13"]);
        let most = err
            .split("use --spacing ")
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .unwrap_or_else(|| panic!("{err}"));
        assert_ne!(most, "6.6666667e13", "{err}");
        ok(&[
            "simulate",
            "--size",
            size,
            "--spacing",
            most,
            "--steps",
            "0",
        ]);
    }
    // A spacing too small for the camera to frame the grid names --spacing, not the
    // --look-at nobody gave.
    let err = refused(&["render", "--spacing", "1e-30", "--out", "x.gif"]);
    assert!(
        err.contains("--spacing 1e-30") && !err.contains("--look-at:"),
        "{err}"
    );
}

#[test]
fn what_was_accepted_silently_is_refused() {
    let dir = fresh("silent");
    let snap = dir.join("a.snap");
    ok(&[
        "simulate",
        "--size",
        "8x8",
        "--steps",
        "1",
        "--save",
        s(&snap),
    ]);
    // A flag that takes one value, given twice: the second no longer silently wins.
    let err = refused(&["simulate", "--load", s(&snap), "--load", s(&snap)]);
    assert!(err.contains("--load") && err.contains("twice"), "{err}");
    let err = refused(&[
        "render", "--size", "8x8", "--size", "16x16", "--out", "x.gif",
    ]);
    assert!(err.contains("--size") && err.contains("twice"), "{err}");
    // --drop and --floater add up, as they always did.
    ok(&[
        "simulate", "--size", "8x8", "--drop", "2,2,1,2", "--drop", "5,5,1,2",
    ]);
    // A drop wholly outside the grid would change nothing.
    let err = refused(&["simulate", "--size", "8x8", "--drop", "1000,4,1,2"]);
    assert!(
        err.contains("--drop 1000,4,1,2") && err.contains("outside"),
        "{err}"
    );
    ok(&["simulate", "--size", "8x8", "--drop", "10,4,1,2"]);
    // `dir/.glb` is a hidden name with no extension, not a directory of OBJ frames.
    let hidden = dir.join(".glb");
    let err = refused(&[
        "bake",
        "--size",
        "8x8",
        "--frames",
        "2",
        "--out",
        s(&hidden),
    ]);
    assert!(err.contains(".glb") && err.contains("name"), "{err}");
    assert_eq!(names(&dir), ["a.snap"]);
}

#[test]
fn a_timestep_error_names_the_flag_that_caused_it() {
    // --dt was not given: the flag that made the default timestep too long is named, and
    // the --dt suggested is taken.
    let err = refused(&["simulate", "--mass", "0.01"]);
    assert!(
        err.contains("--mass 0.01:") && !err.contains("--dt:"),
        "{err}"
    );
    let dt = err
        .split("for example ")
        .nth(1)
        .and_then(|rest| rest.split(')').next())
        .unwrap_or_else(|| panic!("{err}"));
    ok(&["simulate", "--mass", "0.01", "--dt", dt, "--steps", "1"]);
    // Given --dt too long is still --dt's fault.
    let err = refused(&["simulate", "--dt", "5"]);
    assert!(err.contains("--dt"), "{err}");
}

#[test]
fn a_floater_too_large_is_told_in_one_unit() {
    // The size in world units and the limit in cells were mixed ("size = 200 ... at most 64
    // grid cells across"): now the radius given, in cells, and the largest radius taken.
    let err = refused(&["simulate", "--spacing", "0.5", "--floater", "10,10,1,100"]);
    assert!(
        err.contains("200 cells") && err.contains("radius of 16 or less"),
        "{err}"
    );
    ok(&[
        "simulate",
        "--spacing",
        "0.5",
        "--floater",
        "30,30,1,16",
        "--steps",
        "1",
    ]);
}
