// Builds the package's two WebAssembly files from the C ABI crate (springwater-ffi) with
// cargo: the SIMD128 build (`+simd128`) and the portable one, into wasm/.
//   node build.mjs            (npm run build)
// Needs the Rust target: rustup target add wasm32-unknown-unknown. The builds go to
// ../target/web (CARGO_TARGET_DIR overrides), release, one codegen unit, LTO, stripped.
import { execFileSync } from "node:child_process";
import { copyFileSync, mkdirSync, statSync } from "node:fs";
import { fileURLToPath } from "node:url";

const here = fileURLToPath(new URL(".", import.meta.url));
const root = fileURLToPath(new URL("..", import.meta.url));
const base = process.env.CARGO_TARGET_DIR ?? `${root}target/web`;
mkdirSync(`${here}wasm`, { recursive: true });

for (const [name, flags] of [["simd128", "-C target-feature=+simd128"], ["portable", ""]]) {
  const targetDir = `${base}/${name}`;
  execFileSync(
    "cargo",
    ["build", "--release", "--locked", "-p", "springwater-ffi", "--target", "wasm32-unknown-unknown"],
    {
      cwd: root,
      stdio: "inherit",
      env: {
        ...process.env,
        CARGO_TARGET_DIR: targetDir,
        RUSTFLAGS: flags,
        CARGO_PROFILE_RELEASE_DEBUG: "0",
        CARGO_PROFILE_RELEASE_STRIP: "true",
        CARGO_PROFILE_RELEASE_LTO: "true",
        CARGO_PROFILE_RELEASE_CODEGEN_UNITS: "1",
      },
    },
  );
  const out = `${here}wasm/springwater-${name}.wasm`;
  copyFileSync(`${targetDir}/wasm32-unknown-unknown/release/springwater_ffi.wasm`, out);
  console.log(`wasm/springwater-${name}.wasm: ${statSync(out).size} bytes`);
}
