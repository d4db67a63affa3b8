// A client written from DESIGN §5's JavaScript contract alone, run by test/pack.mjs in an
// empty folder where the packed tarball was installed: `import { load } from "springwater"`.
import assert from "node:assert/strict";
import { load } from "springwater";

const sw = await load();
assert.ok(sw.simd === "simd128" || sw.simd === "portable");
const water = new sw.WaterSurface(64, 48);
water.dropAt(20, 20, 1, 3);
const steps = water.advance(0.5);
assert.ok(steps > 0);
water.step(3);
const h = water.heightAt(22, 20);
assert.equal(typeof h, "number");
const xyz = new Float32Array(3 * 64 * 48);
water.writePositions(xyz);
assert.equal(xyz[3 * (20 * 64 + 20) + 1], water.heightAt(20, 20));
const hash = water.stateHash();
assert.equal(typeof hash, "bigint");
const saved = water.saveInto(new Uint8Array(1 << 20));
water.step(10);
assert.notEqual(water.stateHash(), hash);
water.restore(saved);
assert.equal(water.stateHash(), hash);
assert.throws(() => water.dropAt(NaN, 1, 1, 1), (e) => e instanceof Error && /drop x/.test(e.message));
assert.equal(water.stateHash(), hash, "a refused call changed nothing");
water.free();
water.free();
for (const simd of ["simd128", "portable"]) {
  const other = await load({ simd });
  const w = new other.WaterSurface(64, 48);
  w.dropAt(20, 20, 1, 3);
  w.advance(0.5);
  w.step(3);
  assert.equal(w.stateHash(), hash, `${simd}: the same bits`);
  w.free();
}
console.log(`the installed package works (${sw.simd}, state hash ${hash})`);
