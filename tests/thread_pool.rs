//! The step runs on a thread pool the host provides, with results bitwise identical to
//! rayon's global pool.
#![cfg(feature = "parallel")]

mod common;

use common::state_bits;
use springwater::disturb::{Rain, Wake};
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

/// Drops, forces, single steps, multi-step passes and frames with disturbances, on a grid
/// tall enough for several bands.
fn run(pool: Option<Arc<rayon::ThreadPool>>) -> Surface {
    let mut s = Surface::new(Params::with_size(97, 140)).unwrap();
    s.set_thread_pool(pool);
    s.drop_at(30.0, 40.0, 1.5, 3.0).unwrap();
    s.drop_at(70.0, 110.0, -1.0, 2.5).unwrap();
    s.add_force_at(48.5, 70.25, [0.3, 2.0, -0.1]).unwrap();
    for _ in 0..10 {
        s.step().unwrap();
    }
    s.step_n(37).unwrap();
    let mut rain = Rain::new(0.8, 5);
    let mut wake = Wake::circle(&s, 30.0);
    for _ in 0..20 {
        s.advance_with(1.0 / 30.0, &mut (&mut rain, &mut wake))
            .unwrap();
    }
    s
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
