//! Hull meshes: validation (one clear error per defect), mass properties against closed
//! forms, and the shipped boat.

mod hull_meshes;

use hull_meshes::sphere_mesh;
use springwater::body::{BoatShape, Hull};
use springwater::glam::{DQuat, DVec3, Mat3, Quat, Vec3};
use springwater::Error;

fn box_mesh() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let hull = Hull::cuboid([1.0, 2.0, 3.0]).unwrap();
    (hull.vertices().to_vec(), hull.triangles().to_vec())
}

fn refusal(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> String {
    match Hull::new(vertices, triangles) {
        Err(e @ Error::InvalidHull(_)) => e.to_string(),
        other => panic!("expected a hull refusal, got {other:?}"),
    }
}

#[test]
fn bad_meshes_are_refused_each_with_its_own_reason() {
    let (v, t) = box_mesh();

    let mut nan = v.clone();
    nan[3][1] = f32::NAN;
    assert!(refusal(&nan, &t).contains("vertex 3 is (1, NaN, -3): coordinates must be finite"));
    let mut inf = v.clone();
    inf[0][2] = f32::INFINITY;
    assert!(refusal(&inf, &t).contains("must be finite"));
    let mut huge = v.clone();
    huge[5][0] = 2e9;
    assert!(refusal(&huge, &t).contains("at most 1e9"));

    let mut out = t.clone();
    out[4][2] = 8;
    assert!(refusal(&v, &out).contains("triangle 4 refers to vertex 8, but there are 8 vertices"));

    let mut twice = t.clone();
    twice[2] = [1, 1, 5];
    assert!(refusal(&v, &twice).contains("triangle 2 (1, 1, 5) uses a vertex twice"));

    // A vertex added on the midpoint of an edge makes a collinear triangle.
    let mut mid = v.clone();
    mid.push([0.0, -2.0, -3.0]); // between vertex 0 (−1,−2,−3) and vertex 1 (1,−2,−3)
    let mut flat = t.clone();
    flat.push([0, 8, 1]);
    assert!(refusal(&mid, &flat).contains("triangle 12 (0, 8, 1) has zero area"));

    let open = &t[..11];
    assert!(refusal(&v, open).contains("the mesh is open"));

    let mut flipped_one = t.clone();
    flipped_one[7].swap(1, 2);
    assert!(refusal(&v, &flipped_one).contains("windings disagree"));

    // An edge shared by three triangles (a fin glued onto the box's edge 0–4).
    let mut fin_v = v.clone();
    fin_v.push([-3.0, -4.0, 0.0]);
    let mut fin_t = t.clone();
    fin_t.extend([[0, 4, 8], [4, 0, 8]]);
    assert!(refusal(&fin_v, &fin_t).contains("more than two triangles meet"));

    let inside_out: Vec<[u32; 3]> = t.iter().map(|&[a, b, c]| [a, c, b]).collect();
    let message = refusal(&v, &inside_out);
    assert!(
        message.contains("inside out (enclosed volume -48)"),
        "{message}"
    );
    assert!(message.contains("reverse each triangle's vertex order"));

    assert!(refusal(&v, &t[..3]).contains("3 triangles; a hull has 4"));
    let many = vec![[0, 1, 2]; Hull::MAX_TRIANGLES + 1];
    assert!(refusal(&v, &many).contains("65537 triangles"));
    let unused = vec![[0.0; 3]; 37];
    assert!(refusal(&unused, &t).contains("37 vertices for 12 triangles"));

    // A hollow box: an inside-out small box within the big one is a cavity, and allowed.
    let small = Hull::cuboid([0.5, 0.5, 0.5]).unwrap();
    let mut hollow_v = v.clone();
    hollow_v.extend(small.vertices().iter().copied());
    let mut hollow_t = t.clone();
    hollow_t.extend(
        small
            .triangles()
            .iter()
            .map(|&[a, b, c]| [a + 8, c + 8, b + 8]),
    );
    let hollow = Hull::new(&hollow_v, &hollow_t).unwrap();
    assert_eq!(hollow.volume(), 48.0 - 1.0);

    // Four corners of a square joined as a tetrahedron: closed, but it encloses nothing.
    let square = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [0.0, 0.0, 1.0],
    ];
    let tetra = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    assert!(refusal(&square, &tetra).contains("encloses almost no volume"));
}

