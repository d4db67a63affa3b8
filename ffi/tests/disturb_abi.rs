//! The C ABI's rain and wakes, called from Rust as C calls them: made with their settings
//! checked, applied before every substep by `sw_surface_advance_with` with the Rust API's
//! bits, read and moved between frames; refusals make or change nothing.

use springwater::disturb::{Rain, Wake};
use springwater::{Params, Surface};
use springwater_ffi::*;

fn surface() -> *mut SwSurface {
    let mut params = sw_params_default();
    params.cols = 48;
    params.rows = 40;
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
fn rain_and_a_wake_fall_as_the_rust_apis_do() {
    let s = surface();
    let mut rain = std::ptr::null_mut();
    let mut wake = std::ptr::null_mut();
    let mut circle = std::ptr::null_mut();
    let path = [10.0f32, 10.0, 38.0, 10.0, 38.0, 30.0];
    unsafe {
        assert_eq!(sw_rain_create(20.0, 7, 1.0, 2.5, 0.5, &mut rain), SW_OK);
        assert_eq!(
            sw_wake_create(path.as_ptr(), 3, 30.0, 2.0, 1.0, &mut wake),
            SW_OK
        );
        assert_eq!(sw_wake_circle(s, 12.0, 60.0, 2.5, 1.5, &mut circle), SW_OK);
    }
    let mut rust = Surface::new(Params::with_size(48, 40)).unwrap();
    let mut rust_rain = Rain::new(20.0, 7);
    rust_rain.radius = 1.0..2.5;
    rust_rain.depth = 0.5;
    let mut rust_wake = Wake::new(vec![[10.0, 10.0], [38.0, 10.0], [38.0, 30.0]]).unwrap();
    (rust_wake.speed, rust_wake.radius, rust_wake.strength) = (30.0, 2.0, 1.0);
    let mut rust_circle = Wake::circle(&rust, 12.0);

    let list = [rain, wake, circle];
    for _ in 0..30 {
        let mut taken = 0;
        assert_eq!(
            unsafe { sw_surface_advance_with(s, 1.0 / 60.0, list.as_ptr(), 3, &mut taken) },
            SW_OK
        );
        let steps = rust
            .advance_with(
                1.0 / 60.0,
                &mut (&mut rust_rain, &mut rust_wake, &mut rust_circle),
            )
            .unwrap();
        assert_eq!(taken as usize, steps);
    }
    assert_eq!(hash(s), rust.state_hash());
    let (mut fallen, mut time) = (0u64, 0.0f64);
    let mut at = [0.0f32; 2];
    unsafe {
        assert_eq!(sw_rain_fallen(rain, &mut fallen), SW_OK);
        assert_eq!(sw_rain_time(rain, &mut time), SW_OK);
        assert_eq!(sw_wake_position(wake, at.as_mut_ptr()), SW_OK);
    }
    assert_eq!((fallen, time), (rust_rain.fallen(), rust_rain.time()));
    assert!(fallen > 0);
    assert_eq!(at, rust_wake.position());

    // Moved with a rebased world, stopped rain.
    assert_eq!(sw_wake_translate(wake, -2.0, 1.0), SW_OK);
    rust_wake.translate(-2.0, 1.0).unwrap();
    assert_eq!(unsafe { sw_wake_position(wake, at.as_mut_ptr()) }, SW_OK);
    assert_eq!(at, rust_wake.position());
    assert_eq!(sw_rain_set_rate(rain, 0.0), SW_OK);
    rust_rain.rate = 0.0;
    assert_eq!(
        unsafe { sw_surface_advance_with(s, 0.25, list.as_ptr(), 3, std::ptr::null_mut()) },
        SW_OK
    );
    rust.advance_with(
        0.25,
        &mut (&mut rust_rain, &mut rust_wake, &mut rust_circle),
    )
    .unwrap();
    assert_eq!(hash(s), rust.state_hash());
    for d in list {
        sw_disturbance_destroy(d);
    }
    sw_surface_destroy(s);
}

#[test]
fn refused_disturbances_make_and_change_nothing() {
    let s = surface();
    let mut d = std::ptr::null_mut();
    let corners = [1.0f32, 1.0, 1.0, 1.0];
    unsafe {
        for (rate, min, max, depth) in [
            (-1.0, 1.0, 2.0, 0.5),
            (f32::NAN, 1.0, 2.0, 0.5),
            (5.0, 0.0, 2.0, 0.5),
            (5.0, 2.0, 1.0, 0.5),
            (5.0, 1.0, 2.0, 1.5),
        ] {
            assert_eq!(
                sw_rain_create(rate, 1, min, max, depth, &mut d),
                SW_ERROR_INVALID_ARGUMENT
            );
        }
        // A path of one place, a radius of 0, a speed that is not finite.
        assert_eq!(
            sw_wake_create(corners.as_ptr(), 2, 60.0, 2.5, 1.5, &mut d),
            SW_ERROR_INVALID_ARGUMENT
        );
        let path = [1.0f32, 1.0, 5.0, 1.0];
        assert_eq!(
            sw_wake_create(path.as_ptr(), 2, 60.0, 0.0, 1.5, &mut d),
            SW_ERROR_INVALID_ARGUMENT
        );
        assert_eq!(
            sw_wake_circle(s, 5.0, f32::INFINITY, 2.5, 1.5, &mut d),
            SW_ERROR_INVALID_ARGUMENT
        );
        assert_eq!(
            sw_wake_create(std::ptr::null(), 2, 60.0, 2.5, 1.5, &mut d),
            SW_ERROR_NULL_POINTER
        );
    }
    assert!(d.is_null());

    let (mut rain, mut wake) = (std::ptr::null_mut(), std::ptr::null_mut());
    let path = [10.0f32, 10.0, 30.0, 20.0];
    unsafe {
        assert_eq!(sw_rain_create(50.0, 3, 1.5, 3.0, 0.6, &mut rain), SW_OK);
        assert_eq!(
            sw_wake_create(path.as_ptr(), 2, 60.0, 2.5, 1.5, &mut wake),
            SW_OK
        );
    }
    // The wrong kind, a rate out of range, a move that is not finite.
    let mut at = [0.0f32; 2];
    let mut fallen = 0;
    unsafe {
        assert_eq!(
            sw_wake_position(rain, at.as_mut_ptr()),
            SW_ERROR_INVALID_ARGUMENT
        );
        assert_eq!(sw_rain_fallen(wake, &mut fallen), SW_ERROR_INVALID_ARGUMENT);
    }
    assert_eq!(sw_rain_set_rate(rain, -2.0), SW_ERROR_INVALID_ARGUMENT);
    assert_eq!(
        sw_wake_translate(wake, f32::INFINITY, 0.0),
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(unsafe { sw_wake_position(wake, at.as_mut_ptr()) }, SW_OK);
    assert_eq!(at, [10.0, 10.0]);

    // A frame with a handle listed twice, a destroyed one or a NULL one changes nothing.
    let before = hash(s);
    let mut gone = std::ptr::null_mut();
    unsafe { assert_eq!(sw_rain_create(5.0, 1, 1.5, 3.0, 0.6, &mut gone), SW_OK) };
    sw_disturbance_destroy(gone);
    sw_disturbance_destroy(gone);
    for (list, status) in [
        ([rain, rain], SW_ERROR_BUSY),
        ([rain, gone], SW_ERROR_INVALID_HANDLE),
        ([wake, std::ptr::null_mut()], SW_ERROR_NULL_POINTER),
    ] {
        assert_eq!(
            unsafe { sw_surface_advance_with(s, 0.5, list.as_ptr(), 2, std::ptr::null_mut()) },
            status
        );
    }
    assert_eq!(
        unsafe { sw_surface_advance_with(s, -1.0, [rain].as_ptr(), 1, std::ptr::null_mut()) },
        SW_ERROR_INVALID_ARGUMENT
    );
    assert_eq!(hash(s), before);
    unsafe { assert_eq!(sw_rain_fallen(rain, &mut fallen), SW_OK) };
    assert_eq!(fallen, 0);
    // No disturbance at all is an ordinary frame.
    assert_eq!(
        unsafe { sw_surface_advance_with(s, 0.1, std::ptr::null(), 0, std::ptr::null_mut()) },
        SW_OK
    );
    sw_disturbance_destroy(rain);
    sw_disturbance_destroy(wake);
    sw_surface_destroy(s);
}
