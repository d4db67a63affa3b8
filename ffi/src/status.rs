//! Status codes, the thread's last error message, and the guard every exported function
//! runs its body in: no panic crosses the boundary, every failure leaves a message.

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

/// Copies this thread's last error message into `buf` (at most `len` bytes including the
/// terminating NUL; a longer message is cut) and returns the size the whole message needs,
/// NUL included: 1 if no call on this thread has failed yet. With `buf` NULL or `len` 0 it
/// only returns the size. Messages are UTF-8 and stay until the next failing call on the
/// same thread.
///
/// # Safety
///
/// `buf` is NULL or points to `len` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn sw_last_error(buf: *mut std::ffi::c_char, len: usize) -> usize {
    let copied = catch_unwind(|| {
        LAST_ERROR.with(|e| {
            let e = e.borrow();
            if !buf.is_null() && len > 0 {
                let n = e.len().min(len - 1);
                // SAFETY: the caller gives `len` writable bytes at `buf`; `n < len`.
                unsafe {
                    std::ptr::copy_nonoverlapping(e.as_ptr(), buf.cast::<u8>(), n);
                    *buf.add(n) = 0;
                }
            }
            e.len() + 1
        })
    });
    copied.unwrap_or(1)
}

/// A short, static, NUL-terminated name for a status code (`"SW_OK"`,
/// `"SW_ERROR_NULL_POINTER"`, …; `"unknown status"` for any other value).
#[no_mangle]
pub extern "C" fn sw_status_name(status: SwStatus) -> *const std::ffi::c_char {
    let name: &'static std::ffi::CStr = match status {
        SW_OK => c"SW_OK",
        SW_ERROR_NULL_POINTER => c"SW_ERROR_NULL_POINTER",
        SW_ERROR_INVALID_HANDLE => c"SW_ERROR_INVALID_HANDLE",
        SW_ERROR_INVALID_ARGUMENT => c"SW_ERROR_INVALID_ARGUMENT",
        SW_ERROR_BUFFER_TOO_SMALL => c"SW_ERROR_BUFFER_TOO_SMALL",
        SW_ERROR_OUTSIDE_GRID => c"SW_ERROR_OUTSIDE_GRID",
        SW_ERROR_NON_FINITE => c"SW_ERROR_NON_FINITE",
        SW_ERROR_SNAPSHOT => c"SW_ERROR_SNAPSHOT",
        SW_ERROR_JOB_SYSTEM => c"SW_ERROR_JOB_SYSTEM",
        SW_ERROR_BUSY => c"SW_ERROR_BUSY",
        SW_ERROR_INTERNAL => c"SW_ERROR_INTERNAL",
        SW_ERROR_NO_SUCH_FLOATER => c"SW_ERROR_NO_SUCH_FLOATER",
        _ => c"unknown status",
    };
    name.as_ptr()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn last_error() -> String {
        let mut buf = [0 as std::ffi::c_char; 256];
        // SAFETY: a local buffer of the length passed.
        unsafe { sw_last_error(buf.as_mut_ptr(), buf.len()) };
        // SAFETY: sw_last_error NUL-terminates within the buffer.
        unsafe { std::ffi::CStr::from_ptr(buf.as_ptr()) }
            .to_string_lossy()
            .into_owned()
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

    #[test]
    fn every_status_has_a_name() {
        for status in 0..=11 {
            // SAFETY: sw_status_name returns a static C string.
            let name = unsafe { std::ffi::CStr::from_ptr(sw_status_name(-status)) };
            assert!(name.to_str().unwrap().starts_with("SW_"), "{status}");
        }
        // SAFETY: as above.
        let unknown = unsafe { std::ffi::CStr::from_ptr(sw_status_name(5)) };
        assert_eq!(unknown.to_str().unwrap(), "unknown status");
    }
}
