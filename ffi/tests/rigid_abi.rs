//! The C ABI's rigid bodies called from Rust as C calls them: floaters of an earlier
//! header's size, hull handles, pushes at a point, the forces on an engine's body. (The C
//! and C# clients float and right boxes with them: c_client.rs, csharp.rs.)

use springwater::body::Hull;
use springwater_ffi::*;

/// A 32 × 32 surface at the defaults.
fn surface() -> *mut SwSurface {
    let mut params = sw_params_default();
    params.cols = 32;
    params.rows = 32;
    let mut s = std::ptr::null_mut();
    assert_eq!(unsafe { sw_surface_create(&params, &mut s) }, SW_OK);
    s
}

#[test]
fn an_earlier_versions_floater_is_taken_with_defaults_and_filled_only_as_far_as_it_goes() {
    let s = surface();
    // A version 1 caller's floater: its first 80 bytes; the bytes after them stand for
    // memory the caller owns, which the library must neither read nor write.
    let mut old = sw_floater_box(1.0, 0.5, 1.0, 2.0, 16.0, 0.0, 16.0);
    old.struct_size = SW_FLOATER_SIZE_V1;
    // What a version 1 struct does not have is not read: garbage there changes nothing.
    old.orientation = [f32::NAN; 4];
    old.has_inertia = 7;
    let mut id = 0;
    assert_eq!(unsafe { sw_surface_add_floater(s, &old, &mut id) }, SW_OK);
    let mut now = SwFloater::default();
    assert_eq!(unsafe { sw_surface_floater(s, id, &mut now) }, SW_OK);
    assert_eq!(now.orientation, [0.0, 0.0, 0.0, 1.0]);
    assert_eq!(now.has_inertia, 0);

    // Turned and spun by a current caller, set by an old one: the turn stays.
    now.orientation = glam::Quat::from_rotation_z(0.2).to_array();
    now.angular_velocity = [0.0, 0.0, 0.5];
    assert_eq!(unsafe { sw_surface_set_floater(s, id, &now) }, SW_OK);
    old.velocity = [1.0, 0.0, 0.0];
    assert_eq!(unsafe { sw_surface_set_floater(s, id, &old) }, SW_OK);
    let mut back = SwFloater::default();
    assert_eq!(unsafe { sw_surface_floater(s, id, &mut back) }, SW_OK);
    assert_eq!(back.velocity, [1.0, 0.0, 0.0]);
    assert_eq!(back.orientation, now.orientation);
    assert_eq!(back.angular_velocity, now.angular_velocity);

    // Read back into a version 1 struct: its 80 bytes, its size kept, nothing after.
    old.orientation = [7.0; 4];
    old.inertia = [7.0; 9];
    assert_eq!(unsafe { sw_surface_floater(s, id, &mut old) }, SW_OK);
    assert_eq!(old.struct_size, SW_FLOATER_SIZE_V1);
    assert_eq!(old.velocity, back.velocity);
    assert_eq!((old.orientation, old.inertia), ([7.0; 4], [7.0; 9]));
    old.struct_size = SW_FLOATER_SIZE_V1 + 4;
    assert_eq!(
        unsafe { sw_surface_floater(s, id, &mut old) },
        SW_ERROR_INVALID_ARGUMENT
    );
    sw_surface_destroy(s);
}

