//! `springwater bake`: runs the model over `--frames N` frames of `1/--fps` seconds
//! (`Surface::advance`) and writes an animation cache chosen by `--out`'s extension
//! (DESIGN.md §3): `.glb` (glTF 2.0, morph targets), `.mdd` or `.pc2` (point caches beside
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
//! `--frames` (the floaters' paths, 12 bytes per floater and frame, are the exception).

mod glb;
pub mod obj;
mod pointcache;

use crate::args::{
    lib_error, list, next_flag, string, unexpected, value, CliResult, Flag, ModelArgs,
};
use crate::render::{positive, progress, ranged};
use crate::simulate::{starting_surface, MODEL_FLAGS};
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
    /// Completes the file(s) after the last frame.
    fn finish(self: Box<Self>) -> std::io::Result<()>;
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
    let mut model = ModelArgs {
        steps: 0,
        ..ModelArgs::default()
    };
    let mut frames: usize = 48;
    let mut fps: f32 = 24.0;
    let mut out: Option<PathBuf> = None;
    let mut load: Option<PathBuf> = None;
    let mut model_flag: Option<String> = None;
    let mut eye: Option<[f32; 3]> = None;
    let mut optics = RefractionParams::default();
    let mut floaters: Vec<[f32; 4]> = Vec::new();
    let mut rain: f32 = 0.0;
    let mut seed: u64 = 1;
    let mut wake = false;
    while let Some(arg) = next_flag(p)? {
        if let Flag::Long(l) = &arg {
            if MODEL_FLAGS.contains(&l.as_str()) {
                model_flag.get_or_insert_with(|| l.clone());
            }
        }
        if model.parse_flag(&arg, p)? {
            continue;
        }
        let Flag::Long(name) = &arg else {
            return Err(unexpected(arg, "bake"));
        };
        match name.as_str() {
            "frames" => frames = ranged(value(p, "--frames")?, 1, 1_000_000, "--frames")?,
            "fps" => fps = positive(value(p, "--fps")?, "--fps")?,
            "out" => out = Some(string(p, "--out")?.into()),
            "load" => load = Some(string(p, "--load")?.into()),
            "eye" => eye = Some(list(&string(p, "--eye")?, "--eye X,Y,Z")?),
            "depth" => optics.depth = positive(value(p, "--depth")?, "--depth")?,
            "ior" => optics.ior = value(p, "--ior")?,
            "floater" => {
                floaters.push(list(&string(p, "--floater")?, "--floater X,Z,MASS,RADIUS")?)
            }
            "rain" => rain = value(p, "--rain")?,
            "seed" => seed = value(p, "--seed")?,
            "wake" => wake = true,
            _ => return Err(unexpected(arg, "bake")),
        }
    }
    let out = out.ok_or("bake needs --out FILE.glb, FILE.mdd, FILE.pc2 or a directory")?;
    let format = Format::of(&out)?;
    if !(rain.is_finite() && rain >= 0.0) {
        return Err(format!(
            "--rain: {rain} is not a rate >= 0 (drops per second)"
        ));
    }
    optics
        .validate()
        .map_err(|e| format!("bake: {}", lib_error(e)))?;

    let mut surface = starting_surface(
        &model,
        model_flag,
        load.as_deref(),
        &floaters,
        "only --steps, --drop, --floater, --threads and the bake's own flags apply",
    )?;
    let dt = surface.params().dt;
    let mut steps = 0usize;
    // A bake owes every frame its whole time: the game's cap on steps per frame (which
    // drops what a stall owes) would cut frames short. Raised to the most `advance` takes;
    // a frame that could need more (its steps, plus one the clock's carried fraction may
    // complete) is refused here, before any step.
    let frame = 1.0f32 / fps;
    let per_frame =
        (f64::from(frame) * f64::from(surface.params().time_scale) / f64::from(dt)).ceil();
    if per_frame + 1.0 > Surface::MAX_SUBSTEPS as f64 {
        return Err(format!(
            "bake: a frame of 1/{fps} s is {per_frame} steps of dt {dt}, more than the {} one frame may take: raise --fps",
            Surface::MAX_SUBSTEPS
        ));
    }
    surface
        .set_step_cap(Surface::MAX_SUBSTEPS as u32, Overflow::Drop)
        .map_err(lib_error)?;

    // Rain and wake sized in cells, as `render` makes them.
    let h = surface.params().spacing;
    let time_scale = surface.params().time_scale;
    let mut rain = (rain > 0.0).then(|| {
        let mut r = Rain::new(rain, seed);
        r.radius = 1.5 * h..3.0 * h;
        r
    });
    let mut wake = wake.then(|| {
        let cells = surface.params().cols.min(surface.params().rows) as f32;
        let mut w = Wake::circle(&surface, 0.3 * cells * h);
        w.speed = 2.5 * h * time_scale;
        w.radius *= h;
        w.strength /= h * h;
        w
    });

    let calm = model.drops.is_empty() && floaters.is_empty() && rain.is_none() && wake.is_none();
    let calm = calm && load.is_none();
    let params = *surface.params();
    let (cols, rows) = (params.cols, params.rows);
    let width = (cols - 1) as f32 * h;
    let length = (rows - 1) as f32 * h;
    // Without --eye the texture coordinates are seen from straight above the middle.
    let uv_eye = glam::Vec3::from(eye.unwrap_or([0.5 * width, width.max(length), 0.5 * length]));

    // An unwritable path fails now, before any step (the writers create the files again
    // once the rest frame is known, after the warm-up steps).
    if let Err(e) = probe(&out, format) {
        remove_outputs(&out, format);
        return Err(e.to_string());
    }
    let started = Instant::now();
    let interrupted = crate::simulate::on_interrupt();
    let bar = progress(frames as u64, "frames");
    let outcome = model.with_threads(|| -> CliResult<()> {
        // The warm-up stops at Ctrl-C too; the first frame then reports the interruption.
        let hidden = indicatif::ProgressBar::hidden();
        crate::simulate::run_steps_until(&mut surface, model.steps, &interrupted, &hidden)?;
        if interrupted.load(std::sync::atomic::Ordering::Relaxed) {
            return Err(format!(
                "interrupted in the {} warm-up steps, before frame 1; nothing was written",
                model.steps
            ));
        }
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
        let mut writer: Box<dyn Writer> = match format {
            Format::Glb => {
                Box::new(glb::Glb::create(&out, &rest, &first, frames, fps).map_err(&fail)?)
            }
            Format::Mdd | Format::Pc2 => Box::new(
                pointcache::PointCache::create(
                    &out,
                    format == Format::Mdd,
                    &rest,
                    &first,
                    frames,
                    fps,
                )
                .map_err(&fail)?,
            ),
            Format::Directory => Box::new(obj::Sequence::create(&out, &rest).map_err(&fail)?),
        };
        for k in 1..=frames {
            // A cache cut short would not say it was: Ctrl-C leaves no file behind.
            if interrupted.load(std::sync::atomic::Ordering::Relaxed) {
                return Err(format!(
                    "interrupted at frame {k} of {frames}; the partial cache was removed"
                ));
            }
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
    })?;
    bar.finish_and_clear();
    if let Err(e) = outcome {
        remove_outputs(&out, format);
        return Err(e);
    }
    let seconds = started.elapsed().as_secs_f64();
    say!(
        "baked {frames} frames at {fps} fps of a {cols}x{rows} surface: {steps} steps of {dt} ({:.2} per frame), {:.2} s",
        steps as f64 / frames as f64,
        seconds
    );
    for path in outputs(&out, format) {
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        say!("wrote {} ({:.1} KiB)", path.display(), size as f64 / 1024.0);
    }
    if format == Format::Directory {
        say!("wrote {frames} OBJ files to {}", out.display());
    }
    if calm {
        eprintln!(
            "springwater: note: nothing disturbed the water (no --drop, --rain, --wake, \
             --floater or --load): every frame is the calm surface"
        );
    }
    Ok(())
}

