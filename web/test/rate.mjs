// The step rate at 256², one thread, as examples/browser-test.mjs measures it in the page
// and in Node, beside the native command line's `bench` (which this mirrors: the same
// drop, `step_n` in the library, node updates per second).

export const SIZE = 256;

// A 256² surface after the native bench's drop (at the centre, height 1, radius 4 cells),
// stepped for `warmup` seconds first: the engines compile a hot wasm function again, fully
// optimised, in the background (V8's Liftoff, then TurboFan), and a run before that is
// over times the first compiler's code.
export function rateSurface(sw, warmup = 2) {
  const water = new sw.WaterSurface(SIZE, SIZE);
  water.dropAt(SIZE / 2, SIZE / 2, 1, 4);
  run(water, warmup);
  return water;
}

// One timed run of at least `seconds`: `step(20)` (20 steps in one call into wasm) until
// then; node updates per second. 20 steps at 256² take milliseconds, far above the 0.1 ms
// to which a page without cross-origin isolation rounds performance.now().
export function run(water, seconds) {
  let steps = 0;
  const t0 = performance.now();
  let t = t0;
  while (t - t0 < seconds * 1000) {
    water.step(20);
    steps += 20;
    t = performance.now();
  }
  return (steps * SIZE * SIZE) / ((t - t0) / 1000);
}

export function median(values) {
  const s = values.slice().sort((a, b) => a - b);
  const n = s.length;
  return n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
}
