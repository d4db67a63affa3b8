//! The C ABI's frame and per-node calls beyond the fixed-step clock, called from Rust as C
//! calls them: frames cut into variable substeps, every node's pending force and velocity,
//! the uniform acceleration, the ripple speed of parameters, the LOD mesh's parameters and
//! patches, and the water's reflectance. Each gives what the Rust API gives, and a refused
//! call changes nothing (the state hash says so).

use springwater::mesh::{LodMesh, LodParams};
use springwater::refraction::RefractionParams;
use springwater::{Params, Surface};
use springwater_ffi::*;

fn surface(cols: u32, rows: u32) -> *mut SwSurface {
    let mut params = sw_params_default();
    params.cols = cols;
    params.rows = rows;
    let mut s = std::ptr::null_mut();
    assert_eq!(unsafe { sw_surface_create(&params, &mut s) }, SW_OK);
    s
}

fn hash(s: *const SwSurface) -> u64 {
    let mut h = 0;
    assert_eq!(unsafe { sw_surface_state_hash(s, &mut h) }, SW_OK);
    h
}

/// Every node's `[x, y, z]` of three component slices, interleaved as the C calls write them.
fn interleaved([x, y, z]: [&[f32]; 3]) -> Vec<f32> {
    x.iter()
        .zip(y)
        .zip(z)
        .flat_map(|((x, y), z)| [*x, *y, *z])
        .collect()
}

#[test]
fn variable_frames_are_split_and_taken_as_the_rust_api_does() {
    let s = surface(12, 10);
    let mut rust = Surface::new(Params::with_size(12, 10)).unwrap();
    assert_eq!(sw_surface_drop_at(s, 5.0, 5.0, 0.5, 2.0), SW_OK);
    rust.drop_at(5.0, 5.0, 0.5, 2.0).unwrap();
    for frame in [1.0 / 60.0, 0.05, 1.0 / 144.0, 0.0] {
        let (mut n, mut seconds) = (7u32, -1.0f32);
        assert_eq!(
            unsafe { sw_surface_split_frame(s, frame, &mut n, &mut seconds) },
            SW_OK
        );
        let (want_n, want_seconds) = rust.split_frame(frame).unwrap();
        assert_eq!(
            (n as usize, seconds.to_bits()),
            (want_n, want_seconds.to_bits())
        );
        let mut taken = 0u32;
        assert_eq!(
            unsafe { sw_surface_advance_variable(s, frame, &mut taken) },
            SW_OK
        );
        assert_eq!(taken as usize, rust.advance_variable(frame).unwrap());
    }
    assert_eq!(hash(s), rust.state_hash());
    // Either output may be NULL.
    assert_eq!(
        unsafe { sw_surface_split_frame(s, 0.1, std::ptr::null_mut(), std::ptr::null_mut()) },
        SW_OK
    );
    // A negative, non-finite or too long frame is refused and changes nothing.
    let before = hash(s);
    let mut n = 99u32;
    for bad in [-0.1, f32::NAN, f32::INFINITY, 1e6] {
        assert_eq!(
            unsafe { sw_surface_split_frame(s, bad, &mut n, std::ptr::null_mut()) },
            SW_ERROR_INVALID_ARGUMENT,
            "{bad}"
        );
        assert_eq!(
            unsafe { sw_surface_advance_variable(s, bad, std::ptr::null_mut()) },
            SW_ERROR_INVALID_ARGUMENT
        );
    }
    assert_eq!((n, hash(s)), (99, before));
    sw_surface_destroy(s);
}

