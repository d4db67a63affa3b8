//! The C ABI under arbitrary calls: any parameters, floats, buffer lengths, enum values,
//! snapshot bytes and handles (live, destroyed, NULL or made up), in any order. Every call
//! returns a status (never a panic or a crash, never a write past the length it was
//! given), and the live surfaces' positions stay finite.
//!
//! Buffers are real allocations of the length the call is told, so a write past a stated
//! length would be caught by the allocator's bounds only under a sanitizer
//! (`FUZZ_SANITIZER=address fuzz/run.sh 60 ffi`); without one, a canary after each buffer
//! checks it.

#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use springwater_ffi::*;
use std::ptr::null_mut;

#[derive(Debug, Arbitrary)]
enum Handle {
    Live(u8),
    Null,
    MadeUp(usize),
}

#[derive(Debug, Arbitrary)]
enum Call {
    Create {
        cols: u8,
        rows: u8,
        floats: [f32; 10],
        boundary: i32,
    },
    Destroy(Handle),
    Advance(Handle, f32),
    Step(Handle, u8),
    Drop(Handle, [f32; 4]),
    Force(Handle, [f32; 5]),
    Height(Handle, f32, f32),
    Normal(Handle, f32, f32),
    Sample(Handle, Vec<f32>, u8),
    Positions(Handle, u16),
    Normals(Handle, u16),
    Uvs(Handle, [f32; 5], u16),
    Vertices(Handle, [f32; 5], u16),
    Lod(Handle, [f32; 3], [u8; 2], f32, f32),
    Indices(Handle, u16),
    SaveRestore(Handle, Vec<(u16, u8)>, bool),
    Load(Vec<u8>),
    Simd(Handle, i32),
    Energy(Handle),
}

/// A buffer of `len` elements followed by a canary that no call may touch.
struct Buffer<T: Copy> {
    data: Vec<T>,
    len: usize,
    canary: T,
}

impl<T: Copy + PartialEq + std::fmt::Debug> Buffer<T> {
    fn new(len: usize, fill: T, canary: T) -> Self {
        let mut data = vec![fill; len + 4];
        data[len..].fill(canary);
        Self { data, len, canary }
    }
    fn ptr(&mut self) -> *mut T {
        self.data.as_mut_ptr()
    }
    fn check(&self) {
        assert!(
            self.data[self.len..].iter().all(|v| *v == self.canary),
            "wrote past the buffer"
        );
    }
}

fn nodes(s: *mut SwSurface) -> usize {
    let mut n = 0;
    // SAFETY: a valid out-pointer.
    if unsafe { sw_surface_node_count(s, &mut n) } == SW_OK {
        n
    } else {
        0
    }
}

