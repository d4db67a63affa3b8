//! Pointer and length checks: the one place in the C ABI that turns a caller's raw pointer
//! into a Rust value, a reference or a slice. Every `unsafe` block of the crate is here,
//! apart from `jobs.rs`, which calls the host's job-system callbacks and reads back the
//! context it handed them: that argument rests on the job system's contract, not on a
//! caller's pointer, and is made there.
//!
//! # The safety argument
//!
//! C cannot promise anything Rust's type system can see, so the promise is made in words:
//! every exported function that takes a pointer is an `unsafe extern "C" fn` whose
//! `# Safety` section says what the caller gives (a valid struct, or `len` writable
//! elements, or NULL where NULL is allowed). The helpers below are the only code that
//! relies on that promise, and they are only ever handed the pointers and lengths an
//! exported function received: unchanged, or cast to an element type of the same layout
//! (`[T; N]` over runs of `T`, which the language lays out alike; `Vertex` over
//! `SwVertex`, which a compile-time assertion beside the cast checks). Everything that can
//! be checked is checked before a pointer is used:
//!
//! * NULL: an error (`SW_ERROR_NULL_POINTER`), except where the call documents NULL as
//!   "not wanted", and for an empty slice, which never touches its pointer;
//! * alignment: an error, never an unaligned access;
//! * length: the caller's length must hold what the call writes
//!   (`SW_ERROR_BUFFER_TOO_SMALL`), and no slice spans more than `isize::MAX` bytes;
//! * a struct the caller fills ([`Input`]) must first say, in its `struct_size`, that it is
//!   this version's size or the size of an earlier version's struct that the call still
//!   takes ([`Input::EARLIER`]), and only that field is read before: a struct from an
//!   older, smaller header is never read or written past the size it says.
//!
//! What cannot be checked (that memory behind a pointer is really there and nothing else
//! uses it during the call) is the caller's promise. The references and slices these
//! helpers make live only for the call that made them.
//!
//! The helpers are safe functions so that the topic modules read as plain Rust; they are
//! private to the crate, and called only as above.

use crate::handle::{self, Water};
use crate::status::{guard, Failure, Outcome, SwStatus, SW_ERROR_BUFFER_TOO_SMALL};
use crate::SwSurface;
use std::borrow::Cow;
use std::ffi::c_char;

/// A struct the caller fills and hands to the library. Its first field is `struct_size`,
/// which must be `sizeof` the struct of this library's version, or one of
/// [`Input::EARLIER`].
pub(crate) trait Input: Copy {
    /// The function that makes one with its size set.
    const MAKER: &'static str;
    /// The sizes of this struct in earlier versions of the header that calls taking it
    /// with [`input_over`] and [`read_sized_into`] still accept: each is the struct cut
    /// after one of its fields (fields are only ever added at the end; the struct's module
    /// asserts the offsets), so the caller's bytes are a prefix of this version's struct.
    const EARLIER: &'static [usize] = &[];
}

/// Copies the struct the caller passed at `ptr` after checking it: not NULL, aligned, and
/// its `struct_size` this version's.
pub(crate) fn input<T: Input>(ptr: *const T, what: &str) -> Outcome<T> {
    sized(ptr, what, &[])?;
    // SAFETY: non-NULL and aligned (checked), and the caller's struct is as large as this
    // version's (its size says so).
    Ok(unsafe { ptr.read() })
}

/// The struct the caller passed at `ptr`, which may be an earlier version's
/// ([`Input::EARLIER`]): the fields the caller's struct has are the caller's, the fields
/// added since are `base`'s (the defaults of a new value, or the current value a call
/// replaces), and `struct_size` is this version's.
pub(crate) fn input_over<T: Input>(ptr: *const T, what: &str, base: T) -> Outcome<T> {
    let size = sized(ptr, what, T::EARLIER)?;
    let mut value = base;
    // SAFETY: non-NULL and aligned (checked); the caller's struct holds `size` bytes (its
    // size says so), and `size` is at most `size_of::<T>()` and ends at a field of `T`
    // (`Input::EARLIER`), so the bytes copied are whole fields of a valid `T`. The first
    // four, the caller's `struct_size`, stay `base`'s.
    unsafe {
        let from = ptr.cast::<u8>().add(SIZE_FIELD);
        let to = std::ptr::from_mut(&mut value).cast::<u8>().add(SIZE_FIELD);
        std::ptr::copy_nonoverlapping(from, to, size - SIZE_FIELD);
    }
    Ok(value)
}

