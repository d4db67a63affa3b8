//! Absorbing-boundary probe for springwater: ring test (reflected energy against a padded
//! reference run). The measurements of docs/open-water.md, which explains the method.
//!
//! Usage: `cargo run --release --example absorb_probe -- MODE`, MODE one of
//!        limit | pad | walls | sweep | mur | all, or
//!        instant N STEPS W GMAX SHAPE   (SHAPE = a power, cos, smooth, f<share>)
//!
//! `instant` is the 300-step table of docs/open-water.md: the reflected energy after every
//! step (its largest value, the largest over every 4th step, the step it peaks at) for the
//! four cases, and at the last step the measures it was compared with (rms height of the
//! difference in the middle against a pinned wall's, energy against the wall's).
use springwater::{Boundary, Params, Surface};

const M: f64 = 4.0;
const C: f64 = 7.0;
const R: f64 = 0.5;
const KS: f64 = C * (1.0 - R); // transverse stiffness per spring (all 8 families)
const DT: f32 = 0.4;
const INTERIOR: usize = 128; // nodes of the measured interior along a side
fn t_steps() -> usize {
    std::env::var("T_STEPS")
        .ok()
        .map(|v| v.parse().unwrap())
        .unwrap_or(400)
} // time window
const SAMPLE: usize = 4; // sample every SAMPLE steps
const VMAX: f64 = 0.8; // cells/step used to size the reference padding (long-wave speed is 0.648)
fn height() -> f32 {
    std::env::var("HEIGHT")
        .ok()
        .map(|v| v.parse().unwrap())
        .unwrap_or(0.05)
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Pos {
    Centre,
    Corner,
}

#[derive(Clone, Copy, Debug)]
enum Edge {
    /// Pinned outer ring, damping frame of width w (w = 0: plain pinned wall).
    Frame { w: usize, p: i32, gmax: f32 },
    /// No node pinned (free edge), no frame.
    Free,
    /// No node pinned, the outer ring held in-plane by a constant external force equal
    /// and opposite to its rest-state spring pull (vertically free: a Neumann edge).
    FreeHeld,
    /// First-order Mur on the outer ring (heavy driven nodes), plus an optional frame.
    Mur { w: usize, p: i32, gmax: f32 },
}

impl Edge {
    fn w(&self) -> usize {
        match *self {
            Edge::Frame { w, .. } | Edge::Mur { w, .. } => w,
            Edge::Free | Edge::FreeHeld => 0,
        }
    }
}

fn dist_edge(n: usize, c: usize, r: usize) -> usize {
    c.min(r).min(n - 1 - c).min(n - 1 - r)
}

fn source(n: usize, w: usize, pos: Pos) -> (f32, f32) {
    match pos {
        Pos::Centre => ((n / 2) as f32, (n / 2) as f32),
        Pos::Corner => {
            let s = (1.5 * w as f32 + 4.0).max(16.0).round();
            (s, s)
        }
    }
}

fn profile(w: usize, p: i32, gmax: f32, d: usize) -> f32 {
    if d >= w {
        0.0
    } else {
        gmax * (((w - d) as f32) / w as f32).powi(p)
    }
}

fn base_params(n: usize, boundary: Boundary) -> Params {
    let mut p = Params::with_size(n, n);
    p.viscosity = 0.0;
    p.dt = DT;
    p.boundary = boundary;
    p
}

/// Linear vertical energy of a field over the nodes where `inside` holds:
/// ½ m Σ vy² + ½ Σ_springs (both ends inside) c(1−r) (y_i − y_j)².
fn lin_energy(n: usize, y: &[f64], vy: &[f64], inside: &dyn Fn(usize, usize) -> bool) -> f64 {
    let mut e = 0.0;
    for r in 0..n {
        for c in 0..n {
            if !inside(c, r) {
                continue;
            }
            let i = r * n + c;
            e += 0.5 * M * vy[i] * vy[i];
            for (dc, dr) in [(1isize, 0isize), (0, 1), (1, 1), (-1, 1)] {
                let (cj, rj) = (c as isize + dc, r as isize + dr);
                if cj < 0 || rj < 0 || cj >= n as isize || rj >= n as isize {
                    continue;
                }
                let (cj, rj) = (cj as usize, rj as usize);
                if !inside(cj, rj) {
                    continue;
                }
                let d = y[i] - y[rj * n + cj];
                e += 0.5 * KS * d * d;
            }
        }
    }
    e
}

/// Window (n×n at offset off) of y and vy of a surface, in f64.
fn window(s: &Surface, n: usize, off: usize) -> (Vec<f64>, Vec<f64>) {
    let big = s.params().cols;
    let [_, y, _] = s.positions();
    let [_, vy, _] = s.velocities();
    let mut wy = vec![0.0; n * n];
    let mut wv = vec![0.0; n * n];
    for r in 0..n {
        for c in 0..n {
            let j = (r + off) * big + c + off;
            wy[r * n + c] = y[j] as f64;
            wv[r * n + c] = vy[j] as f64;
        }
    }
    (wy, wv)
}

fn padding(n: usize, w: usize, pos: Pos) -> usize {
    let (sx, _) = source(n, w, pos);
    let need = (VMAX * t_steps() as f64 - sx as f64 - w.max(1) as f64) / 2.0;
    need.max(0.0).ceil() as usize + 12
}

struct Reference {
    e0: f64,
    samples: Vec<(Vec<f64>, Vec<f64>)>,
}

fn reference(n: usize, w: usize, pos: Pos, radius: f32, pad: usize) -> Reference {
    let nr = n + 2 * pad;
    let mut s = Surface::new(base_params(nr, Boundary::Pinned)).unwrap();
    let (sx, sz) = source(n, w, pos);
    s.drop_at(sx + pad as f32, sz + pad as f32, height(), radius)
        .unwrap();
    let (y0, v0) = window(&s, nr, 0);
    let e0 = lin_energy(nr, &y0, &v0, &|_, _| true);
    let mut samples = vec![window(&s, n, pad)];
    for _ in 0..t_steps() / SAMPLE {
        s.step_n(SAMPLE as u64).unwrap();
        samples.push(window(&s, n, pad));
    }
    Reference { e0, samples }
}

/// Builds the absorbing-candidate surface. Err(msg) when the public API refuses it.
fn build(n: usize, edge: Edge) -> Result<Surface, String> {
    let boundary = match edge {
        Edge::Free | Edge::FreeHeld | Edge::Mur { .. } => Boundary::Free,
        Edge::Frame { .. } => Boundary::Pinned,
    };
    let mut s = Surface::new(base_params(n, boundary)).map_err(|e| e.to_string())?;
    if let Edge::Frame { w, p, gmax } | Edge::Mur { w, p, gmax } = edge {
        for r in 0..n {
            for c in 0..n {
                let g = profile(w, p, gmax, dist_edge(n, c, r));
                if g > 0.0 {
                    s.set_viscosity(r * n + c, g).map_err(|e| e.to_string())?;
                }
            }
        }
    }
    if let Edge::Mur { .. } = edge {
        for r in 0..n {
            for c in 0..n {
                if dist_edge(n, c, r) == 0 {
                    s.set_mass(r * n + c, 1.0e6).map_err(|e| e.to_string())?;
                }
            }
        }
    }
    Ok(s)
}

/// First-order Mur on the outer ring, applied through heavy ring nodes driven by an
/// external force so that after the step they sit at the Mur value
/// u0' = u1 + α (u1' − u0), with u1' predicted from the linear vertical force at x^k.
fn mur_forces(s: &mut Surface) {
    let n = s.params().cols;
    let c0 = (3.0 * KS / M).sqrt(); // long-wave speed, cells per unit time
    let cdt = c0 * DT as f64;
    let alpha = (cdt - 1.0) / (cdt + 1.0);
    let dt = DT as f64;
    let [_, y, _] = s.positions();
    let [_, vy, _] = s.velocities();
    let gam = s.viscosities();
    let mass = s.masses();
    let mut forces = Vec::with_capacity(4 * n);
    for r in 0..n {
        for c in 0..n {
            if dist_edge(n, c, r) != 0 {
                continue;
            }
            let i = r * n + c;
            // inward neighbour: along the normal (diagonal at corners)
            let ic = if c == 0 {
                1
            } else if c == n - 1 {
                n - 2
            } else {
                c
            };
            let ir = if r == 0 {
                1
            } else if r == n - 1 {
                n - 2
            } else {
                r
            };
            let i1 = ir * n + ic;
            let mut f1 = 0.0;
            for dr in -1isize..=1 {
                for dc in -1isize..=1 {
                    if dr == 0 && dc == 0 {
                        continue;
                    }
                    let j = ((ir as isize + dr) as usize) * n + (ic as isize + dc) as usize;
                    f1 += KS * (y[j] as f64 - y[i1] as f64);
                }
            }
            let v1 = vy[i1] as f64;
            let a1 = (f1 - gam[i1] as f64 * v1) / M;
            let v1n = v1 + dt * a1;
            let u1n = y[i1] as f64 + dt * v1n;
            let target = y[i1] as f64 + alpha * (u1n - y[i] as f64);
            let need_v = (target - y[i] as f64) / dt;
            let f = mass[i] as f64 * (need_v - vy[i] as f64) / dt;
            forces.push((i, f as f32));
        }
    }
    for (i, f) in forces {
        s.add_force(i, [0.0, f, 0.0]).unwrap();
    }
}

/// In-plane force that cancels the rest-state pull of the springs on each outer-ring node
/// of a free grid: −c(1−r)·Σ offsets of the present neighbours.
fn hold_forces(n: usize) -> Vec<(usize, [f32; 3])> {
    let mut out = vec![];
    for r in 0..n {
        for c in 0..n {
            if dist_edge(n, c, r) != 0 {
                continue;
            }
            let (mut fx, mut fz) = (0.0f64, 0.0f64);
            for dr in -1isize..=1 {
                for dc in -1isize..=1 {
                    let (cj, rj) = (c as isize + dc, r as isize + dr);
                    if (dr == 0 && dc == 0)
                        || cj < 0
                        || rj < 0
                        || cj >= n as isize
                        || rj >= n as isize
                    {
                        continue;
                    }
                    fx += C * (1.0 - R) * dc as f64;
                    fz += C * (1.0 - R) * dr as f64;
                }
            }
            out.push((r * n + c, [-fx as f32, 0.0, -fz as f32]));
        }
    }
    out
}

struct Outcome {
    max: f64,
    t_max: usize,
    end: f64,
}

fn run_case(
    n: usize,
    edge: Edge,
    pos: Pos,
    radius: f32,
    refr: &Reference,
) -> Result<Outcome, String> {
    let w = edge.w();
    let mut s = build(n, edge)?;
    let (sx, sz) = source(n, w, pos);
    s.drop_at(sx, sz, height(), radius)
        .map_err(|e| e.to_string())?;
    let roi_w = w.max(1);
    let inside = move |c: usize, r: usize| dist_edge(n, c, r) >= roi_w;
    let mut max = 0.0f64;
    let mut t_max = 0;
    let mut end = 0.0;
    let mur = matches!(edge, Edge::Mur { .. });
    let held = matches!(edge, Edge::Mur { .. } | Edge::FreeHeld);
    let hold = hold_forces(n);
    for k in 1..=t_steps() / SAMPLE {
        if held {
            for _ in 0..SAMPLE {
                for &(i, f) in &hold {
                    s.add_force(i, f).map_err(|e| e.to_string())?;
                }
                if mur {
                    mur_forces(&mut s);
                }
                s.step().map_err(|e| e.to_string())?;
            }
        } else {
            s.step_n(SAMPLE as u64).map_err(|e| e.to_string())?;
        }
        let (ay, av) = window(&s, n, 0);
        let (ry, rv) = &refr.samples[k];
        let dy: Vec<f64> = ay.iter().zip(ry).map(|(a, b)| a - b).collect();
        let dv: Vec<f64> = av.iter().zip(rv).map(|(a, b)| a - b).collect();
        let e = lin_energy(n, &dy, &dv, &inside) / refr.e0;
        if !e.is_finite() {
            return Err("non-finite".into());
        }
        if e > max {
            max = e;
            t_max = k * SAMPLE;
        }
        end = e;
    }
    Ok(Outcome { max, t_max, end })
}

fn limit() {
    // Largest uniform frame viscosity Surface::set_viscosity accepts at dt 0.4.
    let mut s = Surface::new(base_params(8, Boundary::Pinned)).unwrap();
    let (mut lo, mut hi) = (0.0f32, 10.0f32);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let mut t = s.clone();
        if t.set_viscosity(20, mid).is_ok() {
            lo = mid
        } else {
            hi = mid
        }
    }
    let _ = s.set_viscosity(20, lo);
    println!("limit: largest gamma accepted by set_viscosity at dt 0.4 = {lo} (refused at {hi})");
    let mut p = base_params(8, Boundary::Pinned);
    p.viscosity = 3.3;
    println!(
        "limit: Surface::new with viscosity 3.3 -> {:?}",
        Surface::new(p).err().map(|e| e.to_string())
    );
    // Once built without the dt check with a large uniform viscosity, can the frame still be graded?
    let mut p = base_params(8, Boundary::Pinned);
    p.viscosity = 4.0;
    let mut s = Surface::new_without_dt_check(p).unwrap();
    println!(
        "limit: new_without_dt_check(viscosity 4) then set_viscosity(node, 0) -> {:?}",
        s.set_viscosity(20, 0.0).err().map(|e| e.to_string())
    );
}

