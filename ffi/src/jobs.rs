//! The host's job system from C: Box2D-style `enqueue_task` / `finish_task` callbacks
//! adapted to [`springwater::JobSystem`].

use crate::handle::{self, SwSurface};
use crate::ptr::{input, Input};
use crate::status::{guard, Failure, SwStatus};
use std::ffi::c_void;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Runs items `start` to `end − 1` of a task. `task_context` is the pointer the library
/// passed to `enqueue_task`; pass it back unchanged.
pub type SwTaskFn = Option<unsafe extern "C" fn(start: u32, end: u32, task_context: *mut c_void)>;

/// Starts running `task` over items `0` to `item_count − 1`, split into ranges of at least
/// `min_range` items, on the host's workers (the calling thread may take part). Returns a
/// handle that `finish_task` waits on, or NULL if the task already ran to completion
/// inside this call.
pub type SwEnqueueTaskFn = Option<
    unsafe extern "C" fn(
        task: SwTaskFn,
        item_count: u32,
        min_range: u32,
        task_context: *mut c_void,
        user_context: *mut c_void,
    ) -> *mut c_void,
>;

/// Waits until the task `enqueue_task` returned as `user_task` has run every item.
pub type SwFinishTaskFn =
    Option<unsafe extern "C" fn(user_task: *mut c_void, user_context: *mut c_void)>;

/// A host's job system (the shape of Box2D's `enqueueTask` / `finishTask`).
///
/// Each engine pass calls `enqueue_task` twice (one task per colour of bands; each item is
/// a band of rows, independent of the others) and `finish_task` after each, from the
/// thread that called the stepping function, never from inside a task. The normals,
/// refraction and vertex-buffer functions call them once each, from the thread that
/// called them (which may be one of the host's workers, if the host calls from a job:
/// `finish_task` must then be able to wait there). The results are bitwise the same as on
/// the built-in pool. A job system that returns without running every item makes a step
/// fail with `SW_ERROR_JOB_SYSTEM`, changing nothing; the other functions run the items
/// it skipped themselves, on the calling thread. `finish_task` must not return before
/// every item it was given has returned.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct SwJobSystem {
    /// `sizeof(SwJobSystem)`, set by `sw_job_system_default()`: `sw_surface_set_job_system`
    /// refuses any other value (a struct not started from it, or built with a header of
    /// another version than the library's).
    pub struct_size: u32,
    /// Workers that run items at once (1 to 4096): the engine cuts about four bands per
    /// worker.
    pub worker_count: u32,
    /// Starts a task; must not be NULL.
    pub enqueue_task: SwEnqueueTaskFn,
    /// Waits for a task; must not be NULL.
    pub finish_task: SwFinishTaskFn,
    /// Passed to both callbacks unchanged.
    pub user_context: *mut c_void,
}

impl Input for SwJobSystem {
    const MAKER: &'static str = "sw_job_system_default()";
}

const _: () = assert!(std::mem::offset_of!(SwJobSystem, struct_size) == 0);

/// An empty job system with its size set: fill in `worker_count`, the two callbacks and
/// `user_context`, then hand it to `sw_surface_set_job_system`.
#[no_mangle]
pub extern "C" fn sw_job_system_default() -> SwJobSystem {
    SwJobSystem {
        struct_size: size_of::<SwJobSystem>() as u32,
        worker_count: 1,
        enqueue_task: None,
        finish_task: None,
        user_context: std::ptr::null_mut(),
    }
}

/// A validated [`SwJobSystem`].
struct HostJobs {
    workers: usize,
    enqueue: unsafe extern "C" fn(SwTaskFn, u32, u32, *mut c_void, *mut c_void) -> *mut c_void,
    finish: unsafe extern "C" fn(*mut c_void, *mut c_void),
    user: *mut c_void,
}

// SAFETY: the host promises, by installing the job system, that its callbacks may be
// called from any thread that steps the surface, with this user context.
unsafe impl Send for HostJobs {}
// SAFETY: as above.
unsafe impl Sync for HostJobs {}

/// What `task_context` points to while a task runs.
struct TaskContext<'a> {
    task: &'a (dyn Fn(usize) + Sync),
    count: u32,
    panicked: AtomicBool,
}

unsafe extern "C" fn run_items(start: u32, end: u32, task_context: *mut c_void) {
    if task_context.is_null() {
        return;
    }
    // SAFETY: `task_context` is the `TaskContext` that `HostJobs::run` passed to
    // `enqueue_task`, alive until `finish_task` returns (the host calls tasks only then).
    let ctx = unsafe { &*task_context.cast::<TaskContext>() };
    let ran = catch_unwind(AssertUnwindSafe(|| {
        for i in start..end.min(ctx.count) {
            (ctx.task)(i as usize);
        }
    }));
    if ran.is_err() {
        ctx.panicked.store(true, Ordering::Relaxed);
    }
}

impl springwater::JobSystem for HostJobs {
    fn workers(&self) -> usize {
        self.workers
    }

    fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync)) {
        let ctx = TaskContext {
            task,
            count: u32::try_from(count).unwrap_or(u32::MAX),
            panicked: AtomicBool::new(false),
        };
        let context = (&ctx as *const TaskContext).cast_mut().cast::<c_void>();
        // SAFETY: the host's callbacks, validated non-NULL; `ctx` outlives the task, which
        // has finished when `finish_task` returns (or when `enqueue_task` returns NULL).
        unsafe {
            let user_task = (self.enqueue)(Some(run_items), ctx.count, 1, context, self.user);
            if !user_task.is_null() {
                (self.finish)(user_task, self.user);
            }
        }
        assert!(
            !ctx.panicked.load(Ordering::Relaxed),
            "a band task panicked on a job system worker"
        );
    }
}

/// Runs the surface's steps and its normals, refraction and vertex buffers on the host's job
/// system (`jobs`), or on the library's built-in thread pool again when `jobs` is NULL. The
/// job system is copied; its `user_context` must stay valid until the surface is destroyed
/// or another job system is set.
///
/// # Safety
///
/// `jobs` is NULL or points to a valid `SwJobSystem` whose callbacks behave as documented.
#[no_mangle]
pub unsafe extern "C" fn sw_surface_set_job_system(
    surface: *mut SwSurface,
    jobs: *const SwJobSystem,
) -> SwStatus {
    guard(|| {
        let host = if jobs.is_null() {
            None
        } else {
            let jobs = input(jobs, "jobs")?;
            let (Some(enqueue), Some(finish)) = (jobs.enqueue_task, jobs.finish_task) else {
                return Err(Failure::null("enqueue_task or finish_task"));
            };
            if !(1..=4096).contains(&jobs.worker_count) {
                return Err(Failure::invalid(format!(
                    "worker_count = {} is invalid: use 1 to 4096",
                    jobs.worker_count
                )));
            }
            let host: Arc<dyn springwater::JobSystem> = Arc::new(HostJobs {
                workers: jobs.worker_count as usize,
                enqueue,
                finish,
                user: jobs.user_context,
            });
            Some(host)
        };
        handle::with(surface, |w| {
            w.surface.set_job_system(host);
            Ok(())
        })
    })
}
