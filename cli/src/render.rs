//! `springwater render`: the water as an animated GIF (and/or PNG frames).

use crate::args::{
    count, lib_error, list, next_flag, positive, ranged, string, unexpected, value, CliResult,
    Flag, ModelArgs, Short,
};
use crate::boats;
use crate::image::{read_png, write_png, GifWriter, Histogram, Palette};
use crate::output::{self, Output, Pending};
use lexopt::Parser;
use springwater::disturb::{Disturbance, Rain, Wake};
use springwater::render::{Ball, Camera, RenderParams, Renderer, StageTimes, Texture};
use springwater::{Shape, Surface};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Raindrops per second by default: 0.3 per unit of model time at the default time scale of
/// 24.
const DEFAULT_RAIN: f32 = 7.2;

/// The render command's options beyond the model flags.
#[derive(Debug, Clone)]
struct Options {
    frames: usize,
    substeps: usize,
    fps: f32,
    eye: Option<[f32; 3]>,
    look_at: Option<[f32; 3]>,
    fov: f32,
    width: u32,
    height: u32,
    bottom: Option<PathBuf>,
    depth: f32,
    ior: f32,
    caustics: f32,
    lod_pixels: f32,
    rain: f32,
    seed: u64,
    wake: bool,
    follow: bool,
    floaters: usize,
    boats: usize,
    wireframe: bool,
    orbit: f32,
    out: Option<PathBuf>,
    png: Option<PathBuf>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            frames: 72,
            substeps: 3,
            fps: 20.0,
            eye: None,
            look_at: None,
            fov: 45.0,
            width: 400,
            height: 300,
            bottom: None,
            depth: 8.0,
            ior: 1.333,
            caustics: 1.3,
            lod_pixels: 1.5,
            rain: DEFAULT_RAIN,
            seed: 1,
            wake: false,
            follow: false,
            floaters: 0,
            boats: 0,
            wireframe: false,
            orbit: 0.0,
            out: None,
            png: None,
        }
    }
}

/// Steps run before the first frame when `--steps` is not given: the rain has started.
const WARM_UP_STEPS: u64 = 60;

