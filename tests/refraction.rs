//! Refraction UVs and Fresnel: against an independent angle-based Snell computation, the
//! sine law, the lane/scalar twins, and no NaN for any eye, normal or depth.

use glam::{DVec3, Vec3};
use proptest::prelude::*;
use springwater::internals::refract_scalar;
use springwater::mesh::{compute_normals, Normals};
use springwater::refraction::{refract, Refraction, RefractionParams};
use springwater::Grid;
use springwater::MeshView;

/// Nodes with arbitrary positions on a `cols × rows` grid, and arbitrary normals.
#[derive(Debug, Clone)]
struct Scene {
    grid: Grid,
    h: f32,
    p: [Vec<f32>; 3],
    normals: Normals,
}

impl Scene {
    fn flat(cols: usize, rows: usize, h: f32) -> Self {
        let grid = Grid::new(cols, rows);
        let mut p = [Vec::new(), vec![0.0; grid.node_count()], Vec::new()];
        for i in 0..grid.node_count() {
            let (c, r) = grid.coords(i);
            p[0].push(c as f32 * h);
            p[2].push(r as f32 * h);
        }
        let mut s = Self {
            grid,
            h,
            p,
            normals: Normals::new(),
        };
        let view = s.view();
        let mut n = Normals::new();
        compute_normals(&view, &mut n);
        s.normals = n;
        s
    }

    fn view(&self) -> MeshView<'_> {
        MeshView::new(self.grid, self.h, &self.p[0], &self.p[1], &self.p[2]).unwrap()
    }

    fn pos(&self, i: usize) -> Vec3 {
        Vec3::new(self.p[0][i], self.p[1][i], self.p[2][i])
    }

    fn extent(&self) -> [f32; 2] {
        [
            (self.grid.cols - 1) as f32 * self.h,
            (self.grid.rows - 1) as f32 * self.h,
        ]
    }

    fn run(&self, eye: Vec3, params: &RefractionParams) -> Refraction {
        let mut out = Refraction::default();
        refract(&self.view(), &self.normals, eye, params, &mut out).unwrap();
        out
    }
}

/// A scene of `cols × rows` nodes whose positions and normals come from `values`
/// (recycled), positions jittered around the rest grid, normals unit with `n.y ≥ min_up`.
fn scene(cols: usize, rows: usize, values: &[f32], min_up: f32) -> Scene {
    let mut s = Scene::flat(cols, rows, 1.0);
    let mut k = 0;
    let mut next = || {
        let v = values[k % values.len()];
        k += 1;
        v
    };
    for i in 0..s.grid.node_count() {
        s.p[0][i] += 0.3 * next();
        s.p[1][i] = next();
        s.p[2][i] += 0.3 * next();
        let n = Vec3::new(next(), 0.0, next());
        let n = Vec3::new(n.x, min_up.max(1.0 - n.length().min(1.0)) + 0.05, n.z).normalize();
        (s.normals.x[i], s.normals.y[i], s.normals.z[i]) = (n.x, n.y, n.z);
    }
    s
}

/// Snell's law by angles, in f64: the transmitted direction is `−n cos θ2` plus the view
/// ray's tangential direction times `sin θ2`, with `sin θ2 = sin θ1 / ior`.
fn snell_by_angles(p: DVec3, n: DVec3, eye: DVec3, ior: f64) -> Option<DVec3> {
    let d = (p - eye).normalize();
    let cos1 = -n.dot(d);
    if cos1 <= 0.0 {
        return None;
    }
    let sin1 = (1.0 - cos1 * cos1).max(0.0).sqrt();
    let sin2 = sin1 / ior;
    let cos2 = (1.0 - sin2 * sin2).sqrt();
    let tangent = d + cos1 * n;
    let t = if tangent.length() < 1e-12 {
        -n
    } else {
        -cos2 * n + sin2 * tangent.normalize()
    };
    Some(t)
}

/// Node `i`'s coordinate is the bottom point straight below it.
fn assert_below(out: &Refraction, i: usize, p: Vec3, [w, l]: [f32; 2]) {
    let close = |a: f32, b: f32| (a - b).abs() <= 1e-6 * (1.0 + b.abs());
    assert!(
        close(out.u[i], p.x / w) && close(out.v[i], p.z / l),
        "node {i}: ({}, {}) is not below ({}, {})",
        out.u[i],
        out.v[i],
        p.x,
        p.z
    );
}

