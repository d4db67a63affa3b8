//! The levels: [`SimdLevel`], what this CPU runs (asked once), and the names
//! `SPRINGWATER_SIMD` and the command line use.

use std::sync::OnceLock;

/// An instruction set the engine can run on.
///
/// Every level gives the same results, bit for bit; they differ only in speed. The x86-64
/// levels are declared from the narrowest to the widest, so on x86-64 a level compares
/// below a wider one; comparisons between levels of different architectures mean nothing.
/// More levels may be added as the engine learns other instruction sets.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum SimdLevel {
    /// No SIMD: the step is the plain scalar reference loop. Runs everywhere.
    Scalar,
    /// SSE2, part of every x86-64 CPU: 8 lanes in two 128-bit registers.
    Sse2,
    /// AVX2: 8 lanes in one 256-bit register.
    Avx2,
    /// AVX-512F: 16 lanes in one 512-bit register.
    Avx512,
    /// The lane kernels on 8 lanes of plain `f32` arrays, vectorised (or not) by the
    /// compiler: what targets without a SIMD level here run (RISC-V, …; a `wasm32` build
    /// without `+simd128` runs them on one lane, plain scalar code). Runs everywhere but in a `wasm32` build with `+simd128`,
    /// which runs SIMD128 in its place ([`SimdLevel::is_available`]).
    Portable,
    /// NEON (Advanced SIMD), part of every AArch64 CPU: 8 lanes in two 128-bit registers.
    Neon,
    /// WebAssembly SIMD128: 4 lanes in one `v128`. Present in a `wasm32` build made with
    /// `-C target-feature=+simd128` (wasm has no run-time detection).
    Simd128,
}

impl SimdLevel {
    /// Every level: the scalar reference, the x86-64 levels narrowest first, the portable
    /// lanes, then the levels of other architectures.
    pub const ALL: [SimdLevel; 7] = [
        Self::Scalar,
        Self::Sse2,
        Self::Avx2,
        Self::Avx512,
        Self::Portable,
        Self::Neon,
        Self::Simd128,
    ];

    /// The widest level this CPU runs (asked once, then cached): AVX-512, AVX2 or SSE2 on
    /// x86-64, NEON on AArch64, SIMD128 on a `wasm32` build with `+simd128`, the portable
    /// lanes elsewhere (and under Miri).
    pub fn detect() -> SimdLevel {
        static DETECTED: OnceLock<SimdLevel> = OnceLock::new();
        *DETECTED.get_or_init(detect_cpu)
    }

    /// Whether this CPU runs `self`: the scalar reference everywhere; the portable lanes
    /// everywhere but in a `wasm32` build with `+simd128`; an x86-64 level where the CPU
    /// has it; NEON on AArch64; SIMD128 in a `wasm32` build with `+simd128`.
    ///
    /// A `wasm32` build with `+simd128` leaves the portable lanes out: every engine that
    /// loads such a module runs SIMD128, which gives the same bits, and a second copy of
    /// every kernel made a third of the module (the npm package ships it to browsers).
    /// There `portable` runs SIMD128, as a level of another architecture does.
    pub fn is_available(self) -> bool {
        let best = Self::detect();
        match self {
            Self::Scalar => true,
            Self::Portable => !cfg!(all(
                target_arch = "wasm32",
                target_feature = "simd128",
                not(miri)
            )),
            Self::Sse2 | Self::Avx2 | Self::Avx512 => {
                matches!(best, Self::Sse2 | Self::Avx2 | Self::Avx512) && self <= best
            }
            Self::Neon | Self::Simd128 => self == best,
        }
    }

    /// `self` if this CPU runs it, else the widest level it runs ([`SimdLevel::detect`]).
    ///
    /// On x86-64 this clamps a wider level down (`avx512` on an AVX2 CPU runs `avx2`); a
    /// level of another architecture (`neon` on x86-64, `avx2` on AArch64 or in a browser)
    /// runs the CPU's widest level too, so that one setting, written into a game's
    /// configuration, runs on every platform the game ships to.
    pub fn clamped(self) -> SimdLevel {
        if self.is_available() {
            self
        } else {
            Self::detect()
        }
    }

