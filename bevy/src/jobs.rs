//! Stepping on Bevy's [`ComputeTaskPool`]: a [`springwater::JobSystem`] for the engine's
//! colour batches and the render-side stages' parts.

use bevy::tasks::ComputeTaskPool;
use springwater::JobSystem;

/// Runs springwater's colour batches and the render-side stages (normals, refraction, the
/// mesh's attributes) on Bevy's [`ComputeTaskPool`], the pool that Bevy's own parallel
/// queries and multi-threaded executor use, so the water does not start a second set of
/// worker threads (rayon's) that would compete with Bevy's for the cores.
///
/// The batch runs on the pool's threads and on the thread that asked for it. Bevy's
/// default [`TaskPoolPlugin`](bevy::app::TaskPoolPlugin) gives the compute pool the cores
/// left after one IO and one async-compute thread: on a machine of two cores, one thread,
/// so a water stepped from a system of the multi-threaded executor (itself on that
/// thread) steps on one core. Give the compute pool more threads
/// (`TaskPoolOptions::compute`'s `min_threads`) to step on more.
///
/// The plugin gives every surface one of these unless
/// [`SpringwaterPlugin::with_task_pool`](crate::SpringwaterPlugin::with_task_pool) turns
/// it off. Results are bitwise identical to any other job system or thread count
/// (springwater's guarantee; the crate's tests check it).
///
/// If the pool has not been created yet (no `TaskPoolPlugin`), the batch runs on the
/// calling thread, in order.
#[derive(Debug, Clone, Copy, Default)]
pub struct TaskPoolJobs;

impl JobSystem for TaskPoolJobs {
    /// The pool's threads, and the calling thread when it is not one of them (a scope's
    /// caller runs the scope's tasks too).
    fn workers(&self) -> usize {
        let Some(pool) = ComputeTaskPool::try_get() else {
            return 1;
        };
        let in_pool = std::thread::current()
            .name()
            .is_some_and(|name| name.starts_with("Compute Task Pool"));
        pool.thread_num() + usize::from(!in_pool)
    }

    fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync)) {
        match ComputeTaskPool::try_get() {
            Some(pool) if count > 1 && pool.thread_num() > 0 => {
                pool.scope(|scope| {
                    for i in 0..count {
                        scope.spawn(async move { task(i) });
                    }
                });
            }
            _ => (0..count).for_each(task),
        }
    }
}