fn values() -> impl Strategy<Value = Vec<f32>> {
    prop::collection::vec(-1.0f32..1.0, 16..64)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn matches_an_independent_snell_computation(
        (cols, rows) in (2usize..40, 2usize..6),
        vals in values(),
        eye in (-20.0f32..60.0, 2.0f32..50.0, -20.0f32..30.0),
        depth in 0.5f32..20.0,
        ior in 1.0f32..2.5,
    ) {
        let s = scene(cols, rows, &vals, 0.5);
        let eye = Vec3::new(eye.0, eye.1, eye.2);
        let params = RefractionParams { depth, ior };
        let out = s.run(eye, &params);
        let [w, l] = s.extent();
        for i in 0..s.grid.node_count() {
            let p = s.pos(i).as_dvec3();
            let n = s.normals.get(i).as_dvec3();
            let Some(t) = snell_by_angles(p, n, eye.as_dvec3(), ior as f64) else { continue };
            if t.y > -0.2 {
                continue; // near-horizontal rays amplify f32 rounding; covered elsewhere
            }
            let step = (-(depth as f64) - p.y) / t.y;
            if step < 1e-3 {
                continue; // a node at or below the bottom: the fallback, tested elsewhere
            }
            let hit = p + step * t;
            let (u, v) = (hit.x / w as f64, hit.z / l as f64);
            let tol = 2e-4 * (1.0 + step);
            prop_assert!((out.u[i] as f64 - u).abs() * (w as f64) < tol, "node {i}: u {} vs {u}", out.u[i]);
            prop_assert!((out.v[i] as f64 - v).abs() * (l as f64) < tol, "node {i}: v {} vs {v}", out.v[i]);
        }
    }

    /// From the UV back to the ray: n1 sin θ1 = n2 sin θ2, and the ray stays in the plane of
    /// incidence.
    #[test]
    fn sine_law_holds(
        vals in values(),
        eye in (-30.0f32..30.0, 1.0f32..40.0, -30.0f32..30.0),
        depth in 1.0f32..10.0,
        ior in 1.0f32..3.0,
    ) {
        let s = scene(11, 3, &vals, 0.5);
        let eye = Vec3::new(eye.0, eye.1, eye.2);
        let out = s.run(eye, &RefractionParams { depth, ior });
        let [w, l] = s.extent();
        for i in 0..s.grid.node_count() {
            let p = s.pos(i).as_dvec3();
            let n = s.normals.get(i).as_dvec3();
            let d = (p - eye.as_dvec3()).normalize();
            let hit = DVec3::new(out.u[i] as f64 * w as f64, -(depth as f64), out.v[i] as f64 * l as f64);
            let to_hit = hit - p;
            let reaches = snell_by_angles(p, n, eye.as_dvec3(), ior as f64).is_some_and(|t| t.y < -0.1);
            if !reaches || to_hit.length() < 0.5 || to_hit.length() > 200.0 {
                continue;
            }
            let t = to_hit.normalize();
            let sin1 = d.cross(n).length();
            let sin2 = t.cross(n).length();
            prop_assert!((sin1 - ior as f64 * sin2).abs() < 2e-3, "node {i}: {sin1} vs {ior}·{sin2}");
            prop_assert!(d.cross(n).dot(t).abs() < 2e-3, "node {i}: ray leaves the plane of incidence");
            prop_assert!(t.dot(n) < 0.0, "node {i}: the ray goes into the water");
        }
    }

    /// No NaN or infinity, whatever the eye (under water, on a node, far), the normals
    /// (any direction or length, zero) and the depth; Fresnel in [R0, 1].
    #[test]
    fn always_finite(
        vals in prop::collection::vec(-10.0f32..10.0, 16..64),
        eye in prop_oneof![
            (-50.0f32..50.0, -50.0f32..50.0, -50.0f32..50.0),
            (-1e30f32..1e30, -1e30f32..1e30, -1e30f32..1e30),
            Just((3.0f32, 0.0f32, 0.0f32)),
        ],
        depth in prop_oneof![Just(0.0f32), 0.0f32..1e3],
        ior in 1.0f32..10.0,
        zero_normals in any::<bool>(),
    ) {
        let mut s = scene(13, 4, &vals, -1.0);
        for i in 0..s.grid.node_count() {
            let k = vals[i % vals.len()];
            if zero_normals && i % 3 == 0 {
                (s.normals.x[i], s.normals.y[i], s.normals.z[i]) = (0.0, 0.0, 0.0);
            } else {
                (s.normals.x[i], s.normals.y[i], s.normals.z[i]) = (k, -k * 0.5, 1.0 - k);
            }
        }
        let params = RefractionParams { depth, ior };
        let out = s.run(Vec3::new(eye.0, eye.1, eye.2), &params);
        let r0 = params.r0();
        for i in 0..s.grid.node_count() {
            prop_assert!(out.u[i].is_finite() && out.v[i].is_finite(), "node {i}");
            prop_assert!(out.fresnel[i] >= r0 && out.fresnel[i] <= 1.0, "node {i}: {}", out.fresnel[i]);
        }
    }

    /// The lane kernel and its scalar twin agree bitwise, tails and odd cases included.
    #[test]
    fn lanes_match_the_scalar_twin(
        (cols, rows) in (2usize..40, 2usize..5),
        vals in prop::collection::vec(-3.0f32..3.0, 16..64),
        eye in (-20.0f32..40.0, -10.0f32..30.0, -20.0f32..20.0),
        depth in 0.0f32..10.0,
        ior in 1.0f32..3.0,
    ) {
        let s = scene(cols, rows, &vals, -1.0);
        let eye = Vec3::new(eye.0, eye.1, eye.2);
        let params = RefractionParams { depth, ior };
        let lanes = s.run(eye, &params);
        let mut scalar = Refraction::default();
        refract_scalar(&s.view(), &s.normals, eye, &params, &mut scalar).unwrap();
        for i in 0..s.grid.node_count() {
            prop_assert_eq!(lanes.u[i].to_bits(), scalar.u[i].to_bits(), "u at node {}", i);
            prop_assert_eq!(lanes.v[i].to_bits(), scalar.v[i].to_bits(), "v at node {}", i);
            prop_assert_eq!(lanes.fresnel[i].to_bits(), scalar.fresnel[i].to_bits(), "fresnel at node {}", i);
        }
    }
}

