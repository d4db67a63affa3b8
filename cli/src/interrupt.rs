//! Signals: Ctrl-C, SIGTERM and SIGHUP.
//!
//! - **Ctrl-C once**, in a command that can stop early with a complete result (`simulate`):
//!   [`stop_requested`] turns true, the steps stop at the step reached and the outputs are
//!   written as the run left them; the exit code is then 130.
//! - **Ctrl-C once** elsewhere, **Ctrl-C twice**, **SIGTERM** and **SIGHUP**: the run stops
//!   at once, wherever it is (warm-up, rain, frames, encoding): the temporary files of
//!   outputs not yet complete are removed ([`output::abandon_all`]), so every destination
//!   is as it was, and the exit code is 128 + the signal: 130, 143, 129.
//!
//! A thread of its own waits for the signals, so no loop has to poll for them.

use crate::output;
use std::sync::atomic::{AtomicBool, Ordering};

static STOP: AtomicBool = AtomicBool::new(false);

/// True once a first Ctrl-C asked a `graceful` command to stop at the step reached.
pub fn stop_requested() -> bool {
    STOP.load(Ordering::Relaxed)
}

/// Ends the process at once: the outputs not yet complete are dropped, the files that were
/// there stay as they were.
#[cfg_attr(target_family = "wasm", allow(dead_code))]
fn abort(code: i32, name: &str) -> ! {
    let _held = output::abandon_all();
    eprintln!(
        "springwater: stopped by {name}; outputs not yet complete were discarded and the \
         files that were there are as they were"
    );
    std::process::exit(code)
}

/// Starts listening. `graceful`: a first Ctrl-C asks to stop (see [`stop_requested`])
/// instead of stopping at once.
#[cfg(unix)]
pub fn install(graceful: bool) {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return; // without handlers, a signal ends the run as it would any program
    };
    std::thread::spawn(move || {
        for signal in signals.forever() {
            match signal {
                SIGINT if graceful && !STOP.swap(true, Ordering::SeqCst) => {}
                SIGINT => abort(130, "Ctrl-C (SIGINT)"),
                SIGTERM => abort(143, "SIGTERM"),
                _ => abort(129, "SIGHUP"),
            }
        }
    });
}

/// Starts listening for Ctrl-C (the only signal here).
#[cfg(all(not(unix), not(target_family = "wasm")))]
pub fn install(graceful: bool) {
    let _ = ctrlc::set_handler(move || {
        if !(graceful && !STOP.swap(true, Ordering::SeqCst)) {
            abort(130, "Ctrl-C");
        }
    });
}

/// WASI has no signals: a run there ends on Ctrl-C like any program.
#[cfg(target_family = "wasm")]
pub fn install(_graceful: bool) {}
