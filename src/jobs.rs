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
//! The render-side stages read a surface through its [`MeshView`](crate::MeshView), which
//! carries the same host: [`for_each_part`] cuts their outputs into tasks for it, and
//! calls [`JobSystem::run`] once per stage from the thread that called the stage (never
//! from inside a task either). A stage called from inside one of the host's own jobs
//! therefore needs a job system that can wait there.
//!
//! The bits do not depend on where the tasks run: every band computes the same values
//! whichever thread runs it and in whichever order, so a host's job system, rayon's pool
//! and a single thread give the same state.

use std::ops::Range;
use std::sync::{Arc, Mutex, PoisonError};

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
        Runner::of(Some(self)).fmt(f)
    }
}

/// How a batch of independent tasks runs: one colour of the engine, or a render-side
/// stage's parts.
#[derive(Clone, Copy)]
pub(crate) enum Runner<'a> {
    /// On the rayon pool the caller is in (the global one unless inside `install`), or
    /// in order on the calling thread without the `parallel` feature.
    Here,
    /// On a host's rayon pool.
    #[cfg(feature = "parallel")]
    Pool(&'a rayon::ThreadPool),
    /// Through a host's job system.
    Jobs(&'a dyn JobSystem),
}

impl std::fmt::Debug for Runner<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Runner::Here => write!(f, "Here"),
            #[cfg(feature = "parallel")]
            Runner::Pool(pool) => write!(f, "Pool({} threads)", pool.current_num_threads()),
            Runner::Jobs(jobs) => write!(f, "Jobs({} workers)", jobs.workers()),
        }
    }
}

impl<'a> Runner<'a> {
    /// Where a surface's batches run: its host's threads, else where the caller is.
    pub fn of(host: Option<&'a Host>) -> Self {
        match host {
            #[cfg(feature = "parallel")]
            Some(Host::Pool(pool)) => Runner::Pool(pool),
            Some(Host::Jobs(jobs)) => Runner::Jobs(&**jobs),
            None => Runner::Here,
        }
    }
}

impl Runner<'_> {
    /// Threads that run tasks at once.
    pub fn workers(self) -> usize {
        match self {
            #[cfg(feature = "parallel")]
            Runner::Here => rayon::current_num_threads(),
            #[cfg(not(feature = "parallel"))]
            Runner::Here => 1,
            #[cfg(feature = "parallel")]
            Runner::Pool(pool) => pool.current_num_threads(),
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
            #[cfg(feature = "parallel")]
            (Runner::Pool(pool), _) => pool.install(|| Runner::Here.run(count, task)),
            (Runner::Jobs(jobs), _) => jobs.run(count, task),
        }
    }
}

/// Output buffers a stage's tasks each take their own nodes of: one element per node (or
/// per element of whatever `len` of [`for_each_part`] counts), split at a node into the
/// nodes before and the nodes from it on. Splitting moves the borrow, so the parts of one
/// buffer never overlap, and a task that holds a part holds it alone.
pub(crate) trait Split: Sized + Send {
    /// `(self[..at], self[at..])`, in nodes. Panics if `self` holds fewer than `at`.
    fn split(self, at: usize) -> (Self, Self);
}

impl<T: Send> Split for &mut [T] {
    fn split(self, at: usize) -> (Self, Self) {
        self.split_at_mut(at)
    }
}

/// An optional buffer: `None` splits into two `None`s.
impl<S: Split> Split for Option<S> {
    fn split(self, at: usize) -> (Self, Self) {
        self.map(|s| s.split(at)).unzip()
    }
}

/// Several buffers of one length, split at the same node.
impl<S: Split + Default, const K: usize> Split for [S; K] {
    fn split(mut self, at: usize) -> (Self, Self) {
        let head = self.each_mut().map(|s| {
            let (head, tail) = std::mem::take(s).split(at);
            *s = tail;
            head
        });
        (head, self)
    }
}

