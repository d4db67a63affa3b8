//! `springwater render`: reproducible files (seed, threads, one or two drawing passes), PNG
//! frames and bottoms, and one-line errors for bad flags and files.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn springwater(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_springwater"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// The small animation the determinism checks compare, with every moving part on (rain
/// from `seed`, the wake, an orbiting camera, the wireframe), written to `out`.
fn animation<'a>(seed: &'a str, out: &'a std::path::Path, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "render",
        "--size",
        "48x48",
        "--frames",
        "6",
        "--width",
        "96",
        "--height",
        "72",
        "--rain",
        "48",
        "--seed",
        seed,
        "--wake",
        "--orbit",
        "60",
        "--wireframe",
    ];
    args.extend_from_slice(extra);
    args.extend(["--out", out.to_str().unwrap()]);
    args
}

/// A fresh empty directory under the target directory, unique to `name`.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("render-tests")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_same_seed_gives_the_same_file_and_another_seed_another() {
    let dir = scratch("seed");
    let run = |name: &str, seed: &str| {
        let out = dir.join(name);
        let o = springwater(&animation(seed, &out, &[]));
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read(out).unwrap()
    };
    let a = run("a.gif", "5");
    let b = run("b.gif", "5");
    let c = run("c.gif", "6");
    assert!(a.starts_with(b"GIF89a"));
    assert_eq!(a, b, "same seed, different bytes");
    assert_ne!(a, c, "another seed gave the same file");
    // Thread count changes nothing either.
    let one = dir.join("one.gif");
    let o = springwater(&animation("5", &one, &["--threads", "1"]));
    assert!(o.status.success());
    assert_eq!(
        a,
        std::fs::read(one).unwrap(),
        "one thread gave different bytes"
    );
    // Nor does drawing the animation twice (once for the palette, once to encode), the
    // way animations too large to keep in memory are written.
    let twice = dir.join("twice.gif");
    let o = Command::new(env!("CARGO_BIN_EXE_springwater"))
        .env("SPRINGWATER_KEEP_FRAMES_BYTES", "1000")
        .args(animation("5", &twice, &[]))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("twice"));
    assert_eq!(
        a,
        std::fs::read(twice).unwrap(),
        "two passes gave different bytes"
    );
}

