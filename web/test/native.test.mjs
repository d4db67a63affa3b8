// The package against the native library: `springwater simulate`'s CSV and snapshot
// (the command line, built by `cargo build --release -p springwater-cli`; SPRINGWATER_CLI
// names another binary), and the state hash of test/scene.json, which
// ffi/tests/web_scene.rs checks with the Rust API.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { existsSync, mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { fileURLToPath } from "node:url";
import { load } from "springwater";
import { runScene } from "./scene.mjs";

const cli = process.env.SPRINGWATER_CLI ?? fileURLToPath(new URL("../../target/release/springwater", import.meta.url));
const scene = JSON.parse(readFileSync(new URL("./scene.json", import.meta.url), "utf8"));

// The command line's run: 60 steps of a 48 × 40 pool after two drops (cells = world units
// at the default spacing of 1), its CSV parsed and its snapshot's bytes.
function native() {
  assert.ok(existsSync(cli), `${cli} is missing: cargo build --release -p springwater-cli`);
  const dir = mkdtempSync(join(tmpdir(), "springwater-web-"));
  try {
    execFileSync(cli, [
      "simulate", "--size", "48x40", "--steps", "60", "--threads", "1",
      "--drop", "20,15,1,3", "--drop", "30.5,25,-0.5,2",
      "--csv", join(dir, "out.csv"), "--save", join(dir, "out.snap"),
    ], { stdio: "pipe" });
    const rows = readFileSync(join(dir, "out.csv"), "utf8").trim().split("\n");
    assert.equal(rows[0], "col,row,x,y,z");
    return { rows: rows.slice(1).map((r) => r.split(",")), snapshot: readFileSync(join(dir, "out.snap")) };
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

const expected = native();

for (const simd of ["simd128", "portable"]) {
  test(`${simd}: positions equal springwater simulate --csv bit for bit`, async () => {
    const sw = await load({ simd });
    const water = new sw.WaterSurface(48, 40);
    water.dropAt(20, 15, 1, 3);
    water.dropAt(30.5, 25, -0.5, 2);
    water.step(60);
    const xyz = water.positions();
    assert.equal(expected.rows.length, water.nodeCount);
    let moved = 0;
    for (const [col, row, x, y, z] of expected.rows) {
      const i = 3 * (Number(row) * 48 + Number(col));
      // The CSV prints each f32 as the shortest decimal that reads back as the same f32.
      const want = [x, y, z].map((s) => Math.fround(Number(s)));
      const got = [xyz[i], xyz[i + 1], xyz[i + 2]];
      assert.ok(
        got.every((v, k) => Object.is(v, want[k])),
        `node ${col},${row}: ${got} here, ${want} natively`,
      );
      if (want[1] !== 0) moved++;
    }
    assert.ok(moved > 100, "the drops moved the water");
    water.free();
  });

  test(`${simd}: the same state as the command line's snapshot, byte for byte and by hash`, async () => {
    const sw = await load({ simd });
    const water = new sw.WaterSurface(48, 40);
    water.dropAt(20, 15, 1, 3);
    water.dropAt(30.5, 25, -0.5, 2);
    water.step(60);
    assert.deepEqual(Buffer.from(water.saveInto()), expected.snapshot);
    const restored = sw.WaterSurface.load(expected.snapshot);
    assert.equal(restored.stateHash(), water.stateHash());
    restored.free();
    water.free();
  });

  test(`${simd}: the scripted scene (drops, three bodies, rain, a wake) reaches the native state hash`, async () => {
    const sw = await load({ simd });
    assert.match(scene.stateHash, /^[1-9][0-9]*$/, "scene.json has a blessed hash");
    const hash = runScene(sw, scene);
    assert.equal(hash.toString(), scene.stateHash);
  });
}