#[test]
fn a_hull_is_checked_shared_and_outlived_by_its_bodies() {
    let cube = Hull::cuboid([1.0, 0.5, 1.0]).unwrap();
    let xyz: Vec<f32> = cube.vertices().iter().flatten().copied().collect();
    let tris: Vec<u32> = cube.triangles().iter().flatten().copied().collect();
    let mut hull = std::ptr::null_mut();
    let create = |t: &[u32], out| unsafe {
        sw_hull_create(xyz.as_ptr(), xyz.len() / 3, t.as_ptr(), t.len() / 3, out)
    };
    // An open mesh (a triangle missing) is refused with its defect.
    assert_eq!(create(&tris[3..], &mut hull), SW_ERROR_INVALID_ARGUMENT);
    assert!(hull.is_null());
    assert_eq!(
        unsafe { sw_hull_create(std::ptr::null(), 8, tris.as_ptr(), 12, &mut hull) },
        SW_ERROR_NULL_POINTER
    );
    assert_eq!(create(&tris, &mut hull), SW_OK);
    let mut volume = 0.0;
    assert_eq!(unsafe { sw_hull_volume(hull, &mut volume) }, SW_OK);
    assert_eq!(volume, 4.0);

    let s = surface();
    let mut body = SwFloater::default();
    assert_eq!(
        unsafe { sw_floater_hull(hull, 2.0, 16.0, 0.0, 16.0, &mut body) },
        SW_OK
    );
    assert_eq!(body.shape, SW_SHAPE_HULL);
    let (mut a, mut b) = (0, 0);
    assert_eq!(
        unsafe { sw_surface_add_floater(s, &body, &mut a) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { sw_surface_add_hull_floater(s, hull, &body, &mut a) },
        SW_OK
    );
    assert_eq!(
        unsafe { sw_surface_add_hull_floater(s, hull, &body, &mut b) },
        SW_OK
    );
    sw_hull_destroy(hull);
    sw_hull_destroy(hull);
    assert_eq!(
        unsafe { sw_surface_add_hull_floater(s, hull, &body, &mut b) },
        SW_ERROR_INVALID_HANDLE
    );
    // The bodies keep the mesh: they read back as hulls, and set keeps it.
    let mut back = SwFloater::default();
    assert_eq!(unsafe { sw_surface_floater(s, a, &mut back) }, SW_OK);
    assert_eq!((back.shape, back.inertia), (SW_SHAPE_HULL, body.inertia));
    back.position[1] = -0.1;
    assert_eq!(unsafe { sw_surface_set_floater(s, a, &back) }, SW_OK);
    let (mut one, mut two) = (SwFloater::default(), SwFloater::default());
    assert_eq!(unsafe { sw_surface_floater(s, a, &mut one) }, SW_OK);
    assert_eq!(unsafe { sw_surface_floater(s, b, &mut two) }, SW_OK);
    assert_eq!((one.position[1], two.shape), (-0.1, SW_SHAPE_HULL));
    // A sphere cannot become a hull through set (it has no mesh).
    let mut ball = sw_floater_sphere(1.0, 1.0, 8.0, 0.0, 8.0);
    let mut c = 0;
    assert_eq!(unsafe { sw_surface_add_floater(s, &ball, &mut c) }, SW_OK);
    ball.shape = SW_SHAPE_HULL;
    assert_eq!(
        unsafe { sw_surface_set_floater(s, c, &ball) },
        SW_ERROR_INVALID_ARGUMENT
    );
    sw_surface_destroy(s);
}

#[test]
fn body_forces_lift_a_half_submerged_box_by_its_weight_and_push_at_turns_a_body() {
    let s = surface();
    // A box 4 × 2 × 4 of half the water's density at its draft of 1.
    let body = sw_floater_box(2.0, 1.0, 2.0, 16.0, 16.0, 0.0, 16.0);
    let mut push = sw_body_forces_default();
    assert_eq!(
        unsafe { sw_surface_body_forces(s, &body, 1.0 / 60.0, &mut push) },
        SW_OK
    );
    let weight = 16.0 * springwater::Buoyancy::default().gravity;
    assert!((push.force[1] - weight).abs() < 0.02 * weight, "{push:?}");
    for bad in [0.0, -1.0, 2.0, f32::NAN] {
        assert_eq!(
            unsafe { sw_surface_body_forces(s, &body, bad, &mut push) },
            SW_ERROR_INVALID_ARGUMENT
        );
    }
    let mut no_size = SwBodyForces {
        struct_size: 0,
        ..push
    };
    assert_eq!(
        unsafe { sw_surface_body_forces(s, &body, 0.01, &mut no_size) },
        SW_ERROR_INVALID_ARGUMENT
    );

    let mut id = 0;
    assert_eq!(unsafe { sw_surface_add_floater(s, &body, &mut id) }, SW_OK);
    // Up at a point 2 along +x from the centre: torque (2, 0, 0) × (0, 3, 0) = (0, 0, 6).
    let pushed = sw_surface_push_floater_at(s, id, 0.0, 3.0, 0.0, 18.0, 0.0, 16.0);
    assert_eq!(pushed, SW_OK);
    let mut now = SwFloater::default();
    assert_eq!(unsafe { sw_surface_floater(s, id, &mut now) }, SW_OK);
    assert_eq!(
        (now.push, now.push_torque),
        ([0.0, 3.0, 0.0], [0.0, 0.0, 6.0])
    );
    let nan = sw_surface_push_floater_at(s, id, 0.0, 3.0, 0.0, f32::NAN, 0.0, 16.0);
    assert_eq!(nan, SW_ERROR_INVALID_ARGUMENT);
    sw_surface_destroy(s);
}
