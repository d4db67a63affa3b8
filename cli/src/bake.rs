//! `springwater bake`: runs the model over `--frames N` frames of `1/--fps` seconds
//! (`Surface::advance`) and writes an animation cache chosen by `--out`'s extension
//! (`cli/README.md`): `.glb` (glTF 2.0, morph targets), `.mdd` or `.pc2` (point caches beside
//! an OBJ of the rest mesh), or a directory of one OBJ per frame.
//!
//! `advance` runs the game's fixed-step clock: a frame takes the whole steps of `dt` its
//! time completes, so frames whose length is not a whole number of steps alternate (2 and
//! 3 steps at 24 fps and the default time scale) and the cache equals `simulate --steps`
//! with the steps the bake reports, bit for bit.
//!
//! Frame k (from 1) is the state after k frames' steps; the rest mesh (frame 0) is the
//! state before the first frame (after `--steps` warm-up steps, 0 by default, and the
//! drops). Vertex order is the nodes' row-major order in every format. Every writer
//! streams: a frame goes to disk as soon as it is computed, so memory does not grow with
//! `--frames` (the floaters' paths, 28 bytes per floater and frame, are the exception).

mod glb;
pub mod obj;
mod pointcache;

use crate::args::{
    count, lib_error, list, next_flag, positive, ranged, string, unexpected, value, CliResult,
    Flag, Short,
};
use crate::output::{self, Output, Pending};
use crate::start::{check_rain, run_steps_until, Start};
use lexopt::Parser;
use springwater::disturb::{Rain, Wake};
use springwater::mesh::{compute_normals, LodMesh, LodParams, Normals};
use springwater::refraction::{refract, Refraction, RefractionParams};
use springwater::{Overflow, Surface};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// One frame of the water as the writers see it.
pub struct Frame<'a> {
    /// Positions, x, y, z per node, row-major.
    pub positions: [&'a [f32]; 3],
    pub normals: &'a Normals,
    /// Refraction texture coordinates (u, v per node).
    pub uv: &'a Refraction,
    /// Floater centres, in the order given.
    pub floaters: &'a [[f32; 3]],
    /// Floater orientations, body to world, as unit quaternions `[x, y, z, w]`, in the
    /// same order.
    pub orientations: &'a [[f32; 4]],
}

/// The mesh every frame shares: its triangles and the frame it rests in.
pub struct Rest {
    /// Triangles, counter-clockwise seen from +y, 0-based into the row-major nodes.
    pub indices: Vec<u32>,
    pub cols: usize,
    pub rows: usize,
}

/// An animation cache being written, one frame at a time.
trait Writer {
    /// Writes frame `k` (from 1).
    fn frame(&mut self, k: usize, frame: &Frame) -> std::io::Result<()>;
    /// Completes the file(s) after the last frame; returns them, to be moved into place.
    fn finish(self: Box<Self>) -> std::io::Result<Vec<Pending>>;
}

/// What `--out` names.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Format {
    Glb,
    Mdd,
    Pc2,
    Directory,
}

impl Format {
    fn of(path: &Path) -> CliResult<Self> {
        // `.glb` alone is a hidden name without an extension: not a directory bake.
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().to_ascii_lowercase());
        if let Some(ext) = name
            .as_deref()
            .and_then(|n| n.strip_prefix('.'))
            .filter(|e| ["glb", "mdd", "pc2"].contains(e))
        {
            return Err(format!(
                "bake: --out {}: the name is only an extension; give a file name such as \
                 water.{ext}",
                path.display()
            ));
        }
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("glb") => Ok(Format::Glb),
            Some("mdd") => Ok(Format::Mdd),
            Some("pc2") => Ok(Format::Pc2),
            _ if path.is_dir() => Ok(Format::Directory),
            None => Ok(Format::Directory),
            Some(other) => Err(format!(
                "bake: --out {}: '.{other}' is not a format bake writes \
                 (.glb, .mdd, .pc2, or a directory for one OBJ per frame)",
                path.display()
            )),
        }
    }
}

