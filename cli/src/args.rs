//! Flag parsing shared by every subcommand: the model flags every command takes.

use lexopt::{Arg, Parser, ValueExt};

use springwater::{Boundary, Params, SimdLevel, Surface};
use std::ffi::OsString;
use std::str::FromStr;

/// Whether this build can start threads: not on WebAssembly without the atomics feature
/// (`wasm32-wasip1`, `wasm32-unknown-unknown`), where `--threads` above 1 is an error.
const HAS_THREADS: bool = !cfg!(all(target_family = "wasm", not(target_feature = "atomics")));

/// A one-line error for the user; `main` prints it and exits non-zero.
pub type CliResult<T> = Result<T, String>;

/// A command-line argument that owns its text (so the parser can be used again).
#[derive(Debug, Clone, PartialEq)]
pub enum Flag {
    /// `--name`
    Long(String),
    /// `-c`
    Short(char),
    /// A positional value.
    Value(OsString),
}

/// The next argument, or `None` at the end.
pub fn next_flag(p: &mut Parser) -> CliResult<Option<Flag>> {
    Ok(match p.next().map_err(|e| e.to_string())? {
        None => None,
        Some(Arg::Long(l)) => Some(Flag::Long(l.to_string())),
        Some(Arg::Short(c)) => Some(Flag::Short(c)),
        Some(Arg::Value(v)) => Some(Flag::Value(v)),
    })
}

/// Flags that may be given more than once: each adds one more.
const REPEATABLE: [&str; 2] = ["--drop", "--floater"];

/// Refuses a flag given a second time in a command's arguments (a second `--load` or
/// `--size` silently won); [`REPEATABLE`] flags add up. A value that looks like a flag
/// counts as one (a file named `--size`).
pub fn each_once(args: &[std::ffi::OsString]) -> CliResult<()> {
    let mut seen: Vec<&str> = Vec::new();
    for arg in args {
        let Some(arg) = arg.to_str() else { continue };
        if arg == "--" {
            break;
        }
        let flag = arg.split('=').next().unwrap_or(arg);
        if !flag.starts_with("--") || REPEATABLE.contains(&flag) {
            continue;
        }
        if seen.contains(&flag) {
            return Err(format!(
                "{flag} is given twice; give it once (only --drop and --floater add up)"
            ));
        }
        seen.push(flag);
    }
    Ok(())
}

/// The most steps `--steps` takes: ten billion, hours on the smallest grid (more ran until
/// stopped, like a cap that is not there).
pub const MAX_STEPS: u64 = 10_000_000_000;

/// The model flags every subcommand takes.
#[derive(Debug, Clone)]
pub struct ModelArgs {
    pub params: Params,
    pub steps: u64,
    pub drops: Vec<[f32; 4]>,
    pub threads: Option<usize>,
}

impl Default for ModelArgs {
    fn default() -> Self {
        Self {
            params: Params::default(),
            steps: 100,
            drops: Vec::new(),
            threads: None,
        }
    }
}

