//! `springwater simulate`: run the steps, print a summary, optionally write a CSV.

use crate::args::{next_flag, string, unexpected, CliResult, Flag, ModelArgs};
use lexopt::Parser;
use springwater::Surface;
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

pub fn run(p: &mut Parser) -> CliResult<()> {
    let mut model = ModelArgs::default();
    let mut csv: Option<PathBuf> = None;
    while let Some(arg) = next_flag(p)? {
        if model.parse_flag(&arg, p)? {
            continue;
        }
        match arg {
            Flag::Long(l) if l == "csv" => csv = Some(string(p, "--csv")?.into()),
            other => return Err(unexpected(other, "simulate")),
        }
    }
    let mut surface = model.surface()?;
    // Open the output first: an unwritable path fails before any work is done.
    let csv = csv
        .map(|path| create(&path).map(|file| (path, file)))
        .transpose()?;
    let start = Instant::now();
    model.with_threads(|| run_steps(&mut surface, model.steps))??;
    let seconds = start.elapsed().as_secs_f64();
    print_summary(&surface, seconds);
    if let Some((path, file)) = csv {
        write_csv(&surface, file).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Steps `steps` times, naming the failing step.
pub fn run_steps(surface: &mut Surface, steps: u64) -> CliResult<()> {
    for _ in 0..steps {
        surface.step().map_err(|e| e.to_string())?;
    }
    Ok(())
}

pub fn print_summary(s: &Surface, seconds: f64) {
    let p = s.params();
    let [_, y, _] = s.positions();
    let (lo, hi) = y
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let e = s.energy();
    println!(
        "grid        {}x{} nodes, h {}, m {}, c {}, gamma {}, rest ratio {}",
        p.cols, p.rows, p.spacing, p.mass, p.stiffness, p.viscosity, p.rest_ratio
    );
    println!(
        "timestep    {} ({:.0}% of the critical {:.4})",
        p.dt,
        100.0 * p.dt / s.critical_dt(),
        s.critical_dt()
    );
    println!("steps       {} (model time {:.2})", s.steps(), s.time());
    println!("height      min {lo:.5}  max {hi:.5}");
    println!(
        "energy      kinetic {:.6}  potential {:.6}  total {:.6}",
        e.kinetic,
        e.potential,
        e.total()
    );
    if seconds > 0.0 {
        let rate = s.len() as f64 * s.steps() as f64 / seconds;
        println!("wall time   {seconds:.3} s ({rate:.3e} node updates/s)");
    }
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
    for i in 0..grid.len() {
        let (c, r) = grid.coords(i);
        writeln!(w, "{c},{r},{},{},{}", x[i], y[i], z[i])?;
    }
    w.flush()
}
