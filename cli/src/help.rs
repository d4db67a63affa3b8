//! `--help` and `--version`: the program's and each command's flags, with their defaults
//! and units, on stdout.

/// The program's overview: `springwater --help`.
const OVERVIEW: &str = "\
springwater — CPU water surface animation (mass-spring lattice)

usage: springwater <command> [flags]
       springwater <command> --help     that command's flags, defaults and units
       springwater --version

commands:
  render     draw the water as an animated GIF (or PNG frames)
  simulate   run the steps, print a summary; write a CSV or a snapshot, or continue one
  bench      time the step against the scalar reference, a naive baseline and a
             memory-bandwidth floor
  export     write the frame as a Wavefront OBJ (positions, normals, refraction UVs,
             LOD triangles)
  bake       write an animation cache (.glb, .mdd, .pc2, or one OBJ per frame)

Outputs are written beside their destination and moved into place when complete: a run
that fails or is stopped leaves the files that were there as they were. Ctrl-C stops
simulate at the step reached (the outputs still written, exit 130); a second Ctrl-C,
SIGTERM or SIGHUP, and Ctrl-C in the other commands, stop at once (exit 130, 143, 129).
Bad input: one line on stderr, exit 2.
";

/// The model flags every command takes.
const MODEL: &str = "\
model flags (every command; seed defaults):
  --size COLSxROWS     grid size in nodes (128x128)
  --steps N            steps to run (COMMAND_STEPS)
  --dt DT              timestep in model time units (0.4; below the critical timestep)
  --mass M             nodal mass (4)
  --stiffness C        spring coefficient (7)
  --viscosity G        viscosity (0.05)
  --rest-ratio R       rest length / initial length, in [0, 1] (0.5)
  --spacing H          grid step in world units (1)
  --boundary pinned|free|absorbing[:W]
                       edge condition (pinned); absorbing: open water, a damping
                       frame W cells wide inside the grid (32, fewer on grids under
                       98 nodes across)
  --drop COL,ROW,HEIGHT,RADIUS
                       add a drop (repeatable; COL, ROW, RADIUS in cells, HEIGHT in
                       world units)
  --threads N          worker threads, 1 to 1024 (all cores; more than the cores are
                       capped)
";

const SIMULATE: &str = "\
usage: springwater simulate [model flags] [flags]

Runs the steps and prints a summary.

flags:
  --csv FILE           write the nodes as CSV: col,row,x,y,z, one line per node
  --save FILE          write a snapshot of the whole state after the steps
  --load FILE          continue from a snapshot (the model comes from it: only --steps,
                       --drop, --threads, --follow-shift, --csv and --save apply)
  --floater X,Z,MASS,RADIUS
                       a floating ball (repeatable; world units, released at rest on the
                       calm surface; one summary line each)
  --follow-shift DC,DR move the window by DC columns and DR rows (whole cells) after the
                       steps; the CSV's x, z stay world positions
Ctrl-C stops at the step reached and still writes --csv and --save (exit 130).
";

const BENCH: &str = "\
usage: springwater bench [model flags] [flags]

Times the step; the first line names the SIMD level, the last is
nodes=… steps=… seconds=… node_updates_per_s=…

flags:
  --repeats N          timed repeats, the median reported (5)
  --compare LIST       kernels to time beside the engine, comma-separated, from
                       reference, naive, floor, 1step, none (1step,reference,naive,floor)
  --band-rows H        rows per band of the engine's schedule (chosen by the engine)
  --pass-steps K       steps fused per pass over the grid (chosen by the engine)
";

const EXPORT: &str = "\
usage: springwater export [model flags] --eye X,Y,Z --depth D --obj FILE [flags]

Runs the steps, then writes the frame as a Wavefront OBJ: a v, vn and vt (refraction UV)
per node, row-major, and the LOD triangles for the eye.

flags:
  --eye X,Y,Z          the camera, in the water's space (world units; required)
  --depth D            depth of the bottom below the rest surface (world units; required)
  --ior N              index of refraction of the water (1.333)
  --obj FILE           the OBJ to write (required)
  --patch-cells N      LOD patch size in cells, a power of two from 1 to 4096 (16)
  --first-range R      distance from the eye within which patches keep full detail
                       (world units; 32)
  --levels L           LOD levels (5)