pub fn run(p: &mut Parser) -> CliResult<()> {
    let mut model = ModelArgs {
        steps: WARM_UP_STEPS,
        ..ModelArgs::default()
    };
    let mut o = Options::default();
    while let Some(arg) = next_flag(p)? {
        if model.parse_flag(&arg, p)? {
            continue;
        }
        let Flag::Long(name) = &arg else {
            return Err(unexpected(arg, "render"));
        };
        match name.as_str() {
            "frames" => o.frames = ranged(value(p, "--frames")?, 1, 100_000, "--frames")?,
            "substeps" => o.substeps = ranged(value(p, "--substeps")?, 0, 10_000, "--substeps")?,
            "fps" => o.fps = positive(value(p, "--fps")?, "--fps")?,
            "eye" => o.eye = Some(list(&string(p, "--eye")?, "--eye X,Y,Z")?),
            "look-at" => o.look_at = Some(list(&string(p, "--look-at")?, "--look-at X,Y,Z")?),
            "fov" => o.fov = value(p, "--fov")?,
            "width" => o.width = ranged(value(p, "--width")?, 16, 4096, "--width")?,
            "height" => o.height = ranged(value(p, "--height")?, 16, 4096, "--height")?,
            "bottom" => o.bottom = Some(string(p, "--bottom")?.into()),
            "depth" => o.depth = positive(value(p, "--depth")?, "--depth")?,
            "ior" => o.ior = value(p, "--ior")?,
            "caustics" => o.caustics = value(p, "--caustics")?,
            "lod-pixels" => o.lod_pixels = positive(value(p, "--lod-pixels")?, "--lod-pixels")?,
            "rain" => o.rain = value(p, "--rain")?,
            "seed" => o.seed = value(p, "--seed")?,
            "wake" => o.wake = true,
            "follow" => o.follow = true,
            "floaters" => o.floaters = ranged(value(p, "--floaters")?, 0, 1000, "--floaters")?,
            "boats" => {
                // Wider than any count, so a number too large for one is still a number
                // (refused below for want of room), and a negative one is told apart.
                let n: i128 = value(p, "--boats")?;
                if n < 0 {
                    return Err(format!("--boats: {n} is not a number of boats (0 or more)"));
                }
                o.boats = usize::try_from(n).unwrap_or(usize::MAX);
            }
            "wireframe" => o.wireframe = true,
            "orbit" => o.orbit = value(p, "--orbit")?,
            "out" => o.out = Some(string(p, "--out")?.into()),
            "png" => o.png = Some(string(p, "--png")?.into()),
            _ => return Err(unexpected(arg, "render")),
        }
    }
    if !(o.orbit.is_finite() && o.orbit.abs() <= 3600.0) {
        return Err(format!(
            "--orbit: {} is not an angle in degrees between -3600 and 3600",
            Short(o.orbit)
        ));
    }
    if o.out.is_none() && o.png.is_none() {
        return Err("render needs --out FILE.gif or --png DIR (or both)".into());
    }
    if let Some(out) = &o.out {
        output::non_empty(out, "--out")?;
        let gif = out
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("gif"));
        if !gif && !output::is_stream(out) {
            return Err(format!(
                "--out {}: render writes a GIF, and the name does not end in .gif \
                 (for PNG frames use --png DIR)",
                out.display()
            ));
        }
    }
    if let (Some(out), Some(png)) = (&o.out, &o.png) {
        output::distinct(&[("--out", out), ("--png", png)])?;
    }
    if o.follow && o.wake {
        return Err(
            "--follow and --wake cannot be combined: --follow draws its own ball and wake \
             crossing open water; --wake draws one circling the pool"
                .into(),
        );
    }
    // A GIF counts frame times in hundredths of a second, from 2 (what viewers show) to
    // 65535 (0.0016 fps is 62500).
    let (lo, hi) = (0.0016, 50.0);
    if !(o.fps >= lo && o.fps <= hi) {
        return Err(format!(
            "--fps must be between {} and {} (a GIF frame lasts 2 to 62500 hundredths of a \
             second), got {}",
            Short(lo),
            Short(hi),
            Short(o.fps)
        ));
    }
    if !(o.rain.is_finite() && o.rain >= 0.0) {
        return Err(format!(
            "--rain: {} is not a rate >= 0 (drops per second)",
            Short(o.rain)
        ));
    }
    if !(o.ior.is_finite() && o.ior >= 1.0) {
        return Err(format!(
            "--ior: {} is not an index of refraction >= 1",
            Short(o.ior)
        ));
    }
    if !(o.caustics.is_finite() && o.caustics >= 0.0) {
        return Err(format!(
            "--caustics: {} is not a strength >= 0",
            Short(o.caustics)
        ));
    }

    if o.follow && o.boats > 0 {
        return Err(
            "--follow and --boats cannot be combined: the boats keep to the pool, and \
             --follow moves the window away from it"
                .into(),
        );
    }

    // Two surfaces (this one, which checks what the library refuses, and the animation's)
    // and the renderer's nodes: 233 bytes a node measured on 2048 x 2048; and the frames
    // kept for the GIF's palette.
    let kept = (o.width as u64 * o.height as u64 * 3 * o.frames as u64).min(KEEP_FRAMES_BYTES);
    crate::memory::check_grid(&model.params, 240, kept, "render")?;
    // Validates the model and the drops before anything is opened.
    let mut surface = model.surface()?;
    crate::start::check_rain(o.rain, &surface)?;
    let room = boats::room(&surface);
    if o.boats > room {
        let p = surface.params();
        return Err(format!(
            "--boats {}: a {}x{} grid has room for {}; each boat keeps to a square {} \
             cells wide; use fewer boats or a larger --size",
            o.boats,
            p.cols,
            p.rows,
            count(room as u64, "boat"),
            boats::berth_cells()
        ));
    }
    // The balls and boats go on this surface too, in the animation's order, so what the
    // library refuses about them (the timestep the water under them needs) is refused
    // before the renderer is built or any output is started.
    add_balls(&mut surface, o.floaters)?;
    if o.boats > 0 {
        boats::Fleet::launch(&mut surface, o.boats)?;
    }
    let params = *surface.params();
    let mut camera = Camera::framing(params.cols, params.rows, params.spacing, o.width, o.height);
    if let Some(e) = o.eye {
        camera.eye = e.into();
    }
    if let Some(l) = o.look_at {
        camera.look_at = l.into();
    }
    camera.fov_y_degrees = o.fov;
    camera.validate().map_err(|e| match e {
        // The camera was placed by framing the grid: its points are the grid's fault.
        springwater::Error::InvalidParam {
            name: "look_at" | "eye",
            ..
        } if o.eye.is_none() && o.look_at.is_none() => format!(
            "--spacing {}: the camera cannot frame a {}x{} grid at this spacing ({} units \
             across); use a larger --spacing, or place the camera with --eye and --look-at",
            Short(params.spacing),
            params.cols,
            params.rows,
            Short((params.cols.max(params.rows) - 1) as f32 * params.spacing)
        ),
        e => format!("camera: {}", lib_error(e)),
    })?;
    let bottom = match &o.bottom {
        Some(path) => read_png(path)?,
        None => Texture::pool_tiles_for(
            (params.cols - 1) as f32 * params.spacing,
            (params.rows - 1) as f32 * params.spacing,
        ),
    };
    let mut render_params = RenderParams {
        wireframe: o.wireframe,
        ..RenderParams::default()
    };
    render_params.refraction.depth = o.depth;
    render_params.refraction.ior = o.ior;
    render_params.look.caustics = o.caustics;
    render_params.lod_pixels = Some(o.lod_pixels);
    let mut renderer = Renderer::new(render_params, bottom).map_err(lib_error)?;

    // Start every output before any work: an unwritable path fails at once. A render that
    // fails or is stopped part-way leaves the files that were there as they were.
    let gif_file = o
        .out
        .as_ref()
        .map(|path| Output::create(path, "--out"))
        .transpose()?;
    let pngs = o
        .png
        .as_ref()
        .map(|dir| output::Sequence::create(dir, "--png", "frame_", "png", o.frames - 1))
        .transpose()?;

    // A GIF needs its palette before its first frame. Frames that fit in memory are kept
    // and encoded after one pass; larger animations are simulated and drawn twice (the
    // run is deterministic, so both passes see the same frames): once for the palette,
    // once to encode.
    let frame_bytes = o.width as u64 * o.height as u64 * 3;
    let keep = std::env::var("SPRINGWATER_KEEP_FRAMES_BYTES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(KEEP_FRAMES_BYTES);
    let two_pass = gif_file.is_some() && frame_bytes * o.frames as u64 > keep;
    let passes = if two_pass { 2 } else { 1 };
    let bar = crate::progress::bar(o.frames as u64 * passes, "frames");
    let start = Instant::now();
    let mut clock = Clock::default();
    let mut frames: Vec<Vec<u8>> = Vec::new();
    let mut histogram = Histogram::new();
    let mut png_time = Duration::ZERO;
    let run = model.with_threads(|| {
        animate(&model, &o, &mut renderer, &camera, &mut clock, |k, rgb| {
            if let Some(seq) = &pngs {
                let t = Instant::now();
                let shown = seq.path().join(seq.name(k));
                let fail = |e: std::io::Error| format!("cannot write {}: {e}", shown.display());
                let file = std::fs::File::create(seq.frame_path(k)).map_err(fail)?;
                write_png(file, o.width as usize, o.height as usize, rgb).map_err(fail)?;
                png_time += t.elapsed();
            }
            if gif_file.is_some() {
                histogram.add(rgb);
                if !two_pass {
                    frames.push(rgb.to_vec());
                }
            }
            bar.inc(1);
            Ok(())
        })
    })??;

    let mut gif_time = Duration::ZERO;
    let mut pending: Vec<Pending> = pngs.into_iter().map(Pending::Frames).collect();
    if let Some(out) = gif_file {
        let path = out.path().to_path_buf();
        let fail = |e: String| format!("cannot write {}: {e}", path.display());
        let file = out.file().map_err(|e| fail(e.to_string()))?;
        let t = Instant::now();
        let palette = model.with_threads(|| Palette::median_cut(&histogram))?;
        let delay = (100.0 / o.fps).round().clamp(2.0, 65535.0) as u16;
        let mut gif = GifWriter::new(file, o.width as usize, o.height as usize, &palette, delay)
            .map_err(fail)?;
        if two_pass {
            gif_time += t.elapsed();
            model.with_threads(|| {
                animate(&model, &o, &mut renderer, &camera, &mut clock, |_, rgb| {
                    let t = Instant::now();
                    gif.frame(rgb).map_err(fail)?;
                    gif_time += t.elapsed();
                    bar.inc(1);
                    Ok(())
                })
            })??;
        } else {
            bar.set_message("encoding GIF");
            for rgb in &frames {
                gif.frame(rgb).map_err(fail)?;
            }
            gif_time += t.elapsed();
        }
        gif.finish().map_err(fail)?;
        pending.push(Pending::File(out));
    }
    bar.finish_and_clear();
    output::commit_all(pending).map_err(|e| e.to_string())?;

    let drawn = (o.frames as u64 * passes) as f64;
    let ms = |d: Duration| d.as_secs_f64() * 1e3 / drawn;
    let total = start.elapsed();
    say!(
        "rendered {} of {}x{} pixels, a {}x{} surface, {} per frame after {}{}",
        count(o.frames as u64, "frame"),
        o.width,
        o.height,
        params.cols,
        params.rows,
        count(o.substeps as u64, "step"),
        count(model.steps, "warm-up step"),
        if two_pass {
            " (twice: too large to keep for the GIF palette)"
        } else {
            ""
        }
    );
    let lod = renderer.lod();
    let levels = lod.patch_levels();
    let (lo, hi) = levels
        .iter()
        .fold((u8::MAX, 0), |(lo, hi), &l| (lo.min(l), hi.max(l)));
    say!(
        "mesh         {} LOD triangles in the last frame ({} at full detail), levels {lo} to {hi}",
        lod.triangle_count(),
        2 * (params.cols - 1) * (params.rows - 1),
    );
    say!(
        "disturbances: {} (rate {}, seed {}){}",
        count(run.raindrops, "raindrop"),
        Short(o.rain),
        o.seed,
        if o.wake { ", a wake" } else { "" }
    );
    if o.floaters > 0 {
        say!("floaters     {}", count(o.floaters as u64, "ball"));
    }
    if let Some((heel, trim)) = run.tilt {
        say!(
            "boats        {}, heeling up to {:.1}° and trimming up to {:.1}°",
            count(o.boats as u64, "boat"),
            heel,
            trim
        );
    }
    if o.follow {
        say!(
            "window       moved {} columns and {} rows with the ball",
            run.window[0],
            run.window[1]
        );
    }
    say!(
        "per frame    simulation {:.2} ms, normals {:.2} ms, LOD {:.2} ms, refraction {:.2} ms, drawing {:.2} ms",
        ms(clock.simulation),
        ms(clock.stages.normals),
        ms(clock.stages.lod),
        ms(clock.stages.refraction),
        ms(clock.stages.drawing)
    );
    say!(
        "total        {:.2} s ({:.1} ms per frame); GIF palette + encoding {:.2} s, PNG writing {:.2} s",
        total.as_secs_f64(),
        total.as_secs_f64() * 1e3 / o.frames as f64,
        gif_time.as_secs_f64(),
        png_time.as_secs_f64()
    );
    if let Some(path) = &o.out {
        let size = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
        say!("wrote {} ({:.1} KiB)", path.display(), size as f64 / 1024.0);
    }
    if let Some(dir) = &o.png {
        say!(
            "wrote {} to {}",
            count(o.frames as u64, "PNG frame"),
            dir.display()
        );
    }
    Ok(())
}

