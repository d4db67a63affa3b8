//! `springwater bench`: time the engine step, and compare it in the same run with the
//! scalar reference, the naive array-of-structs baseline and the memory floor.

use crate::args::{next_flag, ranged, string, unexpected, value, CliResult, Flag, ModelArgs};
use lexopt::Parser;
use springwater::internals::{MemoryFloor, NaiveSurface, Tuning, MAX_PASS_STEPS};
use springwater::{SimdLevel, Surface};
use std::time::Instant;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kernel {
    Engine,
    SingleSteps,
    Reference,
    Naive,
    Floor,
}

impl Kernel {
    fn name(self) -> &'static str {
        match self {
            Kernel::Engine => "engine",
            Kernel::SingleSteps => "engine-1step",
            Kernel::Reference => "reference",
            Kernel::Naive => "naive",
            Kernel::Floor => "memory-floor",
        }
    }
}

/// The most rounds `--repeats` takes.
const MAX_REPEATS: usize = 10_000;

pub fn run(p: &mut Parser) -> CliResult<()> {
    let mut model = ModelArgs::default();
    let mut repeats: usize = 5;
    let mut band_rows: Option<usize> = None;
    let mut pass_steps: Option<usize> = None;
    let mut compare = vec![
        Kernel::SingleSteps,
        Kernel::Reference,
        Kernel::Naive,
        Kernel::Floor,
    ];
    while let Some(arg) = next_flag(p)? {
        if model.parse_flag(&arg, p)? {
            continue;
        }
        match arg {
            Flag::Long(l) if l == "repeats" => {
                repeats = ranged(value(p, "--repeats")?, 1, MAX_REPEATS, "--repeats")?;
            }
            Flag::Long(l) if l == "band-rows" => {
                let h: usize = value(p, "--band-rows")?;
                if h == 0 {
                    return Err("--band-rows must be at least 1".into());
                }
                band_rows = Some(h);
            }
            Flag::Long(l) if l == "pass-steps" => {
                let k: usize = value(p, "--pass-steps")?;
                if !(1..=MAX_PASS_STEPS).contains(&k) {
                    return Err(format!(
                        "--pass-steps must be between 1 and {}",
                        MAX_PASS_STEPS
                    ));
                }
                pass_steps = Some(k);
            }
            Flag::Long(l) if l == "compare" => {
                compare = string(p, "--compare")?
                    .split(',')
                    .filter(|s| !s.is_empty() && *s != "none")
                    .map(|s| match s {
                        "reference" => Ok(Kernel::Reference),
                        "1step" => Ok(Kernel::SingleSteps),
                        "naive" => Ok(Kernel::Naive),
                        "floor" => Ok(Kernel::Floor),
                        other => Err(format!(
                            "--compare: unknown kernel '{other}' (reference, naive, floor, 1step, none)"
                        )),
                    })
                    .collect::<CliResult<Vec<_>>>()?;
                // Each kernel once, in the order first given.
                let mut seen = Vec::new();
                compare.retain(|k| {
                    let new = !seen.contains(k);
                    seen.push(*k);
                    new
                });
            }
            other => return Err(unexpected(other, "bench")),
        }
    }
    if model.steps == 0 {
        return Err("--steps must be at least 1 for bench".into());
    }
    // The surface and a copy, or the baseline, for each kernel compared (peak resident
    // bytes per node, measured on 2048 x 2048 and rounded up).
    let per_node: u64 = 64
        + compare
            .iter()
            .map(|k| match k {
                Kernel::SingleSteps | Kernel::Reference => 112,
                Kernel::Naive => 144,
                Kernel::Floor => 24,
                Kernel::Engine => 64,
            })
            .sum::<u64>();
    crate::memory::check_grid(&model.params, per_node, 0, "bench")?;
    let mut surface = model.surface()?;
    if let Some(h) = band_rows {
        surface.set_band_rows(h);
    }
    if let Some(k) = pass_steps {
        surface.set_pass_steps(k);
    }
    if model.drops.is_empty() {
        // The same drop as `--drop COLS/2,ROWS/2,1,4` (grid steps) at any spacing.
        let p = surface.params();
        let h = p.spacing;
        surface
            .drop_at(
                p.cols as f32 / 2.0 * h,
                p.rows as f32 / 2.0 * h,
                1.0,
                4.0 * h,
            )
            .map_err(|e| e.to_string())?;
    }
    let threads = model.threads.unwrap_or_else(rayon::current_num_threads);
    let params = *surface.params();
    let nodes = surface.node_count();
    let mut kernels = vec![Kernel::Engine];
    kernels.extend(compare);
    let simd = surface.simd_level();
    say!(
        "bench simd={simd} ({} f32 lanes; CPU's widest {}, build's baseline {}) {}x{} ({nodes} nodes), {} steps x {repeats} repeats, {threads} thread(s)",
        simd.lanes(),
        springwater::SimdLevel::detect(),
        features(),
        params.cols,
        params.rows,
        model.steps,
    );

    let samples = model.with_threads(|| -> CliResult<Vec<Vec<f64>>> {
        let mut naive = kernels.contains(&Kernel::Naive).then(|| {
            let mut n = NaiveSurface::new(&params);
            n.drop_at(
                params.cols,
                params.cols as f32 / 2.0,
                params.rows as f32 / 2.0,
                1.0,
                4.0,
            );
            n
        });
        let mut reference = kernels.contains(&Kernel::Reference).then(|| {
            let mut s = surface.clone();
            s.set_simd_level(SimdLevel::Scalar);
            s
        });
        let mut single = kernels
            .contains(&Kernel::SingleSteps)
            .then(|| surface.clone());
        let mut floor = kernels
            .contains(&Kernel::Floor)
            .then(|| MemoryFloor::new(nodes));
        let mut samples = vec![Vec::new(); kernels.len()];
        // One warm-up round, then `repeats` interleaved rounds so drift hits every kernel.
        // Every kernel runs the same steps from the same start, so each round times all of
        // them on the same stage of the simulation: the early steps of a drop carry
        // subnormal values at the wavefront, which slow scalar code by up to 1.6x here (the
        // engine by a few percent at that stage), so comparing different stages would skew
        // the ratios.
        for round in 0..=repeats {
            for (k, kernel) in kernels.iter().enumerate() {
                let start = Instant::now();
                let steps = match kernel {
                    Kernel::Engine => {
                        surface.step_n(model.steps).map_err(|e| e.to_string())?;
                        model.steps
                    }
                    Kernel::SingleSteps => {
                        let s: &mut Surface = single.as_mut().expect("built above");
                        for _ in 0..model.steps {
                            s.step().map_err(|e| e.to_string())?;
                        }
                        model.steps
                    }
                    Kernel::Reference => {
                        let s: &mut Surface = reference.as_mut().expect("built above");
                        for _ in 0..model.steps {
                            s.step().map_err(|e| e.to_string())?;
                        }
                        model.steps
                    }
                    Kernel::Naive => {
                        let n = naive.as_mut().expect("built above");
                        for _ in 0..model.steps {
                            n.step();
                        }
                        model.steps
                    }
                    Kernel::Floor => {
                        let f = floor.as_mut().expect("built above");
                        for _ in 0..model.steps {
                            f.pass(params.dt, 0.999);
                        }
                        std::hint::black_box(f.checksum());
                        model.steps
                    }
                };
                if round > 0 {
                    samples[k].push(start.elapsed().as_secs_f64() / steps as f64);
                }
            }
        }
        Ok(samples)
    })??;

    let per_step: Vec<f64> = samples.iter().map(|s| median(s)).collect();
    say!(
        "{:<14}{:>16}{:>20}{:>18}",
        "kernel",
        "s/step (median)",
        "node updates/s",
        "engine speed-up"
    );
    for (kernel, t) in kernels.iter().zip(&per_step) {
        let ratio = if *kernel == Kernel::Engine {
            String::from("1.00x")
        } else {
            format!("{:.2}x", t / per_step[0])
        };
        say!(
            "{:<14}{:>16.6e}{:>20.4e}{:>18}",
            kernel.name(),
            t,
            nodes as f64 / t,
            ratio
        );
    }
    let seconds = per_step[0] * model.steps as f64;
    say!(
        "nodes={nodes} steps={} seconds={seconds:.6} node_updates_per_s={:.4e}",
        model.steps,
        nodes as f64 * model.steps as f64 / seconds
    );
    Ok(())
}

fn median(v: &[f64]) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The widest instruction set this build may use everywhere it runs (its compile-time
/// target features), named as [`SimdLevel`] names levels.
fn features() -> &'static str {
    if cfg!(target_feature = "avx512f") {
        "avx512"
    } else if cfg!(target_feature = "avx2") {
        "avx2"
    } else if cfg!(target_arch = "x86_64") {
        "sse2"
    } else if cfg!(target_arch = "aarch64") {
        "neon"
    } else if cfg!(all(target_arch = "wasm32", target_feature = "simd128")) {
        "simd128"
    } else {
        "portable"
    }
}
