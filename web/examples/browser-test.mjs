// The browser test: Debian's Chromium, headless with software WebGL (SwiftShader), driven
// by puppeteer-core, on the pool page served by serve.mjs.
//   node examples/browser-test.mjs [--screenshot FILE]     (npm run test:browser)
// CHROMIUM names the browser (default /usr/bin/chromium); SPRINGWATER_CLI the native
// command line for the step-rate comparison (default ../target/release/springwater).
// Checks: no console error; the water region is not blank; two screenshots 0.5 s apart
// differ there; a scripted click makes rings where it clicked; the in-page state hash of
// test/scene.json equals the native one; and reports the step rate at 256², both builds,
// in the page and in Node, beside the native SSE2 build's (interleaved rounds). Exits 1 on
// a failed check.
import { execFileSync } from "node:child_process";
import { existsSync, readFileSync, writeFileSync } from "node:fs";
import { fileURLToPath } from "node:url";
import puppeteer from "puppeteer-core";
import { load } from "../springwater.js";
import { median, rateSurface, run } from "../test/rate.mjs";
import { serve } from "./serve.mjs";

const args = process.argv.slice(2);
const screenshotTo = args.includes("--screenshot") ? args[args.indexOf("--screenshot") + 1] : null;
const chromium = process.env.CHROMIUM ?? "/usr/bin/chromium";
const cli = process.env.SPRINGWATER_CLI ?? fileURLToPath(new URL("../../target/release/springwater", import.meta.url));
const scene = JSON.parse(readFileSync(new URL("../test/scene.json", import.meta.url), "utf8"));

let failures = 0;
function check(ok, what, detail = "") {
  console.log(`${ok ? "ok" : "not ok"} - ${what}${detail ? `: ${detail}` : ""}`);
  if (!ok) failures++;
}

