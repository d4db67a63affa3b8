// Packs the package (npm pack), installs the tarball into an empty folder and runs
// test/installed.mjs there, as a user of the published package would; prints the packed
// size against the 400 KB target.
//   node test/pack.mjs        (npm run test:pack; after npm run build)
import { execFileSync } from "node:child_process";
import { copyFileSync, mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { fileURLToPath } from "node:url";

const web = fileURLToPath(new URL("..", import.meta.url));
const [packed] = JSON.parse(execFileSync("npm", ["pack", "--json"], { cwd: web, encoding: "utf8" }));
const names = packed.files.map((f) => f.path).sort();
console.log(`${packed.filename}: ${(packed.size / 1000).toFixed(1)} kB packed (target 400 kB), ${names.join(", ")}`);
for (const want of ["springwater.js", "abi.js", "springwater.d.ts", "wasm/springwater-simd128.wasm", "wasm/springwater-portable.wasm"]) {
  if (!names.includes(want)) throw new Error(`the tarball has no ${want}`);
}
const dir = mkdtempSync(join(tmpdir(), "springwater-pack-"));
try {
  writeFileSync(join(dir, "package.json"), JSON.stringify({ name: "client", private: true, type: "module" }));
  execFileSync("npm", ["install", "--no-audit", "--no-fund", "--offline", join(web, packed.filename)], { cwd: dir, stdio: "inherit" });
  copyFileSync(join(web, "test/installed.mjs"), join(dir, "check.mjs"));
  execFileSync(process.execPath, ["check.mjs"], { cwd: dir, stdio: "inherit" });
} finally {
  rmSync(dir, { recursive: true, force: true });
}
