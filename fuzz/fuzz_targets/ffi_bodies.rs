//! The C ABI's body and rollback calls in any order with any arguments: hull meshes
//! (`sw_hull_create` from raw arrays, destroyed, made up), floaters (spheres, boxes, hull
//! bodies; raw fields, orientations and inertias included), poses, pushes, the forces on a
//! body another engine owns, the state hash, `sw_surface_save`, `sw_surface_restore` of
//! saved or damaged bytes, and `sw_surface_load`; handles live, destroyed, NULL or made up.
//!
//! Every call returns a status (a panic or an abort ends the run); a call that fails
//! changes nothing (the surface's snapshot bytes and state hash stay the same); after every
//! call the water and the bodies are finite, the bodies' orientations unit quaternions; a
//! saved frame restores to the hash it had when saved, and loads as a new surface with
//! that hash.

#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::Edits;
use libfuzzer_sys::fuzz_target;
use springwater_ffi::*;
use std::ptr::{null, null_mut};

#[derive(Debug, Arbitrary)]
enum Handle {
    Live,
    Destroyed,
    Null,
    MadeUp(usize),
}

#[derive(Debug, Arbitrary)]
enum HullRef {
    Made(u8),
    Null,
    MadeUp(usize),
}

#[derive(Debug, Arbitrary)]
enum Id {
    Known(u8),
    MadeUp(u64),
}

/// A floater as C passes it: raw fields, or a sane ball or box with a raw turn and spin.
#[derive(Debug, Arbitrary)]
struct Body {
    raw: Option<Raw>,
    sane: (bool, u8, [u8; 3]),
    orientation: [f32; 4],
    angular_velocity: [f32; 3],
    push_torque: [f32; 3],
    inertia: Option<(i32, [f32; 9])>,
}

#[derive(Debug, Arbitrary)]
struct Raw {
    struct_size: u32,
    shape: i32,
    /// radius, half extents, mass, drag
    size: [f32; 6],
    position: [f32; 3],
    velocity: [f32; 3],
    push: [f32; 3],
}

impl Body {
    fn floater(&self) -> SwFloater {
        let (sphere, size, [x, y, z]) = self.sane;
        let size = 0.25 + size as f32 / 64.0;
        let at = [x as f32 / 16.0, y as f32 / 64.0 - 2.0, z as f32 / 16.0];
        let mut f = if sphere {
            sw_floater_sphere(size, size * size, at[0], at[1], at[2])
        } else {
            sw_floater_box(
                size,
                0.5 * size,
                1.5 * size,
                size * size,
                at[0],
                at[1],
                at[2],
            )
        };
        if let Some(r) = &self.raw {
            let [radius, hx, hy, hz, mass, drag] = r.size;
            f.struct_size = match r.struct_size % 4 {
                0 => r.struct_size,
                1 => 80, // version 1
                _ => f.struct_size,
            };
            f.shape = r.shape;
            (f.radius, f.half_extents, f.mass, f.drag) = (radius, [hx, hy, hz], mass, drag);
            (f.position, f.velocity, f.push) = (r.position, r.velocity, r.push);
        }
        self.apply_motion(&mut f);
        f
    }

    /// Orientation, spin, torque and inertia as given (a quaternion of small integers
    /// normalised here reaches past validation more often than raw bits).
    fn apply_motion(&self, f: &mut SwFloater) {
        let q = self.orientation;
        let n2: f32 = q.iter().map(|v| v * v).sum();
        f.orientation = if n2.is_finite() && n2 > 1e-6 && q.iter().all(|v| v.fract() == 0.0) {
            q.map(|v| v / n2.sqrt())
        } else {
            q
        };
        f.angular_velocity = self.angular_velocity;
        f.push_torque = self.push_torque;
        if let Some((has, m)) = self.inertia {
            (f.has_inertia, f.inertia) = (has % 3, m);
        }
    }
}

