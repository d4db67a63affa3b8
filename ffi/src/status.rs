//! Status codes, the thread's last error message, and the guard every exported function
//! runs its body in: no panic crosses the boundary, every failure leaves a message (which
//! `sw_last_error`, in `errors.rs`, hands to the caller).

use springwater::Error;
use std::cell::RefCell;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// A 32-bit status: `SW_OK` (0) or a negative error code. After an error,
/// `sw_last_error` gives this thread's message.
pub type SwStatus = i32;

/// Success.
pub const SW_OK: SwStatus = 0;
/// A required pointer argument was NULL.
pub const SW_ERROR_NULL_POINTER: SwStatus = -1;
/// The surface handle is not one that `sw_surface_create` or `sw_surface_load` returned,
/// or it has been destroyed.
pub const SW_ERROR_INVALID_HANDLE: SwStatus = -2;
/// A number is not finite or outside its range, or an enum value is unknown.
pub const SW_ERROR_INVALID_ARGUMENT: SwStatus = -3;
/// A caller's buffer is shorter than the call needs (the message says how long it must be).
pub const SW_ERROR_BUFFER_TOO_SMALL: SwStatus = -4;
/// A query point is outside the water's rest footprint.
pub const SW_ERROR_OUTSIDE_GRID: SwStatus = -5;
/// A step would have made the state non-finite (the water's, or a floating body's forces
/// or motion); it was not applied.
pub const SW_ERROR_NON_FINITE: SwStatus = -6;
/// A snapshot was refused: truncated, corrupted, or from another format version.
pub const SW_ERROR_SNAPSHOT: SwStatus = -7;
/// The host's job system returned before running every task; the step was not applied.
pub const SW_ERROR_JOB_SYSTEM: SwStatus = -8;
/// Another call on the same surface is in progress (calls on one surface must not
/// overlap, for example from a job system's task); this one changed nothing.
pub const SW_ERROR_BUSY: SwStatus = -9;
/// The library failed internally (a bug: please report the message). The surface the
/// call was made on is unusable from then on; destroy it.
pub const SW_ERROR_INTERNAL: SwStatus = -10;
/// No floating body of this surface has the id: never added, or removed (ids are never
/// reused).
pub const SW_ERROR_NO_SUCH_FLOATER: SwStatus = -11;

/// A failure on its way to the caller: its status and message.
#[derive(Debug)]
pub(crate) struct Failure {
    pub status: SwStatus,
    pub message: String,
}

impl Failure {
    pub fn new(status: SwStatus, message: impl Into<String>) -> Self {
        Self {
            status,
            message: message.into(),
        }
    }

    pub fn null(what: &str) -> Self {
        Self::new(SW_ERROR_NULL_POINTER, format!("{what} is NULL"))
    }

    pub fn invalid(message: impl Into<String>) -> Self {
        Self::new(SW_ERROR_INVALID_ARGUMENT, message)
    }
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        let status = match e {
            Error::LengthMismatch { .. } => SW_ERROR_BUFFER_TOO_SMALL,
            Error::OutsideGrid { .. } => SW_ERROR_OUTSIDE_GRID,
            Error::NonFinite { .. } | Error::FloaterNonFinite { .. } => SW_ERROR_NON_FINITE,
            Error::NoSuchFloater(_) => SW_ERROR_NO_SUCH_FLOATER,
            Error::Snapshot(_) | Error::Io { .. } => SW_ERROR_SNAPSHOT,
            Error::JobSystem => SW_ERROR_JOB_SYSTEM,
            _ => SW_ERROR_INVALID_ARGUMENT,
        };
        Self::new(status, e.to_string())
    }
}

pub(crate) type Outcome<T = ()> = Result<T, Failure>;

thread_local! {
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Runs `body`, turning an error or a panic into a status and this thread's last error.
pub(crate) fn guard(body: impl FnOnce() -> Outcome) -> SwStatus {
    let failure = match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => return SW_OK,
        Ok(Err(failure)) => failure,
        Err(panic) => Failure::new(SW_ERROR_INTERNAL, panic_message(&*panic)),
    };
    set_last_error(&failure.message);
    failure.status
}

pub(crate) fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    let what = panic
        .downcast_ref::<&str>()
        .copied()
        .or_else(|| panic.downcast_ref::<String>().map(String::as_str))
        .unwrap_or("a panic without a message");
    format!("internal error in springwater: {what}")
}

fn set_last_error(message: &str) {
    // A message with a NUL inside would end early in C: cut it there.
    let message = message.split('\0').next().unwrap_or_default();
    LAST_ERROR.with(|e| {
        let mut e = e.borrow_mut();
        e.clear();
        e.push_str(message);
    });
}

/// Runs `f` on this thread's last error message ("" if no call on this thread has failed).
pub(crate) fn with_last_error<R>(f: impl FnOnce(&str) -> R) -> R {
    LAST_ERROR.with(|e| f(&e.borrow()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn last_error() -> String {
        with_last_error(str::to_owned)
    }

    #[test]
    fn a_panic_becomes_an_internal_error_with_its_message() {
        let status = guard(|| panic!("boom {}", 42));
        assert_eq!(status, SW_ERROR_INTERNAL);
        assert_eq!(last_error(), "internal error in springwater: boom 42");
    }

    #[test]
    fn errors_leave_their_message_and_success_keeps_the_last_one() {
        assert_eq!(guard(|| Err(Failure::null("xyz"))), SW_ERROR_NULL_POINTER);
        assert_eq!(guard(|| Ok(())), SW_OK);
        assert_eq!(last_error(), "xyz is NULL");
        // A NUL inside a message ends it.
        assert_eq!(
            guard(|| Err(Failure::invalid("a\0b"))),
            SW_ERROR_INVALID_ARGUMENT
        );
        assert_eq!(last_error(), "a");
    }
}