#[test]
fn a_degenerate_inertia_is_refused() {
    // A large inside-out box around a smaller outward one, crossing it: positive total
    // volume from a mesh that turns inside out, with one negative principal moment.
    let outer = Hull::cuboid([3.0, 0.2, 0.2]).unwrap();
    let inner = Hull::cuboid([0.5, 2.0, 2.0]).unwrap();
    let mut v = outer.vertices().to_vec();
    v.extend(inner.vertices().iter().copied());
    let mut t: Vec<[u32; 3]> = outer
        .triangles()
        .iter()
        .map(|&[a, b, c]| [a, c, b])
        .collect();
    t.extend(inner.triangles().iter().map(|tri| tri.map(|i| i + 8)));
    // Inner volume 16, outer −0.96: positive in total, but ∫x² dV is negative.
    let message = refusal(&v, &t);
    assert!(message.contains("not positive definite"), "{message}");
}

#[test]
fn a_hull_whose_volume_is_below_the_smallest_f32_is_refused() {
    // Found by the `hulls` fuzz target (fuzz/regressions/hulls/volume-below-f32): a box
    // 1e-15 across is well shaped, but its volume of 6e-45 is 0 as an f32, so the hull
    // reported a volume of 0 and no body could be made of it.
    let tiny = |scale: f32| {
        let (v, t) = box_mesh();
        let v: Vec<[f32; 3]> = v.iter().map(|p| p.map(|c| c * scale)).collect();
        Hull::new(&v, &t)
    };
    let message = tiny(1e-15).unwrap_err().to_string();
    assert!(
        message.contains("less than the smallest normal f32"),
        "{message}"
    );
    // 4.8e-38 cubic units: kept, with a positive volume.
    let smallest = tiny(1e-13).unwrap();
    assert!(
        smallest.volume() >= f32::MIN_POSITIVE,
        "{}",
        smallest.volume()
    );
}

#[test]
fn vertices_split_at_seams_are_joined_by_position() {
    // The box with its own four vertices per face, as a game mesh with hard normals has.
    let (v, t) = box_mesh();
    let mut split_v = Vec::new();
    let mut split_t = Vec::new();
    for pair in t.chunks(2) {
        let base = split_v.len() as u32;
        let quad = [pair[0][0], pair[0][1], pair[0][2], pair[1][2]];
        split_v.extend(quad.iter().map(|&i| v[i as usize]));
        split_t.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
    }
    let joined = Hull::new(&v, &t).unwrap();
    let split = Hull::new(&split_v, &split_t).unwrap();
    assert_eq!(split.volume(), joined.volume());
    assert_eq!(split.centroid(), joined.centroid());
    assert_eq!(split.inertia(3.0), joined.inertia(3.0));
    // -0 and +0 are the same position.
    let mut signed = split_v.clone();
    for p in &mut signed {
        for c in p.iter_mut() {
            if *c == 0.0 {
                *c = -0.0;
            }
        }
    }
    assert!(Hull::new(&signed, &split_t).is_ok());
}

/// The inertia tensor of a solid cuboid of half extents `e` and mass `m` about its centre.
fn cuboid_inertia(e: [f64; 3], m: f64) -> [f64; 3] {
    let [a, b, c] = e.map(|x| x * x);
    [m * (b + c) / 3.0, m * (a + c) / 3.0, m * (a + b) / 3.0]
}