#[derive(Debug, Arbitrary)]
enum Call {
    Hull {
        xyz: Vec<f32>,
        triangles: Vec<u32>,
        lie: Option<(u16, u16)>,
    },
    Cuboid([u8; 3]),
    DestroyHull(HullRef),
    Volume(HullRef),
    Add(Handle, Body),
    AddHull(Handle, HullRef, f32, Body, bool),
    Set(Handle, Id, Body),
    Get(Handle, Id),
    Remove(Handle, Id),
    Push(Handle, Id, [f32; 3]),
    PushAt(Handle, Id, [f32; 6]),
    Forces(Handle, Body, f32, bool),
    HullForces(Handle, HullRef, Body, f32),
    Step(Handle),
    Buoyancy(Handle, [f32; 2]),
    Hash(Handle),
    Save(Handle, u16),
    Restore(Handle, u8, Edits),
    Load(u8, Edits),
}

/// The surface's snapshot bytes and state hash (empty and 0 for a handle that is not live).
fn state(s: *mut SwSurface) -> (Vec<u8>, u64) {
    let mut size = 0;
    let mut hash = 0;
    // SAFETY: valid out-pointers and a buffer of the length passed.
    unsafe {
        if sw_surface_save(s, null_mut(), 0, &mut size) != SW_OK {
            return (Vec::new(), 0);
        }
        let mut bytes = vec![0u8; size];
        assert_eq!(
            sw_surface_save(s, bytes.as_mut_ptr(), size, &mut size),
            SW_OK
        );
        assert_eq!(sw_surface_state_hash(s, &mut hash), SW_OK);
        (bytes, hash)
    }
}

/// Runs a call: a failure must leave the surface as it was.
fn unchanged_unless_ok(s: *mut SwSurface, call: impl FnOnce() -> SwStatus) -> SwStatus {
    let before = state(s);
    let status = call();
    assert!(status <= SW_OK, "status {status}");
    if status != SW_OK {
        assert!(
            state(s) == before,
            "a failing call ({status}) changed the surface"
        );
    }
    status
}

/// The water finite, every body finite with a unit orientation.
fn check_finite(s: *mut SwSurface) {
    // SAFETY: valid out-pointers and buffers of the lengths passed.
    unsafe {
        let mut nodes = 0;
        assert_eq!(sw_surface_node_count(s, &mut nodes), SW_OK);
        let mut xyz = vec![0.0f32; 3 * nodes];
        assert_eq!(
            sw_surface_write_positions(s, xyz.as_mut_ptr(), xyz.len()),
            SW_OK
        );
        assert!(xyz.iter().all(|v| v.is_finite()), "non-finite water");
        let mut ids = [0u64; 8];
        let mut count = 0;
        assert_eq!(
            sw_surface_floater_ids(s, ids.as_mut_ptr(), 8, &mut count),
            SW_OK
        );
        for &id in &ids[..count.min(8)] {
            let mut f = SwFloater::default();
            assert_eq!(sw_surface_floater(s, id, &mut f), SW_OK);
            let fields = [f.position, f.velocity, f.angular_velocity, f.water_force];
            assert!(fields.iter().flatten().all(|v| v.is_finite()), "{f:?}");
            let n2: f32 = f.orientation.iter().map(|v| v * v).sum();
            assert!((n2 - 1.0).abs() < 1e-5, "orientation {:?}", f.orientation);
        }
    }
}

/// Most bodies on the surface, so that inputs stay fast.
const MAX_BODIES: usize = 4;

fn count(s: *mut SwSurface) -> usize {
    let mut n = 0;
    // SAFETY: a valid out-pointer.
    unsafe { sw_surface_floater_count(s, &mut n) };
    n
}

