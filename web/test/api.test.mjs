// The package's API under Node, on both builds: refusals, views, snapshots, bodies,
// disturbances and memory. Run with `node --test test/` (npm test) after `npm run build`.
import { test } from "node:test";
import assert from "node:assert/strict";
import { load, hasSimd128 } from "springwater";

const builds = ["simd128", "portable"];

test("load() picks SIMD128 where the engine validates it, and each build says what it runs", async () => {
  assert.equal(hasSimd128(), true, "Node 18+ runs SIMD128");
  assert.equal((await load()).simd, "simd128");
  for (const simd of builds) {
    const sw = await load({ simd });
    assert.equal(sw.simd, simd);
    const water = new sw.WaterSurface(16, 16);
    assert.equal(water.simdLevel, simd);
    water.free();
  }
  await assert.rejects(load({ simd: "avx2" }), /expected "simd128" or "portable"/);
});

for (const simd of builds) {
  test(`${simd}: the two builds give the same bits`, async () => {
    const hashes = [];
    for (const build of builds) {
      const sw = await load({ simd: build });
      const water = new sw.WaterSurface(40, 30);
      water.dropAt(12, 10, 1, 3);
      water.advance(0.5);
      hashes.push(water.stateHash());
      water.free();
    }
    assert.equal(hashes[0], hashes[1]);
  });

  test(`${simd}: every refusal throws the library's message and changes nothing`, async () => {
    const sw = await load({ simd });
    const water = new sw.WaterSurface(32, 24);
    water.dropAt(10, 10, 0.8, 3);
    water.step(3);
    const ball = water.addFloater(sw.sphere(1, 2, [16, 0, 12]));
    const hash = water.stateHash();
    const snapshot = water.save();

    // Each refused call: an Error whose code names the library's status, whose message is
    // the library's (non-empty, naming the problem), and the state unchanged.
    const refused = (what, f, code, pattern) => {
      assert.throws(f, (e) => {
        assert.ok(e instanceof Error, `${what}: not an Error`);
        assert.equal(e.code, code, `${what}: ${e.message}`);
        assert.match(e.message, pattern, what);
        return true;
      });
      assert.equal(water.stateHash(), hash, `${what} changed the state`);
    };
    refused("a grid too small", () => new sw.WaterSurface(1, 1), "SW_ERROR_INVALID_ARGUMENT", /too small/);
    refused("a negative spacing", () => new sw.WaterSurface({ cols: 8, rows: 8, spacing: -1 }), "SW_ERROR_INVALID_ARGUMENT", /spacing/);
    refused("a drop at NaN", () => water.dropAt(NaN, 3, 1, 1), "SW_ERROR_INVALID_ARGUMENT", /drop x/);
    refused("a drop of radius 0", () => water.dropAt(3, 3, 1, 0), "SW_ERROR_INVALID_ARGUMENT", /radius/);
    refused("a negative frame time", () => water.advance(-1), "SW_ERROR_INVALID_ARGUMENT", /frame/);
    refused("an infinite force", () => water.addForceAt(5, 5, Infinity, 0, 0), "SW_ERROR_INVALID_ARGUMENT", /force|fx/);
    refused("a step cap of 0", () => water.setStepCap(0), "SW_ERROR_INVALID_ARGUMENT", /step/);
    refused("a height off the grid", () => water.heightAt(-5, 100), "SW_ERROR_OUTSIDE_GRID", /outside/);
    refused("a sample off the grid", () => water.sample([1, 1, 500, 1]), "SW_ERROR_OUTSIDE_GRID", /outside/);
    refused("a positions buffer too short", () => water.writePositions(new Float32Array(10)), "SW_ERROR_BUFFER_TOO_SMALL", /\d/);
    refused("an index of refraction of 0", () => water.refractionUvs({ eye: [1, 5, 1], ior: 0 }), "SW_ERROR_INVALID_ARGUMENT", /ior|refraction/);
    refused("an LOD patch of 3 cells", () => water.setLodParams({ patchCells: 3 }), "SW_ERROR_INVALID_ARGUMENT", /patch/);
    refused("following NaN", () => water.follow(NaN, 0), "SW_ERROR_INVALID_ARGUMENT", /NaN/);
    refused("a truncated snapshot", () => water.restore(snapshot.subarray(0, 100)), "SW_ERROR_SNAPSHOT", /snapshot|truncated|short/i);
    const corrupt = snapshot.slice();
    corrupt[corrupt.length >> 1] ^= 0xff;
    refused("a corrupted snapshot", () => water.restore(corrupt), "SW_ERROR_SNAPSHOT", /checksum|corrupt|crc/i);
    refused("loading garbage", () => sw.WaterSurface.load(new Uint8Array([1, 2, 3])), "SW_ERROR_SNAPSHOT", /snapshot|truncated|short/i);
    refused("a body nobody added", () => water.floater(999), "SW_ERROR_NO_SUCH_FLOATER", /999/);
    refused("removing a body nobody added", () => water.removeFloater(999), "SW_ERROR_NO_SUCH_FLOATER", /999/);
    refused("a body of negative mass", () => water.addFloater(sw.sphere(1, -2, [5, 0, 5])), "SW_ERROR_INVALID_ARGUMENT", /mass/);
    refused("a body outside the pool", () => water.addFloater(sw.sphere(1, 2, [1e20, 0, 5])), "SW_ERROR_INVALID_ARGUMENT", /position/);
    refused("an orientation not of unit length", () => water.setFloater(ball, { orientation: [0, 0, 0, 2] }), "SW_ERROR_INVALID_ARGUMENT", /orientation/);
    refused("a NaN push", () => water.pushFloater(ball, [NaN, 0, 0]), "SW_ERROR_INVALID_ARGUMENT", /push|force/);
    refused("a negative gravity", () => (water.buoyancy = { gravity: -1 }), "SW_ERROR_INVALID_ARGUMENT", /gravity/);
    refused("forces over a negative tick", () => water.bodyForces(sw.sphere(1, 2, [16, 0, 12]), -1), "SW_ERROR_INVALID_ARGUMENT", /seconds/);
    refused("an open hull", () => new sw.Hull([0, 0, 0, 1, 0, 0, 0, 1, 0], [0, 1, 2]), "SW_ERROR_INVALID_ARGUMENT", /hull|closed|edge/i);
    refused("rain at a negative rate", () => new sw.Rain(-1, 1), "SW_ERROR_INVALID_ARGUMENT", /rain rate/);
    refused("a wake of one point", () => new sw.Wake([[3, 3], [3, 3]]), "SW_ERROR_INVALID_ARGUMENT", /wake path/);
    const rain = new sw.Rain(10, 1);
    rain.free();
    refused("advancing with rain already freed", () => water.advance(0.1, [rain]), "SW_ERROR_INVALID_HANDLE", /not a live rain or wake/);

    assert.throws(() => new sw.WaterSurface({ cols: 8, rows: 8, boundary: "sticky" }), /boundary is sticky/);
    assert.throws(() => new sw.WaterSurface({ cols: 8, rows: 8, colour: 1 }), /unknown parameter colour/);

    water.free();
    water.free(); // twice is harmless
    for (const call of [() => water.heightAt(5, 5), () => water.positions(), () => water.restore(snapshot), () => water.stateHash()]) {
      assert.throws(call, (e) => e.code === "SW_ERROR_INVALID_HANDLE" && /not a live surface/.test(e.message));
    }
  });

  test(`${simd}: views are over wasm memory, written by each call, and survive its growth`, async () => {
    const sw = await load({ simd });
    const water = new sw.WaterSurface(64, 48);
    water.dropAt(20, 20, 1, 4);
    water.step(10);
    const copy = new Float32Array(3 * water.nodeCount);
    water.writePositions(copy);
    const before = water.positions();
    assert.deepEqual(before, copy);
    assert.ok(before.buffer === sw.lib.memory.buffer, "positions() is a view over wasm memory");

    const bytes = sw.memoryBytes;
    const big = new sw.WaterSurface(700, 700); // grows the memory
    assert.ok(sw.memoryBytes > bytes, "the big surface grew the memory");
    assert.equal(before.length, 0, "a view kept across growth is detached (asked again below)");

    // Each view checked as it comes: asking for the next one may grow the memory again.
    for (const get of [() => water.positions(), () => water.normals(), () => water.refractionUvs({ eye: [30, 40, -20] })]) {
      const view = get();
      assert.ok(view.buffer === sw.lib.memory.buffer, "a view over the current memory");
      assert.ok(view.length > 0 && view.every(Number.isFinite));
    }
    assert.deepEqual(water.positions(), copy);
    assert.equal(water.vertices({ eye: [30, 40, -20] }).length, 8 * water.nodeCount);
    water.step(5);
    water.writePositions(copy);
    assert.deepEqual(water.positions(), copy, "a new view shows the new state");
    assert.equal(water.updateLod(30, 40, -20), true);
    const indices = water.lodIndices();
    assert.ok(indices.length > 0 && indices.length % 3 === 0);
    assert.ok(Math.max(...indices) < water.nodeCount);
    big.free();
    water.free();
  });

  test(`${simd}: saveInto reuses its buffer; restore and load give the same state`, async () => {
    const sw = await load({ simd });
    const water = new sw.WaterSurface(48, 32);
    water.dropAt(20, 12, 1, 3);
    water.addFloater(sw.box([1.5, 0.5, 1], 3, [30, 0, 16]));
    water.advance(0.25);
    const hash = water.stateHash();
    const buf = new Uint8Array(1 << 20);
    const saved = water.saveInto(buf);
    assert.equal(saved.buffer, buf.buffer, "saved into the given buffer");
    assert.equal(water.saveInto(buf).buffer, buf.buffer);
    const small = water.saveInto(new Uint8Array(4));
    assert.deepEqual(small, saved, "a buffer too small: a new one, the same bytes");
    water.advance(0.5);
    assert.notEqual(water.stateHash(), hash);
    water.restore(saved);
    assert.equal(water.stateHash(), hash);
    const loaded = sw.WaterSurface.load(saved);
    assert.equal(loaded.stateHash(), hash);
    assert.equal(loaded.floaterCount, 1);
    loaded.advance(0.5);
    water.advance(0.5);
    assert.equal(loaded.stateHash(), water.stateHash());
    loaded[Symbol.dispose]();
    water.free();
  });

  test(`${simd}: bodies float, hulls come from arrays, bodyForces pushes back on the water`, async () => {
    const sw = await load({ simd });
    const water = new sw.WaterSurface(64, 64);
    const hull = new sw.Hull(
      [2, 0, 0, -2, 0, 0, 0, 0.8, 0, 0, -0.8, 0, 0, 0, 1, 0, 0, -1],
      [0, 2, 4, 1, 4, 2, 0, 4, 3, 0, 5, 2, 1, 3, 4, 1, 2, 5, 0, 3, 5, 1, 5, 3],
    );
    assert.ok(Math.abs(hull.volume - (8 * 2 * 0.8 * 1) / 6) < 1e-5, `volume ${hull.volume}`);
    const boat = water.addFloater(hull.floater(1, [32, 1, 32]));
    hull.free();
    hull.free();
    const ball = water.addFloater(sw.sphere(1, 1, [16, 2, 16]));
    assert.deepEqual(water.floaterIds(), [boat, ball]);
    water.pushFloaterAt(boat, [0, 0, 5], [33, 0, 32]);
    water.advance(2);
    const b = water.floater(boat);
    assert.equal(b.shape, "hull");
    assert.ok(b.position[1] < 0.8 && b.position[1] > -0.8, `the boat floats: y ${b.position[1]}`);
    assert.ok(Math.abs(b.orientation[1]) > 1e-4, "the push at a point turned the boat");
    water.setFloater(ball, { velocity: [5, 0, 0] });
    assert.deepEqual(water.floater(ball).velocity, [5, 0, 0]);
    water.removeFloater(ball);
    assert.equal(water.floaterCount, 1);

    const hash = water.stateHash();
    const { force, torque } = water.bodyForces(sw.sphere(1, 1, [40, -0.5, 40]), 1 / 60);
    assert.ok(force[1] > 0, `buoyancy pushes up: ${force}`);
    assert.equal(torque.length, 3);
    assert.notEqual(water.stateHash(), hash, "the water got the opposite");
    water.free();
  });

  test(`${simd}: rain and wakes disturb the water, the same drops for the same seed`, async () => {
    const sw = await load({ simd });
    const hashes = [];
    for (let run = 0; run < 2; run++) {
      const water = new sw.WaterSurface(48, 48);
      const rain = new sw.Rain(30, 5);
      const wake = new sw.Wake([[10, 10], [38, 10], [38, 38], [10, 38]], { speed: 20 });
      for (let frame = 0; frame < 30; frame++) water.advance(1 / 60, [rain, wake]);
      assert.ok(water.energy.total > 0);
      rain.rate = 0;
      water.advance(0.1, [rain]);
      hashes.push(water.stateHash());
      rain.free();
      wake.free();
      water.free();
    }
    assert.equal(hashes[0], hashes[1]);
  });

  test(`${simd}: no leak over 10,000 create/free cycles (the memory stays the same size)`, async () => {
    const sw = await load({ simd });
    const cycle = () => {
      const water = new sw.WaterSurface(32, 32);
      water.dropAt(16, 16, 0.5, 2);
      water.step(1);
      water.positions();
      water.saveInto();
      water.addFloater(sw.sphere(1, 1, [10, 0, 10]));
      water.free();
    };
    for (let i = 0; i < 200; i++) cycle();
    const bytes = sw.memoryBytes;
    for (let i = 0; i < 10000; i++) cycle();
    assert.equal(sw.memoryBytes, bytes);
  });
}