/// The bytes of `struct_size`, every `Input` struct's first field.
const SIZE_FIELD: usize = size_of::<u32>();

/// Checks that the struct at `ptr` is not NULL, is aligned, and says in its `struct_size`
/// that it is as large as this version's or one of `earlier`; returns that size. The size
/// is read alone, so that a smaller struct (from an older header) is never read or written
/// past its end.
fn sized<T: Input>(ptr: *const T, what: &str, earlier: &[usize]) -> Outcome<usize> {
    aligned(ptr, what)?;
    if ptr.is_null() {
        return Err(Failure::null(what));
    }
    // SAFETY: non-NULL and aligned; every `Input` struct starts with its `u32` size.
    let size = unsafe { ptr.cast::<u32>().read() } as usize;
    let want = size_of::<T>();
    let known = size == want || (earlier.contains(&size) && (SIZE_FIELD..want).contains(&size));
    if !known {
        let also = match earlier {
            [] => String::new(),
            sizes => format!(" (or an earlier version's {sizes:?})"),
        };
        return Err(Failure::invalid(format!(
            "{what}->struct_size is {size}, this library's struct is {want} bytes{also}: \
             start it from {} or set it to sizeof the struct (a header of another version \
             than the library's gives another size)",
            T::MAKER
        )));
    }
    Ok(size)
}

/// The body of every call that writes a sized struct (one with `struct_size` first) to
/// `out`: like [`read_into`], and the caller's struct must first say it is this version's
/// size or an earlier version's ([`Input::EARLIER`]), so that a caller built against
/// another header is never written past its end: an earlier version's struct gets the
/// fields it has, and keeps its `struct_size`.
pub(crate) fn read_sized_into<T: Input>(
    surface: *const SwSurface,
    out: *mut T,
    read: impl FnOnce(&mut Water) -> Outcome<T>,
) -> SwStatus {
    guard(|| sized_out(out, || handle::with(surface, read)))
}

/// Writes what `make` gives to the caller's sized struct at `out`, checked as for
/// [`read_sized_into`] before `make` runs.
pub(crate) fn sized_out<T: Input>(out: *mut T, make: impl FnOnce() -> Outcome<T>) -> Outcome {
    let size = sized(out.cast_const(), "out", T::EARLIER)?;
    let value = make()?;
    // SAFETY: non-NULL and aligned (checked), and the caller's struct holds `size` bytes,
    // at most `size_of::<T>()` and ending at a field (`Input::EARLIER`): whole fields of
    // `value` are written over the caller's, all but `struct_size`.
    unsafe {
        let from = std::ptr::from_ref(&value).cast::<u8>().add(SIZE_FIELD);
        let to = out.cast::<u8>().add(SIZE_FIELD);
        std::ptr::copy_nonoverlapping(from, to, size - SIZE_FIELD);
    }
    Ok(())
}

/// The body of every call that reads one value of a surface into `out`: the guard, the
/// out-pointer check (before anything is looked up), the handle lookup.
pub(crate) fn read_into<T>(
    surface: *const SwSurface,
    out: *mut T,
    read: impl FnOnce(&mut Water) -> Outcome<T>,
) -> SwStatus {
    guard(|| {
        let out = out_ref(out, "out")?;
        *out = handle::with(surface, read)?;
        Ok(())
    })
}

/// An out-pointer the call must write.
pub(crate) fn out_ref<'a, T>(ptr: *mut T, what: &str) -> Outcome<&'a mut T> {
    aligned(ptr, what)?;
    // SAFETY: aligned (checked), and NULL becomes `None`; the caller gives a valid pointer.
    unsafe { ptr.as_mut() }.ok_or_else(|| Failure::null(what))
}