/// Runs `task(range, part)` for every unit of `0..len` cut into `unit`-long ranges (the
/// last may be shorter), `part` being `parts`' elements of `range` ([`Split`]); the units
/// are grouped into tasks at least `min_len` long run by `runner`: as many tasks as that
/// allows on rayon (whose work stealing balances them), about four per worker for a job
/// system (whose tasks may each cost a hand-over).
///
/// Every unit runs exactly once, whatever indices the runner passes: each task's part is
/// split off before the batch and kept behind a lock, and running a task first takes its
/// part out. A job system that repeats a task runs it once, one that invents indices runs
/// nothing for them, and a task a job system skipped runs on the calling thread after the
/// batch. So tasks write disjoint parts of the outputs, in safe code. That every part is
/// written when this returns rests on [`JobSystem::run`]'s contract that no call of the
/// task outlives `run`: safe Rust cannot break it (the task is borrowed for the call), a
/// C host must keep it (`finish_task` waits for every item).
pub(crate) fn for_each_part<P: Split>(
    runner: Runner<'_>,
    len: usize,
    unit: usize,
    min_len: usize,
    parts: P,
    task: &(dyn Fn(Range<usize>, P) + Sync),
) {
    let unit = unit.max(1);
    let units = len.div_ceil(unit);
    let per_worker = match runner {
        Runner::Jobs(_) => units.div_ceil(4 * runner.workers()),
        _ => 1,
    };
    let per = min_len.div_ceil(unit).max(per_worker).max(1);
    let count = units.div_ceil(per);
    // A task's nodes, with their part: its units, one after the other.
    let run = |nodes: Range<usize>, mut part: P| {
        for first in nodes.clone().step_by(unit) {
            let end = (first + unit).min(nodes.end);
            let (head, rest) = part.split(end - first);
            task(first..end, head);
            part = rest;
        }
    };
    if count <= 1 {
        run(0..len, parts);
        return;
    }
    let span = per * unit;
    let nodes = |i: usize| i * span..((i + 1) * span).min(len);
    let mut tasks = Vec::with_capacity(count);
    let mut rest = parts;
    for i in 0..count {
        let (head, tail) = rest.split(nodes(i).len());
        tasks.push(Mutex::new(Some(head)));
        rest = tail;
    }
    // Task `i`'s part, for the one call that takes it first. The lock is never held while
    // anything can panic, so it is never poisoned; taking the part regardless keeps that
    // an argument, not an assumption.
    let claim = |i: usize| -> Option<P> {
        let slot = tasks.get(i)?;
        slot.lock().unwrap_or_else(PoisonError::into_inner).take()
    };
    runner.run(count, &|i| {
        if let Some(part) = claim(i) {
            run(nodes(i), part)
        }
    });
    for i in 0..count {
        if let Some(part) = claim(i) {
            run(nodes(i), part);
        }
    }
}

/// A mutable slice that tasks running at once take disjoint parts of: which part a task
/// takes follows from its index (the engine's bands), and a claim makes sure each index
/// runs at most once, whatever the job system does, so no part is ever taken twice.
pub(crate) struct Disjoint<'a, T> {
    ptr: *mut T,
    len: usize,
    _borrow: std::marker::PhantomData<&'a mut [T]>,
}

// SAFETY: a `Disjoint` is a `&mut [T]` handed out in non-overlapping parts; sending or
// sharing it across threads is sending those parts, which needs `T: Send`.
unsafe impl<T: Send> Send for Disjoint<'_, T> {}
// SAFETY: as above; shared access only ever produces non-overlapping `&mut` parts.
unsafe impl<T: Send> Sync for Disjoint<'_, T> {}

impl<'a, T> Disjoint<'a, T> {
    pub fn new(s: &'a mut [T]) -> Self {
        Self {
            ptr: s.as_mut_ptr(),
            len: s.len(),
            _borrow: std::marker::PhantomData,
        }
    }

    /// The whole slice's length.
    pub fn len(&self) -> usize {
        self.len
    }

    /// `self[range]`, mutable.
    ///
    /// # Safety
    ///
    /// No other part overlapping `range` may be alive while this one is.
    pub unsafe fn part(&self, range: Range<usize>) -> &'a mut [T] {
        assert!(range.start <= range.end && range.end <= self.len);
        // SAFETY: in bounds (checked above) of a slice borrowed mutably for `'a`; the
        // caller guarantees no overlapping part is alive.
        unsafe { std::slice::from_raw_parts_mut(self.ptr.add(range.start), range.len()) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Breaks the contract every way at once: runs each task but the last twice, calls
    /// indices past the count, and never runs the last task.
    struct Careless;

    impl JobSystem for Careless {
        fn workers(&self) -> usize {
            3
        }
        fn run(&self, count: usize, task: &(dyn Fn(usize) + Sync)) {
            let some = 0..count.saturating_sub(1);
            some.clone().chain(some.rev()).for_each(task);
            (count..count + 4).for_each(task);
        }
    }

    /// Every unit of every buffer is handed out once, to the task of its range, for every
    /// length around the unit and the task size, whatever the runner does.
    #[test]
    fn each_task_gets_its_own_part_of_every_buffer_once() {
        let careless = Careless;
        for runner in [Runner::Here, Runner::Jobs(&careless)] {
            for len in [0, 1, 6, 7, 8, 49, 50, 51, 333, 1000] {
                let (mut a, mut b) = (vec![0usize; len], vec![0usize; len]);
                let parts = [Some(&mut a[..]), Some(&mut b[..]), None];
                let unit = 7;
                for_each_part(runner, len, unit, 20, parts, &|range, [a, b, none]| {
                    assert!(range.start % unit == 0 && range.start < range.end);
                    assert!(range.len() == unit || range.end == len);
                    assert!(none.is_none());
                    for part in [a, b] {
                        let part = part.expect("a buffer's part");
                        assert_eq!(part.len(), range.len());
                        for (k, x) in part.iter_mut().enumerate() {
                            *x += range.start + k + 1;
                        }
                    }
                });
                let once: Vec<usize> = (1..=len).collect();
                assert!(a == once && b == once, "{runner:?}, {len} nodes");
            }
        }
    }
}
