//! What a WebAssembly host needs beside the C ABI (compiled only for `wasm32`; not in the
//! header): memory it can write into before a call. The npm package in `web/` calls these;
//! everything else it calls is the C ABI itself (rain and wakes as `SwDisturbance`
//! handles, `sw_surface_advance_with`).
//!
//! Buffers are kept in a table keyed by their address, so freeing one the library did not
//! hand out (or freeing twice) is a no-op instead of undefined behaviour, and no `unsafe`
//! code is needed here.

use std::cell::RefCell;
use std::collections::HashMap;

thread_local! {
    static BUFFERS: RefCell<HashMap<usize, Box<[u64]>>> = RefCell::new(HashMap::new());
}

/// Allocates `bytes` bytes (rounded up to 8, zeroed, aligned to 8) and returns their
/// address, or NULL for 0 bytes or when memory cannot grow.
#[no_mangle]
pub extern "C" fn sw_wasm_alloc(bytes: usize) -> *mut u8 {
    if bytes == 0 {
        return std::ptr::null_mut();
    }
    let words = bytes.div_ceil(8);
    let mut storage = Vec::new();
    if storage.try_reserve_exact(words).is_err() {
        return std::ptr::null_mut();
    }
    storage.resize(words, 0u64);
    let mut buffer = storage.into_boxed_slice();
    let address = buffer.as_mut_ptr().cast::<u8>();
    BUFFERS.with(|b| b.borrow_mut().insert(address as usize, buffer));
    address
}

/// Frees a buffer `sw_wasm_alloc` returned. NULL, and any other address, are no-ops.
#[no_mangle]
pub extern "C" fn sw_wasm_free(address: *mut u8) {
    BUFFERS.with(|b| b.borrow_mut().remove(&(address as usize)));
}