    /// The level `SPRINGWATER_SIMD` names if it is set and not empty (clamped to what the
    /// CPU has), else [`SimdLevel::detect`]. An unknown value of the variable is an error
    /// that names it.
    /// The library never calls this itself (a [`Surface`](crate::Surface) starts at
    /// [`SimdLevel::detect`]): the command line and the tests do, and a host that wants the
    /// variable honoured passes the result to
    /// [`Surface::set_simd_level`](crate::Surface::set_simd_level).
    pub fn from_env() -> crate::Result<SimdLevel> {
        match std::env::var(ENV) {
            Ok(v) if v.trim().is_empty() => Ok(Self::detect()),
            Ok(v) => v.parse::<SimdLevel>().map(SimdLevel::clamped),
            Err(std::env::VarError::NotPresent) => Ok(Self::detect()),
            Err(std::env::VarError::NotUnicode(_)) => Err(crate::Error::InvalidSimdLevel {
                value: "(not valid UTF-8)".into(),
            }),
        }
    }

    /// The name `SPRINGWATER_SIMD` and the CLI use: `scalar`, `sse2`, `avx2`, `avx512`,
    /// `portable`, `neon`, `simd128`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Scalar => "scalar",
            Self::Sse2 => "sse2",
            Self::Avx2 => "avx2",
            Self::Avx512 => "avx512",
            Self::Portable => "portable",
            Self::Neon => "neon",
            Self::Simd128 => "simd128",
        }
    }

    /// `f32` lanes per vector at this level (1 for scalar; the portable level has 1 in a
    /// `wasm32` build, 8 elsewhere).
    pub fn lanes(self) -> usize {
        match self {
            Self::Scalar => 1,
            Self::Portable if cfg!(target_arch = "wasm32") => 1,
            Self::Sse2 | Self::Avx2 | Self::Portable | Self::Neon => 8,
            Self::Simd128 => 4,
            Self::Avx512 => 16,
        }
    }
}

/// The environment variable that forces a level.
pub const ENV: &str = "SPRINGWATER_SIMD";

impl std::fmt::Display for SimdLevel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for SimdLevel {
    type Err = crate::Error;

    fn from_str(s: &str) -> crate::Result<Self> {
        Self::ALL
            .into_iter()
            .find(|l| l.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| crate::Error::InvalidSimdLevel { value: s.into() })
    }
}

#[cfg(all(target_arch = "x86_64", not(miri)))]
fn detect_cpu() -> SimdLevel {
    if std::arch::is_x86_feature_detected!("avx512f") {
        SimdLevel::Avx512
    } else if std::arch::is_x86_feature_detected!("avx2") {
        SimdLevel::Avx2
    } else {
        SimdLevel::Sse2
    }
}

/// NEON is part of every AArch64 CPU (the `aarch64` targets enable it in their baseline).
#[cfg(all(target_arch = "aarch64", not(miri)))]
fn detect_cpu() -> SimdLevel {
    SimdLevel::Neon
}

/// A `wasm32` build has SIMD128 exactly when it was compiled with `+simd128`: a module
/// that uses it does not load in an engine without it, so there is nothing to detect.
#[cfg(all(target_arch = "wasm32", target_feature = "simd128", not(miri)))]
fn detect_cpu() -> SimdLevel {
    SimdLevel::Simd128
}

/// Miri and other targets run the portable lanes.
#[cfg(not(any(
    all(target_arch = "x86_64", not(miri)),
    all(target_arch = "aarch64", not(miri)),
    all(target_arch = "wasm32", target_feature = "simd128", not(miri)),
)))]
fn detect_cpu() -> SimdLevel {
    SimdLevel::Portable
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn level_names_round_trip() {
        for l in SimdLevel::ALL {
            assert_eq!(l.name().parse::<SimdLevel>().unwrap(), l);
        }
        let unknown = "avx3".parse::<SimdLevel>().unwrap_err().to_string();
        for l in SimdLevel::ALL {
            assert!(unknown.contains(l.name()), "{unknown} names {l}");
        }
        let best = SimdLevel::detect();
        assert!(best.is_available());
        for l in SimdLevel::ALL {
            // A level the CPU lacks runs its widest; one it has runs as asked.
            let want = if l.is_available() { l } else { best };
            assert_eq!(l.clamped(), want, "{l}");
        }
        // Exactly one level of each architecture can be the widest here.
        let native = [SimdLevel::Neon, SimdLevel::Simd128];
        assert_eq!(native.map(|l| l.is_available()), native.map(|l| l == best));
        if cfg!(all(target_arch = "aarch64", not(miri))) {
            assert_eq!(best, SimdLevel::Neon);
        }
        if cfg!(all(
            target_arch = "wasm32",
            target_feature = "simd128",
            not(miri)
        )) {
            assert_eq!(best, SimdLevel::Simd128);
        }
    }
}
