//! `springwater simulate`: run the steps, print a summary, optionally write a CSV and a
//! snapshot, or continue from a snapshot.
//!
//! With `--load FILE` the model (grid, parameters, per-node and per-spring tables, step
//! count) comes from the snapshot, so the flags that define a model are refused next to it;
//! `--steps`, `--drop` (added to the loaded state before the steps), `--threads`, `--csv`
//! and `--save` apply as usual.
//!
//! `--follow-shift DC,DR` moves the window by whole cells after the steps, before the CSV
//! and the snapshot are written (`Surface::shift`): the CSV's `x`, `z` are positions in the
//! water frame, so a node of the overlap appears with the bits of an unshifted run's node
//! `(col + DC, row + DR)`, and the strip that came in is calm.

use crate::args::{list, next_flag, number, string, unexpected, CliResult, Flag, ModelArgs, Short};
use lexopt::Parser;
use springwater::{Floater, Surface};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

/// Model flags whose values a snapshot already holds.
pub const MODEL_FLAGS: [&str; 8] = [
    "size",
    "dt",
    "mass",
    "stiffness",
    "viscosity",
    "rest-ratio",
    "spacing",
    "boundary",
];

pub fn run(p: &mut Parser) -> CliResult<()> {
    let mut model = ModelArgs::default();
    let mut csv: Option<PathBuf> = None;
    let mut save: Option<PathBuf> = None;
    let mut load: Option<PathBuf> = None;
    let mut model_flag: Option<String> = None;
    let mut floaters: Vec<[f32; 4]> = Vec::new();
    let mut follow_shift: Option<[i32; 2]> = None;
    while let Some(arg) = next_flag(p)? {
        if let Flag::Long(l) = &arg {
            if MODEL_FLAGS.contains(&l.as_str()) {
                model_flag.get_or_insert_with(|| l.clone());
            }
        }
        if model.parse_flag(&arg, p)? {
            continue;
        }
        match arg {
            Flag::Long(l) if l == "csv" => csv = Some(string(p, "--csv")?.into()),
            Flag::Long(l) if l == "save" => save = Some(string(p, "--save")?.into()),
            Flag::Long(l) if l == "load" => load = Some(string(p, "--load")?.into()),
            Flag::Long(l) if l == "follow-shift" => {
                follow_shift = Some(cells(&string(p, "--follow-shift")?)?)
            }
            Flag::Long(l) if l == "floater" => {
                floaters.push(list(&string(p, "--floater")?, "--floater X,Z,MASS,RADIUS")?)
            }
            other => return Err(unexpected(other, "simulate")),
        }
    }
    let mut surface = starting_surface(
        &model,
        model_flag,
        load.as_deref(),
        &floaters,
        "only --steps, --drop, --threads, --follow-shift, --csv and --save apply",
    )?;
    // Open the outputs first: an unwritable path fails before any work is done.
    let csv = csv
        .map(|path| create(&path).map(|file| (path, file)))
        .transpose()?;
    let save = save
        .map(|path| create(&path).map(|file| (path, file)))
        .transpose()?;
    let start = Instant::now();
    let interrupted = on_interrupt();
    let bar = crate::render::progress(model.steps, "steps");
    let outcome = model.with_threads(|| {
        let done = run_steps_until(&mut surface, model.steps, &interrupted, &bar)?;
        if let Some([dc, dr]) = follow_shift {
            surface
                .shift(dc, dr)
                .map_err(|e| format!("--follow-shift {dc},{dr}: {e}"))?;
        }
        Ok(done)
    });
    bar.finish_and_clear();
    if let Err(e) | Ok(Err(e)) = outcome {
        // Leave no empty output behind that a later --load would only call truncated.
        for (path, _) in csv.iter().chain(&save) {
            let _ = std::fs::remove_file(path);
        }
        return Err(e);
    }
    let steps_run = outcome.unwrap_or(Ok(0)).unwrap_or(0);
    let seconds = start.elapsed().as_secs_f64();
    // The files before the report: a report that cannot be printed leaves them complete.
    let mut wrote = Vec::new();
    if let Some((path, file)) = csv {
        write_csv(&surface, file).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        wrote.push(path);
    }
    if let Some((path, file)) = save {
        surface
            .save(std::io::BufWriter::new(file))
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        wrote.push(path);
    }
    print_summary(&surface, steps_run, seconds)?;
    for path in &wrote {
        say!("wrote {}", path.display());
    }
    if steps_run < model.steps {
        eprintln!(
            "springwater: interrupted after {steps_run} of {} steps; {}",
            model.steps,
            if wrote.is_empty() {
                "the summary is the state reached".to_owned()
            } else {
                format!(
                    "{} the state reached",
                    if wrote.len() == 1 {
                        "the file holds"
                    } else {
                        "the files hold"
                    }
                )
            }
        );
        std::process::exit(130);
    }
    Ok(())
}

/// A flag that Ctrl-C (SIGINT, or SIGTERM) raises: the steps stop at the next one and the
/// outputs are written as the run left them. A second Ctrl-C ends the process at once.
pub fn on_interrupt() -> Arc<AtomicBool> {
    let flag = Arc::new(AtomicBool::new(false));
    let raised = flag.clone();
    // Without a handler (it cannot be installed twice, and WASI has no signals) Ctrl-C
    // ends the run as before.
    #[cfg(not(target_family = "wasm"))]
    let _ = ctrlc::set_handler(move || {
        if raised.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
    });
    #[cfg(target_family = "wasm")]
    drop(raised);
    flag
}