#[test]
fn forces_velocities_and_the_acceleration_match_the_rust_api() {
    let (cols, rows) = (7, 6);
    let s = surface(cols, rows);
    let mut rust = Surface::new(Params::with_size(cols as usize, rows as usize)).unwrap();
    let n = (cols * rows) as usize;
    let xyz: Vec<f32> = (0..3 * n).map(|i| 0.01 * (i % 11) as f32 - 0.04).collect();
    assert_eq!(
        unsafe { sw_surface_set_forces(s, xyz.as_ptr(), xyz.len()) },
        SW_OK
    );
    let [x, y, z]: [Vec<f32>; 3] = std::array::from_fn(|k| xyz.chunks(3).map(|f| f[k]).collect());
    rust.set_forces([&x, &y, &z]).unwrap();
    assert_eq!(sw_surface_add_force(s, 9, 0.0, 0.5, 0.0), SW_OK);
    rust.add_force(9, [0.0, 0.5, 0.0]).unwrap();
    // The buffer may be longer than the nodes.
    let mut forces = vec![7.0f32; 3 * n + 2];
    assert_eq!(
        unsafe { sw_surface_write_forces(s, forces.as_mut_ptr(), forces.len()) },
        SW_OK
    );
    assert_eq!(&forces[..3 * n], interleaved(rust.forces()));
    assert_eq!(&forces[3 * n..], [7.0, 7.0]);

    assert_eq!(sw_surface_set_acceleration(s, 0.0, -2.0, 0.5), SW_OK);
    rust.set_acceleration([0.0, -2.0, 0.5]).unwrap();
    let mut params = sw_params_default();
    assert_eq!(unsafe { sw_surface_params(s, &mut params) }, SW_OK);
    assert_eq!(
        [
            params.acceleration_x,
            params.acceleration_y,
            params.acceleration_z
        ],
        [0.0, -2.0, 0.5]
    );
    assert_eq!(sw_surface_step(s, 3), SW_OK);
    rust.step_n(3).unwrap();
    let mut velocities = vec![0.0f32; 3 * n];
    assert_eq!(
        unsafe { sw_surface_write_velocities(s, velocities.as_mut_ptr(), velocities.len()) },
        SW_OK
    );
    assert_eq!(velocities, interleaved(rust.velocities()));
    assert!(velocities.iter().any(|&v| v != 0.0));
    assert_eq!(hash(s), rust.state_hash());

    // Refusals change nothing: a short buffer, a value that is not finite.
    let before = hash(s);
    let mut bad = xyz.clone();
    bad[4] = f32::NAN;
    assert_eq!(
        unsafe { sw_surface_set_forces(s, bad.as_ptr(), bad.len()) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { sw_surface_set_forces(s, xyz.as_ptr(), 3 * n - 1) },
        SW_ERROR_BUFFER_TOO_SMALL
    );
    assert_eq!(
        unsafe { sw_surface_set_forces(s, std::ptr::null(), 3 * n) },
        SW_ERROR_NULL_POINTER
    );
    assert_eq!(
        sw_surface_set_acceleration(s, f32::INFINITY, 0.0, 0.0),
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { sw_surface_write_velocities(s, velocities.as_mut_ptr(), 3 * n - 1) },
        SW_ERROR_BUFFER_TOO_SMALL
    );
    assert_eq!(
        unsafe { sw_surface_write_forces(s, forces.as_mut_ptr(), 3 * n - 1) },
        SW_ERROR_BUFFER_TOO_SMALL
    );
    assert_eq!(hash(s), before);
    assert_eq!(unsafe { sw_surface_params(s, &mut params) }, SW_OK);
    assert_eq!(params.acceleration_x, 0.0);
    sw_surface_destroy(s);
}

#[test]
fn the_ripple_speed_is_read_and_set_through_the_time_scale() {
    let mut c = sw_params_default();
    let mut speed = 0.0;
    assert_eq!(unsafe { sw_params_ripple_speed(&c, &mut speed) }, SW_OK);
    assert_eq!(speed.to_bits(), Params::default().ripple_speed().to_bits());
    assert_eq!(unsafe { sw_params_set_ripple_speed(&mut c, 128.0) }, SW_OK);
    let mut rust = Params::default();
    rust.set_ripple_speed(128.0).unwrap();
    assert_eq!(c.time_scale.to_bits(), rust.time_scale.to_bits());
    assert_eq!(c.dt, sw_params_default().dt, "only the time scale changes");

    // Refused, the struct unchanged: a speed not above 0, lattice without a ripple speed.
    let kept = c.time_scale;
    for bad in [0.0, -1.0, f32::NAN] {
        assert_eq!(
            unsafe { sw_params_set_ripple_speed(&mut c, bad) },
            SW_ERROR_INVALID_ARGUMENT
        );
    }
    let mut slack = c;
    slack.rest_ratio = 1.0;
    assert_eq!(
        unsafe { sw_params_set_ripple_speed(&mut slack, 10.0) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!((c.time_scale, slack.time_scale), (kept, kept));
    let mut unsized_params = c;
    unsized_params.struct_size = 4;
    assert_eq!(
        unsafe { sw_params_ripple_speed(&unsized_params, &mut speed) },
        SW_ERROR_INVALID_ARGUMENT
    );
}

#[test]
fn the_lod_mesh_is_read_back_and_built_from_chosen_levels() {
    let s = surface(33, 17);
    let mut lod = sw_lod_params_default();
    let mut max = 0;
    assert_eq!(unsafe { sw_lod_params_max_levels(&lod, &mut max) }, SW_OK);
    assert_eq!(max, LodParams::default().max_levels());
    lod.patch_cells = 8;
    lod.levels = 9; // too many for 8 cells: max_levels still answers
    assert_eq!(unsafe { sw_lod_params_max_levels(&lod, &mut max) }, SW_OK);
    assert_eq!(max, 4);
    lod.patch_cells = 6;
    assert_eq!(
        unsafe { sw_lod_params_max_levels(&lod, &mut max) },
        SW_ERROR_INVALID_ARGUMENT
    );
    lod.patch_cells = 8;
    lod.levels = 3;
    assert_eq!(unsafe { sw_surface_set_lod_params(s, &lod) }, SW_OK);
    let mut back = sw_lod_params_default();
    assert_eq!(unsafe { sw_surface_lod_params(s, &mut back) }, SW_OK);
    assert_eq!((back.patch_cells, back.levels), (8, 3));

    let mut grid = [9usize; 2];
    assert_eq!(
        unsafe { sw_surface_lod_patch_grid(s, grid.as_mut_ptr()) },
        SW_OK
    );
    assert_eq!(grid, [0, 0], "not built yet");
    // 4 × 2 patches; the levels are capped at the last and balanced.
    let levels = [0u8, 1, 2, 9, 0, 0, 1, 2];
    let mut changed = 0;
    assert_eq!(
        unsafe { sw_surface_set_lod_levels(s, levels.as_ptr(), levels.len(), &mut changed) },
        SW_OK
    );
    let rust_surface = Surface::new(Params::with_size(33, 17)).unwrap();
    let mut rust = LodMesh::new(LodParams::default().with_patch_cells(8).with_levels(3)).unwrap();
    assert!(rust.set_levels(&rust_surface.mesh_view(), &levels).unwrap());
    assert_eq!(changed, 1);
    assert_eq!(
        unsafe { sw_surface_lod_patch_grid(s, grid.as_mut_ptr()) },
        SW_OK
    );
    assert_eq!(grid, rust.patch_grid());
    let mut count = 0;
    assert_eq!(
        unsafe { sw_surface_lod_patch_levels(s, std::ptr::null_mut(), 0, &mut count) },
        SW_OK
    );
    let mut patch = vec![0u8; count];
    assert_eq!(
        unsafe { sw_surface_lod_patch_levels(s, patch.as_mut_ptr(), count, &mut count) },
        SW_OK
    );
    assert_eq!(patch, rust.patch_levels());
    assert_eq!(
        unsafe { sw_surface_lod_triangle_levels(s, std::ptr::null_mut(), 0, &mut count) },
        SW_OK
    );
    assert_eq!(count, rust.triangle_count());
    let mut triangles = vec![0u8; count];
    assert_eq!(
        unsafe { sw_surface_lod_triangle_levels(s, triangles.as_mut_ptr(), count - 1, &mut count) },
        SW_ERROR_BUFFER_TOO_SMALL
    );
    assert_eq!(
        unsafe { sw_surface_lod_triangle_levels(s, triangles.as_mut_ptr(), count, &mut count) },
        SW_OK
    );
    assert_eq!(triangles, rust.triangle_levels());
    let mut indices = vec![0u32; 3 * count];
    assert_eq!(
        unsafe { sw_surface_lod_indices(s, indices.as_mut_ptr(), indices.len(), &mut count) },
        SW_OK
    );
    assert_eq!(indices, rust.indices());

    // The same levels again change nothing; a wrong count is refused and keeps the mesh.
    assert_eq!(
        unsafe { sw_surface_set_lod_levels(s, levels.as_ptr(), levels.len(), &mut changed) },
        SW_OK
    );
    assert_eq!(changed, 0);
    assert_eq!(
        unsafe { sw_surface_set_lod_levels(s, levels.as_ptr(), 7, &mut changed) },
        SW_ERROR_BUFFER_TOO_SMALL
    );
    assert_eq!(
        unsafe { sw_surface_lod_patch_levels(s, patch.as_mut_ptr(), patch.len(), &mut count) },
        SW_OK
    );
    assert_eq!(patch, rust.patch_levels());
    sw_surface_destroy(s);
}

#[test]
fn the_reflectance_at_normal_incidence_is_the_rust_apis() {
    let mut view = sw_refraction_default();
    let mut r0 = 0.0;
    assert_eq!(unsafe { sw_refraction_r0(&view, &mut r0) }, SW_OK);
    assert_eq!(r0.to_bits(), RefractionParams::default().r0().to_bits());
    view.ior = 0.5;
    assert_eq!(
        unsafe { sw_refraction_r0(&view, &mut r0) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { sw_refraction_r0(&view, std::ptr::null_mut()) },
        SW_ERROR_NULL_POINTER
    );
}