pub fn run(p: &mut Parser) -> CliResult<()> {
    let mut start = Start::with_steps(0);
    let mut frames: usize = 48;
    let mut fps: f32 = 24.0;
    let mut out: Option<PathBuf> = None;
    let mut eye: Option<[f32; 3]> = None;
    let mut optics = RefractionParams::default();
    let mut rain: f32 = 0.0;
    let mut seed: u64 = 1;
    let mut wake = false;
    while let Some(arg) = next_flag(p)? {
        if start.parse_flag(&arg, p)? {
            continue;
        }
        let Flag::Long(name) = &arg else {
            return Err(unexpected(arg, "bake"));
        };
        match name.as_str() {
            "frames" => frames = ranged(value(p, "--frames")?, 1, 1_000_000, "--frames")?,
            "fps" => fps = positive(value(p, "--fps")?, "--fps")?,
            "out" => out = Some(string(p, "--out")?.into()),
            "eye" => eye = Some(list(&string(p, "--eye")?, "--eye X,Y,Z")?),
            "depth" => optics.depth = positive(value(p, "--depth")?, "--depth")?,
            "ior" => optics.ior = value(p, "--ior")?,
            "rain" => rain = value(p, "--rain")?,
            "seed" => seed = value(p, "--seed")?,
            "wake" => wake = true,
            _ => return Err(unexpected(arg, "bake")),
        }
    }
    let out = out.ok_or("bake needs --out FILE.glb, FILE.mdd, FILE.pc2 or a directory")?;
    output::non_empty(&out, "--out")?;
    let format = Format::of(&out)?;
    if !(rain.is_finite() && rain >= 0.0) {
        return Err(format!(
            "--rain: {} is not a rate >= 0 (drops per second)",
            Short(rain)
        ));
    }
    optics
        .validate()
        .map_err(|e| format!("bake: {}", lib_error(e)))?;
    let rest_obj = matches!(format, Format::Mdd | Format::Pc2).then(|| rest_obj_path(&out));
    if let Some(obj) = &rest_obj {
        check_rest_obj(&out, obj)?;
    }
    // Every path the bake reads or writes is its own (through symbolic links too).
    let mut paths: Vec<(&str, &Path)> = vec![("--out", &out)];
    paths.extend(
        rest_obj
            .as_deref()
            .map(|obj| ("--out (its rest mesh)", obj)),
    );
    paths.extend(start.load.as_deref().map(|load| ("--load", load)));
    output::distinct(&paths)?;

    let model = &start.model;
    // The surface, its normals and refraction coordinates, the triangles and the writer's
    // rest frame: 134 bytes a node for a point cache and 180 for a .glb, measured on
    // 2048 x 2048.
    let per_node = if format == Format::Glb { 192 } else { 144 };
    if start.load.is_none() {
        // A .glb past the format's 4 GiB is refused before the grid is built (with --load,
        // once the snapshot gives the grid, below).
        if format == Format::Glb {
            glb::check_size(&out, &model.params, frames, start.floaters.len())?;
        }
        crate::memory::check_grid(&model.params, per_node, 0, "bake")?;
    }
    let mut surface = start
        .surface("only --steps, --drop, --floater, --threads and the bake's own flags apply")?;
    check_rain(rain, &surface)?;
    let params = *surface.params();
    let dt = params.dt;
    // A bake owes every frame its whole time: the game's cap on steps per frame (which
    // drops what a stall owes) would cut frames short. Raised to the most `advance` takes;
    // a frame that could need more (its steps, plus one the clock's carried fraction may
    // complete) is refused here, before any step.
    let frame = 1.0f32 / fps;
    let step_seconds = f64::from(dt) / f64::from(params.time_scale);
    let per_frame = (f64::from(frame) / step_seconds).ceil();
    if per_frame + 1.0 > Surface::MAX_SUBSTEPS as f64 {
        let most = Surface::MAX_SUBSTEPS - 1;
        let fps_needed = Short((1.0 / (most as f64 * step_seconds)) as f32);
        // A longer timestep is a remedy only below the critical one.
        let dt_needed = f64::from(frame) * f64::from(params.time_scale) / most as f64;
        let or_dt = if dt_needed < 0.95 * f64::from(surface.critical_dt()) {
            format!(", or --dt {} or more", Short(dt_needed as f32))
        } else {
            String::new()
        };
        return Err(format!(
            "bake: --fps {}: a frame of {} s is {per_frame} steps of dt {} ({} s each), more \
             than the {most} one frame may take; use --fps {fps_needed} or more{or_dt}",
            Short(fps),
            Short(frame),
            Short(dt),
            Short(step_seconds as f32),
        ));
    }
    if f64::from(frame) < step_seconds {
        return Err(format!(
            "bake: --fps {}: a frame of {} s is shorter than one step ({} s), so most \
             frames would repeat the one before; use --fps {} or less",
            Short(fps),
            Short(frame),
            Short(step_seconds as f32),
            Short((1.0 / step_seconds) as f32)
        ));
    }
    surface
        .set_step_cap(Surface::MAX_SUBSTEPS as u32, Overflow::Drop)
        .map_err(lib_error)?;
    // A snapshot's clock may owe time (a game stalled before saving): the first frame owes
    // it too, and past the cap it would be cut short. No flag changes a loaded clock.
    let owed = surface.owed_seconds();
    if let (Some(load), true) = (
        &start.load,
        (owed + f64::from(frame)) / step_seconds > Surface::MAX_SUBSTEPS as f64,
    ) {
        return Err(format!(
            "--load {}: the snapshot's clock owes {} s of steps ({:.3e} steps of {} s), \
             more than one frame of the bake may take ({} steps); save it once the game \
             has caught up, or bake from the model flags",
            load.display(),
            Short(owed as f32),
            owed / step_seconds,
            Short(step_seconds as f32),
            Surface::MAX_SUBSTEPS
        ));
    }
    if format == Format::Glb {
        glb::check_size(&out, &params, frames, surface.floaters().len())?;
    }
    if let Some(load) = &start.load {
        // The snapshot gave the grid: what the bake adds to the surface it built (the
        // surface itself is the 64 bytes a node `bench` measures), asked before any step.
        let nodes = params.cols as u64 * params.rows as u64;
        crate::memory::check(
            nodes.saturating_mul(per_node - 64),
            &format!(
                "bake --load {} (a {}x{} grid)",
                load.display(),
                params.cols,
                params.rows
            ),
            "bake a snapshot of a smaller grid",
        )?;
    }

    // Rain and wake sized in cells, as `render` makes them.
    let h = params.spacing;
    let mut rain = (rain > 0.0).then(|| {
        let mut r = Rain::new(rain, seed);
        r.radius = 1.5 * h..3.0 * h;
        r
    });
    let mut wake = wake.then(|| {
        let cells = params.cols.min(params.rows) as f32;
        let mut w = Wake::circle(&surface, 0.3 * cells * h);
        w.speed = 2.5 * h * params.time_scale;
        w.radius *= h;
        w.strength /= h * h;
        w
    });

    let calm = model.drops.is_empty() && start.floaters.is_empty() && rain.is_none();
    let calm = calm && wake.is_none() && start.load.is_none();
    let (cols, rows) = (params.cols, params.rows);
    let width = (cols - 1) as f32 * h;
    let length = (rows - 1) as f32 * h;
    // Without --eye the texture coordinates are seen from straight above the middle.
    let uv_eye = glam::Vec3::from(eye.unwrap_or([0.5 * width, width.max(length), 0.5 * length]));

    // Every output is started before any step: an unwritable path fails now.
    let mut files = match format {
        Format::Directory => Targets::Frames(output::Sequence::create(
            &out, "--out", "water_", "obj", frames,
        )?),
        _ => Targets::Files(
            Output::create(&out, "--out")?,
            rest_obj
                .as_deref()
                .map(|obj| Output::create(obj, "--out (its rest mesh)"))
                .transpose()?,
        ),
    };
    let started = Instant::now();
    let bar = crate::progress::bar(frames as u64, "frames");
    let mut steps = 0usize;
    let written = model.with_threads(|| -> CliResult<Vec<Pending>> {
        let hidden = indicatif::ProgressBar::hidden();
        run_steps_until(&mut surface, model.steps, &hidden)?;
        let mut shading = Shading::new(uv_eye, optics);
        shading.update(&surface)?;
        // The triangles: full detail, or for a .glb baked for an eye, that eye's LOD.
        let levels = if eye.is_some() && format == Format::Glb {
            LodParams::default().levels
        } else {
            1
        };
        let mut lod = LodMesh::new(LodParams::default().with_levels(levels)).map_err(lib_error)?;
        lod.update(&surface.mesh_view(), uv_eye);
        let rest = Rest {
            indices: lod.indices().to_vec(),
            cols,
            rows,
        };
        let fail = |e: std::io::Error| e.to_string();
        let first = shading.frame(&surface);
        let mut writer: Box<dyn Writer> = match std::mem::replace(&mut files, Targets::Taken) {
            Targets::Files(out, None) => {
                Box::new(glb::Glb::create(out, &rest, &first, frames, fps).map_err(&fail)?)
            }
            Targets::Files(out, Some(obj)) => Box::new(
                pointcache::PointCache::create(
                    out,
                    obj,
                    format == Format::Mdd,
                    &rest,
                    &first,
                    frames,
                    fps,
                )
                .map_err(&fail)?,
            ),
            Targets::Frames(seq) => Box::new(obj::Sequence::new(seq, &rest)),
            Targets::Taken => unreachable!("the outputs are taken once"),
        };
        for k in 1..=frames {
            let step = match (&mut rain, &mut wake) {
                (None, None) => surface.advance(frame),
                _ => surface.advance_with(frame, &mut (&mut rain, &mut wake)),
            };
            steps += step.map_err(|e| format!("frame {k}: {e}"))?;
            // Checked above, so never: a frame whose time was cut is not the frame asked for.
            if surface.dropped_seconds() > 0.0 {
                return Err(format!(
                    "frame {k}: the clock dropped time; lower --dt or raise --fps"
                ));
            }
            shading.update(&surface)?;
            writer
                .frame(k, &shading.frame(&surface))
                .map_err(|e| format!("frame {k}: {}", fail(e)))?;
            bar.inc(1);
        }
        writer.finish().map_err(fail)
    })??;
    bar.finish_and_clear();
    output::commit_all(written).map_err(|e| e.to_string())?;
    let seconds = started.elapsed().as_secs_f64();
    say!(
        "baked {} at {} fps of a {cols}x{rows} surface: {} of {} ({:.2} per frame), {:.2} s",
        count(frames as u64, "frame"),
        Short(fps),
        count(steps as u64, "step"),
        Short(dt),
        steps as f64 / frames as f64,
        seconds
    );
    for path in outputs(&out, format) {
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        say!("wrote {} ({:.1} KiB)", path.display(), size as f64 / 1024.0);
    }
    if format == Format::Directory {
        say!(
            "wrote {} to {}",
            count(frames as u64, "OBJ file"),
            out.display()
        );
    }
    if calm {
        eprintln!(
            "springwater: note: nothing disturbed the water (no --drop, --rain, --wake, \
             --floater or --load): every frame is the calm surface"
        );
    }
    Ok(())
}

