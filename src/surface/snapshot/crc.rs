//! The snapshot's checksum: CRC-32 with the IEEE polynomial (reflected, `0xEDB88320`: the
//! checksum of zlib, PNG and Ethernet) over every byte before it.
//!
//! Natively `crc32fast` computes it, with carry-less multiplies where the CPU has them. On
//! WebAssembly it has none of those, and its fallback loop reads sixteen tables of 1 KiB
//! held as constant data: 16 kB in each of the npm package's two modules that gzip cannot
//! shrink (random-looking words; `docs/performance.md`). There the `Sliced` loop below
//! runs instead: eight bytes a round from eight tables it computes at the first checksum,
//! into memory the module does not ship. The choice between the two is made here and
//! nowhere else (callers use `hash` and `Hasher`). Both compute the same function, so a
//! snapshot saved on one platform loads on every other; the tests hold `Sliced` to the
//! standard check value on every target and to `crc32fast` natively.

#[cfg(not(target_family = "wasm"))]
pub(super) use crc32fast::{hash, Hasher};

#[cfg(target_family = "wasm")]
pub(super) use Sliced as Hasher;

/// The checksum of `bytes`.
#[cfg(target_family = "wasm")]
pub(super) fn hash(bytes: &[u8]) -> u32 {
    let mut h = Sliced::new();
    h.update(bytes);
    h.finalize()
}

/// CRC-32 eight bytes a round ("slicing by eight"), the same interface as
/// `crc32fast::Hasher`.
#[cfg(any(test, target_family = "wasm"))]
pub(super) struct Sliced {
    /// The register, inverted (as the checksum starts and ends).
    state: u32,
}

#[cfg(any(test, target_family = "wasm"))]
impl Sliced {
    pub fn new() -> Self {
        Self { state: !0 }
    }

    pub fn update(&mut self, bytes: &[u8]) {
        let t = tables();
        let byte = |word: u32, shift: u32| ((word >> shift) & 0xff) as usize;
        let mut crc = self.state;
        let mut rounds = bytes.chunks_exact(8);
        for r in &mut rounds {
            let low = crc ^ u32::from_le_bytes([r[0], r[1], r[2], r[3]]);
            let high = u32::from_le_bytes([r[4], r[5], r[6], r[7]]);
            crc = t[7][byte(low, 0)]
                ^ t[6][byte(low, 8)]
                ^ t[5][byte(low, 16)]
                ^ t[4][byte(low, 24)]
                ^ t[3][byte(high, 0)]
                ^ t[2][byte(high, 8)]
                ^ t[1][byte(high, 16)]
                ^ t[0][byte(high, 24)];
        }
        for &b in rounds.remainder() {
            crc = t[0][byte(crc ^ u32::from(b), 0)] ^ (crc >> 8);
        }
        self.state = crc;
    }

    pub fn finalize(self) -> u32 {
        !self.state
    }
}

/// `tables()[0][b]`: the register after shifting byte `b` through it; `tables()[k][b]`:
/// the same followed by `k` zero bytes.
#[cfg(any(test, target_family = "wasm"))]
fn tables() -> &'static [[u32; 256]; 8] {
    static TABLES: std::sync::OnceLock<[[u32; 256]; 8]> = std::sync::OnceLock::new();
    TABLES.get_or_init(|| {
        let mut t = [[0u32; 256]; 8];
        for (b, entry) in (0u32..).zip(t[0].iter_mut()) {
            *entry = (0..8).fold(b, |c, _| (c >> 1) ^ (0xEDB8_8320 & (c & 1).wrapping_neg()));
        }
        for k in 1..8 {
            for b in 0..256 {
                let previous = t[k - 1][b];
                t[k][b] = (previous >> 8) ^ t[0][(previous & 0xff) as usize];
            }
        }
        t
    })
}

#[cfg(test)]
mod tests {
    use super::Sliced;

    fn sliced(bytes: &[u8]) -> u32 {
        let mut h = Sliced::new();
        h.update(bytes);
        h.finalize()
    }

    #[test]
    fn the_check_value() {
        assert_eq!(sliced(b"123456789"), 0xCBF4_3926);
        assert_eq!(sliced(b""), 0);
    }

    #[cfg(not(target_family = "wasm"))]
    #[test]
    fn agrees_with_crc32fast_in_any_pieces() {
        let bytes: Vec<u8> = (0u32..5000)
            .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
            .collect();
        for len in [0, 1, 7, 8, 9, 15, 16, 17, 63, 64, 65, 1000, 5000] {
            assert_eq!(
                sliced(&bytes[..len]),
                crc32fast::hash(&bytes[..len]),
                "{len}"
            );
        }
        let mut h = Sliced::new();
        for piece in bytes.chunks(37) {
            h.update(piece);
        }
        assert_eq!(h.finalize(), crc32fast::hash(&bytes));
    }
}
