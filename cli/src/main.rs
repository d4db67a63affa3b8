//! The `springwater` command line: a thin layer over the library (DESIGN.md §3).
//!
//! Every failure ends with one line on stderr and a non-zero exit code.

/// `println!` for a command's report on stdout, written through [`write_out`]: in a function
/// that returns [`args::CliResult`], it never panics.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::write_out(format_args!("{}\n", format_args!($($arg)*)))?
    };
}

mod args;
mod bake;
mod bench;
mod export;
mod image;
mod render;
mod simulate;

use std::process::ExitCode;

const USAGE: &str = "\
springwater — CPU water surface animation (mass-spring lattice)

usage: springwater <command> [flags]

commands:
  render     draw the water as an animated GIF        --out FILE.gif | --png DIR
  simulate   run the steps and print a summary        [--csv FILE] [--save FILE]
             floating balls: --floater X,Z,MASS,RADIUS (repeatable; world units,
             released at rest on the calm surface; one summary line each)
             continue from a snapshot: simulate --load FILE --steps N [--drop …]
             a progress bar on a terminal; Ctrl-C stops at the step reached and
             still writes --csv and --save
             move the window after the steps: --follow-shift DC,DR (whole cells;
             the CSV's x, z stay world positions, the strip that comes in is calm)
  bench      time the step against the scalar reference, a naive AoS
             baseline and a memory-bandwidth floor    [--repeats N] [--compare LIST]
                                                      [--band-rows H]
  export     write the frame as a Wavefront OBJ (positions, normals, refraction UVs,
             LOD triangles)   --eye X,Y,Z --depth D [--ior N] --obj FILE
                              [--patch-cells N] [--first-range R] [--levels L]
  bake       write an animation cache for Blender, game engines and DCC tools
             --frames N (48) --fps F (24) --out FILE.glb | FILE.mdd | FILE.pc2 | DIR
             [--eye X,Y,Z: LOD triangles for that eye, refraction UVs seen from it]
             [--depth D] [--ior N] [--floater X,Z,MASS,RADIUS] [--rain RATE]
             [--seed S] [--wake] [--load FILE]; --steps N: warm-up steps (0)

model flags (seed defaults):
  --size COLSxROWS     grid size (128x128)
  --steps N            steps to run (100)
  --dt DT              timestep (0.4; must be below the critical timestep)
  --mass M             nodal mass (4.0)
  --stiffness C        spring coefficient (7.0)
  --viscosity G        viscosity (0.05)
  --rest-ratio R       rest length / initial length, in [0, 1] (0.5)
  --spacing H          grid step (1.0)
  --boundary pinned|free|absorbing[:W]
                       edge condition (pinned); absorbing: open water, a damping
                       frame W cells wide inside the grid (32, fewer on grids
                       under 98 nodes across)
  --drop COL,ROW,HEIGHT,RADIUS   add a drop (repeatable)
  --threads N          worker threads (all cores; more than the cores are capped)

render flags (defaults in brackets):
  --out FILE.gif       the animation (a looping GIF, one median-cut palette)
  --png DIR            also (or instead) every frame as DIR/frame_NNNN.png
  --frames N           frames to draw (72)
  --substeps N         simulation steps between frames (3)
  --fps F              GIF frame rate (20)
  --steps N            steps before the first frame, rain falling (60)
  --width W --height H image size in pixels (400x300)
  --eye X,Y,Z          camera position (above the near edge of the pool)
  --look-at X,Y,Z      point in the middle of the image (near the pool's centre)
  --fov DEGREES        vertical field of view (45)
  --bottom FILE.png    pool bottom texture (built-in tiles)
  --depth D            depth of the bottom below the surface (8)
  --ior N              index of refraction of the water (1.333)
  --caustics S         caustic strength, 0 for none (1.3)
  --lod-pixels P       on-screen size of a cell where the LOD starts to coarsen (1.5)
  --rain RATE          raindrops per second, 0 for none (7.2)
  --seed S             random seed of the rain (1); same seed, same file
  --wake               a ball circling the pool, leaving a wake
  --follow             a ball crossing open water in a straight line, the window and
                       the camera following it (use with --boundary absorbing)
  --floaters N         N balls floating on the water, bobbing in the rain (0)
  --wireframe          overlay the LOD triangles, coloured by level
  --orbit DEGREES      turn the camera about the target over the animation (0)
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

/// Writes to stdout. A reader that has gone away (`springwater bench | head -1`) is not an
/// error: the rest of the report is dropped and the command still does all its work (the
/// files it was asked to write are written). Any other write error is reported.
fn write_out(text: std::fmt::Arguments) -> args::CliResult<()> {
    use std::io::Write;
    match std::io::stdout().lock().write_fmt(text) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(format!("cannot write to standard output: {e}"))
        }
        _ => Ok(()),
    }
}

fn run() -> args::CliResult<()> {
    let mut p = lexopt::Parser::from_env();
    // No command, `-h` and `--help` are the `help` command.
    let command = match args::next_flag(&mut p)? {
        Some(args::Flag::Value(v)) => v.to_string_lossy().into_owned(),
        Some(args::Flag::Short('h')) | None => "help".to_owned(),
        Some(args::Flag::Long(l)) if l == "help" => "help".to_owned(),
        Some(other) => return Err(args::unexpected(other, "springwater")),
    };
    match command.as_str() {
        "simulate" => simulate::run(&mut p),
        "bench" => bench::run(&mut p),
        "render" => render::run(&mut p),
        "export" => export::run(&mut p),
        "bake" => bake::run(&mut p),
        "help" => write_out(format_args!("{USAGE}")),
        other => Err(format!(
            "unknown command '{other}' (render, simulate, bench, export, bake; see springwater --help)"
        )),
    }
}