fn pad_check() {
    for &(w, pos, radius) in &[
        (8usize, Pos::Corner, 2.0f32),
        (8, Pos::Corner, 4.0),
        (48, Pos::Corner, 2.0),
        (8, Pos::Centre, 2.0),
        (0, Pos::Corner, 2.0),
    ] {
        let n = INTERIOR + 2 * w;
        let p = padding(n, w, pos);
        let a = reference(n, w, pos, radius, p);
        let b = reference(n, w, pos, radius, p + 60);
        let roi_w = w.max(1);
        let inside = |c: usize, r: usize| dist_edge(n, c, r) >= roi_w;
        let mut max = 0.0f64;
        for k in 0..a.samples.len() {
            let dy: Vec<f64> = a.samples[k]
                .0
                .iter()
                .zip(&b.samples[k].0)
                .map(|(x, y)| x - y)
                .collect();
            let dv: Vec<f64> = a.samples[k]
                .1
                .iter()
                .zip(&b.samples[k].1)
                .map(|(x, y)| x - y)
                .collect();
            max = max.max(lin_energy(n, &dy, &dv, &inside) / a.e0);
        }
        println!("pad: W={w} {pos:?} r={radius} N={n} pad={p} (ref grid {}²): max diff vs pad+60 = {max:.3e}", n + 2 * p);
    }
}