/// What a frame needs beyond the positions, computed from the surface after each frame
/// into buffers that keep their capacity.
struct Shading {
    eye: glam::Vec3,
    optics: RefractionParams,
    normals: Normals,
    uv: Refraction,
    floaters: Vec<[f32; 3]>,
}

impl Shading {
    fn new(eye: glam::Vec3, optics: RefractionParams) -> Self {
        Self {
            eye,
            optics,
            normals: Normals::new(),
            uv: Refraction::default(),
            floaters: Vec::new(),
        }
    }

    /// Normals, refraction UVs and floater centres for the surface as it is.
    fn update(&mut self, s: &Surface) -> CliResult<()> {
        let view = s.mesh_view();
        compute_normals(&view, &mut self.normals);
        refract(&view, &self.normals, self.eye, &self.optics, &mut self.uv)
            .map_err(|e| format!("bake: {e}"))?;
        self.floaters.clear();
        self.floaters
            .extend(s.floaters().map(|(_, f)| f.position.to_array()));
        Ok(())
    }

    /// The frame the writers take: `s`'s positions with what [`Shading::update`] computed.
    fn frame<'a>(&'a self, s: &'a Surface) -> Frame<'a> {
        Frame {
            positions: s.positions(),
            normals: &self.normals,
            uv: &self.uv,
            floaters: &self.floaters,
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

/// Creates the outputs (empty) or the directory, to find an unwritable path early.
fn probe(out: &Path, format: Format) -> std::io::Result<()> {
    match format {
        Format::Directory => std::fs::create_dir_all(out).map_err(|e| {
            std::io::Error::new(e.kind(), format!("cannot create {}: {e}", out.display()))
        }),
        _ => outputs(out, format)
            .iter()
            .try_for_each(|path| create_io(path).map(drop)),
    }
}

/// A bake that failed leaves no truncated file behind (the frames of a directory stay).
fn remove_outputs(out: &Path, format: Format) {
    for path in outputs(out, format) {
        let _ = std::fs::remove_file(path);
    }
    if format == Format::Glb {
        let _ = std::fs::remove_file(glb::part_path(out));
    }
}

/// Creates a file for a writer, buffered; the error names the file.
pub fn create_io(path: &Path) -> std::io::Result<std::io::BufWriter<std::fs::File>> {
    std::fs::File::create(path)
        .map(std::io::BufWriter::new)
        .map_err(|e| named(path, e))
}

/// An I/O error that says which file it was about: "cannot write PATH: ERROR".
pub fn named(path: &Path, e: std::io::Error) -> std::io::Error {
    std::io::Error::new(e.kind(), format!("cannot write {}: {e}", path.display()))
}
