//! Surface handles. A `SwSurface *` is a key into a registry of live surfaces, never
//! dereferenced: a NULL, stale (destroyed) or made-up handle is an error status, not a
//! crash. Each surface sits behind its own lock, so overlapping calls on one surface
//! (from two threads, or from a job system's task) get `SW_ERROR_BUSY` instead of racing.

use crate::status::{
    guard, Failure, Outcome, SwStatus, SW_ERROR_BUSY, SW_ERROR_INTERNAL, SW_ERROR_INVALID_HANDLE,
};
use springwater::mesh::{LodMesh, LodParams, Normals};
use springwater::Surface;
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, RwLock, TryLockError};

/// A water surface (opaque). Create it with `sw_surface_create` or `sw_surface_load`,
/// free it with `sw_surface_destroy`.
pub struct SwSurface {
    _opaque: [u8; 0],
}

/// What a handle owns: the surface and the render-side buffers kept between frames.
pub(crate) struct Water {
    pub surface: Surface,
    pub lod: LodMesh,
    pub normals: Normals,
    pub queries: Queries,
    /// The last save (`sw_surface_save`), its capacity kept between calls.
    pub save: Vec<u8>,
}

/// The batched queries' buffers, kept between calls.
#[derive(Default)]
pub(crate) struct Queries {
    pub points: Vec<[f32; 2]>,
    pub heights: Vec<f32>,
    pub normals: Vec<glam::Vec3>,
    pub velocities: Vec<glam::Vec3>,
    pub each: Vec<Option<springwater::WaterSample>>,
}

impl Water {
    /// A new surface's handle contents: the default LOD parameters, empty buffers.
    pub(crate) fn new(surface: Surface) -> Self {
        Self {
            surface,
            lod: LodMesh::new(LodParams::default()).expect("the default LOD parameters are valid"),
            normals: Normals::new(),
            queries: Default::default(),
            save: Vec::new(),
        }
    }
}

/// The live handles of one kind: each key is a handle's value, the entry what it owns.
pub(crate) struct Registry<T> {
    map: RwLock<Option<HashMap<usize, Arc<T>>>>,
}

/// Handles of every kind count up from one counter and are never reused: a destroyed
/// handle stays invalid, and a handle of one kind is never a live handle of another.
static NEXT: AtomicUsize = AtomicUsize::new(1);

impl<T> Registry<T> {
    pub(crate) const fn new() -> Self {
        Self {
            map: RwLock::new(None),
        }
    }

    /// Registers `value` and returns its new handle's value.
    pub(crate) fn insert(&self, value: T) -> usize {
        let key = NEXT.fetch_add(1, Ordering::Relaxed);
        let mut map = self.map.write().unwrap_or_else(|e| e.into_inner());
        map.get_or_insert_with(HashMap::new)
            .insert(key, Arc::new(value));
        key
    }

    /// Removes the handle `key`; whether it was live. A call still using it finishes
    /// first (it holds its own reference).
    pub(crate) fn remove(&self, key: usize) -> bool {
        let mut map = self.map.write().unwrap_or_else(|e| e.into_inner());
        map.as_mut().and_then(|m| m.remove(&key)).is_some()
    }

    /// What the handle `key` owns, if it is live.
    pub(crate) fn get(&self, key: usize) -> Option<Arc<T>> {
        let map = self.map.read().unwrap_or_else(|e| e.into_inner());
        map.as_ref().and_then(|m| m.get(&key).cloned())
    }
}

static SURFACES: Registry<Mutex<Water>> = Registry::new();

/// Registers `water` and returns its new handle.
pub(crate) fn insert(water: Water) -> *mut SwSurface {
    SURFACES.insert(Mutex::new(water)) as *mut SwSurface
}

/// Removes `handle`; whether it was live. A call still running on it finishes first.
pub(crate) fn remove(handle: *const SwSurface) -> bool {
    SURFACES.remove(handle as usize)
}

/// The body of a call that only needs the surface: `f` on it, in the guard.
pub(crate) fn call(handle: *const SwSurface, f: impl FnOnce(&mut Water) -> Outcome) -> SwStatus {
    guard(|| with(handle, f))
}

/// Runs `f` on the surface behind `handle`, holding its lock.
pub(crate) fn with<T>(
    handle: *const SwSurface,
    f: impl FnOnce(&mut Water) -> Outcome<T>,
) -> Outcome<T> {
    if handle.is_null() {
        return Err(Failure::null("surface"));
    }
    let Some(entry) = SURFACES.get(handle as usize) else {
        return Err(Failure::new(
            SW_ERROR_INVALID_HANDLE,
            format!(
                "surface handle {handle:p} is not a live surface (never created, or destroyed)"
            ),
        ));
    };
    let mut water = match entry.try_lock() {
        Ok(water) => water,
        Err(TryLockError::WouldBlock) => {
            return Err(Failure::new(
                SW_ERROR_BUSY,
                "another call on this surface is in progress; calls on one surface must not \
                 overlap",
            ))
        }
        Err(TryLockError::Poisoned(_)) => {
            return Err(Failure::new(
                SW_ERROR_INTERNAL,
                "this surface failed internally in an earlier call; destroy it",
            ))
        }
    };
    f(&mut water)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::status::SW_OK;
    use springwater::Params;

    fn water() -> Water {
        Water::new(Surface::new(Params::with_size(8, 8)).unwrap())
    }

    #[test]
    fn a_surface_that_panicked_refuses_every_later_call_until_destroyed() {
        let h = insert(water());
        assert_eq!(guard(|| with(h, |_| Ok(()))), SW_OK);
        assert_eq!(guard(|| with(h, |_| panic!("inside"))), SW_ERROR_INTERNAL);
        assert_eq!(guard(|| with(h, |_| Ok(()))), SW_ERROR_INTERNAL);
        assert!(remove(h));
        assert_eq!(guard(|| with(h, |_| Ok(()))), SW_ERROR_INVALID_HANDLE);
        assert!(!remove(h));
    }

    #[test]
    fn an_overlapping_call_on_one_surface_is_busy_and_others_are_not() {
        let (a, b) = (insert(water()), insert(water()));
        let inner = guard(|| {
            with(a, |_| {
                assert_eq!(guard(|| with(a, |_| Ok(()))), SW_ERROR_BUSY);
                assert_eq!(guard(|| with(b, |_| Ok(()))), SW_OK);
                Ok(())
            })
        });
        assert_eq!(inner, SW_OK);
        assert!(remove(a) && remove(b));
    }

    #[test]
    fn handles_are_never_reused() {
        let a = insert(water());
        assert!(remove(a));
        let b = insert(water());
        assert_ne!(a, b);
        assert_eq!(guard(|| with(a, |_| Ok(()))), SW_ERROR_INVALID_HANDLE);
        assert!(remove(b));
    }
}