#[test]
fn straight_down_through_a_flat_surface_seen_from_above() {
    let s = Scene::flat(33, 17, 0.5);
    let [w, l] = s.extent();
    let params = RefractionParams {
        depth: 3.0,
        ior: 1.333,
    };
    for i in [0, 5, 100, 33 * 17 - 1] {
        let p = s.pos(i);
        let out = s.run(p + Vec3::new(0.0, 7.0, 0.0), &params);
        assert_below(&out, i, p, [w, l]);
        assert!(
            (out.fresnel[i] - params.r0()).abs() < 1e-7,
            "Fresnel is R0 looking straight down"
        );
    }
}

#[test]
fn oblique_view_bends_towards_the_normal() {
    // Eye at 45° over a flat surface: without refraction the ray would travel `depth`
    // sideways; with it, depth·tan(asin(sin45°/ior)).
    let s = Scene::flat(41, 41, 1.0);
    let i = s.grid.index(20, 20);
    let eye = Vec3::new(10.0, 10.0, 20.0);
    let params = RefractionParams {
        depth: 5.0,
        ior: 1.333,
    };
    let out = s.run(eye, &params);
    let sin2 = (0.5f64).sqrt() / 1.333;
    let shift = 5.0 * sin2 / (1.0 - sin2 * sin2).sqrt();
    let expected_u = (20.0 + shift) / 40.0;
    assert!(
        (out.u[i] as f64 - expected_u).abs() < 1e-5,
        "{} vs {expected_u}",
        out.u[i]
    );
    assert!((out.v[i] - 0.5).abs() < 1e-6);
    // With ior 1 there is no bending: the ray goes on at 45°.
    let straight = s.run(
        eye,
        &RefractionParams {
            depth: 5.0,
            ior: 1.0,
        },
    );
    assert!((straight.u[i] - 25.0 / 40.0).abs() < 1e-5);
}

#[test]
fn fresnel_is_r0_head_on_and_tends_to_one_at_grazing() {
    let s = Scene::flat(201, 3, 1.0);
    let params = RefractionParams::default();
    let r0 = params.r0();
    assert!((r0 - 0.0204).abs() < 1e-3, "water's R0 is about 2%");
    let i = s.grid.index(0, 1);
    let head_on = s.run(Vec3::new(0.0, 3.0, 1.0), &params);
    assert!((head_on.fresnel[i] - r0).abs() < 1e-7);
    // Lower and lower eye over a node far away: reflectance rises monotonically to 1.
    let mut last = 0.0;
    for y in [100.0, 30.0, 10.0, 3.0, 1.0, 0.1, 0.001] {
        let f = s.run(Vec3::new(200.0, y, 1.0), &params).fresnel[i];
        assert!(f > last, "rising: {f} after {last} at eye height {y}");
        last = f;
    }
    assert!(last > 0.999, "grazing: {last}");
}

#[test]
fn an_eye_under_water_gets_the_fallback_coordinate_and_total_reflection() {
    let s = Scene::flat(21, 21, 1.0);
    let [w, l] = s.extent();
    let params = RefractionParams {
        depth: 5.0,
        ior: 1.333,
    };
    let eye = Vec3::new(10.0, -2.0, 10.0);
    let out = s.run(eye, &params);
    for i in 0..s.grid.node_count() {
        let p = s.pos(i);
        assert_below(&out, i, p, [w, l]);
        let d = (p - eye).normalize();
        let sin_air = 1.333 * (1.0 - d.y * d.y).sqrt();
        if sin_air > 1.001 {
            assert_eq!(out.fresnel[i], 1.0, "node {i}: beyond the critical angle");
        } else if sin_air < 0.999 {
            assert!(out.fresnel[i] < 1.0 && out.fresnel[i] >= params.r0());
        }
    }
    // Looking straight up from below: R0 too.
    assert!((out.fresnel[s.grid.index(10, 10)] - params.r0()).abs() < 1e-6);
}