/// An optional out-pointer: NULL means "not wanted".
pub(crate) fn optional<'a, T>(ptr: *mut T, what: &str) -> Outcome<Option<&'a mut T>> {
    aligned(ptr, what)?;
    // SAFETY: aligned (checked); the caller gives a valid pointer or NULL.
    Ok(unsafe { ptr.as_mut() })
}

/// An out-pointer to `N` elements, such as the three floats of a normal.
pub(crate) fn out_array<'a, T, const N: usize>(ptr: *mut T, what: &str) -> Outcome<&'a mut [T; N]> {
    // `[T; N]` has the size of `N` elements and the alignment of one.
    out_ref(ptr.cast::<[T; N]>(), what)
}

/// `len` elements at `ptr`, read only. NULL is allowed for `len` 0.
pub(crate) fn in_slice<'a, T>(ptr: *const T, len: usize, what: &str) -> Outcome<&'a [T]> {
    if len == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(Failure::null(what));
    }
    aligned(ptr, what)?;
    too_long::<T>(len, what)?;
    // SAFETY: non-NULL, aligned, not too long for a slice; the caller gives `len` elements.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// `len` writable elements at `ptr`. NULL is allowed for `len` 0.
pub(crate) fn out_slice<'a, T>(ptr: *mut T, len: usize, what: &str) -> Outcome<&'a mut [T]> {
    if len == 0 {
        return Ok(&mut []);
    }
    if ptr.is_null() {
        return Err(Failure::null(what));
    }
    aligned(ptr, what)?;
    too_long::<T>(len, what)?;
    // SAFETY: non-NULL, aligned, not too long for a slice; the caller gives `len` elements.
    Ok(unsafe { std::slice::from_raw_parts_mut(ptr, len) })
}

/// The first `n` of the `len` writable elements at `ptr`; fails unless `len ≥ n`.
pub(crate) fn out_buffer<'a, T>(
    ptr: *mut T,
    len: usize,
    n: usize,
    what: &str,
) -> Outcome<&'a mut [T]> {
    need(len, n, what)?;
    out_slice(ptr, n, what)
}

/// `n` writable groups of `N` elements (`[x, y, z]` triples, `[u, v]` pairs) at `ptr`,
/// whose buffer holds `len` elements; fails unless `len ≥ N·n`.
pub(crate) fn out_groups<'a, T, const N: usize>(
    ptr: *mut T,
    len: usize,
    n: usize,
    what: &str,
) -> Outcome<&'a mut [[T; N]]> {
    need(len, n * N, what)?;
    // `[T; N]` has the size of `N` elements and the alignment of one.
    out_slice(ptr.cast::<[T; N]>(), n, what)
}

/// The body of every call that copies a list of variable length out of a surface, the C
/// way: the list's length goes to `count` (which must not be NULL); a NULL `ptr` only asks
/// for it, otherwise the `len` elements at `ptr` must hold the list and get a copy.
pub(crate) fn copy_list_into<T: Clone>(
    surface: *const SwSurface,
    (ptr, len, what): (*mut T, usize, &str),
    (count, count_what): (*mut usize, &str),
    list: impl FnOnce(&mut Water) -> Cow<'_, [T]>,
) -> SwStatus {
    guard(|| {
        let count = out_ref(count, count_what)?;
        handle::with(surface, |w| {
            let list = list(w);
            *count = list.len();
            if !ptr.is_null() {
                out_buffer(ptr, len, list.len(), what)?.clone_from_slice(&list);
            }
            Ok(())
        })
    })
}

/// Copies `text` to the `len` bytes at `buf` as a NUL-terminated C string, cut to fit;
/// with `buf` NULL or `len` 0 it writes nothing.
pub(crate) fn copy_c_string(text: &str, buf: *mut c_char, len: usize) {
    if buf.is_null() || len == 0 {
        return;
    }
    let n = text.len().min(len - 1);
    // SAFETY: the caller gives `len` writable bytes at `buf` (bytes need no alignment);
    // `n < len`, so the text and its NUL fit.
    unsafe {
        std::ptr::copy_nonoverlapping(text.as_ptr(), buf.cast::<u8>(), n);
        *buf.add(n) = 0;
    }
}