const server = await serve(0);
const url = `http://127.0.0.1:${server.address().port}/examples/pool/`;
const browser = await puppeteer.launch({
  executablePath: chromium,
  headless: true,
  args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"],
});
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 960, height: 600 });
  const errors = [];
  page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
  page.on("pageerror", (e) => errors.push(String(e)));
  page.on("requestfailed", (r) => errors.push(`request failed: ${r.url()}`));
  await page.goto(url);
  await page.waitForFunction(() => window.poolReady === true, { timeout: 60000 });
  await new Promise((r) => setTimeout(r, 1500));

  // The water's region on screen: the projected pool, shrunk by a sixth on each side.
  const region = await page.evaluate(() => {
    const p = window.pool;
    const { cols, rows } = p.water.params;
    const corners = [[0, 0], [cols - 1, 0], [0, rows - 1], [cols - 1, rows - 1]].map(([x, z]) => p.toScreen(x, 0, z));
    const xs = corners.map((c) => c[0]);
    const ys = corners.map((c) => c[1]);
    const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
    const dx = (x1 - x0) / 6;
    const dy = (y1 - y0) / 6;
    return { x: Math.round(x0 + dx), y: Math.round(y0 + dy), w: Math.round(x1 - x0 - 2 * dx), h: Math.round(y1 - y0 - 2 * dy) };
  });
  const shot = async () => Buffer.from(await page.screenshot({ type: "png" })).toString("base64");
  // Pixel statistics of screenshots, decoded in the page: per-shot luminance mean, standard
  // deviation and colour count in the region; per pair, the mean difference, the share of
  // pixels changed by more than 8 and the centroid of those.
  const stats = (shots) =>
    page.evaluate(
      async (shots, r) => {
        const pixels = [];
        for (const b64 of shots) {
          const bitmap = await createImageBitmap(await (await fetch(`data:image/png;base64,${b64}`)).blob());
          const c = new OffscreenCanvas(bitmap.width, bitmap.height);
          const g = c.getContext("2d");
          g.drawImage(bitmap, 0, 0);
          pixels.push(g.getImageData(r.x, r.y, r.w, r.h).data);
        }
        const one = pixels.map((d) => {
          let sum = 0;
          let sq = 0;
          const colours = new Set();
          for (let i = 0; i < d.length; i += 4) {
            const l = 0.299 * d[i] + 0.587 * d[i + 1] + 0.114 * d[i + 2];
            sum += l;
            sq += l * l;
            colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
          }
          const n = d.length / 4;
          return { mean: sum / n, sd: Math.sqrt(sq / n - (sum / n) ** 2), colours: colours.size };
        });
        let diff = 0;
        let changed = 0;
        let cx = 0;
        let cy = 0;
        if (pixels.length === 2) {
          const [a, b] = pixels;
          for (let i = 0; i < a.length; i += 4) {
            const d = (Math.abs(a[i] - b[i]) + Math.abs(a[i + 1] - b[i + 1]) + Math.abs(a[i + 2] - b[i + 2])) / 3;
            diff += d;
            if (d > 8) {
              changed++;
              cx += (i / 4) % r.w;
              cy += Math.floor(i / 4 / r.w);
            }
          }
        }
        const n = pixels[0].length / 4;
        return { one, diff: diff / n, changed: changed / n, centroid: changed ? [r.x + cx / changed, r.y + cy / changed] : null };
      },
      shots,
      region,
    );

  const first = await shot();
  await new Promise((r) => setTimeout(r, 500));
  const second = await shot();
  const moving = await stats([first, second]);
  const look = moving.one[0];
  check(look.sd > 8 && look.colours > 200, "the water region is not blank", `luminance ${look.mean.toFixed(1)} ± ${look.sd.toFixed(1)}, ${look.colours} colours in ${region.w}×${region.h} px`);
  check(moving.diff > 0.3 && moving.changed > 0.002, "two screenshots 0.5 s apart differ", `mean difference ${moving.diff.toFixed(2)}, ${(100 * moving.changed).toFixed(2)}% of pixels changed`);

  // A click on the paused pool: rings where it clicked. The simulation is deterministic, so
  // the same 30 steps from the same saved state without the click are the control: the
  // two screenshots differ only by the drop.
  const target = [84, 40];
  const [px, py] = await page.evaluate(([x, z]) => {
    window.pool.pause(true);
    window.pool.saved = window.pool.water.save();
    window.pool.water.step(30);
    return window.pool.toScreen(x, 0, z);
  }, target);
  await new Promise((r) => setTimeout(r, 300));
  const before = await shot();
  await page.evaluate(() => window.pool.water.restore(window.pool.saved));
  await page.mouse.click(px, py);
  await page.evaluate(() => window.pool.step(30));
  await new Promise((r) => setTimeout(r, 300));
  const after = await shot();
  const drop = await page.evaluate(() => window.pool.lastDrop);
  const rings = await stats([before, after]);
  const off = rings.centroid ? Math.hypot(rings.centroid[0] - px, rings.centroid[1] - py) : Infinity;
  check(
    drop && Math.hypot(drop[0] - target[0], drop[1] - target[1]) < 1.5 && rings.changed > 0.003 && off < 60,
    "a click makes rings where it clicked",
    `drop at ${drop?.map((v) => v.toFixed(2))}, aimed at ${target}; ${(100 * rings.changed).toFixed(2)}% of pixels changed, centred ${off.toFixed(1)} px from the click`,
  );
  await page.evaluate(() => window.pool.pause(false));

  // The scripted scene in the page, both builds: the native state hash.
  const hashes = await page.evaluate(async (scene) => {
    const { load } = await import("/springwater.js");
    const { runScene } = await import("/test/scene.mjs");
    const out = {};
    for (const simd of ["simd128", "portable"]) out[simd] = runScene(await load({ simd }), scene).toString();
    return out;
  }, scene);
  for (const [simd, hash] of Object.entries(hashes)) {
    check(hash === scene.stateHash, `in-page state hash (${simd}) equals the native one`, `${hash}, native ${scene.stateHash}`);
  }


  if (screenshotTo) {
    await page.evaluate(() => {
      const p = window.pool;
      for (const [x, z] of [[40, 60], [95, 30], [70, 100]]) p.water.dropAt(x, z, -2.5, 3);
    });
    await new Promise((r) => setTimeout(r, 700));
    writeFileSync(screenshotTo, await page.screenshot({ type: "png" }));
    console.log(`# screenshot: ${screenshotTo}`);
  }
  // The step rate at 256², one thread (test/rate.mjs): both builds in the page and in this
  // Node process, beside the native command line at SSE2 on one thread, the same drop and
  // node updates per second. The machine may be shared, so the runs are interleaved: each
  // round times every one of them once, in turn, and the figures are medians over the
  // rounds, the ratio the median of each round's SIMD128 over SSE2.
  // The pool page is closed first: its frames, drawn in software, would take the cores.
  // The rates are taken in a page of the same origin that runs nothing else.
  const ROUNDS = 9;
  const SECONDS = 0.3;
  const ratePage = await browser.newPage();
  ratePage.on("pageerror", (e) => errors.push(String(e)));
  await ratePage.goto(`http://127.0.0.1:${server.address().port}/test/rate.mjs`);
  await page.close();
  await ratePage.evaluate(async () => {
    const { load } = await import("/springwater.js");
    const { rateSurface } = await import("/test/rate.mjs");
    window.rateWater = {};
    for (const simd of ["simd128", "portable"]) window.rateWater[simd] = rateSurface(await load({ simd }));
  });
  const inNode = {};
  for (const simd of ["simd128", "portable"]) inNode[simd] = rateSurface(await load({ simd }));
  const native = () => {
    // One warm-up round of 400 steps, then 400 timed (about 0.2 s at SSE2).
    const text = execFileSync(cli, ["bench", "--size", "256x256", "--threads", "1", "--compare", "none", "--steps", "400", "--repeats", "1"], {
      env: { ...process.env, SPRINGWATER_SIMD: "sse2" },
      encoding: "utf8",
    });
    return Number(/node_updates_per_s=([0-9.e+]+)/.exec(text)?.[1]);
  };
  const hasNative = existsSync(cli);
  const rounds = [];
  for (let k = 0; k < ROUNDS; k++) {
    const round = hasNative ? { native: native() } : {};
    Object.assign(
      round,
      await ratePage.evaluate(async (seconds) => {
        const { run } = await import("/test/rate.mjs");
        return { simd128: run(window.rateWater.simd128, seconds), portable: run(window.rateWater.portable, seconds) };
      }, SECONDS),
    );
    round.nodeSimd128 = run(inNode.simd128, SECONDS);
    round.nodePortable = run(inNode.portable, SECONDS);
    rounds.push(round);
  }
  const m = (v) => `${(v / 1e6).toFixed(1)}`;
  const of = (key) => median(rounds.map((r) => r[key]));
  for (const [k, r] of rounds.entries()) {
    console.log(`# round ${k + 1}: Chromium simd128 ${m(r.simd128)}, portable ${m(r.portable)}; Node simd128 ${m(r.nodeSimd128)}, portable ${m(r.nodePortable)}` +
      (hasNative ? `; native SSE2 ${m(r.native)}; simd128/SSE2 ${(r.simd128 / r.native).toFixed(2)} (Node ${(r.nodeSimd128 / r.native).toFixed(2)})` : "") + " M node updates/s");
  }
  console.log(`# step rate at 256x256, one thread, median of ${ROUNDS} rounds (M node updates/s): Chromium simd128 ${m(of("simd128"))}, portable ${m(of("portable"))}; ` +
    `Node simd128 ${m(of("nodeSimd128"))}, portable ${m(of("nodePortable"))}` +
    (hasNative
      ? `; native SSE2 ${m(of("native"))}; simd128/SSE2 in Chromium ${median(rounds.map((r) => r.simd128 / r.native)).toFixed(2)}, in Node ${median(rounds.map((r) => r.nodeSimd128 / r.native)).toFixed(2)} (target 0.6)`
      : " (no native command line to compare)"));
  check(rounds.every((r) => r.simd128 > 0 && r.portable > 0), "the in-page step rate at 256² is reported for SIMD128 and portable");
  check(errors.length === 0, "no console error", errors.join(" | "));
} finally {
  await browser.close();
  server.close();
}
console.log(failures ? `# ${failures} failed` : "# all passed");
process.exit(failures ? 1 : 0);