#[test]
fn png_frames_and_a_png_bottom_work() {
    let dir = scratch("png");
    // A 4×4 checkerboard PNG as the bottom.
    let bottom = dir.join("checker.png");
    common::grey_png(&bottom, 4, 4, |r| {
        (0..4)
            .map(|c| if (c + r) % 2 == 0 { 255 } else { 0 })
            .collect()
    });
    let frames = dir.join("frames");
    let o = springwater(&[
        "render",
        "--size",
        "32x32",
        "--frames",
        "3",
        "--width",
        "64",
        "--height",
        "48",
        "--bottom",
        bottom.to_str().unwrap(),
        "--png",
        frames.to_str().unwrap(),
        "--wireframe",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for stage in ["simulation", "normals", "LOD", "refraction", "drawing"] {
        assert!(
            stdout.contains(stage),
            "the summary does not mention {stage}: {stdout}"
        );
    }
    for k in 0..3 {
        let path = frames.join(format!("frame_{k:04}.png"));
        let decoder =
            png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
        let info = decoder.read_info().unwrap().info().clone();
        assert_eq!((info.width, info.height), (64, 48));
    }
}

#[test]
fn bad_flags_and_files_get_one_line_errors() {
    let dir = scratch("errors");
    let garbage = dir.join("not-a.png");
    std::fs::write(&garbage, b"this is not a PNG file").unwrap();
    let gif = dir.join("x.gif");
    let gif = gif.to_str().unwrap();
    let missing = dir.join("missing.png");
    let unwritable = dir.join("no-such-dir").join("x.gif");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["render"], "--out"),
        (vec!["render", "--frames", "abc", "--out", gif], "--frames"),
        (vec!["render", "--frames", "0", "--out", gif], "--frames"),
        (vec!["render", "--width", "-3", "--out", gif], "--width"),
        (vec!["render", "--eye", "1,2", "--out", gif], "--eye"),
        (vec!["render", "--eye", "1,nan,3", "--out", gif], "--eye"),
        (vec!["render", "--depth", "0", "--out", gif], "--depth"),
        (vec!["render", "--rain", "-1", "--out", gif], "--rain"),
        (vec!["render", "--bogus", "--out", gif], "--bogus"),
        (
            vec![
                "render",
                "--eye",
                "10,10,10",
                "--look-at",
                "10,10,10",
                "--out",
                gif,
            ],
            "look-at",
        ),
        (
            vec![
                "render",
                "--bottom",
                missing.to_str().unwrap(),
                "--out",
                gif,
            ],
            "missing.png",
        ),
        (
            vec![
                "render",
                "--bottom",
                garbage.to_str().unwrap(),
                "--out",
                gif,
            ],
            "not-a.png",
        ),
        (
            vec!["render", "--out", unwritable.to_str().unwrap()],
            "x.gif",
        ),
        (vec!["render", "--dt", "0.6", "--out", gif], "timestep"),
        (vec!["render", "--boats", "-1", "--out", gif], "--boats"),
        (vec!["render", "--boats", "two", "--out", gif], "--boats"),
        (
            vec!["render", "--size", "32x32", "--boats", "5", "--out", gif],
            "room for 4 boats",
        ),
        (
            vec!["render", "--boats", "99999999999999999999", "--out", gif],
            "--boats",
        ),
        (
            vec!["render", "--boats", "2", "--follow", "--out", gif],
            "--follow",
        ),
    ];
    for (args, mention) in cases {
        let o = springwater(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} succeeded");
        assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
        assert_eq!(
            stderr.trim_end().lines().count(),
            1,
            "{args:?}: not one line: {stderr}"
        );
        assert!(
            stderr.starts_with("springwater: error:"),
            "{args:?}: {stderr}"
        );
        assert!(
            stderr.contains(mention),
            "{args:?}: the error does not mention {mention}: {stderr}"
        );
    }
    // A simulation that fails part-way reports the step and leaves no truncated GIF.
    let broken = dir.join("broken.gif");
    let o = springwater(&[
        "render",
        "--size",
        "32x32",
        "--frames",
        "3",
        "--drop",
        "16,16,-1e30,1",
        "--out",
        broken.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && stderr.contains("non-finite"),
        "{stderr}"
    );
    assert!(
        !broken.exists(),
        "a failed render left {}",
        broken.display()
    );
}

#[test]
fn rain_falls_per_second() {
    // 60 warm-up steps and 40 frames of 3 steps: 180 steps of 1/60 s, 3 seconds. At 60
    // drops a second about 180 fall (a Poisson count: 5 standard deviations either side);
    // a rate per unit of model time would make it 24 times as many.
    let dir = scratch("rain-per-second");
    let gif = dir.join("rain.gif");
    let out = springwater(&[
        "render",
        "--size",
        "48x48",
        "--frames",
        "40",
        "--width",
        "64",
        "--height",
        "48",
        "--rain",
        "60",
        "--out",
        gif.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(
        report.contains("3 steps per frame after 60 warm-up steps"),
        "{report}"
    );
    let drops: f64 = report
        .split("disturbances: ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no raindrop count in {report}"));
    let (mean, sd) = (180.0, 180f64.sqrt());
    assert!(
        (drops - mean).abs() < 5.0 * sd,
        "{drops} raindrops in 3 s at 60 a second"
    );
}

#[test]
fn boats_float_pitch_and_roll_and_are_drawn() {
    let dir = scratch("boats");
    let run = |boats: &str| {
        let (gif, png) = (dir.join(format!("{boats}.gif")), dir.join(boats));
        let o = springwater(&[
            "render",
            "--size",
            "64x64",
            "--frames",
            "4",
            "--width",
            "240",
            "--height",
            "180",
            "--rain",
            "20",
            "--boats",
            boats,
            "--out",
            gif.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
        ]);
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let bytes = std::fs::read(&gif).unwrap();
        assert!(bytes.starts_with(b"GIF89a"), "not a GIF");
        // Every frame's pixels, one after the other.
        let mut pixels = Vec::new();
        for k in 0..4 {
            let file = std::fs::File::open(png.join(format!("frame_{k:04}.png"))).unwrap();
            let mut reader = png::Decoder::new(std::io::BufReader::new(file))
                .read_info()
                .unwrap();
            let mut frame = vec![0; reader.output_buffer_size().unwrap()];
            reader.next_frame(&mut frame).unwrap();
            pixels.extend(frame);
        }
        (stdout, pixels)
    };
    let (report, with) = run("3");
    let (_, without) = run("0");
    // "boats        3 boats, heeling up to H° and trimming up to T°"
    let line = report
        .lines()
        .find(|l| l.starts_with("boats "))
        .unwrap_or_else(|| panic!("no boats line in {report}"));
    assert!(line.contains("3 boats"), "{line}");
    let degrees: Vec<f32> = line
        .split(' ')
        .filter_map(|w| w.strip_suffix('°'))
        .map(|w| w.parse().unwrap())
        .collect();
    assert_eq!(degrees.len(), 2, "{line}");
    // The rain rocks them: more than a degree either way, and not capsized.
    assert!(
        degrees.iter().all(|&d| d > 1.0 && d < 60.0),
        "heel and trim {degrees:?}"
    );
    // The hulls are drawn: the first boat's topsides are red, a colour nothing else in
    // the picture has (water, sky, paving).
    let red = |rgb: &[u8]| {
        rgb.chunks_exact(3)
            .filter(|p| p[0] > 100 && p[0] / 2 > p[1] && p[0] / 2 > p[2])
            .count()
    };
    assert_eq!(red(&without), 0, "red without boats");
    assert!(red(&with) >= 40, "{} red pixels in 4 frames", red(&with));
}
