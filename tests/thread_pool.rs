//! The step runs on a thread pool the host provides, with results bitwise identical to
//! rayon's global pool.
#![cfg(feature = "parallel")]

mod common;

use common::state_bits;
use springwater::{Params, Surface};
use std::sync::Arc;

fn pool(threads: usize) -> Arc<rayon::ThreadPool> {
    Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap(),
    )
}

fn run(pool: Option<Arc<rayon::ThreadPool>>) -> Surface {
    common::every_stepping_path(|s| s.set_thread_pool(pool))
}

#[test]
fn a_hosts_one_and_two_thread_pools_give_the_default_bits() {
    let default = run(None);
    for threads in [1, 2] {
        let hosted = run(Some(pool(threads)));
        assert_eq!(hosted.steps(), default.steps());
        assert!(
            state_bits(&hosted) == state_bits(&default),
            "a {threads}-thread host pool differs from the global pool"
        );
    }
}

#[test]
fn the_pool_is_kept_by_clones_and_restores_and_can_be_removed() {
    let host = pool(2);
    let mut s = Surface::new(Params::with_size(33, 33)).unwrap();
    s.set_thread_pool(Some(host.clone()));
    let saved = s.to_bytes();
    s.drop_at(16.0, 16.0, 1.0, 3.0).unwrap();
    s.restore(&saved).unwrap();
    assert!(Arc::ptr_eq(s.thread_pool().unwrap(), &host));
    assert!(Arc::ptr_eq(s.clone().thread_pool().unwrap(), &host));
    // A surface loaded from bytes has no host pool until one is set.
    assert!(Surface::from_bytes(&saved).unwrap().thread_pool().is_none());
    // Stepping from inside the host's pool (an engine's job) works and matches.
    let mut inside = s.clone();
    host.install(|| inside.step_n(5)).unwrap();
    s.set_thread_pool(None);
    assert!(s.thread_pool().is_none());
    s.step_n(5).unwrap();
    assert!(state_bits(&s) == state_bits(&inside));
}
