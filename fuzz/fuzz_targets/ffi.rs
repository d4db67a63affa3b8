//! The C ABI under arbitrary calls: any parameters (the absorbing boundary's width among
//! them), floats, buffer lengths, enum values, snapshot bytes, floating bodies, floater ids
//! (live, removed or made up) and handles (live, destroyed, NULL or made up), in any order.
//! Every call returns a status (never a panic or a crash, never a write past the length it
//! was given), the live surfaces' positions and bodies stay finite, and a floater call that
//! fails changes nothing (the surface's snapshot bytes stay the same).
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

/// A floater id: one a surface returned (maybe removed since), or any number.
#[derive(Debug, Arbitrary)]
enum Id {
    Known(u8),
    MadeUp(u64),
}

/// A floating body's fields, as raw as C can pass them.
#[derive(Debug, Arbitrary)]
struct Body {
    shape: i32,
    /// radius, half extents, mass, drag
    size: [f32; 6],
    position: [f32; 3],
    velocity: [f32; 3],
    push: [f32; 3],
    water_force: [f32; 3],
    orientation: [f32; 4],
    angular_velocity: [f32; 3],
    /// Start from `sw_floater_sphere` / `sw_floater_box` with small sane values instead.
    sane: Option<(bool, u8, [u8; 3])>,
}

impl Body {
    fn floater(&self) -> SwFloater {
        if let Some((sphere, size, [x, y, z])) = self.sane {
            let size = 0.25 + size as f32 / 32.0;
            let at = [x as f32 / 6.0, y as f32 / 64.0 - 2.0, z as f32 / 6.0];
            let mass = size * size;
            return if sphere {
                sw_floater_sphere(size, mass, at[0], at[1], at[2])
            } else {
                sw_floater_box(size, 0.5 * size, 1.5 * size, mass, at[0], at[1], at[2])
            };
        }
        let [radius, hx, hy, hz, mass, drag] = self.size;
        SwFloater {
            struct_size: size_of::<SwFloater>() as u32,
            shape: self.shape,
            radius,
            half_extents: [hx, hy, hz],
            mass,
            drag,
            position: self.position,
            velocity: self.velocity,
            push: self.push,
            water_force: self.water_force,
            orientation: self.orientation,
            angular_velocity: self.angular_velocity,
            ..SwFloater::default()
        }
    }
}

