//! Where the engine's colour batches run: rayon's pool, or a host's own job system.
//!
//! A step runs two colours one after the other; within a colour every band is an
//! independent task (bands of one colour touch no common node, see `src/springs.rs`). A
//! [`JobSystem`] is anything that can run such a batch of tasks and wait for it: a game
//! engine's worker threads, Bevy's task pools, a C engine's job scheduler through
//! `springwater-ffi`. The engine calls [`JobSystem::run`] twice per pass, from the thread
//! that stepped the surface, and never from inside a task, so a job system that cannot
//! wait from a worker thread works too.
//!
//! The bits do not depend on where the tasks run: every band computes the same values
//! whichever thread runs it and in whichever order, so a host's job system, rayon's pool
//! and a single thread give the same state.

use std::sync::Arc;

/// A host's job system that runs the engine's colour batches on its own threads.
///
/// ```
/// use std::sync::Arc;
/// use springwater::{JobSystem, Params, Surface};
///
/// /// A job system that runs every task on the calling thread, in order.
/// struct Inline;
///
/// impl JobSystem for Inline {
///     fn workers(&self) -> usize {
///         1
///     }
///     fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync)) {
///         (0..count).for_each(task);
///     }
/// }
///
/// let mut water = Surface::new(Params::with_size(64, 64))?;
/// water.set_job_system(Some(Arc::new(Inline)));
/// water.drop_at(32.0, 32.0, 1.0, 3.0)?;
/// water.advance(1.0 / 60.0)?;
/// # Ok::<(), springwater::Error>(())
/// ```
pub trait JobSystem: Send + Sync {
    /// How many tasks can run at once. The engine cuts a grid into about four bands per
    /// worker (at least 8 rows each), which keeps workers busy without making tasks tiny.
    fn workers(&self) -> usize;

    /// Calls `task(i)` exactly once for every `i` in `0..count`, on any threads and in any
    /// order, and returns when every call has returned. The tasks of one call never wait
    /// for each other. A task does not panic unless the crate has a bug; if one does, the
    /// job system may propagate the panic or abort.
    fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync));
}

/// rayon's thread pool as a job system: the batch runs on the pool's threads.
#[cfg(feature = "parallel")]
impl JobSystem for rayon::ThreadPool {
    fn workers(&self) -> usize {
        self.current_num_threads()
    }

    fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync)) {
        use rayon::prelude::*;
        self.install(|| (0..count).into_par_iter().for_each(task));
    }
}

/// The host's threads a surface steps on, when not rayon's global pool.
#[derive(Clone)]
pub(crate) enum Host {
    /// A rayon pool: every stepping call runs inside it.
    #[cfg(feature = "parallel")]
    Pool(Arc<rayon::ThreadPool>),
    /// Any job system: each colour's batch goes through [`JobSystem::run`].
    Jobs(Arc<dyn JobSystem>),
}

impl std::fmt::Debug for Host {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            #[cfg(feature = "parallel")]
            Host::Pool(pool) => write!(f, "Pool({} threads)", pool.current_num_threads()),
            Host::Jobs(jobs) => write!(f, "Jobs({} workers)", jobs.workers()),
        }
    }
}

/// How the engine runs one colour's tasks.
#[derive(Clone, Copy)]
pub(crate) enum Runner<'a> {
    /// On the rayon pool the caller is in (the global one unless inside `install`), or
    /// in order on the calling thread without the `parallel` feature.
    Here,
    /// Through a host's job system.
    Jobs(&'a dyn JobSystem),
}

impl Runner<'_> {
    /// Threads that run tasks at once.
    pub fn workers(self) -> usize {
        match self {
            #[cfg(feature = "parallel")]
            Runner::Here => rayon::current_num_threads(),
            #[cfg(not(feature = "parallel"))]
            Runner::Here => 1,
            Runner::Jobs(jobs) => jobs.workers().max(1),
        }
    }

    /// Calls `task(i)` for every `i` in `0..count` and returns when all have returned.
    pub fn run(self, count: usize, task: &(dyn Fn(usize) + Sync)) {
        match (self, count) {
            (_, 0) => {}
            (_, 1) => task(0),
            #[cfg(feature = "parallel")]
            (Runner::Here, _) => {
                use rayon::prelude::*;
                (0..count).into_par_iter().for_each(task)
            }
            #[cfg(not(feature = "parallel"))]
            (Runner::Here, _) => (0..count).for_each(task),
            (Runner::Jobs(jobs), _) => jobs.run(count, task),
        }
    }
}
