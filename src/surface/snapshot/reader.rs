//! A forward reader over the bytes of a snapshot, for the sections (`read.rs`) and the
//! bodies (`bodies.rs`).

/// A forward reader over bytes whose length has been checked already.
pub(super) struct Reader<'a> {
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