#[derive(Debug, Arbitrary)]
enum Call {
    Create {
        cols: u8,
        rows: u8,
        floats: [f32; 10],
        boundary: i32,
        absorbing_width: u32,
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
    AddFloater(Handle, Body),
    RemoveFloater(Handle, Id),
    GetFloater(Handle, Id),
    SetFloater(Handle, Id, Body),
    PushFloater(Handle, Id, [f32; 3]),
    FloaterIds(Handle, u8),
    Buoyancy(Handle, [f32; 2]),
    /// A body added to a surface, then calls on its id: reaches the calls that take an id
    /// with a live one far more often than separate calls do.
    Floating(Handle, Body, Vec<Op>),
}

#[derive(Debug, Arbitrary)]
enum Op {
    Get,
    Set(Body),
    Push([f32; 3]),
    Step(u8),
    Remove,
}

/// Most bodies the target puts on one surface, so that long frames stay fast.
const MAX_BODIES: usize = 4;

/// The surface's snapshot bytes (empty for a handle that is not live).
fn state(s: *mut SwSurface) -> Vec<u8> {
    let mut size = 0;
    // SAFETY: valid out-pointers and a buffer of the length passed.
    unsafe {
        if sw_surface_save(s, null_mut(), 0, &mut size) != SW_OK {
            return Vec::new();
        }
        let mut bytes = vec![0u8; size];
        assert_eq!(
            sw_surface_save(s, bytes.as_mut_ptr(), size, &mut size),
            SW_OK
        );
        bytes
    }
}

/// Runs a floater call on `s`: a failure must leave the whole state as it was.
fn unchanged_unless_ok(s: *mut SwSurface, call: impl FnOnce() -> SwStatus) -> SwStatus {
    let before = state(s);
    let status = call();
    if status != SW_OK {
        assert!(
            state(s) == before,
            "a failing call ({status}) changed the surface"
        );
    }
    status
}

/// Adds `body` to `s` (unless it has `MAX_BODIES` already) and returns its id if that
/// worked; `ids` collects every id with its surface.
fn add(s: *mut SwSurface, body: &Body, ids: &mut Vec<(*mut SwSurface, u64)>) -> Option<u64> {
    if floater_count(s) >= MAX_BODIES {
        return None;
    }
    let f = body.floater();
    let mut id = u64::MAX;
    // SAFETY: valid pointers; the handle may be anything.
    let status = unchanged_unless_ok(s, || unsafe { sw_surface_add_floater(s, &f, &mut id) });
    if status != SW_OK {
        assert_eq!(id, u64::MAX);
        return None;
    }
    // Ids are never reused: each is above every earlier one of its surface.
    let mut earlier = ids.iter().filter(|(on, _)| *on == s);
    assert!(earlier.all(|&(_, e)| e < id), "id {id} reused");
    ids.push((s, id));
    let mut back = SwFloater::default();
    // SAFETY: a valid out-pointer.
    assert_eq!(unsafe { sw_surface_floater(s, id, &mut back) }, SW_OK);
    assert_eq!(back.water_force, [0.0; 3]);
    assert_eq!((back.mass, back.position), (f.mass, f.position));
    Some(id)
}

fn remove(s: *mut SwSurface, id: u64) {
    if unchanged_unless_ok(s, || sw_surface_remove_floater(s, id)) == SW_OK {
        let mut back = SwFloater::default();
        // SAFETY: a valid out-pointer.
        let status = unsafe { sw_surface_floater(s, id, &mut back) };
        assert_eq!(status, SW_ERROR_NO_SUCH_FLOATER);
    }
}

fn get(s: *mut SwSurface, id: u64) {
    let mut back = SwFloater::default();
    // SAFETY: a valid out-pointer.
    if unsafe { sw_surface_floater(s, id, &mut back) } == SW_OK {
        assert!(finite(&back), "{back:?}");
    }
}

fn set(s: *mut SwSurface, id: u64, body: &Body) {
    let f = body.floater();
    let mut before = SwFloater::default();
    // SAFETY (both): valid pointers; the handle and id may be anything.
    let had = unsafe { sw_surface_floater(s, id, &mut before) } == SW_OK;
    if unchanged_unless_ok(s, || unsafe { sw_surface_set_floater(s, id, &f) }) == SW_OK {
        assert!(had);
        let mut back = SwFloater::default();
        // SAFETY: a valid out-pointer.
        assert_eq!(unsafe { sw_surface_floater(s, id, &mut back) }, SW_OK);
        // The water force is output only: it keeps its value.
        assert_eq!(back.water_force, before.water_force);
        assert_eq!((back.velocity, back.push), (f.velocity, f.push));
    }
}

fn push(s: *mut SwSurface, id: u64, [fx, fy, fz]: [f32; 3]) {
    unchanged_unless_ok(s, || sw_surface_push_floater(s, id, fx, fy, fz));
}

fn floater_count(s: *mut SwSurface) -> usize {
    let mut n = 0;
    // SAFETY: a valid out-pointer.
    if unsafe { sw_surface_floater_count(s, &mut n) } == SW_OK {
        n
    } else {
        0
    }
}

fn finite(f: &SwFloater) -> bool {
    [f.radius, f.mass, f.drag]
        .iter()
        .chain(&f.half_extents)
        .chain(&f.position)
        .chain(&f.velocity)
        .chain(&f.push)
        .chain(&f.water_force)
        .all(|v| v.is_finite())
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
    // Every id a surface returned, removed or not, with its surface.
    let mut ids: Vec<(*mut SwSurface, u64)> = Vec::new();
    let id_of = |id: &Id, ids: &[(*mut SwSurface, u64)]| match id {
        Id::Known(i) if !ids.is_empty() => ids[*i as usize % ids.len()].1,
        Id::Known(i) => *i as u64,
        Id::MadeUp(v) => *v,
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
                    absorbing_width,
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
                    // Mostly widths that fit some grid, sometimes any number.
                    p.absorbing_width = if absorbing_width >> 31 == 1 {
                        *absorbing_width
                    } else {
                        absorbing_width % 24
                    };
                    let mut s = null_mut();
                    if sw_surface_create(&p, &mut s) == SW_OK {
                        // The parameters read back as given (the width is 32 unless the
                        // boundary is absorbing), and build the same surface again.
                        let mut back = sw_params_default();
                        assert_eq!(sw_surface_params(s, &mut back), SW_OK);
                        if p.boundary != SW_BOUNDARY_ABSORBING {
                            p.absorbing_width = 32;
                        }
                        assert_eq!(format!("{back:?}"), format!("{p:?}"));
                        let mut again = null_mut();
                        assert_eq!(sw_surface_create(&back, &mut again), SW_OK);
                        let mut back_again = sw_params_default();
                        assert_eq!(sw_surface_params(again, &mut back_again), SW_OK);
                        assert_eq!(format!("{back_again:?}"), format!("{p:?}"));
                        sw_surface_destroy(again);
                        live.push(s);
                    } else {
                        assert!(s.is_null());
                        // Defaults on a small grid always work, with any boundary (an
                        // absorbing frame as wide as the grid leaves room for).
                        let mut p = sw_params_default();
                        p.cols = 2 + *cols as u32 % 38;
                        p.rows = 2 + *rows as u32 % 38;
                        let room = (p.cols.min(p.rows) - 2) / 2;
                        match *boundary {
                            SW_BOUNDARY_FREE => p.boundary = SW_BOUNDARY_FREE,
                            SW_BOUNDARY_ABSORBING if room >= 1 => {
                                p.boundary = SW_BOUNDARY_ABSORBING;
                                p.absorbing_width = 1 + absorbing_width % room;
                            }
                            _ => {}
                        }
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
                    sw_surface_drop_at(pick(h, &live, &dead), *x, *z, *hgt, *r);
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
                Call::AddFloater(h, body) => {
                    add(pick(h, &live, &dead), body, &mut ids);
                }
                Call::RemoveFloater(h, id) => remove(pick(h, &live, &dead), id_of(id, &ids)),
                Call::GetFloater(h, id) => get(pick(h, &live, &dead), id_of(id, &ids)),
                Call::SetFloater(h, id, body) => set(pick(h, &live, &dead), id_of(id, &ids), body),
                Call::PushFloater(h, id, force) => {
                    push(pick(h, &live, &dead), id_of(id, &ids), *force)
                }
                Call::Floating(h, body, ops) => {
                    let s = pick(h, &live, &dead);
                    let Some(id) = add(s, body, &mut ids) else {
                        continue;
                    };
                    for op in ops.iter().take(8) {
                        match op {
                            Op::Get => get(s, id),
                            Op::Set(body) => set(s, id, body),
                            Op::Push(force) => push(s, id, *force),
                            Op::Step(n) => {
                                sw_surface_step(s, *n as u32 % 8);
                            }
                            Op::Remove => remove(s, id),
                        }
                    }
                }
                Call::FloaterIds(h, len) => {
                    let s = pick(h, &live, &dead);
                    let mut count = usize::MAX;
                    let mut b = Buffer::new(*len as usize % 8, 0u64, u64::MAX - 1);
                    let status = sw_surface_floater_ids(s, b.ptr(), b.len, &mut count);
                    if status == SW_OK {
                        assert_eq!(count, floater_count(s));
                        // In the order they were added: increasing.
                        assert!(b.data[..count].windows(2).all(|w| w[0] < w[1]));
                    } else if status == SW_ERROR_BUFFER_TOO_SMALL {
                        assert!(count > b.len);
                    }
                    b.check();
                }
                Call::Buoyancy(h, [gravity, density]) => {
                    let s = pick(h, &live, &dead);
                    let b = SwBuoyancy {
                        gravity: *gravity,
                        density: *density,
                        ..sw_buoyancy_default()
                    };
                    if unchanged_unless_ok(s, || sw_surface_set_buoyancy(s, &b)) == SW_OK {
                        let mut back = SwBuoyancy::default();
                        assert_eq!(sw_surface_buoyancy(s, &mut back), SW_OK);
                        assert_eq!(back, b);
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
