//! The `springwater` command line: a thin layer over the library (DESIGN.md §3).
//!
//! Every failure ends with one line on stderr and a non-zero exit code.

mod args;
mod bench;
mod export;
mod simulate;

use std::process::ExitCode;

const USAGE: &str = "\
springwater — CPU water surface animation (mass-spring lattice)

usage: springwater <command> [flags]

commands:
  simulate   run the steps and print a summary        [--csv FILE]
  bench      time the step against the scalar reference, a naive AoS
             baseline and a memory-bandwidth floor    [--repeats N] [--compare LIST]
                                                      [--band-rows H]
  export     write the frame as a Wavefront OBJ (positions, normals, refraction UVs,
             LOD triangles)   --eye X,Y,Z --depth D [--ior N] --obj FILE
                              [--patch-cells N] [--first-range R] [--levels L]

model flags (seed defaults):
  --size COLSxROWS     grid size (128x128)
  --steps N            steps to run (100)
  --dt DT              timestep (0.4; must be below the critical timestep)
  --mass M             nodal mass (4.0)
  --stiffness C        spring coefficient (7.0)
  --viscosity G        viscosity (0.05)
  --rest-ratio R       rest length / initial length, in [0, 1] (0.5)
  --spacing H          grid step (1.0)
  --boundary pinned|free  edge condition (pinned)
  --drop COL,ROW,HEIGHT,RADIUS   add a drop (repeatable)
  --threads N          worker threads (all cores)
";

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("springwater: error: {message}");
            ExitCode::from(2)
        }
    }
}

fn run() -> args::CliResult<()> {
    let mut p = lexopt::Parser::from_env();
    let command = match args::next_flag(&mut p)? {
        Some(args::Flag::Value(v)) => v.to_string_lossy().into_owned(),
        Some(args::Flag::Short('h')) | None => {
            print!("{USAGE}");
            return Ok(());
        }
        Some(args::Flag::Long(l)) if l == "help" => {
            print!("{USAGE}");
            return Ok(());
        }
        Some(other) => return Err(args::unexpected(other, "springwater")),
    };
    match command.as_str() {
        "simulate" => simulate::run(&mut p),
        "bench" => bench::run(&mut p),
        "export" => export::run(&mut p),
        "help" => {
            print!("{USAGE}");
            Ok(())
        }
        other => Err(format!(
            "unknown command '{other}' (simulate, bench, export; see springwater --help)"
        )),
    }
}
