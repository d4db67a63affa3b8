// Runs the scripted scene of scene.json with the package (`sw` from load()); returns the
// final state hash. ffi/tests/web_scene.rs runs the same scene with the Rust API.
export function runScene(sw, scene) {
  const water = new sw.WaterSurface(scene.cols, scene.rows);
  for (const [x, z, height, radius] of scene.drops) water.dropAt(x, z, height, radius);
  const s = scene.sphere;
  water.addFloater({ ...sw.sphere(s.radius, s.mass, s.position), velocity: s.velocity });
  const b = scene.box;
  water.addFloater(sw.box(b.halfExtents, b.mass, b.position));
  const h = scene.hull;
  const hull = new sw.Hull(h.vertices, h.triangles);
  const body = hull.floater(h.mass, h.position);
  body.angularVelocity = h.angularVelocity;
  water.addFloater(body);
  hull.free();
  const r = scene.rain;
  const rain = new sw.Rain(r.rate, r.seed, { radius: r.radius, depth: r.depth });
  const w = scene.wake;
  const wake = new sw.Wake(w.path, { speed: w.speed, radius: w.radius, strength: w.strength });
  for (let frame = 0; frame < scene.frames; frame++) {
    water.advance(1 / scene.framesPerSecond, [rain, wake]);
  }
  const hash = water.stateHash();
  rain.free();
  wake.free();
  water.free();
  return hash;
}