fn close(a: f32, b: f64, tol: f64) -> bool {
    (a as f64 - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn a_twelve_triangle_box_has_the_cuboids_mass_properties() {
    for e in [[1.5f32, 0.25, 2.0], [0.5, 0.5, 0.5], [10.0, 0.1, 3.0]] {
        let hull = Hull::cuboid(e).unwrap();
        assert_eq!(hull.triangles().len(), 12);
        let e64 = e.map(f64::from);
        assert!(close(hull.volume(), 8.0 * e64[0] * e64[1] * e64[2], 1e-7));
        assert!(hull.centroid().abs().max_element() < 1e-6);
        let mass = 7.0;
        let inertia = hull.inertia(mass);
        let want = cuboid_inertia(e64, mass as f64);
        let diag = [inertia.x_axis.x, inertia.y_axis.y, inertia.z_axis.z];
        for k in 0..3 {
            assert!(close(diag[k], want[k], 1e-6), "{diag:?} vs {want:?}");
        }
        let off = [inertia.x_axis.y, inertia.x_axis.z, inertia.y_axis.z];
        assert!(
            off.iter().all(|v| (v.abs() as f64) < 1e-6 * want[0]),
            "{off:?}"
        );
    }
}

#[test]
fn a_moved_and_turned_box_has_the_turned_inertia() {
    let e = [2.0, 0.5, 1.0];
    let q = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 0.7);
    let shift = DVec3::new(10.0, -3.0, 7.0);
    let base = Hull::cuboid(e).unwrap();
    let moved: Vec<[f32; 3]> = base
        .vertices()
        .iter()
        .map(|v| {
            (q * DVec3::from(v.map(f64::from)) + shift)
                .as_vec3()
                .to_array()
        })
        .collect();
    let hull = Hull::new(&moved, base.triangles()).unwrap();
    assert!((hull.centroid().as_dvec3() - shift).abs().max_element() < 1e-5);
    assert!(close(hull.volume(), 8.0, 1e-5));
    let want = cuboid_inertia(e.map(f64::from), 2.0);
    let r = springwater::glam::DMat3::from_quat(q);
    let rotated = r * springwater::glam::DMat3::from_diagonal(want.into()) * r.transpose();
    let got = hull.inertia(2.0).as_dmat3();
    assert!(
        (got - rotated)
            .to_cols_array()
            .iter()
            .all(|d| d.abs() < 1e-5),
        "{got} vs {rotated}"
    );
    // Centred, the centroid is at the origin to the f32 rounding of the coordinates.
    let centred = hull.centred().unwrap();
    assert!(centred.centroid().abs().max_element() < 1e-5);
    assert_eq!(centred.triangles(), hull.triangles());
}

#[test]
fn a_corner_tetrahedron_matches_its_integrals() {
    // The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1): ∫x² dV = 1/60 and ∫xy dV = 1/120
    // over it (Dirichlet integrals), V = 1/6, centroid (1/4, 1/4, 1/4).
    let v = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let t = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let hull = Hull::new(&v, &t).unwrap();
    assert!(close(hull.volume(), 1.0 / 6.0, 1e-7));
    assert!((hull.centroid() - Vec3::splat(0.25)).abs().max_element() < 1e-7);
    let (vol, c) = (1.0 / 6.0, 0.25);
    let xx = 1.0 / 60.0 - vol * c * c; // about the centroid
    let xy = 1.0 / 120.0 - vol * c * c;
    let mass = 3.0;
    let rho = mass / vol;
    let inertia = hull.inertia(mass as f32);
    assert!(close(inertia.x_axis.x, rho * 2.0 * xx, 1e-6));
    assert!(close(inertia.x_axis.y, -rho * xy, 1e-6));
    assert_eq!(inertia, inertia.transpose());
}

#[test]
fn a_fine_sphere_mesh_approaches_the_ball() {
    let (v, t) = sphere_mesh(2.0, 5); // 8192 triangles
    let hull = Hull::new(&v, &t).unwrap();
    let ball = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
    // The inscribed polyhedron falls short of the ball by about the chord sag.
    assert!((hull.volume() as f64 / ball - 1.0).abs() < 3e-3);
    let i = hull.inertia(5.0);
    let want = 0.4 * 5.0 * 4.0;
    for d in [i.x_axis.x, i.y_axis.y, i.z_axis.z] {
        assert!((d as f64 / want - 1.0).abs() < 5e-3, "{d} vs {want}");
    }
}

#[test]
fn the_boat_is_a_closed_symmetric_displacement_hull() {
    let shape = BoatShape::default();
    let boat = shape.hull().unwrap();
    assert_eq!(boat.triangles().len(), 2024);
    let c = boat.centroid();
    assert!(c.z.abs() < 1e-6, "symmetric about z = 0: {c}");
    assert!(c.x < 0.0, "fuller aft than at the sharp bow: {c}");
    // Between a wedge and the enclosing box of 6 × 2 × 1.25.
    let block = boat.volume() / (6.0 * 2.0 * 1.25);
    assert!((0.35..0.8).contains(&block), "{block}");
    let i = boat.inertia(1.0);
    assert!(
        i.y_axis.y > i.z_axis.z && i.z_axis.z > i.x_axis.x,
        "long, wide, shallow: {i}"
    );
    // The mesh mirrored port to starboard has the same volume (winding reversed by the
    // mirror, so reverse the triangles back).
    let mirrored: Vec<[f32; 3]> = boat
        .vertices()
        .iter()
        .map(|&[x, y, z]| [x, y, -z])
        .collect();
    let rewound: Vec<[u32; 3]> = boat
        .triangles()
        .iter()
        .map(|&[a, b, c]| [a, c, b])
        .collect();
    let mirror = Hull::new(&mirrored, &rewound).unwrap();
    assert!(close(mirror.volume(), boat.volume() as f64, 1e-6));
    // Coarse and fine boats agree on the volume to a few per cent.
    let mut coarse = shape;
    coarse.stations = 10;
    coarse.segments = 3;
    let coarse = coarse.hull().unwrap();
    assert!(((coarse.volume() / boat.volume()) - 1.0).abs() < 0.05);
    let bad_shapes: [fn(&mut BoatShape); 4] = [
        |b| b.beam = 0.0,
        |b| b.length = f32::NAN,
        |b| b.stations = 1,
        |b| b.segments = 2000,
    ];
    for change in bad_shapes {
        let mut bad = shape;
        change(&mut bad);
        assert!(
            matches!(bad.hull(), Err(Error::InvalidParam { .. })),
            "{bad:?}"
        );
    }
}

const ASSET: &str = "assets/boat.obj";
const ASSET_NOTES: [&str; 3] = [
    "springwater's boat hull: springwater::body::BoatShape::default(), 2024 triangles",
    "length 6, beam 2, depth 1; bow +x, y up, starboard +z, origin on the keel amidships",
    "generated; rewrite with SPRINGWATER_BLESS=1 cargo test --test hull boat_asset",
];

#[test]
fn the_boat_asset_is_the_generators_boat() {
    let text = BoatShape::default().hull().unwrap().to_obj(&ASSET_NOTES);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(ASSET);
    if std::env::var_os("SPRINGWATER_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &text).unwrap();
    }
    let on_disk = std::fs::read_to_string(&path).expect("assets/boat.obj exists");
    assert!(
        on_disk == text,
        "{ASSET} differs from BoatShape::default(); see its header"
    );
    // And it reads back as the same hull.
    let mut v = Vec::new();
    let mut t = Vec::new();
    for line in on_disk.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => v.push([0; 3].map(|_| words.next().unwrap().parse::<f32>().unwrap())),
            Some("f") => t.push([0; 3].map(|_| words.next().unwrap().parse::<u32>().unwrap() - 1)),
            _ => {}
        }
    }
    assert_eq!(
        Hull::new(&v, &t).unwrap(),
        BoatShape::default().hull().unwrap()
    );
}

#[test]
fn inertia_is_symmetric_and_scales_with_mass() {
    let hull = BoatShape::default().hull().unwrap();
    let one = hull.inertia(1.0);
    let ten = hull.inertia(10.0);
    assert_eq!(one, one.transpose());
    let diff = ten - one * 10.0;
    assert!(diff
        .to_cols_array()
        .iter()
        .all(|d| d.abs() < 1e-5 * ten.x_axis.x));
    let _ = (Mat3::IDENTITY, Quat::IDENTITY);
}

#[cfg(feature = "serde")]
#[test]
fn a_hull_goes_through_serde_and_is_validated_on_the_way_back() {
    let boat = BoatShape::default().hull().unwrap();
    let json = serde_json::to_string(&boat).unwrap();
    let back: Hull = serde_json::from_str(&json).unwrap();
    assert_eq!(back, boat);
    // One triangle dropped: the file no longer describes a closed mesh.
    let mut value: serde_json::Value = serde_json::from_str(&json).unwrap();
    value["triangles"].as_array_mut().unwrap().pop();
    let error = serde_json::from_value::<Hull>(value)
        .unwrap_err()
        .to_string();
    assert!(error.contains("the mesh is open"), "{error}");
}