/// The outputs a bake starts before its first step.
enum Targets {
    /// The cache, and the rest OBJ beside a point cache.
    Files(Output, Option<Output>),
    /// A directory of OBJ frames.
    Frames(output::Sequence),
    /// Handed to the writer.
    Taken,
}

/// Refuses to replace an OBJ beside a point cache that `bake` did not write (its first
/// line says so): `--out model.pc2` must not overwrite the user's `model.obj`.
fn check_rest_obj(out: &Path, obj: &Path) -> CliResult<()> {
    use std::io::BufRead;
    if !obj.is_file() {
        return Ok(());
    }
    let mut first = String::new();
    let file =
        std::fs::File::open(obj).map_err(|e| format!("cannot read {}: {e}", obj.display()))?;
    let _ = std::io::BufReader::new(file).read_line(&mut first);
    if first
        .strip_prefix("# ")
        .is_some_and(|t| t.starts_with(obj::REST_TITLE))
    {
        return Ok(());
    }
    Err(format!(
        "--out {}: the rest mesh goes to {}, which exists and was not written by bake; \
         move it or choose another name",
        out.display(),
        obj.display()
    ))
}

/// What a frame needs beyond the positions, computed from the surface after each frame
/// into buffers that keep their capacity.
struct Shading {
    eye: glam::Vec3,
    optics: RefractionParams,
    normals: Normals,
    uv: Refraction,
    floaters: Vec<[f32; 3]>,
    orientations: Vec<[f32; 4]>,
}

