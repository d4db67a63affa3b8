//! Stepping on Bevy's [`ComputeTaskPool`]: a [`springwater::JobSystem`] for the engine's
//! colour batches.

use bevy::tasks::ComputeTaskPool;
use springwater::JobSystem;

/// Runs springwater's colour batches on Bevy's [`ComputeTaskPool`], the pool that Bevy's
/// own parallel queries and multi-threaded executor use, so the water does not start a
/// second set of worker threads (rayon's) that would compete with Bevy's for the cores.
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
    fn workers(&self) -> usize {
        ComputeTaskPool::try_get().map_or(1, |pool| pool.thread_num().max(1))
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
