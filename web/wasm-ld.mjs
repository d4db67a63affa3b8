#!/usr/bin/env node
// The linker of the package's builds (build.mjs names it): Rust's own wasm-ld (rust-lld),
// run with the module's exports cut to the sw_* functions springwater.js and abi.js name.
// The C ABI exports every function of its header; the package's JavaScript calls fewer, and the
// linker then leaves out what only the others reach (the spring, mass and pin edits, the
// job system's hook, ...). The compiler's output is not changed: the linker only drops
// functions nothing calls.
//   SPRINGWATER_LLD: rust-lld's path (build.mjs finds it in the toolchain's sysroot)
import { spawnSync } from "node:child_process";
import { readFileSync } from "node:fs";

const used = new Set(
  ["./springwater.js", "./abi.js"].flatMap((file) =>
    readFileSync(new URL(file, import.meta.url), "utf8").match(/\bsw_[a-z0-9_]+/g),
  ),
);
// rustc may pass its arguments in a response file (@path, one argument a line).
const given = process.argv.slice(2).flatMap((a) =>
  a.startsWith("@") ? readFileSync(a.slice(1), "utf8").split("\n").filter((l) => l !== "") : [a],
);
const args = [];
let dropped = 0;
for (let i = 0; i < given.length; i++) {
  const a = given[i];
  if (a === "-flavor") {
    i++; // added below
    continue;
  }
  const name = a.startsWith("--export=") ? a.slice(9) : a === "--export" ? given[i + 1] : null;
  if (name?.startsWith("sw_") && !used.has(name)) {
    if (a === "--export") i++;
    dropped++;
    continue;
  }
  args.push(a);
}
const lld = process.env.SPRINGWATER_LLD;
if (!lld) throw new Error("SPRINGWATER_LLD is not set (build.mjs sets it)");
const run = spawnSync(lld, ["-flavor", "wasm", ...args], { stdio: "inherit" });
if (run.error) throw run.error;
if (run.status === 0 && process.env.SPRINGWATER_LINK_VERBOSE) {
  console.error(`wasm-ld.mjs: ${dropped} exports of the C ABI left out`);
}
process.exit(run.status ?? 1);