fuzz_target!(|calls: Vec<Call>| {
    let mut p = sw_params_default();
    (p.cols, p.rows, p.dt) = (12, 10, 0.2);
    let (mut live, mut dead) = (null_mut(), null_mut());
    // SAFETY (every call below): pointers are to live locals or buffers of at least the
    // length passed; handles may be anything, which is what is being tested.
    unsafe {
        assert_eq!(sw_surface_create(&p, &mut live), SW_OK);
        assert_eq!(sw_surface_create(&p, &mut dead), SW_OK);
        sw_surface_destroy(dead);
    }
    let pick = |h: &Handle| match h {
        Handle::Live => live,
        Handle::Destroyed => dead,
        Handle::Null => null_mut(),
        Handle::MadeUp(v) => *v as *mut SwSurface,
    };
    let mut hulls: Vec<*mut SwHull> = Vec::new();
    let hull = |h: &HullRef, hulls: &[*mut SwHull]| match h {
        HullRef::Made(k) if !hulls.is_empty() => hulls[*k as usize % hulls.len()],
        HullRef::Made(_) | HullRef::Null => null_mut(),
        HullRef::MadeUp(v) => *v as *mut SwHull,
    };
    let mut ids: Vec<u64> = Vec::new();
    let id_of = |id: &Id, ids: &[u64]| match id {
        Id::Known(k) if !ids.is_empty() => ids[*k as usize % ids.len()],
        Id::Known(k) => *k as u64,
        Id::MadeUp(v) => *v,
    };
    // Saved frames: bytes and the hash they had.
    let mut frames: Vec<(Vec<u8>, u64)> = Vec::new();
    for call in calls.iter().take(48) {
        unsafe {
            match call {
                Call::Hull {
                    xyz,
                    triangles,
                    lie,
                } => {
                    // Pointers with their true counts, or NULL with any count.
                    let (v, t) = (
                        &xyz[..xyz.len().min(96) / 3 * 3],
                        &triangles[..triangles.len().min(96) / 3 * 3],
                    );
                    let (vp, vn, tp, tn) = match lie {
                        None => (v.as_ptr(), v.len() / 3, t.as_ptr(), t.len() / 3),
                        Some((a, b)) => (null(), *a as usize, null(), *b as usize),
                    };
                    let mut h = null_mut();
                    let status = sw_hull_create(vp, vn, tp, tn, &mut h);
                    assert!(status <= SW_OK);
                    if status == SW_OK {
                        hulls.push(h);
                    } else {
                        assert!(h.is_null());
                    }
                }
                Call::Cuboid(e) => {
                    // A box's 8 corners and 12 triangles, as a game would pass them.
                    let e = e.map(|v| 0.1 + v as f32 / 64.0);
                    let mut xyz = Vec::new();
                    for i in 0..8 {
                        let pick = |bit: i32, v: f32| if i & bit == 0 { -v } else { v };
                        xyz.extend([pick(1, e[0]), pick(2, e[1]), pick(4, e[2])]);
                    }
                    let quads = [
                        [0, 4, 6, 2],
                        [1, 3, 7, 5],
                        [0, 1, 5, 4],
                        [2, 6, 7, 3],
                        [0, 2, 3, 1],
                        [4, 5, 7, 6],
                    ];
                    let t: Vec<u32> = quads
                        .iter()
                        .flat_map(|&[a, b, c, d]| [a, b, c, a, c, d])
                        .collect();
                    let mut h = null_mut();
                    assert_eq!(
                        sw_hull_create(xyz.as_ptr(), 8, t.as_ptr(), 12, &mut h),
                        SW_OK
                    );
                    hulls.push(h);
                }
                Call::DestroyHull(h) => sw_hull_destroy(hull(h, &hulls)),
                Call::Volume(h) => {
                    let mut v = f32::NAN;
                    if sw_hull_volume(hull(h, &hulls), &mut v) == SW_OK {
                        assert!(v.is_finite() && v > 0.0);
                    }
                }
                Call::Add(h, b) => {
                    let s = pick(h);
                    if count(s) >= MAX_BODIES {
                        continue;
                    }
                    let f = b.floater();
                    let mut id = u64::MAX;
                    if unchanged_unless_ok(s, || sw_surface_add_floater(s, &f, &mut id)) == SW_OK {
                        ids.push(id);
                    }
                }
                Call::AddHull(h, hr, mass, b, from_hull) => {
                    let s = pick(h);
                    if count(s) >= MAX_BODIES {
                        continue;
                    }
                    let hp = hull(hr, &hulls);
                    let mut f = b.floater();
                    if *from_hull {
                        // Start from the hull's own body, then turn and spin it.
                        let at = f.position;
                        if sw_floater_hull(hp, *mass, at[0], at[1], at[2], &mut f) == SW_OK {
                            b.apply_motion(&mut f);
                        }
                    }
                    let mut id = u64::MAX;
                    let status =
                        unchanged_unless_ok(s, || sw_surface_add_hull_floater(s, hp, &f, &mut id));
                    if status == SW_OK {
                        ids.push(id);
                    }
                }
                Call::Set(h, id, b) => {
                    let (s, f) = (pick(h), b.floater());
                    unchanged_unless_ok(s, || sw_surface_set_floater(s, id_of(id, &ids), &f));
                }
                Call::Get(h, id) => {
                    let mut f = SwFloater::default();
                    let _ = sw_surface_floater(pick(h), id_of(id, &ids), &mut f);
                }
                Call::Remove(h, id) => {
                    let s = pick(h);
                    unchanged_unless_ok(s, || sw_surface_remove_floater(s, id_of(id, &ids)));
                }
                Call::Push(h, id, [x, y, z]) => {
                    let s = pick(h);
                    unchanged_unless_ok(s, || {
                        sw_surface_push_floater(s, id_of(id, &ids), *x, *y, *z)
                    });
                }
                Call::PushAt(h, id, [fx, fy, fz, x, y, z]) => {
                    let s = pick(h);
                    unchanged_unless_ok(s, || {
                        sw_surface_push_floater_at(s, id_of(id, &ids), *fx, *fy, *fz, *x, *y, *z)
                    });
                }
                Call::Forces(h, b, seconds, sized) => {
                    let (s, f) = (pick(h), b.floater());
                    let mut out = sw_body_forces_default();
                    if !sized {
                        out.struct_size = 7;
                    }
                    let status = unchanged_unless_ok(s, || {
                        sw_surface_body_forces(s, &f, *seconds, &mut out)
                    });
                    if status == SW_OK {
                        assert!(out.force.iter().chain(&out.torque).all(|v| v.is_finite()));
                    }
                }
                Call::HullForces(h, hr, b, seconds) => {
                    let (s, hp) = (pick(h), hull(hr, &hulls));
                    let mut f = b.floater();
                    f.shape = SW_SHAPE_HULL;
                    let mut out = sw_body_forces_default();
                    unchanged_unless_ok(s, || {
                        sw_surface_hull_body_forces(s, hp, &f, *seconds, &mut out)
                    });
                }
                Call::Step(h) => {
                    let s = pick(h);
                    unchanged_unless_ok(s, || sw_surface_step(s, 1));
                }
                Call::Buoyancy(h, [g, d]) => {
                    let s = pick(h);
                    let mut b = sw_buoyancy_default();
                    (b.gravity, b.density) = (*g, *d);
                    unchanged_unless_ok(s, || sw_surface_set_buoyancy(s, &b));
                }
                Call::Hash(h) => {
                    let mut out = 0;
                    let _ = sw_surface_state_hash(pick(h), &mut out);
                }
                Call::Save(h, len) => {
                    let s = pick(h);
                    let mut buf = vec![0u8; *len as usize];
                    let mut size = 0;
                    let status = unchanged_unless_ok(s, || {
                        sw_surface_save(s, buf.as_mut_ptr(), buf.len(), &mut size)
                    });
                    if status == SW_OK {
                        buf.truncate(size);
                        frames.push((buf, state(s).1));
                    }
                }
                Call::Restore(h, k, edits) => {
                    let Some((frame, hash)) = frames.get(*k as usize % frames.len().max(1)) else {
                        continue;
                    };
                    let s = pick(h);
                    let mut bytes = frame.clone();
                    edits.apply(&mut bytes);
                    let status = unchanged_unless_ok(s, || {
                        sw_surface_restore(s, bytes.as_ptr(), bytes.len())
                    });
                    if status == SW_OK && bytes == *frame {
                        assert_eq!(state(s).1, *hash, "a restored frame hashes differently");
                    }
                }
                Call::Load(k, edits) => {
                    let Some((frame, hash)) = frames.get(*k as usize % frames.len().max(1)) else {
                        continue;
                    };
                    let mut bytes = frame.clone();
                    edits.apply(&mut bytes);
                    let mut out = null_mut();
                    let status = sw_surface_load(bytes.as_ptr(), bytes.len(), &mut out);
                    assert!(status <= SW_OK);
                    if status == SW_OK {
                        if bytes == *frame {
                            assert_eq!(state(out).1, *hash, "a loaded frame hashes differently");
                        }
                        check_finite(out);
                        sw_surface_destroy(out);
                    } else {
                        assert!(out.is_null());
                    }
                }
            }
        }
        check_finite(live);
    }
    sw_surface_destroy(live);
    for h in hulls {
        sw_hull_destroy(h);
    }
});