fn print(edge: Edge, n: usize, pos: Pos, radius: f32, o: &Result<Outcome, String>) {
    let (w, p, g) = match edge {
        Edge::Frame { w, p, gmax } | Edge::Mur { w, p, gmax } => (w, p, gmax),
        Edge::Free | Edge::FreeHeld => (0, 0, 0.0),
    };
    let kind = match edge {
        Edge::Frame { w: 0, .. } => "pinned",
        Edge::Frame { .. } => "frame",
        Edge::Free => "free",
        Edge::FreeHeld => "free-held",
        Edge::Mur { .. } => "mur",
    };
    let frame_nodes = n * n - INTERIOR * INTERIOR;
    match o {
        Ok(o) => println!(
            "RES {kind} W={w} p={p} g={g} N={n} frame_nodes={frame_nodes} bump={} {pos:?} refl_max={:.3e} t_max={} refl_end={:.3e}",
            radius, o.max, o.t_max, o.end
        ),
        Err(e) => println!("RES {kind} W={w} p={p} g={g} N={n} bump={} {pos:?} FAILED: {e}", radius),
    }
}

fn sweep(edges_for_w: &dyn Fn(usize) -> Vec<Edge>, ws: &[usize]) {
    for &w in ws {
        let n = INTERIOR + 2 * w;
        for pos in [Pos::Centre, Pos::Corner] {
            for radius in [4.0f32, 2.0] {
                let pad = padding(n, w, pos);
                let refr = reference(n, w, pos, radius, pad);
                let roi_w = w.max(1);
                let (ry, rv) = refr.samples.last().unwrap();
                let resid = lin_energy(n, ry, rv, &|c, r| dist_edge(n, c, r) >= roi_w) / refr.e0;
                println!(
                    "REF W={w} N={n} pad={pad} bump={radius} {pos:?} roi_energy_at_T={resid:.3e}"
                );
                for edge in edges_for_w(w) {
                    let o = run_case(n, edge, pos, radius, &refr);
                    print(edge, n, pos, radius, &o);
                }
            }
        }
    }
}

