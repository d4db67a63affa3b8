//! What a failed call leaves for the caller: this thread's last message, and a name for
//! every status code.

use crate::ptr::copy_c_string;
use crate::status::*;
use std::ffi::CStr;
use std::panic::catch_unwind;

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
    last_error_into(buf, len)
}

/// The body of [`sw_last_error`].
fn last_error_into(buf: *mut std::ffi::c_char, len: usize) -> usize {
    let copied = catch_unwind(|| {
        with_last_error(|e| {
            copy_c_string(e, buf, len);
            e.len() + 1
        })
    });
    copied.unwrap_or(1)
}

/// A short, static, NUL-terminated name for a status code (`"SW_OK"`,
/// `"SW_ERROR_NULL_POINTER"`, …; `"unknown status"` for any other value).
#[no_mangle]
pub extern "C" fn sw_status_name(status: SwStatus) -> *const std::ffi::c_char {
    status_name(status).as_ptr()
}

fn status_name(status: SwStatus) -> &'static CStr {
    match status {
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
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_last_error_is_copied_cut_to_fit_and_sized_whole() {
        assert_eq!(
            guard(|| Err(Failure::invalid("abcdef"))),
            SW_ERROR_INVALID_ARGUMENT
        );
        let mut buf = [0 as std::ffi::c_char; 4];
        assert_eq!(last_error_into(buf.as_mut_ptr(), buf.len()), 7);
        let bytes = buf.map(|c| c as u8);
        assert_eq!(CStr::from_bytes_until_nul(&bytes).unwrap(), c"abc");
        assert_eq!(last_error_into(std::ptr::null_mut(), 0), 7);
    }

    #[test]
    fn every_status_has_a_name() {
        for status in 0..=11 {
            let name = status_name(-status);
            assert!(name.to_str().unwrap().starts_with("SW_"), "{status}");
        }
        assert_eq!(status_name(5), c"unknown status");
    }
}
