//! Little-endian fields, the shared vocabulary of the snapshot's sections: the [`Sink`]
//! an encoder sends its fields to, runs of `f32` and `u32` written to it, a forward
//! [`Reader`] over bytes whose length is checked, and the error a malformed section gives.
//! The snapshot (`snapshot/`) frames the format and writes the water's sections; the
//! bodies' subsystem (`bodies/section.rs`) writes and reads its own.

use crate::error::Error;

/// Where an encoder's fields go. Encoders take it as `dyn Sink`, so their code exists once
/// for both sinks (saving and the state hash): a call per field or row, not per value.
pub(crate) trait Sink {
    /// Bytes of a field that decides the surface's future.
    fn state(&mut self, bytes: &[u8]);
    /// Bytes that frame the data or only keep count (magic, version, length, steps taken,
    /// model time, seconds dropped): saved, not hashed.
    fn record(&mut self, bytes: &[u8]);
}

/// `values` little-endian, as state.
pub(crate) fn floats(sink: &mut dyn Sink, values: &[f32]) {
    words(sink, bytemuck::cast_slice(values));
}

/// `values` little-endian, as state.
pub(crate) fn words(sink: &mut dyn Sink, values: &[u32]) {
    if cfg!(target_endian = "little") {
        sink.state(bytemuck::cast_slice(values));
    } else {
        for chunk in values.chunks(256) {
            let mut bytes = [0u8; 1024];
            for (b, v) in bytes.chunks_exact_mut(4).zip(chunk) {
                b.copy_from_slice(&v.to_le_bytes());
            }
            sink.state(&bytes[..4 * chunk.len()]);
        }
    }
}

/// The error of snapshot bytes or contents that are refused.
pub(crate) fn bad(msg: impl Into<String>) -> Error {
    Error::Snapshot(msg.into())
}

/// A forward reader over bytes whose length has been checked already.
pub(crate) struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    /// A reader at the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Self::at(bytes, 0)
    }
    /// A reader at byte `at` of `bytes`.
    pub fn at(bytes: &'a [u8], at: usize) -> Self {
        Reader { bytes, at }
    }
    pub fn take(&mut self, len: usize) -> &'a [u8] {
        let s = &self.bytes[self.at..self.at + len];
        self.at += len;
        s
    }
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes(self.take(4).try_into().expect("4 bytes"))
    }
    pub fn u64(&mut self) -> u64 {
        u64::from_le_bytes(self.take(8).try_into().expect("8 bytes"))
    }
    pub fn f32(&mut self) -> f32 {
        f32::from_bits(self.u32())
    }
    pub fn f64(&mut self) -> f64 {
        f64::from_bits(self.u64())
    }
    /// Whether every byte has been read (the layout read was the one the length says).
    pub fn at_end(&self) -> bool {
        self.at == self.bytes.len()
    }
}