fn main() {
    let mode = std::env::args().nth(1).unwrap_or_else(|| "all".into());
    let gs: Vec<f32> = std::env::var("GAMMAS")
        .ok()
        .map(|v| v.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or(vec![0.8, 1.6, 3.19]);
    let ws: Vec<usize> = std::env::var("WIDTHS")
        .ok()
        .map(|v| v.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or(vec![8, 16, 32, 48]);
    let ps: Vec<i32> = std::env::var("POWERS")
        .ok()
        .map(|v| v.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or(vec![1, 2, 3]);
    match mode.as_str() {
        "limit" => limit(),
        "pad" => pad_check(),
        "walls" => sweep(
            &|_| {
                vec![
                    Edge::Frame {
                        w: 0,
                        p: 1,
                        gmax: 0.0,
                    },
                    Edge::Free,
                    Edge::FreeHeld,
                ]
            },
            &[0],
        ),
        "sweep" => sweep(
            &|w| {
                let mut v = vec![];
                for &p in &ps {
                    for &g in &gs {
                        v.push(Edge::Frame { w, p, gmax: g });
                    }
                }
                v
            },
            &ws,
        ),
        "mur" => sweep(
            &|w| {
                if w <= 1 {
                    vec![Edge::Mur {
                        w: 0,
                        p: 1,
                        gmax: 0.0,
                    }]
                } else {
                    let mut v = vec![];
                    for &p in &ps {
                        for &g in &gs {
                            v.push(Edge::Mur { w, p, gmax: g });
                        }
                    }
                    v
                }
            },
            &ws,
        ),
        "instant" => {
            let a: Vec<String> = std::env::args().collect();
            let shape = match a[6].as_str() {
                "cos" => Shape::Cos,
                "smooth" => Shape::Smooth,
                x if x.starts_with('f') => Shape::Onset(x[1..].parse().unwrap()),
                x => Shape::Power(x.parse().unwrap()),
            };
            instant(
                a[2].parse().unwrap(),
                a[3].parse().unwrap(),
                a[4].parse().unwrap(),
                a[5].parse().unwrap(),
                shape,
            );
        }
        "cands" => {
            // CANDS="frame:28:2:2.4,mur:24:2:1.2"
            let list: Vec<Edge> = std::env::var("CANDS")
                .unwrap()
                .split(',')
                .map(|c| {
                    let f: Vec<&str> = c.split(':').collect();
                    let (w, p, gmax) = (
                        f[1].parse().unwrap(),
                        f[2].parse().unwrap(),
                        f[3].parse().unwrap(),
                    );
                    if f[0] == "mur" {
                        Edge::Mur { w, p, gmax }
                    } else {
                        Edge::Frame { w, p, gmax }
                    }
                })
                .collect();
            let mut wl: Vec<usize> = list.iter().map(|e| e.w()).collect();
            wl.sort();
            wl.dedup();
            sweep(
                &|w| list.iter().copied().filter(|e| e.w() == w).collect(),
                &wl,
            );
        }
        _ => {
            limit();
            pad_check();
        }
    }
}

/// Shapes of the frame's profile over `s = (W − d)/W` (0 at the frame's inner edge, 1 at
/// the pinned ring), each times γmax.
#[derive(Clone, Copy, Debug)]
enum Shape {
    /// `s^p`.
    Power(f64),
    /// `(1 − cos πs)/2`: zero slope at both ends.
    Cos,
    /// `3s² − 2s³` (smoothstep).
    Smooth,
    /// Smoothstep over the inner `share` of the frame, flat at γmax beyond.
    Onset(f64),
}

fn shaped(shape: Shape, w: usize, gmax: f32, d: usize) -> f32 {
    if d == 0 || d >= w {
        return 0.0;
    }
    let s = (w - d) as f64 / w as f64;
    let v = match shape {
        Shape::Power(p) => s.powf(p),
        Shape::Cos => 0.5 * (1.0 - (std::f64::consts::PI * s).cos()),
        Shape::Smooth => s * s * (3.0 - 2.0 * s),
        Shape::Onset(f) => {
            let t = (s / f).min(1.0);
            t * t * (3.0 - 2.0 * t)
        }
    };
    (gmax as f64 * v) as f32
}

/// The ring test taken at every step: the frame (`shape`, width `w`, `gmax`) on an `n × n`
/// grid, a pinned pool of the same size and the padded reference stepped side by side.
fn instant(n: usize, steps: usize, w: usize, gmax: f32, shape: Shape) {
    let mut line = format!("n {n} steps {steps} W {w} gmax {gmax} {shape:?}:");
    for (radius, pos) in [
        (4.0f32, Pos::Centre),
        (4.0, Pos::Corner),
        (2.0, Pos::Centre),
        (2.0, Pos::Corner),
    ] {
        let (sx, sz) = source(n, w, pos);
        let reach = VMAX * steps as f64 - sx as f64 - w.max(1) as f64;
        let pad = (reach / 2.0).max(0.0).ceil() as usize + 12;
        let big = n + 2 * pad;
        let mut refr = Surface::new(base_params(big, Boundary::Pinned)).unwrap();
        refr.drop_at(sx + pad as f32, sz + pad as f32, height(), radius)
            .unwrap();
        let all = |_: usize, _: usize| true;
        let (y0, v0) = window(&refr, big, 0);
        let e0 = lin_energy(big, &y0, &v0, &all);
        let mut open = Surface::new(base_params(n, Boundary::Pinned)).unwrap();
        let mut wall = Surface::new(base_params(n, Boundary::Pinned)).unwrap();
        for r in 0..n {
            for c in 0..n {
                open.set_viscosity(r * n + c, shaped(shape, w, gmax, dist_edge(n, c, r)))
                    .unwrap();
            }
        }
        open.drop_at(sx, sz, height(), radius).unwrap();
        wall.drop_at(sx, sz, height(), radius).unwrap();
        let middle = |c: usize, r: usize| dist_edge(n, c, r) >= w.max(1);
        let diff = |s: &Surface, refr: &Surface| {
            let ((y, v), (ry, rv)) = (window(s, n, 0), window(refr, n, pad));
            let dy: Vec<f64> = y.iter().zip(&ry).map(|(a, b)| a - b).collect();
            let dv: Vec<f64> = v.iter().zip(&rv).map(|(a, b)| a - b).collect();
            (dy, dv)
        };
        let (mut worst, mut every4, mut at) = (0.0f64, 0.0f64, 0);
        for t in 1..=steps {
            refr.step().unwrap();
            open.step().unwrap();
            wall.step().unwrap();
            let (dy, dv) = diff(&open, &refr);
            let e = lin_energy(n, &dy, &dv, &middle) / e0;
            if e > worst {
                worst = e;
                at = t;
            }
            if t % SAMPLE == 0 {
                every4 = every4.max(e);
            }
        }
        let ((ay, av), (wy, wv)) = (diff(&open, &refr), diff(&wall, &refr));
        let rms = |y: &[f64]| {
            let mut s = 0.0;
            for r in 0..n {
                for c in 0..n {
                    if middle(c, r) {
                        s += y[r * n + c] * y[r * n + c];
                    }
                }
            }
            s
        };
        let (ea, ew) = (
            lin_energy(n, &ay, &av, &middle),
            lin_energy(n, &wy, &wv, &middle),
        );
        line += &format!(
            " | r{radius} {pos:?}: worst {worst:.2e} (step {at}), every 4th {every4:.2e}; last step: rms height vs wall {:.3}, energy vs wall {:.1e}, energy vs bump {:.1e}",
            (rms(&ay) / rms(&wy)).sqrt(),
            ea / ew,
            ea / e0
        );
    }
    println!("{line}");
}
