// Compiled by `tsc` (npm run typecheck), never run: the declarations as a client uses them.
import { load, type Floater, type Springwater } from "springwater";

async function frame(): Promise<bigint> {
  const sw: Springwater = await load();
  const level: "simd128" | "portable" = sw.simd;
  using water = new sw.WaterSurface(64, 64);
  const open = new sw.WaterSurface({ cols: 32, rows: 32, boundary: "absorbing" });
  open.free();
  const steps: number = water.advance(1 / 60);
  water.step(2);
  water.dropAt(32, 32, 1, 3);
  const h: number = water.heightAt(10, 10);
  const out = new Float32Array(3 * water.nodeCount);
  water.writePositions(out);
  const positions: Float32Array = water.positions();
  const uvs: Float32Array = water.refractionUvs({ eye: [32, 40, -30], depth: 8 });
  if (water.updateLod(32, 40, -30)) {
    const indices: Uint32Array = water.lodIndices();
    void indices;
  }
  const ball: Floater = sw.sphere(1, 2, [20, 0, 20]);
  const id: number = water.addFloater(ball);
  water.pushFloater(id, [1, 0, 0]);
  const hull = new sw.Hull([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]);
  const boat = hull.floater(1, [30, 0, 30]);
  const { force, torque } = water.bodyForces(boat, 1 / 60);
  using rain = new sw.Rain(10, 7n);
  water.advance(1 / 60, [rain]);
  let buf: Uint8Array = new Uint8Array(0);
  buf = water.saveInto(buf);
  water.restore(buf);
  void [level, steps, h, positions, uvs, force, torque];
  return water.stateHash();
}
void frame;