#[test]
fn rays_that_never_reach_the_bottom_use_the_point_below_the_node() {
    let mut s = Scene::flat(9, 9, 1.0);
    let [w, l] = s.extent();
    let params = RefractionParams {
        depth: 2.0,
        ior: 1.333,
    };
    // Node 10 is below the bottom; node 20 is on an overhang facing the eye, whose normal
    // points down a little, so the refracted ray goes back up.
    s.p[1][10] = -3.0;
    let n = Vec3::new(-1.0, -0.3, 0.0).normalize();
    (s.normals.x[20], s.normals.y[20], s.normals.z[20]) = (n.x, n.y, n.z);
    let out = s.run(Vec3::new(-50.0, 1.0, 2.0), &params);
    for i in [10, 20] {
        assert_below(&out, i, s.pos(i), [w, l]);
    }
    // The eye exactly on a node sees it edge-on: the point below, full reflection.
    let on = s.run(s.pos(40), &params);
    assert_below(&on, 40, s.pos(40), [w, l]);
    assert_eq!(on.fresnel[40], 1.0);
}

#[test]
fn bad_input_is_refused_and_changes_nothing() {
    let s = Scene::flat(5, 5, 1.0);
    let mut out = s.run(Vec3::new(1.0, 5.0, 1.0), &RefractionParams::default());
    let before = out.clone();
    let ok = RefractionParams::default();
    let eye = Vec3::new(1.0, 5.0, 1.0);
    for bad in [
        RefractionParams { depth: -1.0, ..ok },
        RefractionParams {
            depth: f32::NAN,
            ..ok
        },
        RefractionParams { ior: 0.9, ..ok },
        RefractionParams {
            ior: f32::INFINITY,
            ..ok
        },
    ] {
        assert!(bad.validate().is_err());
        assert!(refract(&s.view(), &s.normals, eye, &bad, &mut out).is_err());
    }
    assert!(refract(
        &s.view(),
        &s.normals,
        Vec3::new(f32::NAN, 1.0, 1.0),
        &ok,
        &mut out
    )
    .is_err());
    let short = Normals {
        x: vec![0.0; 3],
        y: vec![1.0; 3],
        z: vec![0.0; 3],
    };
    assert!(refract(&s.view(), &short, eye, &ok, &mut out).is_err());
    assert_eq!(out, before);
}

/// The fused pass gives bitwise what the two calls give, for grids narrower and wider than
/// one parallel task, with a surface that is not flat.
#[test]
fn the_fused_pass_equals_normals_then_refraction() {
    use springwater::refraction::normals_and_refraction;
    for (cols, rows) in [(2, 2), (7, 3), (129, 97), (5000, 3), (300, 40)] {
        let mut s = Scene::flat(cols, rows, 0.7);
        for i in 0..cols * rows {
            s.p[1][i] = ((i * 37 % 101) as f32 / 101.0 - 0.5) * 0.8;
            s.p[0][i] += ((i * 13 % 7) as f32 - 3.0) * 0.01;
        }
        let eye = Vec3::new(3.0, 12.0, -4.0);
        let params = RefractionParams::default();
        let mut normals = Normals::new();
        compute_normals(&s.view(), &mut normals);
        let mut separate = Refraction::default();
        refract(&s.view(), &normals, eye, &params, &mut separate).unwrap();
        let (mut fused_normals, mut fused) = (Normals::new(), Refraction::default());
        normals_and_refraction(&s.view(), eye, &params, &mut fused_normals, &mut fused).unwrap();
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&fused_normals.x), bits(&normals.x), "{cols}x{rows}");
        assert_eq!(bits(&fused_normals.y), bits(&normals.y), "{cols}x{rows}");
        assert_eq!(bits(&fused_normals.z), bits(&normals.z), "{cols}x{rows}");
        assert_eq!(bits(&fused.u), bits(&separate.u), "{cols}x{rows}");
        assert_eq!(bits(&fused.v), bits(&separate.v), "{cols}x{rows}");
        assert_eq!(
            bits(&fused.fresnel),
            bits(&separate.fresnel),
            "{cols}x{rows}"
        );
    }
    let s = Scene::flat(4, 4, 1.0);
    let (mut n, mut r) = (Normals::new(), Refraction::default());
    let bad = RefractionParams {
        depth: -1.0,
        ..Default::default()
    };
    assert!(normals_and_refraction(&s.view(), Vec3::ONE, &bad, &mut n, &mut r).is_err());
}
