//! The surface a command starts from (the model flags, or a snapshot with `--load`, and
//! the `--floater` balls), and the steps it runs: what `simulate` and `bake` share.

use crate::args::{list, string, CliResult, Flag, ModelArgs, Short};
use lexopt::Parser;
use springwater::{Floater, Surface};
use std::io::Read;
use std::path::{Path, PathBuf};

/// Model flags whose values a snapshot already holds.
const MODEL_FLAGS: [&str; 8] = [
    "size",
    "dt",
    "mass",
    "stiffness",
    "viscosity",
    "rest-ratio",
    "spacing",
    "boundary",
];

/// The flags that choose the starting surface.
#[derive(Debug, Clone, Default)]
pub struct Start {
    pub model: ModelArgs,
    /// `--load FILE`.
    pub load: Option<PathBuf>,
    /// The first model flag given (refused next to `--load`).
    model_flag: Option<String>,
    /// `--floater X,Z,MASS,RADIUS`, in the order given.
    pub floaters: Vec<[f32; 4]>,
}

impl Start {
    /// Starts from the model flags' defaults with `steps` steps.
    pub fn with_steps(steps: u64) -> Self {
        Self {
            model: ModelArgs {
                steps,
                ..ModelArgs::default()
            },
            ..Self::default()
        }
    }

    /// Consumes `arg` if it is a model flag, `--load` or `--floater`.
    pub fn parse_flag(&mut self, arg: &Flag, p: &mut Parser) -> CliResult<bool> {
        if let Flag::Long(l) = arg {
            if MODEL_FLAGS.contains(&l.as_str()) {
                self.model_flag.get_or_insert_with(|| l.clone());
            }
        }
        if self.model.parse_flag(arg, p)? {
            return Ok(true);
        }
        match arg {
            Flag::Long(l) if l == "load" => self.load = Some(string(p, "--load")?.into()),
            Flag::Long(l) if l == "floater" => self
                .floaters
                .push(list(&string(p, "--floater")?, "--floater X,Z,MASS,RADIUS")?),
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// The snapshot `--load` names, with the `--drop`s added, or the model the flags
    /// describe (a model flag may not come with `--load`: `what_applies` says which flags
    /// do), and the `--floater` balls on it, released at rest on the calm surface.
    pub fn surface(&self, what_applies: &str) -> CliResult<Surface> {
        let mut surface = match (&self.load, &self.model_flag) {
            (Some(_), Some(flag)) => {
                return Err(format!(
                    "--{flag} cannot be combined with --load: the model comes from the \
                     snapshot ({what_applies})"
                ))
            }
            (Some(path), None) => {
                let mut s = load_snapshot(path)?;
                if s.steps().checked_add(self.model.steps).is_none() {
                    return Err(format!(
                        "--steps {}: the snapshot {} has taken {} steps, and the count \
                         would pass the largest there is ({}); use --steps {} or fewer",
                        self.model.steps,
                        path.display(),
                        s.steps(),
                        u64::MAX,
                        u64::MAX - s.steps()
                    ));
                }
                self.model.apply_drops(&mut s)?;
                s
            }
            (None, _) => self.model.surface()?,
        };
        let h = surface.params().spacing;
        for &[x, z, mass, radius] in &self.floaters {
            let given = format!("--floater {x},{z},{mass},{radius}");
            surface
                .add_floater(Floater::sphere(radius, mass, [x, 0.0, z]))
                .map_err(|e| match e {
                    // The library counts the limit in cells and the size in world units.
                    springwater::Error::InvalidParam {
                        name: "floater size",
                        ..
                    } => format!(
                        "{given}: a radius of {} is {} cells of spacing {}; a body may be at \
                         most {} cells across, so use a radius of {} or less",
                        Short(radius),
                        Short(radius / h),
                        Short(h),
                        springwater::floater::MAX_CELLS,
                        Short(springwater::floater::MAX_CELLS / 2.0 * h)
                    ),
                    e => format!("{given}: {e}"),
                })?;
        }
        Ok(surface)
    }
}

/// Reads a snapshot file, naming it in the error. The file must hold exactly one snapshot:
/// bytes after it are refused, as `Surface::from_bytes` refuses them.
pub fn load_snapshot(path: &Path) -> CliResult<Surface> {
    crate::output::non_empty(path, "--load")?;
    check_load_memory(path)?;
    let fail = |e: std::io::Error| format!("cannot read {}: {e}", path.display());
    let mut file = std::io::BufReader::new(std::fs::File::open(path).map_err(fail)?);
    let mut surface = Surface::load(&mut file).map_err(|e| format!("{}: {e}", path.display()))?;
    crate::args::forced_level(&mut surface)?;
    // One byte is enough to know there is more (and reads nothing more from a device).
    if file.read(&mut [0u8]).map_err(fail)? != 0 {
        return Err(format!(
            "{}: snapshot refused: trailing data after the snapshot's last byte",
            path.display()
        ));
    }
    Ok(surface)
}

/// Refuses a snapshot file whose loading needs more memory than the system gives, before
/// reading it. Loading holds the file's bytes, the decoded snapshot and the new surface at
/// once: 248 bytes a node at the peak (resident memory, measured loading 2048 x 2048;
/// asked here as 256). A snapshot has 77 bytes a node besides 204 of header and checksum,
/// and its bodies take bytes but no nodes, so its length bounds its nodes from above. A
/// path that is not a regular file (a FIFO, a device) has no length to go by.
fn check_load_memory(path: &Path) -> CliResult<()> {
    let Ok(meta) = std::fs::metadata(path) else {
        return Ok(()); // opening it says what is wrong
    };
    if !meta.is_file() {
        return Ok(());
    }
    let nodes = meta.len().saturating_sub(204) / 77;
    crate::memory::check(
        nodes.saturating_mul(256),
        &format!(
            "--load {}: loading a snapshot of up to {nodes} nodes",
            path.display()
        ),
        "load it where there is more memory, or save a smaller grid",
    )
}

/// Steps up to `steps` times, stopping early when a first Ctrl-C asks to
/// ([`crate::interrupt::stop_requested`]); returns the steps taken. The bar (drawn only on a
/// terminal) moves every 64 steps.
pub fn run_steps_until(
    surface: &mut Surface,
    steps: u64,
    bar: &indicatif::ProgressBar,
) -> CliResult<u64> {
    for done in 0..steps {
        if crate::interrupt::stop_requested() {
            return Ok(done);
        }
        surface.step().map_err(|e| e.to_string())?;
        if done % 64 == 63 {
            bar.set_position(done + 1);
        }
    }
    Ok(steps)
}

/// The most raindrops per node and step: a node shows one dent per step, and more drops
/// than nodes make the rain cost more than the step it disturbs, many times over.
const MAX_RAIN_PER_NODE_STEP: f64 = 1.0;

/// Refuses a rain rate above [`MAX_RAIN_PER_NODE_STEP`] for `surface`, before any step.
pub fn check_rain(rain: f32, surface: &Surface) -> CliResult<()> {
    let p = surface.params();
    let steps_per_second = f64::from(p.time_scale) / f64::from(p.dt);
    let limit = MAX_RAIN_PER_NODE_STEP * surface.node_count() as f64 * steps_per_second;
    if f64::from(rain) > limit {
        return Err(format!(
            "--rain {}: at most {} drops per second on this surface (one drop per node and \
             step: {} nodes, {} steps per second); more is not rain but a flood that costs \
             more than the steps",
            Short(rain),
            limit.floor(),
            surface.node_count(),
            Short(steps_per_second as f32)
        ));
    }
    Ok(())
}
