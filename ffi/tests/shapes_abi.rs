//! The C ABI's shapes beyond making and adding bodies, called from Rust as C calls them: a
//! point's velocity on a body, bounding radii, and the hulls the library makes (a box, the
//! boat, a hull moved onto its centroid) with their centroids, vertices and triangles. Each
//! gives the Rust API's bits; a refused call makes nothing.

use springwater::body::{BoatShape, Hull};
use springwater::{Floater, Shape};
use springwater_ffi::*;
use std::sync::Arc;

#[test]
fn a_points_velocity_and_a_bodys_bounding_radius_are_the_rust_apis() {
    let mut body = sw_floater_box(1.0, 0.5, 2.0, 3.0, 4.0, 0.0, 5.0);
    body.velocity = [1.0, -0.5, 0.25];
    body.angular_velocity = [0.3, 1.5, -0.2];
    let mut rust = Floater::cuboid([1.0, 0.5, 2.0], 3.0, [4.0, 0.0, 5.0]);
    rust.velocity = glam::Vec3::new(1.0, -0.5, 0.25);
    rust.angular_velocity = glam::Vec3::new(0.3, 1.5, -0.2);
    let mut v = [0.0f32; 3];
    assert_eq!(
        unsafe { sw_floater_velocity_at(&body, 5.0, 0.5, 3.0, v.as_mut_ptr()) },
        SW_OK
    );
    assert_eq!(v, rust.velocity_at([5.0, 0.5, 3.0]).to_array());
    // The shape does not count: a hull body's point moves the same.
    let hull_body = SwFloater {
        shape: SW_SHAPE_HULL,
        ..body
    };
    let mut w = [0.0f32; 3];
    assert_eq!(
        unsafe { sw_floater_velocity_at(&hull_body, 5.0, 0.5, 3.0, w.as_mut_ptr()) },
        SW_OK
    );
    assert_eq!(w, v);
    let mut spinning = body;
    spinning.angular_velocity[1] = f32::NAN;
    assert_eq!(
        unsafe { sw_floater_velocity_at(&spinning, 0.0, 0.0, 0.0, w.as_mut_ptr()) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { sw_floater_velocity_at(&body, f32::INFINITY, 0.0, 0.0, w.as_mut_ptr()) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(w, v, "a refused call writes nothing");

    let mut r = 0.0;
    assert_eq!(unsafe { sw_floater_bounding_radius(&body, &mut r) }, SW_OK);
    assert_eq!(r, rust.shape.bounding_radius());
    let ball = sw_floater_sphere(1.5, 2.0, 0.0, 0.0, 0.0);
    assert_eq!(unsafe { sw_floater_bounding_radius(&ball, &mut r) }, SW_OK);
    assert_eq!(r, 1.5);
    let flat = sw_floater_sphere(-1.0, 2.0, 0.0, 0.0, 0.0);
    assert_eq!(
        unsafe { sw_floater_bounding_radius(&flat, &mut r) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { sw_floater_bounding_radius(&hull_body, &mut r) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(r, 1.5);
}

/// The vertices and triangles of a hull handle, read the C way (the count first).
fn mesh_of(hull: *const SwHull) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let (mut vertices, mut triangles) = (0, 0);
    unsafe {
        assert_eq!(
            sw_hull_vertices(hull, std::ptr::null_mut(), 0, &mut vertices),
            SW_OK
        );
        assert_eq!(
            sw_hull_triangles(hull, std::ptr::null_mut(), 0, &mut triangles),
            SW_OK
        );
    }
    let mut xyz = vec![0.0f32; 3 * vertices];
    let mut indices = vec![0u32; 3 * triangles];
    unsafe {
        assert_eq!(
            sw_hull_vertices(hull, xyz.as_mut_ptr(), xyz.len() - 1, &mut vertices),
            SW_ERROR_BUFFER_TOO_SMALL
        );
        assert_eq!(
            sw_hull_vertices(hull, xyz.as_mut_ptr(), xyz.len(), &mut vertices),
            SW_OK
        );
        assert_eq!(
            sw_hull_triangles(hull, indices.as_mut_ptr(), indices.len(), &mut triangles),
            SW_OK
        );
    }
    (
        xyz.chunks(3).map(|v| [v[0], v[1], v[2]]).collect(),
        indices.chunks(3).map(|t| [t[0], t[1], t[2]]).collect(),
    )
}

#[test]
fn the_hulls_the_library_makes_are_the_rust_apis() {
    let mut boat = std::ptr::null_mut();
    let mut shape = sw_boat_shape_default();
    shape.stations = 12;
    shape.segments = 4;
    assert_eq!(unsafe { sw_hull_boat(&shape, &mut boat) }, SW_OK);
    let mut rust_shape = BoatShape::default();
    (rust_shape.stations, rust_shape.segments) = (12, 4);
    let rust_boat = rust_shape.hull().unwrap();
    let (vertices, triangles) = mesh_of(boat);
    assert_eq!(
        (&vertices[..], &triangles[..]),
        (rust_boat.vertices(), rust_boat.triangles())
    );
    let mut centroid = [0.0f32; 3];
    assert_eq!(
        unsafe { sw_hull_centroid(boat, centroid.as_mut_ptr()) },
        SW_OK
    );
    assert_eq!(centroid, rust_boat.centroid().to_array());
    assert!(centroid[1] > 0.0, "the origin is on the keel");

    let mut centred = std::ptr::null_mut();
    assert_eq!(unsafe { sw_hull_centred(boat, &mut centred) }, SW_OK);
    let rust_centred = rust_boat.centred().unwrap();
    assert_eq!(mesh_of(centred).0, rust_centred.vertices());
    let mut r = 0.0;
    assert_eq!(unsafe { sw_hull_bounding_radius(centred, &mut r) }, SW_OK);
    assert_eq!(r, Shape::Hull(Arc::new(rust_centred)).bounding_radius());
    // The boat it came from is as it was.
    assert_eq!(mesh_of(boat).0, vertices);

    let mut cuboid = std::ptr::null_mut();
    assert_eq!(unsafe { sw_hull_cuboid(1.0, 0.5, 2.0, &mut cuboid) }, SW_OK);
    let rust_cuboid = Hull::cuboid([1.0, 0.5, 2.0]).unwrap();
    let (vertices, triangles) = mesh_of(cuboid);
    assert_eq!((vertices.len(), triangles.len()), (8, 12));
    assert_eq!(
        (&vertices[..], &triangles[..]),
        (rust_cuboid.vertices(), rust_cuboid.triangles())
    );
    let mut volume = 0.0;
    assert_eq!(unsafe { sw_hull_volume(cuboid, &mut volume) }, SW_OK);
    assert_eq!(volume, 8.0);

    // Refused, making nothing: a size out of range, a stale or NULL handle.
    let mut none = std::ptr::null_mut();
    assert_eq!(
        unsafe { sw_hull_cuboid(-1.0, 0.5, 2.0, &mut none) },
        SW_ERROR_INVALID_ARGUMENT
    );
    shape.stations = 1;
    assert_eq!(
        unsafe { sw_hull_boat(&shape, &mut none) },
        SW_ERROR_INVALID_ARGUMENT
    );
    shape = sw_boat_shape_default();
    shape.struct_size += 4;
    assert_eq!(
        unsafe { sw_hull_boat(&shape, &mut none) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert!(none.is_null());
    sw_hull_destroy(cuboid);
    assert_eq!(
        unsafe { sw_hull_centroid(cuboid, centroid.as_mut_ptr()) },
        SW_ERROR_INVALID_HANDLE
    );
    assert_eq!(
        unsafe { sw_hull_centred(std::ptr::null(), &mut none) },
        SW_ERROR_NULL_POINTER
    );
    assert!(none.is_null());
    sw_hull_destroy(boat);
    sw_hull_destroy(centred);
}
