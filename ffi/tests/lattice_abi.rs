//! The C ABI's lattice edits (pins, per-node masses and viscosities, single springs) and
//! torque pushes, called from Rust as C calls them: each does what the Rust method of the
//! same name does, and a refused call changes nothing (the state hash says so).

use springwater::{Family, Params, Spring, SpringId, Surface};
use springwater_ffi::*;

/// A 6 × 5 surface at the defaults.
fn surface() -> *mut SwSurface {
    let mut params = sw_params_default();
    params.cols = 6;
    params.rows = 5;
    let mut s = std::ptr::null_mut();
    assert_eq!(unsafe { sw_surface_create(&params, &mut s) }, SW_OK);
    s
}

fn hash(s: *const SwSurface) -> u64 {
    let mut h = 0;
    assert_eq!(unsafe { sw_surface_state_hash(s, &mut h) }, SW_OK);
    h
}

#[test]
fn pins_are_set_read_one_by_one_and_read_whole() {
    let s = surface();
    let mut pinned = [7u8; 31];
    assert_eq!(
        unsafe { sw_surface_write_pinned(s, pinned.as_mut_ptr(), 31) },
        SW_OK
    );
    // The default boundary pins the outer ring; the buffer may be longer than needed.
    assert_eq!((pinned[0], pinned[7], pinned[30]), (1, 0, 7));
    assert_eq!(sw_surface_set_pinned(s, 7, 1), SW_OK);
    let mut one = 0;
    assert_eq!(unsafe { sw_surface_is_pinned(s, 7, &mut one) }, SW_OK);
    assert_eq!(one, 1);
    assert_eq!(sw_surface_set_pinned(s, 0, 0), SW_OK);
    assert_eq!(
        unsafe { sw_surface_write_pinned(s, pinned.as_mut_ptr(), 30) },
        SW_OK
    );
    assert_eq!((pinned[0], pinned[7]), (0, 1));

    let before = hash(s);
    assert_eq!(sw_surface_set_pinned(s, 30, 1), SW_ERROR_INVALID_ARGUMENT);
    assert_eq!(sw_surface_set_pinned(s, 8, 2), SW_ERROR_INVALID_ARGUMENT);
    assert_eq!(
        unsafe { sw_surface_is_pinned(s, 30, &mut one) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { sw_surface_is_pinned(s, 7, std::ptr::null_mut()) },
        SW_ERROR_NULL_POINTER
    );
    assert_eq!(
        unsafe { sw_surface_write_pinned(s, pinned.as_mut_ptr(), 29) },
        SW_ERROR_BUFFER_TOO_SMALL
    );
    assert_eq!(hash(s), before);
    sw_surface_destroy(s);
}

#[test]
fn masses_and_viscosities_match_the_rust_api_and_refusals_change_nothing() {
    let s = surface();
    let mut rust = Surface::new(Params::with_size(6, 5)).unwrap();
    let masses: Vec<f32> = (0..30).map(|i| 4.0 + 0.5 * (i % 4) as f32).collect();
    let viscosities: Vec<f32> = (0..30).map(|i| 0.02 * (i % 5) as f32).collect();
    assert_eq!(
        unsafe { sw_surface_set_masses(s, masses.as_ptr(), masses.len()) },
        SW_OK
    );
    assert_eq!(
        unsafe { sw_surface_set_viscosities(s, viscosities.as_ptr(), viscosities.len()) },
        SW_OK
    );
    assert_eq!(sw_surface_set_mass(s, 14, 6.0), SW_OK);
    assert_eq!(sw_surface_set_viscosity(s, 15, 0.3), SW_OK);
    rust.set_masses(&masses).unwrap();
    rust.set_viscosities(&viscosities).unwrap();
    rust.set_mass(14, 6.0).unwrap();
    rust.set_viscosity(15, 0.3).unwrap();
    let (mut m, mut v) = ([0.0f32; 30], [0.0f32; 30]);
    assert_eq!(
        unsafe { sw_surface_write_masses(s, m.as_mut_ptr(), 30) },
        SW_OK
    );
    assert_eq!(
        unsafe { sw_surface_write_viscosities(s, v.as_mut_ptr(), 30) },
        SW_OK
    );
    assert_eq!(
        (m.to_vec(), v.to_vec()),
        (rust.masses().to_vec(), rust.viscosities().to_vec())
    );

    // A whole table with one bad value, or too short, changes no node.
    let before = hash(s);
    let mut bad = masses.clone();
    bad[29] = 0.01; // past the critical timestep
    assert_eq!(
        unsafe { sw_surface_set_masses(s, bad.as_ptr(), 30) },
        SW_ERROR_INVALID_ARGUMENT
    );
    bad[29] = f32::NAN;
    assert_eq!(
        unsafe { sw_surface_set_viscosities(s, bad.as_ptr(), 30) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { sw_surface_set_masses(s, masses.as_ptr(), 29) },
        SW_ERROR_BUFFER_TOO_SMALL
    );
    assert_eq!(
        unsafe { sw_surface_set_masses(s, std::ptr::null(), 30) },
        SW_ERROR_NULL_POINTER
    );
    assert_eq!(sw_surface_set_mass(s, 3, -1.0), SW_ERROR_INVALID_ARGUMENT);
    assert_eq!(sw_surface_set_mass(s, 30, 4.0), SW_ERROR_INVALID_ARGUMENT);
    assert_eq!(
        sw_surface_set_viscosity(s, 3, f32::INFINITY),
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { sw_surface_write_masses(s, m.as_mut_ptr(), 29) },
        SW_ERROR_BUFFER_TOO_SMALL
    );
    assert_eq!(hash(s), before);
    assert_eq!(hash(s), rust.state_hash());

    // The same water afterwards.
    assert_eq!(sw_surface_drop_at(s, 2.0, 2.0, 0.5, 1.0), SW_OK);
    assert_eq!(sw_surface_step(s, 30), SW_OK);
    rust.drop_at(2.0, 2.0, 0.5, 1.0).unwrap();
    rust.step_n(30).unwrap();
    assert_eq!(hash(s), rust.state_hash());
    sw_surface_destroy(s);
}

#[test]
fn springs_are_named_by_family_and_origin() {
    let s = surface();
    let mut rust = Surface::new(Params::with_size(6, 5)).unwrap();
    let id = SpringId {
        family: Family::SE,
        origin: 7,
    };
    let mut out = [0.0f32; 2];
    assert_eq!(
        unsafe { sw_surface_spring(s, SW_FAMILY_SE, 7, out.as_mut_ptr()) },
        SW_OK
    );
    let want = rust.spring(id).unwrap();
    assert_eq!(out, [want.rest, want.stiffness]);
    assert_eq!(sw_surface_set_spring(s, SW_FAMILY_SE, 7, 1.0, 6.0), SW_OK);
    rust.set_spring(
        id,
        Spring {
            rest: 1.0,
            stiffness: 6.0,
        },
    )
    .unwrap();
    assert_eq!(
        unsafe { sw_surface_spring(s, SW_FAMILY_SE, 7, out.as_mut_ptr()) },
        SW_OK
    );
    assert_eq!(out, [1.0, 6.0]);
    assert_eq!(hash(s), rust.state_hash());

    // No spring east of the last column, none south-west of the first; no family 4.
    let before = hash(s);
    out = [9.0; 2];
    for (family, node) in [
        (SW_FAMILY_E, 5),
        (SW_FAMILY_SW, 6),
        (4, 7),
        (SW_FAMILY_S, 30),
    ] {
        assert_eq!(
            unsafe { sw_surface_spring(s, family, node, out.as_mut_ptr()) },
            SW_ERROR_INVALID_ARGUMENT,
            "{family} {node}"
        );
        assert_eq!(
            sw_surface_set_spring(s, family, node, 1.0, 6.0),
            SW_ERROR_INVALID_ARGUMENT
        );
    }
    assert_eq!(out, [9.0; 2], "nothing written");
    // Too stiff for the timestep; a negative rest length.
    assert_eq!(
        sw_surface_set_spring(s, SW_FAMILY_S, 0, 0.5, 100.0),
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        sw_surface_set_spring(s, SW_FAMILY_S, 0, -0.5, 7.0),
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(hash(s), before);
    sw_surface_destroy(s);
}

#[test]
fn a_torque_push_adds_to_the_bodys_push_torque() {
    let s = surface();
    let body = sw_floater_box(1.0, 0.5, 1.0, 2.0, 2.5, 0.0, 2.0);
    let mut id = 0;
    assert_eq!(unsafe { sw_surface_add_floater(s, &body, &mut id) }, SW_OK);
    assert_eq!(sw_surface_push_floater_torque(s, id, 0.0, 1.5, 0.0), SW_OK);
    assert_eq!(sw_surface_push_floater_torque(s, id, 0.5, 0.5, 0.0), SW_OK);
    let mut now = SwFloater::default();
    assert_eq!(unsafe { sw_surface_floater(s, id, &mut now) }, SW_OK);
    assert_eq!((now.push, now.push_torque), ([0.0; 3], [0.5, 2.0, 0.0]));
    let before = hash(s);
    assert_eq!(
        sw_surface_push_floater_torque(s, id, f32::NAN, 0.0, 0.0),
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        sw_surface_push_floater_torque(s, id + 1, 1.0, 0.0, 0.0),
        SW_ERROR_NO_SUCH_FLOATER
    );
    assert_eq!(hash(s), before);
    sw_surface_destroy(s);
}
