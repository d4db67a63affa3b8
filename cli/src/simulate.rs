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

use crate::args::{number, string, unexpected, CliResult, Flag, Short};
use crate::output::{self, Output};
use crate::start::{run_steps_until, Start};
use lexopt::Parser;
use springwater::window::MAX_ORIGIN_CELLS;
use springwater::Surface;
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

pub fn run(p: &mut Parser) -> CliResult<()> {
    let mut start = Start::with_steps(100);
    let mut csv: Option<PathBuf> = None;
    let mut save: Option<PathBuf> = None;
    let mut follow_shift: Option<[i32; 2]> = None;
    while let Some(arg) = crate::args::next_flag(p)? {
        if start.parse_flag(&arg, p)? {
            continue;
        }
        match arg {
            Flag::Long(l) if l == "csv" => csv = Some(string(p, "--csv")?.into()),
            Flag::Long(l) if l == "save" => save = Some(string(p, "--save")?.into()),
            Flag::Long(l) if l == "follow-shift" => {
                follow_shift = Some(cells(&string(p, "--follow-shift")?)?)
            }
            other => return Err(unexpected(other, "simulate")),
        }
    }
    // `--save` may replace its own `--load` input (the new file moves into place only when
    // complete); the CSV may replace neither.
    let mut named = Vec::new();
    named.extend(csv.as_deref().map(|p| ("--csv", p)));
    named.extend(save.as_deref().map(|p| ("--save", p)));
    output::distinct(&named)?;
    if let (Some(c), Some(l)) = (&csv, &start.load) {
        output::distinct(&[("--csv", c), ("--load", l)])?;
    }
    let mut surface =
        start.surface("only --steps, --drop, --threads, --follow-shift, --csv and --save apply")?;
    let model = &start.model;
    if let Some([dc, dr]) = follow_shift {
        // Checked before the steps: a shift the window cannot take refuses the run now.
        let [oc, or] = surface.origin_cells();
        for (name, origin, d) in [("DC", oc, dc), ("DR", or, dr)] {
            let (lo, hi) = (-MAX_ORIGIN_CELLS - origin, MAX_ORIGIN_CELLS - origin);
            if !(lo..=hi).contains(&i64::from(d)) {
                return Err(format!(
                    "--follow-shift {dc},{dr}: {name} {d} is out of range: the window may \
                     move {lo} to {hi} cells from where it is (within {MAX_ORIGIN_CELLS} \
                     cells of the water's origin, where every cell index is an exact f32)"
                ));
            }
        }
    }
    // Open the outputs first: an unwritable path fails before any work is done.
    let csv = csv.map(|path| Output::create(&path, "--csv")).transpose()?;
    let save = save
        .map(|path| Output::create(&path, "--save"))
        .transpose()?;
    let started = Instant::now();
    let bar = crate::progress::bar(model.steps, "steps");
    let outcome = model.with_threads(|| {
        let done = run_steps_until(&mut surface, model.steps, &bar)?;
        if let Some([dc, dr]) = follow_shift {
            surface
                .shift(dc, dr)
                .map_err(|e| format!("--follow-shift {dc},{dr}: {e}"))?;
        }
        Ok::<_, String>(done)
    });
    bar.finish_and_clear();
    // A failure drops the outputs: the files that were there stay as they were.
    let steps_run = outcome??;
    let seconds = started.elapsed().as_secs_f64();
    // The files before the report: a report that cannot be printed leaves them complete.
    let mut wrote = Vec::new();
    let mut pending = Vec::new();
    if let Some(out) = csv {
        let fail = |e: std::io::Error| format!("cannot write {}: {e}", out.path().display());
        write_csv(&surface, out.file().map_err(fail)?).map_err(fail)?;
        wrote.push(out.path().to_path_buf());
        pending.push(output::Pending::File(out));
    }
    if let Some(out) = save {
        let fail = |e: String| format!("cannot write {}: {e}", out.path().display());
        let file = out.file().map_err(|e| fail(e.to_string()))?;
        surface
            .save(std::io::BufWriter::new(file))
            .map_err(|e| fail(e.to_string()))?;
        wrote.push(out.path().to_path_buf());
        pending.push(output::Pending::File(out));
    }
    output::commit_all(pending).map_err(|e| e.to_string())?;
    print_summary(&surface, steps_run, seconds)?;
    for path in &wrote {
        say!("wrote {}", path.display());
    }
    if steps_run < model.steps {
        eprintln!(
            "springwater: interrupted after {steps_run} of {}; {}",
            crate::args::count(model.steps, "step"),
            match wrote.len() {
                0 => "the summary is the state reached",
                1 => "the file holds the state reached",
                _ => "the files hold the state reached",
            }
        );
        std::process::exit(130);
    }
    Ok(())
}

/// Parses `DC,DR`: two whole numbers of cells (signed; the range is checked against the
/// window's origin before the steps).
fn cells(v: &str) -> CliResult<[i32; 2]> {
    const WHAT: &str = "--follow-shift DC,DR";
    let limit = 2 * MAX_ORIGIN_CELLS;
    let one = |s: &str| -> CliResult<i32> {
        let d: i64 = number(s, WHAT)?;
        i32::try_from(d)
            .ok()
            .filter(|d| i64::from(*d).abs() <= limit)
            .ok_or_else(|| {
                format!(
                    "{WHAT}: {d} is out of range: a shift moves the window at most \
                     {MAX_ORIGIN_CELLS} cells from the water's origin"
                )
            })
    };
    match v.split(',').collect::<Vec<_>>()[..] {
        [dc, dr] => Ok([one(dc)?, one(dr)?]),
        _ => Err(format!(
            "{WHAT} expects 2 comma-separated whole numbers, got '{v}'"
        )),
    }
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
        "steps       {} (model time {}, {} s)",
        s.steps(),
        fixed(s.model_time(), 2),
        fixed(s.time(), 3)
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

/// `v` with `places` decimals, or in scientific notation past a trillion (a snapshot may
/// hold a model time of 1e308, three hundred digits in fixed notation).
fn fixed(v: f64, places: usize) -> String {
    if v.abs() < 1e12 {
        format!("{v:.places$}")
    } else {
        format!("{v:.3e}")
    }
}
