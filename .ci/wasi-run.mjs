// Runs a wasm32-wasip1 program under Node's WASI (cargo's runner for that target):
//   node --no-warnings --single-threaded .ci/wasi-run.mjs program.wasm [args...]
// --single-threaded: Node 20's background threads crash its exit now and then (SIGSEGV after
// the program has finished; 1 run in 3 for the parity test) when a program's memory is
// large; without them 28 runs in 28 exited cleanly.
// The program sees its arguments, its environment, the current directory and the whole
// file system for absolute paths ("/", listed after "."; listed first, absolute paths
// failed with ENOENT under Node 20). Its exit code is this process's.
import { readFile } from "node:fs/promises";
import { WASI } from "node:wasi";
import process from "node:process";

const [program, ...args] = process.argv.slice(2);
const wasi = new WASI({
  version: "preview1",
  args: [program, ...args],
  env: process.env,
  preopens: { ".": process.cwd(), "/": "/" },
  returnOnExit: true,
});
const module = await WebAssembly.compile(await readFile(program));
const instance = await WebAssembly.instantiate(module, wasi.getImportObject());
process.exit(wasi.start(instance));