/// Frames kept in memory for the GIF palette before `render` switches to two passes
/// (the environment variable `SPRINGWATER_KEEP_FRAMES_BYTES` overrides it, for tests).
const KEEP_FRAMES_BYTES: u64 = 768 << 20;

/// Time spent simulating and in each render stage.
#[derive(Debug, Default)]
struct Clock {
    simulation: Duration,
    stages: StageTimes,
}

/// What a pass over the animation saw.
#[derive(Debug)]
struct Run {
    /// Raindrops that fell.
    raindrops: u64,
    /// Whole cells the window travelled (`Surface::origin_cells`).
    window: [i64; 2],
    /// With boats, the greatest heel and trim of any boat in any frame, degrees.
    tilt: Option<(f32, f32)>,
}

/// Builds the surface and its disturbances, runs the warm-up steps, then simulates and
/// draws every frame in order, handing each (sRGB pixels, row by row) to `each`.
fn animate(
    model: &ModelArgs,
    o: &Options,
    renderer: &mut Renderer,
    camera: &Camera,
    clock: &mut Clock,
    mut each: impl FnMut(usize, &[u8]) -> CliResult<()>,
) -> CliResult<Run> {
    let mut surface = model.surface()?;
    // Every pass starts from the same LOD state, so passes draw the same frames.
    renderer.reset().map_err(|e| e.to_string())?;
    // Rain and wake sized in cells, as they look on any spacing (the library takes world
    // units).
    let h = surface.params().spacing;
    let mut rain = Rain::new(o.rain, o.seed);
    rain.radius = 1.5 * h..3.0 * h;
    let cells = surface.params().cols.min(surface.params().rows) as f32;
    let mut wake = (o.wake || o.follow).then(|| {
        let mut wake = if o.follow {
            // A straight line across open water, far longer than the animation goes: from
            // a third of the way across the window, along +x through its middle.
            let p = surface.params();
            let (x, z) = ((p.cols - 1) as f32 * h / 3.0, (p.rows - 1) as f32 * h / 2.0);
            Wake::new(vec![[x, z], [x + 1.0e5 * h, z]]).expect("two distinct corners")
        } else {
            Wake::circle(&surface, 0.3 * cells * h)
        };
        // 2.5 cells per unit of model time, whatever the spacing and time scale.
        wake.speed = 2.5 * h * surface.params().time_scale;
        wake.radius *= h;
        // The same push per node as at spacing 1 (the library's strength is a pressure).
        wake.strength /= h * h;
        wake
    });
    add_balls(&mut surface, o.floaters)?;
    let mut fleet = match o.boats {
        0 => None,
        n => Some(boats::Fleet::launch(&mut surface, n)?),
    };
    let mut painter = boats::Painter::default();
    let mut balls = Vec::new();
    for k in 0..o.frames {
        let t = Instant::now();
        let steps = if k == 0 {
            model.steps
        } else {
            o.substeps as u64
        };
        if o.follow {
            // Step by step, the window re-centred on the ball after each one.
            for _ in 0..steps {
                let mut disturbances: Vec<&mut dyn Disturbance> = vec![&mut rain];
                disturbances.extend(wake.as_mut().map(|w| w as &mut dyn Disturbance));
                run_steps(&mut surface, &mut disturbances, 1)?;
                if let Some(w) = &wake {
                    let [x, z] = w.position();
                    surface.follow(x, z).map_err(|e| e.to_string())?;
                }
            }
        } else {
            let mut disturbances: Vec<&mut dyn Disturbance> = vec![&mut rain];
            if let Some(w) = wake.as_mut() {
                disturbances.push(w);
            }
            if let Some(f) = fleet.as_mut() {
                disturbances.push(f);
            }
            run_steps(&mut surface, &mut disturbances, steps)?;
        }
        clock.simulation += t.elapsed();
        balls.clear();
        balls.extend(wake.as_ref().map(|w| boat(&surface, w)));
        let floaters = surface
            .floaters()
            .filter(|(_, f)| !matches!(f.shape, Shape::Hull(_)));
        balls.extend(floaters.enumerate().map(|(k, (_, f))| Ball {
            centre: f.position,
            radius: f.shape.bounding_radius(),
            colours: BUOY_COLOURS[k % BUOY_COLOURS.len()],
        }));
        if wake.is_some() || !balls.is_empty() {
            renderer.set_balls(&balls).map_err(|e| e.to_string())?;
        }
        if let Some(fleet) = &mut fleet {
            fleet.observe(&surface);
            let hulls = painter.facets(&surface, fleet);
            renderer.set_facets(hulls).map_err(|e| e.to_string())?;
        }
        let mut camera = *camera;
        // The camera rides with the window (positions are in the water frame).
        let [ox, oz] = surface.origin();
        camera.eye += glam::Vec3::new(ox, 0.0, oz);
        camera.look_at += glam::Vec3::new(ox, 0.0, oz);
        if o.orbit != 0.0 {
            // Turn the eye about the vertical through the target, `orbit` degrees in all.
            let angle =
                (o.orbit * k as f32 / o.frames.max(2).saturating_sub(1) as f32).to_radians();
            let arm = camera.eye - camera.look_at;
            camera.eye = camera.look_at + glam::Quat::from_rotation_y(angle) * arm;
        }
        renderer
            .render(&surface.mesh_view(), &camera)
            .map_err(|e| e.to_string())?;
        clock.stages += renderer.times();
        each(k, renderer.frame().rgb())?;
    }
    Ok(Run {
        raindrops: rain.fallen(),
        window: surface.origin_cells(),
        tilt: fleet.map(|f| f.greatest_tilt()),
    })
}