fuzz_target!(|calls: Vec<Call>| {
    let mut live: Vec<*mut SwSurface> = Vec::new();
    let mut dead: Vec<*mut SwSurface> = Vec::new();
    let pick = |h: &Handle, live: &[*mut SwSurface], dead: &[*mut SwSurface]| match h {
        Handle::Live(i) if !live.is_empty() => live[*i as usize % live.len()],
        Handle::Live(i) if !dead.is_empty() => dead[*i as usize % dead.len()],
        Handle::Live(_) | Handle::Null => null_mut(),
        Handle::MadeUp(v) => *v as *mut SwSurface,
    };
    for call in calls.iter().take(64) {
        // SAFETY (every call below): pointers are to live locals or buffers of at least
        // the length passed; handles may be anything, which is what is being tested.
        unsafe {
            match call {
                Call::Create {
                    cols,
                    rows,
                    floats,
                    boundary,
                } => {
                    let mut p = sw_params_default();
                    p.cols = (*cols % 40) as u32;
                    p.rows = (*rows % 40) as u32;
                    let f = floats;
                    [p.spacing, p.mass, p.stiffness, p.viscosity, p.dt] =
                        [f[0], f[1], f[2], f[3], f[4]];
                    [p.rest_ratio, p.time_scale] = [f[5], f[6]];
                    [p.acceleration_x, p.acceleration_y, p.acceleration_z] = [f[7], f[8], f[9]];
                    p.boundary = *boundary;
                    let mut s = null_mut();
                    if sw_surface_create(&p, &mut s) == SW_OK {
                        live.push(s);
                    } else {
                        assert!(s.is_null());
                        // Defaults on a small grid always work.
                        let mut p = sw_params_default();
                        p.cols = 2 + p.cols % 16;
                        p.rows = 3;
                        assert_eq!(sw_surface_create(&p, &mut s), SW_OK);
                        live.push(s);
                    }
                }
                Call::Destroy(h) => {
                    let s = pick(h, &live, &dead);
                    sw_surface_destroy(s);
                    if let Some(i) = live.iter().position(|&l| l == s) {
                        dead.push(live.swap_remove(i));
                    }
                }
                Call::Advance(h, t) => {
                    let mut n = 0;
                    sw_surface_advance(pick(h, &live, &dead), *t, &mut n);
                }
                Call::Step(h, n) => {
                    sw_surface_step(pick(h, &live, &dead), *n as u32 % 8);
                }
                Call::Drop(h, [x, z, hgt, r]) => {
                    sw_surface_drop(pick(h, &live, &dead), *x, *z, *hgt, *r);
                }
                Call::Force(h, [x, z, fx, fy, fz]) => {
                    sw_surface_add_force_at(pick(h, &live, &dead), *x, *z, *fx, *fy, *fz);
                }
                Call::Height(h, x, z) => {
                    let mut out = 0.0;
                    sw_surface_height_at(pick(h, &live, &dead), *x, *z, &mut out);
                }
                Call::Normal(h, x, z) => {
                    let mut out = [0.0f32; 3];
                    sw_surface_normal_at(pick(h, &live, &dead), *x, *z, out.as_mut_ptr());
                    sw_surface_velocity_at(pick(h, &live, &dead), *x, *z, out.as_mut_ptr());
                }
                Call::Sample(h, xz, out_len) => {
                    let count = xz.len() / 2;
                    let mut out = Buffer::new(
                        *out_len as usize % 8,
                        SwSample::default(),
                        SwSample {
                            height: 7.0,
                            ..Default::default()
                        },
                    );
                    let status = sw_surface_sample(
                        pick(h, &live, &dead),
                        xz.as_ptr(),
                        count,
                        out.ptr(),
                        out.len,
                    );
                    if status == SW_OK {
                        assert!(out.len >= count);
                    }
                    assert!(out.data[out.len..].iter().all(|s| s.height == 7.0));
                }
                Call::Positions(h, len) => {
                    let s = pick(h, &live, &dead);
                    let mut b = Buffer::new(*len as usize % 6000, 0.0f32, -7.0);
                    if sw_surface_write_positions(s, b.ptr(), b.len) == SW_OK {
                        assert!(b.data[..3 * nodes(s)].iter().all(|v| v.is_finite()));
                    }
                    b.check();
                }
                Call::Normals(h, len) => {
                    let mut b = Buffer::new(*len as usize % 6000, 0.0f32, -7.0);
                    sw_surface_write_normals(pick(h, &live, &dead), b.ptr(), b.len);
                    b.check();
                }
                Call::Uvs(h, [x, y, z, depth, ior], len) => {
                    let mut r = sw_refraction_default();
                    [r.eye_x, r.eye_y, r.eye_z, r.depth, r.ior] = [*x, *y, *z, *depth, *ior];
                    let mut b = Buffer::new(*len as usize % 4000, 0.0f32, -7.0);
                    if sw_surface_write_refraction_uvs(pick(h, &live, &dead), &r, b.ptr(), b.len)
                        == SW_OK
                    {
                        assert!(b.data[..b.len].iter().all(|v| v.is_finite()));
                    }
                    b.check();
                }
                Call::Vertices(h, [x, y, z, depth, ior], len) => {
                    let mut r = sw_refraction_default();
                    [r.eye_x, r.eye_y, r.eye_z, r.depth, r.ior] = [*x, *y, *z, *depth, *ior];
                    let canary = SwVertex {
                        uv: [-7.0, -7.0],
                        ..Default::default()
                    };
                    let mut b = Buffer::new(
                        *len as usize % 2000,
                        SwVertex::default(),
                        SwVertex::default(),
                    );
                    b.data[b.len..].fill(canary);
                    b.canary = canary;
                    sw_surface_write_vertices(pick(h, &live, &dead), &r, b.ptr(), b.len);
                    assert!(b.data[b.len..].iter().all(|v| v.uv == [-7.0, -7.0]));
                }
                Call::Lod(h, eye, [patch, levels], range, hysteresis) => {
                    let s = pick(h, &live, &dead);
                    let mut p = sw_lod_params_default();
                    p.patch_cells = 1 << (patch % 14);
                    p.levels = *levels as u32 % 16;
                    p.first_range = *range;
                    p.hysteresis = *hysteresis;
                    sw_surface_set_lod_params(s, &p);
                    let mut changed = 0;
                    sw_surface_update_lod(s, eye[0], eye[1], eye[2], &mut changed);
                }
                Call::Indices(h, len) => {
                    let s = pick(h, &live, &dead);
                    let mut count = 0;
                    let mut b = Buffer::new(*len as usize % 20000, 0u32, u32::MAX);
                    if sw_surface_lod_indices(s, b.ptr(), b.len, &mut count) == SW_OK {
                        let n = nodes(s) as u32;
                        assert!(b.data[..count].iter().all(|&i| i < n));
                    }
                    b.check();
                }
                Call::SaveRestore(h, edits, truncate) => {
                    let s = pick(h, &live, &dead);
                    let mut size = 0;
                    if sw_surface_save(s, null_mut(), 0, &mut size) != SW_OK {
                        continue;
                    }
                    let mut bytes = vec![0u8; size];
                    assert_eq!(
                        sw_surface_save(s, bytes.as_mut_ptr(), size, &mut size),
                        SW_OK
                    );
                    for (at, xor) in edits {
                        let i = *at as usize % bytes.len();
                        bytes[i] ^= xor;
                    }
                    let len = if *truncate {
                        bytes.len() / 2
                    } else {
                        bytes.len()
                    };
                    sw_surface_restore(s, bytes.as_ptr(), len);
                }
                Call::Load(bytes) => {
                    let mut s = null_mut();
                    if sw_surface_load(bytes.as_ptr(), bytes.len(), &mut s) == SW_OK {
                        live.push(s);
                    }
                }
                Call::Simd(h, level) => {
                    let mut ran = 0;
                    sw_surface_set_simd_level(pick(h, &live, &dead), *level, &mut ran);
                }
                Call::Energy(h) => {
                    let mut e = SwEnergy::default();
                    if sw_surface_energy(pick(h, &live, &dead), &mut e) == SW_OK {
                        assert!(!e.total.is_nan());
                    }
                }
            }
        }
        let mut message = [0 as std::ffi::c_char; 64];
        // SAFETY: a local buffer of the length passed.
        assert!(unsafe { sw_last_error(message.as_mut_ptr(), message.len()) } >= 1);
    }
    for s in live {
        sw_surface_destroy(s);
    }
});