impl ModelArgs {
    /// Consumes `arg` if it is a model flag. Returns false for flags it does not know.
    pub fn parse_flag(&mut self, arg: &Flag, p: &mut Parser) -> CliResult<bool> {
        let Flag::Long(name) = arg else {
            return Ok(false);
        };
        let params = &mut self.params;
        match name.as_str() {
            "size" => {
                let v = string(p, "--size")?;
                let (c, r) = v.split_once(['x', 'X']).ok_or_else(|| {
                    format!("--size expects COLSxROWS (for example 256x128), got '{v}'")
                })?;
                params.cols = number(c, "--size columns")?;
                params.rows = number(r, "--size rows")?;
            }
            "steps" => self.steps = ranged(value(p, "--steps")?, 0, MAX_STEPS, "--steps")?,
            "dt" => params.dt = value(p, "--dt")?,
            "mass" => params.mass = value(p, "--mass")?,
            "stiffness" => params.stiffness = value(p, "--stiffness")?,
            "viscosity" => params.viscosity = value(p, "--viscosity")?,
            "rest-ratio" => params.rest_ratio = value(p, "--rest-ratio")?,
            "spacing" => params.spacing = value(p, "--spacing")?,
            "boundary" => params.boundary = boundary(&string(p, "--boundary")?)?,
            "drop" => self
                .drops
                .push(list(&string(p, "--drop")?, "--drop COL,ROW,HEIGHT,RADIUS")?),
            "threads" => {
                let n: usize = value(p, "--threads")?;
                if n == 0 || n > 1024 {
                    return Err(format!("--threads must be between 1 and 1024, got {n}"));
                }
                // More threads than cores only slow the step (a 64x64 grid on 1000 threads
                // runs some 2,000 times slower than on 2) and change no result (the step is
                // bitwise the same for any thread count), so they are capped, with a word.
                if n > 1 && !HAS_THREADS {
                    return Err(format!(
                        "--threads {n}: this build (for {}) runs on one thread; use --threads 1",
                        std::env::consts::ARCH
                    ));
                }
                let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
                if n > cores {
                    eprintln!(
                        "springwater: warning: --threads {n} is more than the {cores} cores \
                         here; using {cores} (more threads than cores only slow the step)"
                    );
                }
                self.threads = Some(n.min(cores));
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// A validated surface with the drops applied.
    pub fn surface(&self) -> CliResult<Surface> {
        let mut s = Surface::new(self.params).map_err(|e| self.params_error(e))?;
        forced_level(&mut s)?;
        self.apply_drops(&mut s)?;
        Ok(s)
    }

    /// A refused model in the flags' words, with the limit for this grid where the library
    /// states it as a formula.
    fn params_error(&self, e: springwater::Error) -> String {
        let p = &self.params;
        let (name, value) = match &e {
            springwater::Error::InvalidParam { name, value, .. } => (*name, *value),
            springwater::Error::TimestepTooLarge { .. } => {
                // The default timestep, made too long by another flag: that flag is named.
                let d = Params::default();
                let changed: Vec<String> = [
                    ("--mass", p.mass, d.mass),
                    ("--stiffness", p.stiffness, d.stiffness),
                    ("--viscosity", p.viscosity, d.viscosity),
                    ("--spacing", p.spacing, d.spacing),
                    ("--rest-ratio", p.rest_ratio, d.rest_ratio),
                ]
                .iter()
                .filter(|(_, given, default)| given != default)
                .map(|(flag, given, _)| format!("{flag} {}", Short(*given)))
                .collect();
                if p.dt != d.dt || changed.is_empty() {
                    return lib_error(e);
                }
                return format!("{}: with the default --dt, {e}", changed.join(", "));
            }
            _ => return lib_error(e),
        };
        let across = p.cols.min(p.rows);
        match (name, p.boundary) {
            ("absorbing width", Boundary::Absorbing { width })
                if width == Boundary::ABSORBING_WIDTH =>
            {
                format!(
                    "--boundary absorbing: a {}x{} grid is too small for an absorbing frame; \
                     use a grid of at least 4x4 nodes",
                    p.cols, p.rows
                )
            }
            ("absorbing width", _) if across >= 4 => format!(
                "--boundary absorbing:{value}: a {}x{} grid takes an absorbing frame 1 to {} \
                 cells wide",
                p.cols,
                p.rows,
                (across - 2) / 2
            ),
            ("spacing", _) if value.is_finite() && value > 0.0 => format!(
                "--spacing {}: too large for a {}x{} grid, which may span at most 1e15 units \
                 (squared lengths must stay finite); use --spacing {} or less",
                short_f64(value),
                p.cols,
                p.rows,
                Short(largest_spacing(p.cols.max(p.rows)))
            ),
            _ => lib_error(e),
        }
    }

    /// Applies every `--drop` to `s`. The flag speaks grid steps (`COL,ROW` and `RADIUS`
    /// in cells, the contract of the command line); the library speaks world units, so
    /// they are multiplied by the spacing here. `HEIGHT` is a length in world units.
    pub fn apply_drops(&self, s: &mut Surface) -> CliResult<()> {
        let spacing = s.params().spacing;
        let (cols, rows) = (s.params().cols as f32, s.params().rows as f32);
        let [oc, or] = s.origin_cells().map(|o| o as f32);
        for &[col, row, height, radius] in &self.drops {
            // Past 11 radii a drop's bump is below the smallest f32: it changes nothing.
            let gap = |at: f32, origin: f32, n: f32| (origin - at).max(at - (origin + n - 1.0));
            let gap = gap(col, oc, cols)
                .max(0.0)
                .hypot(gap(row, or, rows).max(0.0));
            if gap > 11.0 * radius {
                return Err(format!(
                    "--drop {col},{row},{height},{radius}: wholly outside the {}x{} grid \
                     (columns {oc} to {}, rows {or} to {}), so it would change nothing; \
                     give a point on the grid or a larger radius",
                    cols,
                    rows,
                    oc + cols - 1.0,
                    or + rows - 1.0
                ));
            }
            s.drop_at(col * spacing, row * spacing, height, radius * spacing)
                .map_err(|e| format!("--drop {col},{row},{height},{radius}: {e}"))?;
        }
        Ok(())
    }

    /// Runs `f` on a rayon pool of `--threads` threads (the global pool without the flag).
    /// On a target without threads ([`HAS_THREADS`]), `--threads 1` runs `f` on the one
    /// thread there is (the flag refuses more).
    pub fn with_threads<T: Send>(&self, f: impl FnOnce() -> T + Send) -> CliResult<T> {
        match self.threads {
            None => Ok(f()),
            Some(_) if !HAS_THREADS => Ok(f()),
            Some(n) => rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map(|pool| pool.install(f))
                .map_err(|e| format!("cannot start {n} threads: {e}")),
        }
    }
}

/// `pinned`, `free`, `absorbing` or `absorbing:WIDTH`.
fn boundary(v: &str) -> CliResult<Boundary> {
    let expected = "--boundary expects 'pinned', 'free', 'absorbing' or 'absorbing:WIDTH'";
    Ok(match v.split_once(':') {
        None if v == "pinned" => Boundary::Pinned,
        None if v == "free" => Boundary::Free,
        None if v == "absorbing" => Boundary::absorbing(),
        Some(("absorbing", w)) => Boundary::Absorbing {
            width: w.parse().map_err(|_| {
                format!("{expected}; WIDTH must be a whole number of cells, got '{w}'")
            })?,
        },
        _ => return Err(format!("{expected}, got '{v}'")),
    })
}

/// A library error in the command line's words: the flag that set the refused value goes
/// first, with the value in its shortest form (the library names `Params` fields and
/// arguments, not flags, and carries values as `f64`).
pub fn lib_error(e: springwater::Error) -> String {
    use springwater::Error;
    let flag = match &e {
        Error::GridTooSmall { .. } | Error::GridTooLarge { .. } => Some("--size"),
        Error::TimestepTooLarge { .. } => Some("--dt"),
        Error::InvalidParam { name, .. } => match *name {
            "spacing" => Some("--spacing"),
            "mass" => Some("--mass"),
            "stiffness" => Some("--stiffness"),
            "viscosity" => Some("--viscosity"),
            "dt" => Some("--dt"),
            "rest_ratio" => Some("--rest-ratio"),
            "absorbing width" => Some("--boundary"),
            "look_at" => Some("--look-at"),
            "eye" => Some("--eye"),
            "patch_cells" => Some("--patch-cells"),
            "first_range" => Some("--first-range"),
            "depth" => Some("--depth"),
            "ior" => Some("--ior"),
            "field of view" => Some("--fov"),
            _ => None,
        },
        _ => None,
    };
    match (flag, &e) {
        // The camera's points: the value the library carries is a distance, not what the
        // user typed.
        (Some(flag @ ("--look-at" | "--eye")), Error::InvalidParam { expected, .. }) => {
            format!("{flag}: {expected}")
        }
        (
            Some(flag),
            Error::InvalidParam {
                value, expected, ..
            },
        ) => {
            format!("{flag} {}: {expected}", short_f64(*value))
        }
        (Some(flag), _) => format!("{flag}: {e}"),
        (None, _) => e.to_string(),
    }
}

/// A library value in the form the user typed it: an `f32`'s shortest round-trip form
/// where the value is an `f32` (`-0.1`, not `-0.10000000149011612`).
fn short_f64(v: f64) -> String {
    let single = v as f32;
    if f64::from(single) == v || !v.is_finite() {
        Short(single).to_string()
    } else {
        v.to_string()
    }
}

/// The next value as a UTF-8 string.
pub fn string(p: &mut Parser, flag: &str) -> CliResult<String> {
    let v: OsString = p.value().map_err(|_| format!("{flag} needs a value"))?;
    v.string()
        .map_err(|_| format!("{flag}: the value is not valid UTF-8"))
}

/// The next value parsed as `T`.
pub fn value<T: FromStr>(p: &mut Parser, flag: &str) -> CliResult<T> {
    let v = string(p, flag)?;
    number(&v, flag)
}

/// Parses a number, naming the flag in the error.
pub fn number<T: FromStr>(v: &str, what: &str) -> CliResult<T> {
    v.trim().parse().map_err(|_| {
        let kind = match std::any::type_name::<T>() {
            "f32" | "f64" => "number",
            _ => "whole number",
        };
        format!("{what}: '{v}' is not a valid {kind}")
    })
}

/// Parses `N` comma-separated numbers.
pub fn list<const N: usize>(v: &str, what: &str) -> CliResult<[f32; N]> {
    let parts: Vec<&str> = v.split(',').collect();
    if parts.len() != N {
        return Err(format!(
            "{what} expects {N} comma-separated numbers, got '{v}'"
        ));
    }
    let mut out = [0.0; N];
    for (o, s) in out.iter_mut().zip(parts) {
        let v: f32 = number(s, what)?;
        *o = v;
        if !v.is_finite() {
            return Err(format!("{what}: '{s}' is not a finite number"));
        }
    }
    Ok(out)
}

/// The error for a flag no subcommand knows.
pub fn unexpected(arg: Flag, command: &str) -> String {
    match arg {
        Flag::Long(l) => format!("{command}: unknown flag --{l} (see springwater --help)"),
        Flag::Short(c) => format!("{command}: unknown flag -{c} (see springwater --help)"),
        Flag::Value(v) => format!("{command}: unexpected argument '{}'", v.to_string_lossy()),
    }
}

/// An `f32` in its shortest round-trip form, in exponent notation where that is shorter
/// (`2.4915726e-37`, not 37 zeros and the digits; `0.25`, not `2.5e-1`).
#[derive(Debug, Clone, Copy)]
pub struct Short(pub f32);

impl std::fmt::Display for Short {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let plain = self.0.to_string();
        let exponent = format!("{:e}", self.0);
        f.write_str(if exponent.len() < plain.len() {
            &exponent
        } else {
            &plain
        })
    }
}

/// The largest spacing a grid `nodes` wide takes: its span at most 1e15 units, as the
/// library checks it (in f64), so the value suggested is one that is accepted (1e15 / 15
/// rounded to f32 is just past it).
fn largest_spacing(nodes: usize) -> f32 {
    let cells = (nodes.max(2) - 1) as f64;
    let mut most = (1e15 / cells) as f32;
    while f64::from(most) * cells > 1e15 {
        most = most.next_down();
    }
    most
}

/// `n` and its noun, singular or plural: "1 frame", "3 frames".
pub fn count(n: impl Into<u64>, noun: &str) -> String {
    let n = n.into();
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// `v` if it is within `lo..=hi`; the error names the flag, the value and the range.
pub fn ranged<T: PartialOrd + std::fmt::Display>(v: T, lo: T, hi: T, flag: &str) -> CliResult<T> {
    if v < lo || v > hi {
        Err(format!("{flag} must be between {lo} and {hi}, got {v}"))
    } else {
        Ok(v)
    }
}

/// `v` if it is finite and above zero.
pub fn positive(v: f32, flag: &str) -> CliResult<f32> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!(
            "{flag} must be a finite number > 0, got {}",
            Short(v)
        ))
    }
}

/// Runs `s` at the level `SPRINGWATER_SIMD` names, if it is set and not empty (clamped to
/// what the CPU has): the command line's way to force a level, which the library itself
/// never reads.
pub fn forced_level(s: &mut Surface) -> CliResult<()> {
    s.set_simd_level(SimdLevel::from_env().map_err(lib_error)?);
    Ok(())
}