impl Shading {
    fn new(eye: glam::Vec3, optics: RefractionParams) -> Self {
        Self {
            eye,
            optics,
            normals: Normals::new(),
            uv: Refraction::default(),
            floaters: Vec::new(),
            orientations: Vec::new(),
        }
    }

    /// Normals, refraction UVs and floater poses for the surface as it is.
    fn update(&mut self, s: &Surface) -> CliResult<()> {
        let view = s.mesh_view();
        compute_normals(&view, &mut self.normals);
        refract(&view, &self.normals, self.eye, &self.optics, &mut self.uv)
            .map_err(|e| format!("bake: {e}"))?;
        self.floaters.clear();
        self.floaters
            .extend(s.floaters().map(|(_, f)| f.position.to_array()));
        self.orientations.clear();
        self.orientations
            .extend(s.floaters().map(|(_, f)| f.orientation.to_array()));
        Ok(())
    }

    /// The frame the writers take: `s`'s positions with what [`Shading::update`] computed.
    fn frame<'a>(&'a self, s: &'a Surface) -> Frame<'a> {
        Frame {
            positions: s.positions(),
            normals: &self.normals,
            uv: &self.uv,
            floaters: &self.floaters,
            orientations: &self.orientations,
        }
    }
}

/// The rest mesh OBJ written beside a point cache: `water.mdd` → `water.obj`.
pub fn rest_obj_path(cache: &Path) -> PathBuf {
    cache.with_extension("obj")
}

/// The single files a bake writes (none for a directory).
fn outputs(out: &Path, format: Format) -> Vec<PathBuf> {
    match format {
        Format::Glb => vec![out.to_path_buf()],
        Format::Mdd | Format::Pc2 => vec![out.to_path_buf(), rest_obj_path(out)],
        Format::Directory => Vec::new(),
    }
}
