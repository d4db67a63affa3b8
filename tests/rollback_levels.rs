//! Rollback as netcode runs it, on every SIMD level this CPU has and every thread count:
//! save every frame into reused buffers, roll back now and then, simulate the same inputs
//! again, and compare the state hashes with the scalar reference's straight run, frame by
//! frame (the scene is `tests/common/rollback.rs`; `tests/rollback.rs` holds its golden
//! hashes and a short rollback, which CI also runs on AArch64 and wasm32).

mod common;
#[path = "common/rollback.rs"]
mod scene;

use scene::{pool, straight, with_rollback, DEPTH, FRAMES, PERIOD};
use springwater::SimdLevel;

#[test]
fn rollback_gives_the_straight_runs_hashes_on_every_level_and_thread_count() {
    let expected = straight(SimdLevel::Scalar, FRAMES);
    // A level the CPU lacks would run its widest one again; without the parallel
    // feature there is one thread.
    let threads: &[usize] = if cfg!(feature = "parallel") {
        &[1, 2]
    } else {
        &[1]
    };
    for level in SimdLevel::ALL.into_iter().filter(|l| l.is_available()) {
        for &threads in threads {
            let (mut s, ids) = pool();
            s.set_simd_level(level);
            #[cfg(feature = "parallel")]
            {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads);
                s.set_thread_pool(Some(std::sync::Arc::new(pool.build().unwrap())));
            }
            let what = format!("{level} ({:?}) on {threads} threads", s.simd_level());
            let again = with_rollback(&mut s, ids, &expected, &what);
            assert_eq!(again, FRAMES / PERIOD * DEPTH);
        }
    }
}
