// Builds the package's two WebAssembly files from the C ABI crate (springwater-ffi) with
// cargo: the SIMD128 build (`+simd128`) and the portable one, into wasm/.
//   node build.mjs            (npm run build)
// Needs the Rust target: rustup target add wasm32-wasip1. The builds go to ../target/web
// (CARGO_TARGET_DIR overrides), release, one codegen unit, LTO, stripped (no custom
// sections are left; wasm32 aborts on panic by default), linked by wasm-ld.mjs: Rust's own
// rust-lld with the exports cut to the functions springwater.js calls. The SIMD128 build
// at opt-level 3; the portable one, the fallback for engines without SIMD128, at "s": 8%
// smaller gzipped than at 3 for 0.8x the step rate ("z": 10%, 0.47x). Both with LLVM's
// inliner held to small functions, and the SIMD128 build without runtime unrolling or
// auto-vectorisation (the options below), at the same step rates: the modules about 11%
// and 3% smaller gzipped (209 and 202 kB, docs/performance.md). Measured and not used for
// the SIMD128 build: opt-level "s" (0.48x the step rate), and with the options above
// opt-level 2 (6 kB smaller gzipped), #[inline] functions inlined only below 50 (5 kB), or
// full unrolling below a cost of 150 with no non-trivial unswitching (1.7 kB), each at
// 0.72x the rate; for both, wasm-opt -O2, -O3 or -Os from npm's binaryen (within 2%, up to
// 8 minutes a module) (docs/performance.md).
//
// Why wasm32-wasip1 and not wasm32-unknown-unknown: the library's exponentials (drops,
// wakes) call the C library's expf, and wasm32-unknown-unknown has none, so Rust's own
// port stands in and rounds some results differently: its heights differ from the native
// ones in the last bits. wasm32-wasip1 links wasi-libc, whose expf gives the native bits
// (CI checks the command line's CSVs across x86-64, AArch64 and wasm32-wasip1). The module
// imports five WASI functions (random bytes, environment, stderr, exit), which
// springwater.js provides in a few lines, in browsers too.
import { execFileSync } from "node:child_process";
import { join } from "node:path";
import { copyFileSync, mkdirSync, statSync } from "node:fs";
import { fileURLToPath } from "node:url";

const here = fileURLToPath(new URL(".", import.meta.url));
const root = fileURLToPath(new URL("..", import.meta.url));
const base = process.env.CARGO_TARGET_DIR ?? `${root}target/web`;
mkdirSync(`${here}wasm`, { recursive: true });
// rust-lld of the toolchain that builds (rustup's shim picks the same one for cargo).
const rustc = (args) => execFileSync("rustc", args, { cwd: root, encoding: "utf8" });
const host = rustc(["-vV"]).match(/^host: (.+)$/m)[1];
const lld = join(rustc(["--print", "sysroot"]).trim(), "lib", "rustlib", host, "bin", "rust-lld");

// LLVM's options (docs/performance.md). Both builds: inline a function only below a cost
// of 25 (LLVM's default at opt-level 3: 250; lower at "s"); the row kernels' lane
// operations are #[inline(always)], which this does not touch. The SIMD128 build also: no
// loop unrolled by a count known only at run time, no auto-vectorisation (the kernels are
// vectorised by hand). The portable build also inlines functions Rust marks #[inline] only
// below 50 (325): in the SIMD128 build that costs the row kernels a quarter of their rate.
const inlining = "-C llvm-args=-inline-threshold=25 ";
const loops = "-C llvm-args=-unroll-runtime=false -C no-vectorize-loops -C no-vectorize-slp ";
for (const [name, flags, opt] of [
  ["simd128", `-C target-feature=+simd128 ${inlining}${loops}`, "3"],
  ["portable", `${inlining}-C llvm-args=-inlinehint-threshold=50 `, "s"],
]) {
  const targetDir = `${base}/${name}`;
  execFileSync(
    "cargo",
    ["build", "--release", "--locked", "-p", "springwater-ffi", "--target", "wasm32-wasip1"],
    {
      cwd: root,
      stdio: "inherit",
      env: {
        ...process.env,
        CARGO_TARGET_DIR: targetDir,
        RUSTFLAGS: `${flags}-C linker-flavor=wasm-ld`,
        CARGO_TARGET_WASM32_WASIP1_LINKER: `${here}wasm-ld.mjs`,
        SPRINGWATER_LLD: lld,
        CARGO_PROFILE_RELEASE_OPT_LEVEL: opt,
        CARGO_PROFILE_RELEASE_DEBUG: "0",
        CARGO_PROFILE_RELEASE_STRIP: "true",
        CARGO_PROFILE_RELEASE_LTO: "true",
        CARGO_PROFILE_RELEASE_CODEGEN_UNITS: "1",
      },
    },
  );
  const out = `${here}wasm/springwater-${name}.wasm`;
  copyFileSync(`${targetDir}/wasm32-wasip1/release/springwater_ffi.wasm`, out);
  console.log(`wasm/springwater-${name}.wasm: ${statSync(out).size} bytes`);
}