/// Stripe colours of the floating balls, linear RGB.
const BUOY_COLOURS: [[[f32; 3]; 2]; 3] = [
    [[0.9, 0.35, 0.01], [0.85, 0.85, 0.8]],
    [[0.05, 0.25, 0.8], [0.9, 0.8, 0.1]],
    [[0.1, 0.6, 0.1], [0.85, 0.85, 0.8]],
];

/// The largest radius of a `--floaters` ball, in cells.
const MAX_BALL_CELLS: f32 = 30.0;

/// `n` balls at half the water's density, spread over the pool on a sunflower spiral
/// inside its middle 70% and dropped from just above the water so they splash in.
fn add_balls(surface: &mut Surface, n: usize) -> CliResult<()> {
    let p = *surface.params();
    let (w, l) = (
        (p.cols - 1) as f32 * p.spacing,
        (p.rows - 1) as f32 * p.spacing,
    );
    // A fortieth of the pool, at least 1.2 cells and at most 30 (the water carries a body
    // up to 64 cells across).
    let radius = (0.025 * w.min(l)).clamp(1.2 * p.spacing, MAX_BALL_CELLS * p.spacing);
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    for k in 0..n {
        let r = 0.35 * ((k as f32 + 0.5) / n as f32).sqrt();
        let a = k as f32 * golden;
        let at = [
            w * (0.5 + r * a.cos()),
            0.5 * radius,
            l * (0.5 + r * a.sin()),
        ];
        let mut ball = springwater::Floater::sphere(radius, 1.0, at);
        ball.mass = 0.5 * surface.buoyancy().density * ball.shape.volume();
        surface
            .add_floater(ball)
            .map_err(|e| format!("--floaters: {e}"))?;
    }
    Ok(())
}

/// The object making the wake: a red and white ball floating where the wake is.
fn boat(surface: &Surface, wake: &Wake) -> Ball {
    let [x, z] = wake.position();
    let y = surface.height_at(x, z).unwrap_or(0.0);
    let radius = 0.8 * wake.radius;
    Ball {
        centre: glam::Vec3::new(x, y + 0.2 * radius, z),
        radius,
        colours: [[0.8, 0.03, 0.02], [0.85, 0.85, 0.8]],
    }
}

/// `steps` steps, each preceded by every disturbance.
fn run_steps(
    surface: &mut Surface,
    disturbances: &mut [&mut dyn Disturbance],
    steps: u64,
) -> CliResult<()> {
    for _ in 0..steps {
        // Disturbances take the step's length in seconds.
        let seconds = surface.params().dt / surface.params().time_scale;
        for d in disturbances.iter_mut() {
            d.apply(surface, seconds).map_err(|e| e.to_string())?;
        }
        surface.step().map_err(|e| e.to_string())?;
    }
    Ok(())
}