";

const BAKE: &str = "\
usage: springwater bake [model flags] --out FILE.glb|FILE.mdd|FILE.pc2|DIR [flags]

Runs the model over N frames of 1/F seconds and writes an animation cache chosen by
--out: .glb (glTF 2.0, morph targets), .mdd or .pc2 (point caches, the rest mesh as an
OBJ of the same name beside them), or a directory (water_0001.obj … one per frame).
In a .glb every floating body is a node animated by translation and rotation channels.

flags:
  --out PATH           the cache (required)
  --frames N           frames, 1 to 1000000 (48)
  --fps F              frames per second (24)
  --steps N            warm-up steps before the rest frame (0)
  --eye X,Y,Z          LOD triangles for that eye (.glb) and refraction UVs seen from it
                       (world units; straight above the middle)
  --depth D            depth of the bottom for the refraction UVs (world units; 8)
  --ior N              index of refraction (1.333)
  --floater X,Z,MASS,RADIUS
                       a floating ball (repeatable; world units)
  --rain RATE          raindrops per second, at most one per node and step (0)
  --seed S             random seed of the rain (1)
  --wake               a ball circling the pool, leaving a wake
  --load FILE          start from a snapshot (the model comes from it)
Ctrl-C stops at once and leaves the files that were there as they were (exit 130).
";

const RENDER: &str = "\
usage: springwater render [model flags] --out FILE.gif | --png DIR [flags]

Draws the water as a looping GIF (one median-cut palette) and/or PNG frames.

flags:
  --out FILE.gif       the animation
  --png DIR            also (or instead) every frame as DIR/frame_0000.png …
  --frames N           frames to draw, 1 to 100000 (72)
  --substeps N         simulation steps between frames, 0 to 10000 (3)
  --fps F              GIF frame rate, 0.0016 to 50 frames per second (20)
  --steps N            steps before the first frame, rain falling (60)
  --width W            image width in pixels, 16 to 4096 (400)
  --height H           image height in pixels, 16 to 4096 (300)
  --eye X,Y,Z          camera position (world units; above the near edge of the pool)
  --look-at X,Y,Z      point in the middle of the image (near the pool's centre)
  --fov DEGREES        vertical field of view (45)
  --bottom FILE.png    pool bottom texture (built-in tiles)
  --depth D            depth of the bottom below the surface (world units; 8)
  --ior N              index of refraction of the water, 1 or more (1.333)
  --caustics S         caustic strength, 0 for none (1.3)
  --lod-pixels P       on-screen size of a cell where the LOD starts to coarsen (1.5)
  --rain RATE          raindrops per second, 0 for none, at most one per node and step
                       (7.2)
  --seed S             random seed of the rain (1); same seed, same file
  --wake               a ball circling the pool, leaving a wake
  --follow             a ball crossing open water in a straight line, the window and the
                       camera following it (use with --boundary absorbing; not with --wake)
  --floaters N         balls floating on the water, 0 to 1000 (0)
  --boats N            boats (the shipped hull) under way in circles, pitching and
                       rolling in the rain and leaving wakes; one per square of 15x15
                       cells of the pool (0; not with --follow)
  --wireframe          overlay the LOD triangles, coloured by level
  --orbit DEGREES      turn the camera about the target over the animation, -3600 to
                       3600 (0)
";

/// The help text of `command` (`None`: the program's), or `None` for an unknown command.
pub fn text(command: Option<&str>) -> Option<String> {
    let (own, steps) = match command {
        None => {
            return Some(format!(
                "{OVERVIEW}\n{}",
                MODEL.replace("COMMAND_STEPS", "100; render 60, bake 0")
            ))
        }
        Some("simulate") => (SIMULATE, "100"),
        Some("bench") => (BENCH, "100"),
        Some("export") => (EXPORT, "100"),
        Some("bake") => (BAKE, "0"),
        Some("render") => (RENDER, "60"),
        Some(_) => return None,
    };
    Some(format!("{own}\n{}", MODEL.replace("COMMAND_STEPS", steps)))
}

/// `springwater --version`.
pub fn version() -> String {
    format!("springwater {}\n", env!("CARGO_PKG_VERSION"))
}