/// Steps up to `steps` times, stopping early when `stop` is raised; returns the steps
/// taken. The bar (drawn only on a terminal) moves every 64 steps.
pub fn run_steps_until(
    surface: &mut Surface,
    steps: u64,
    stop: &AtomicBool,
    bar: &indicatif::ProgressBar,
) -> CliResult<u64> {
    for done in 0..steps {
        if stop.load(Ordering::Relaxed) {
            return Ok(done);
        }
        surface.step().map_err(|e| e.to_string())?;
        if done % 64 == 63 {
            bar.set_position(done + 1);
        }
    }
    Ok(steps)
}

/// Parses `DC,DR`: two whole numbers of cells (signed).
fn cells(v: &str) -> CliResult<[i32; 2]> {
    const WHAT: &str = "--follow-shift DC,DR";
    match v.split(',').collect::<Vec<_>>()[..] {
        [dc, dr] => Ok([number(dc, WHAT)?, number(dr, WHAT)?]),
        _ => Err(format!(
            "{WHAT} expects 2 comma-separated whole numbers, got '{v}'"
        )),
    }
}

/// The surface a command starts from: the snapshot `load` names, with the `--drop`s added,
/// or the model the flags describe (`model_flag`, the first model flag given, may not come
/// with `--load`: `what_applies` says which flags do), and the `--floater` balls on it,
/// released at rest on the calm surface.
pub fn starting_surface(
    model: &ModelArgs,
    model_flag: Option<String>,
    load: Option<&Path>,
    floaters: &[[f32; 4]],
    what_applies: &str,
) -> CliResult<Surface> {
    let mut surface = match (load, model_flag) {
        (Some(_), Some(flag)) => {
            return Err(format!(
                "--{flag} cannot be combined with --load: the model comes from the snapshot \
                 ({what_applies})"
            ))
        }
        (Some(path), None) => {
            let mut s = load_snapshot(path)?;
            model.apply_drops(&mut s)?;
            s
        }
        (None, _) => model.surface()?,
    };
    for &[x, z, mass, radius] in floaters {
        surface
            .add_floater(Floater::sphere(radius, mass, [x, 0.0, z]))
            .map_err(|e| format!("--floater {x},{z},{mass},{radius}: {e}"))?;
    }
    Ok(surface)
}

/// Reads a snapshot file, naming it in the error. The file must hold exactly one snapshot:
/// data after it is refused (`Surface::from_bytes`), not left unread as a stream would.
pub fn load_snapshot(path: &Path) -> CliResult<Surface> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut s = Surface::from_bytes(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    crate::args::forced_level(&mut s)?;
    Ok(s)
}

/// Steps `steps` times, naming the failing step.
pub fn run_steps(surface: &mut Surface, steps: u64) -> CliResult<()> {
    for _ in 0..steps {
        surface.step().map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Prints the summary; `steps_run` (this run's steps, not the loaded ones) sets the rate.
pub fn print_summary(s: &Surface, steps_run: u64, seconds: f64) -> CliResult<()> {
    let p = s.params();
    let [_, y, _] = s.positions();
    let (lo, hi) = y
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let e = s.energy();
    say!(
        "grid        {}x{} nodes, h {}, m {}, c {}, gamma {}, rest ratio {}",
        p.cols,
        p.rows,
        p.spacing,
        p.mass,
        p.stiffness,
        p.viscosity,
        p.rest_ratio
    );
    say!(
        "timestep    {} ({:.0}% of the critical {:.4})",
        p.dt,
        100.0 * p.dt / s.critical_dt(),
        s.critical_dt()
    );
    say!(
        "steps       {} (model time {:.2}, {:.3} s)",
        s.steps(),
        s.model_time(),
        s.time()
    );
    say!("height      min {lo:.5}  max {hi:.5}");
    say!(
        "energy      kinetic {:.6}  potential {:.6}  total {:.6}",
        e.kinetic,
        e.potential,
        e.total()
    );
    if seconds > 0.0 {
        let rate = s.node_count() as f64 * steps_run as f64 / seconds;
        say!("wall time   {seconds:.3} s ({rate:.3e} node updates/s)");
    }
    if let Some(peak) = peak_memory() {
        let per_node = peak as f64 / s.node_count() as f64;
        say!(
            "memory      {:.1} MB peak ({per_node:.1} bytes per node)",
            peak as f64 / 1e6
        );
    }
    say!(
        "simd        {} (the CPU's widest: {})",
        s.simd_level(),
        springwater::SimdLevel::detect()
    );
    for (k, (_, f)) in s.floaters().enumerate() {
        let (p, v) = (f.position, f.velocity);
        say!(
            "floater {k} position {} {} {} velocity {} {} {}",
            Short(p.x),
            Short(p.y),
            Short(p.z),
            Short(v.x),
            Short(v.y),
            Short(v.z)
        );
    }
    Ok(())
}

/// The process's peak resident memory in bytes (`VmHWM` of `/proc/self/status`), where the
/// system reports it (Linux). Not on wasm32: a WASI runtime that lets the program see the
/// host's `/proc` would report its own memory, not the program's.
fn peak_memory() -> Option<u64> {
    if cfg!(target_family = "wasm") {
        return None;
    }
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Creates an output file, with a one-line error naming it.
pub fn create(path: &std::path::Path) -> CliResult<std::fs::File> {
    std::fs::File::create(path).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

pub fn write_csv(s: &Surface, file: std::fs::File) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(file);
    writeln!(w, "col,row,x,y,z")?;
    let grid = s.grid();
    let [x, y, z] = s.positions();
    for i in 0..grid.node_count() {
        let (c, r) = grid.coords(i);
        writeln!(w, "{c},{r},{},{},{}", Short(x[i]), Short(y[i]), Short(z[i]))?;
    }
    w.flush()
}