/// Fails unless a buffer of `len` holds `needed`.
pub(crate) fn need(len: usize, needed: usize, what: &str) -> Outcome {
    if len >= needed {
        Ok(())
    } else {
        Err(Failure::new(
            SW_ERROR_BUFFER_TOO_SMALL,
            format!("{what} holds {len}, the call needs {needed}"),
        ))
    }
}

fn aligned<T>(ptr: *const T, what: &str) -> Outcome {
    if ptr.is_null() || ptr.align_offset(std::mem::align_of::<T>()) == 0 {
        Ok(())
    } else {
        Err(Failure::invalid(format!(
            "{what} ({ptr:p}) is not aligned to {} bytes",
            std::mem::align_of::<T>()
        )))
    }
}

fn too_long<T>(len: usize, what: &str) -> Outcome {
    match len.checked_mul(std::mem::size_of::<T>().max(1)) {
        Some(bytes) if bytes <= isize::MAX as usize => Ok(()),
        _ => Err(Failure::invalid(format!(
            "{what}: length {len} is too large"
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::status::{SW_ERROR_INVALID_ARGUMENT, SW_ERROR_NULL_POINTER};
    use std::ffi::CStr;

    #[test]
    fn a_c_string_is_cut_to_fit_and_always_terminated() {
        let mut buf = [b'x' as c_char; 4];
        copy_c_string("abcdef", buf.as_mut_ptr(), buf.len());
        let bytes = buf.map(|c| c as u8);
        assert_eq!(CStr::from_bytes_until_nul(&bytes).unwrap(), c"abc");
        copy_c_string("", buf.as_mut_ptr(), buf.len());
        assert_eq!(buf[0], 0);
        // A zero length writes nothing, not even the NUL.
        let mut one = [b'x' as c_char];
        copy_c_string("abc", one.as_mut_ptr(), 0);
        assert_eq!(one[0], b'x' as c_char);
        copy_c_string("abc", std::ptr::null_mut(), 8);
    }

    #[test]
    fn slices_refuse_null_misaligned_and_oversized_pointers_before_touching_them() {
        let mut floats = [0.0f32; 4];
        let p = floats.as_mut_ptr();
        assert_eq!(out_slice(p, 4, "p").unwrap().len(), 4);
        assert!(out_slice(std::ptr::null_mut::<f32>(), 0, "p")
            .unwrap()
            .is_empty());
        let status = |e: Failure| e.status;
        assert_eq!(
            out_slice(std::ptr::null_mut::<f32>(), 1, "p").map_err(status),
            Err(SW_ERROR_NULL_POINTER)
        );
        let odd = p.cast::<u8>().wrapping_add(1).cast::<f32>();
        assert_eq!(
            in_slice(odd.cast_const(), 1, "p").map_err(status),
            Err(SW_ERROR_INVALID_ARGUMENT)
        );
        assert_eq!(
            out_slice(p, usize::MAX / 2, "p").map_err(status),
            Err(SW_ERROR_INVALID_ARGUMENT)
        );
        assert_eq!(
            out_groups::<_, 3>(p, 5, 2, "p").map_err(status),
            Err(SW_ERROR_BUFFER_TOO_SMALL)
        );
        assert_eq!(out_groups::<_, 2>(p, 4, 2, "p").unwrap().len(), 2);
    }

    #[test]
    fn a_sized_struct_must_say_this_versions_size() {
        #[derive(Debug, Clone, Copy)]
        #[repr(C)]
        struct Two {
            struct_size: u32,
            value: u32,
        }
        impl Input for Two {
            const MAKER: &'static str = "two()";
        }
        let good = Two {
            struct_size: 8,
            value: 7,
        };
        assert_eq!(input(&good, "two").unwrap().value, 7);
        let old = Two {
            struct_size: 4,
            ..good
        };
        let e = input(&old, "two").unwrap_err();
        assert_eq!(e.status, SW_ERROR_INVALID_ARGUMENT);
        assert!(e.message.contains("two->struct_size is 4") && e.message.contains("two()"));
        assert_eq!(
            input(std::ptr::null::<Two>(), "two").unwrap_err().status,
            SW_ERROR_NULL_POINTER
        );
    }
}
