//! Results are bitwise identical for any thread count and with the `parallel` feature off.
//!
//! Within one build the test compares 1, 2, 3 and 4 threads. Across builds, each build
//! writes its fingerprint of the same run to `target/tmp/determinism-<features>.txt`; the
//! build without `parallel` compares against the parallel one when it is there (CI runs
//! both, and sets `SPRINGWATER_CROSS_BUILD=1` to make a missing file an error).

mod common;

use common::{fingerprint, state_bits};
use springwater::{Params, Surface};

fn run() -> Surface {
    let mut params = Params::with_size(150, 131);
    params.viscosity = 0.01;
    let mut s = common::new_surface(params).unwrap();
    s.drop_at(40.0, 50.0, 2.0, 3.0).unwrap();
    s.drop_at(110.0, 90.0, -1.5, 2.5).unwrap();
    s.add_force(75 * 150 + 60, [0.5, 2.0, -0.25]).unwrap();
    for _ in 0..300 {
        s.step().unwrap();
    }
    s
}

fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

#[test]
fn one_to_four_threads_give_identical_bits() {
    let reference = state_bits(&in_pool(1, run));
    for threads in 2..=4 {
        let bits = state_bits(&in_pool(threads, run));
        assert!(bits == reference, "{threads} threads differ from 1 thread");
    }
}

#[test]
fn parallel_feature_on_and_off_give_identical_bits() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
    let mine = format!("{:016x}", fingerprint(&in_pool(2, run)));
    let name = |parallel: bool| {
        dir.join(format!(
            "determinism-{}.txt",
            if parallel { "parallel" } else { "serial" }
        ))
    };
    let parallel = cfg!(feature = "parallel");
    // The serial build of CI's cross-build step must really be serial: a feature turned
    // back on by unification would compare the parallel build with itself.
    assert!(
        !(parallel && std::env::var_os("SPRINGWATER_CROSS_BUILD").is_some()),
        "SPRINGWATER_CROSS_BUILD is for the build without `parallel`, and this one has it"
    );
    std::fs::write(name(parallel), &mine).unwrap();
    match std::fs::read_to_string(name(!parallel)) {
        Ok(other) => assert_eq!(
            mine,
            other.trim(),
            "parallel={parallel} differs from the other build"
        ),
        Err(_) if std::env::var_os("SPRINGWATER_CROSS_BUILD").is_some() && !parallel => {
            panic!("no fingerprint from the parallel build to compare with")
        }
        Err(_) => {}
    }
}
