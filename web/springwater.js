// springwater for JavaScript: the library's C ABI (springwater-ffi, built for
// wasm32-wasip1) wrapped in classes, as the C# package wraps the same functions.
// Every call goes to the library; this file and abi.js (the structs' layouts, the moves
// in and out of wasm memory, refused calls as Errors carrying the library's message) only
// move numbers between JavaScript and the module.

import {
  BUOYANCY_SIZE,
  Buffers,
  FLOATER_SIZE,
  FORCES_SIZE,
  LOD_SIZE,
  Lib,
  PARAMS_SIZE,
  SAMPLE_FLOATS,
  asBytes,
  readFloater,
  readParams,
  vec,
  writeRefraction,
} from "./abi.js";

const WASM = {
  simd128: new URL("./wasm/springwater-simd128.wasm", import.meta.url),
  portable: new URL("./wasm/springwater-portable.wasm", import.meta.url),
};

// A module of one function, () -> v128 { i32x4.splat(0) }: valid where the engine has
// SIMD128.
const SIMD_PROBE = new Uint8Array([
  0x00, 0x61, 0x73, 0x6d, 0x01, 0x00, 0x00, 0x00, // magic, version 1
  0x01, 0x05, 0x01, 0x60, 0x00, 0x01, 0x7b, // type: () -> v128
  0x03, 0x02, 0x01, 0x00, // one function of that type
  0x0a, 0x08, 0x01, 0x06, 0x00, 0x41, 0x00, 0xfd, 0x11, 0x0b, // i32.const 0; i32x4.splat
]);

/** Whether this engine runs WebAssembly SIMD128. */
export function hasSimd128() {
  return WebAssembly.validate(SIMD_PROBE);
}

/**
 * Loads the library: the SIMD128 build where this engine validates SIMD128, else the
 * portable one. `options.simd` forces one ("simd128" or "portable"); `options.wasm`
 * gives the module's bytes, a Response or a URL instead of the packaged file.
 */
export async function load(options = {}) {
  let simd = options.simd ?? (hasSimd128() ? "simd128" : "portable");
  if (simd !== "simd128" && simd !== "portable") {
    throw new Error(`simd is ${String(simd)}, expected "simd128" or "portable"`);
  }
  if (simd === "simd128" && !hasSimd128()) {
    throw new Error("this engine does not run WebAssembly SIMD128");
  }
  const module = await compile(options.wasm ?? WASM[simd]);
  let memory = null;
  const instance = await WebAssembly.instantiate(module, system(module, () => memory));
  memory = instance.exports.memory;
  return new Springwater(instance.exports, simd);
}

// The few WASI functions the module imports (it is built for wasm32-wasip1, whose C
// library gives the same math bits as the native builds): random bytes for hash maps'
// seeds, an empty environment, stderr to the console (a panic's message), and exit as an
// exception. Anything else it might import answers "not supported".
function system(module, memory) {
  const wasi = {};
  const bytes = () => new Uint8Array(memory().buffer);
  const u32 = () => new DataView(memory().buffer);
  let stderr = "";
  const implemented = {
    random_get(p, n) {
      // (Seeds of hash maps, whose order the library's results never depend on.)
      const out = bytes().subarray(p, p + n);
      if (globalThis.crypto?.getRandomValues) {
        for (let i = 0; i < n; i += 65536) crypto.getRandomValues(out.subarray(i, Math.min(n, i + 65536)));
      } else {
        for (let i = 0; i < n; i++) out[i] = (Math.random() * 256) | 0;
      }
      return 0;
    },
    environ_sizes_get(count, size) {
      u32().setUint32(count, 0, true);
      u32().setUint32(size, 0, true);
      return 0;
    },
    environ_get() {
      return 0;
    },
    fd_write(fd, iovs, n, written) {
      const d = u32();
      let total = 0;
      for (let k = 0; k < n; k++) {
        const p = d.getUint32(iovs + 8 * k, true);
        const len = d.getUint32(iovs + 8 * k + 4, true);
        stderr += new TextDecoder().decode(bytes().slice(p, p + len));
        total += len;
      }
      const lines = stderr.split("\n");
      stderr = lines.pop();
      for (const line of lines) (fd === 1 ? console.log : console.error)(`springwater: ${line}`);
      d.setUint32(written, total, true);
      return 0;
    },
    proc_exit(code) {
      throw new Error(`springwater exited with code ${code}`);
    },
  };
  for (const { module: from, name } of WebAssembly.Module.imports(module)) {
    if (from !== "wasi_snapshot_preview1") throw new Error(`unexpected import ${from}.${name}`);
    wasi[name] = implemented[name] ?? (() => 52); // ENOSYS
  }
  return { wasi_snapshot_preview1: wasi };
}

async function compile(source) {
  if (source instanceof URL || typeof source === "string") {
    const url = new URL(source, import.meta.url);
    if (url.protocol === "file:") {
      const { readFile } = await import("node:fs/promises");
      return WebAssembly.compile(await readFile(url));
    }
    source = await fetch(url);
  }
  if (typeof Response !== "undefined" && source instanceof Response) {
    if (!source.ok) throw new Error(`cannot fetch ${source.url}: ${source.status}`);
    return WebAssembly.compile(await source.arrayBuffer());
  }
  return WebAssembly.compile(source);
}

/** One instance of the library; `load()` makes it. */
class Springwater {
  constructor(exports, simd) {
    const lib = new Lib(exports);
    const level = exports.sw_simd_level_detect();
    this.simd = lib.string(exports.sw_simd_level_name(level));
    if (this.simd !== simd) {
      throw new Error(`the ${simd} build runs ${this.simd}`);
    }
    this.version = lib.string(exports.sw_version());
    this.lib = lib;
    this.WaterSurface = class extends WaterSurface {
      static lib = lib;
    };
    this.Hull = class extends Hull {
      static lib = lib;
    };
    this.Rain = class extends Rain {
      static lib = lib;
    };
    this.Wake = class extends Wake {
      static lib = lib;
    };
  }

  /** The seed's defaults on a 128 × 128 grid. */
  defaultParams() {
    return this.lib.paramsDefault();
  }

  /** A ball at rest, upright, with the default drag (a body to add or to ask forces for). */
  sphere(radius, mass, position) {
    const [x, y, z] = vec(position, 3, "position");
    return this.lib.callStruct("sw_floater_sphere", FLOATER_SIZE, readFloater, radius, mass, x, y, z);
  }

  /** A box of half extents `[hx, hy, hz]` at rest, upright, with the default drag. */
  box(halfExtents, mass, position) {
    const [hx, hy, hz] = vec(halfExtents, 3, "halfExtents");
    const [x, y, z] = vec(position, 3, "position");
    return this.lib.callStruct("sw_floater_box", FLOATER_SIZE, readFloater, hx, hy, hz, mass, x, y, z);
  }

  /** The wasm memory's size in bytes (it only grows). */
  get memoryBytes() {
    return this.lib.memory.buffer.byteLength;
  }
}

/**
 * A water surface: a mass-spring lattice of cols × rows nodes, in world units, y up. Every
 * method does what it says or throws an Error with the library's message, changing
 * nothing. `free()` (or `using`) frees it; twice is harmless.
 */
class WaterSurface {
  #lib;
  #handle;
  #buffers;
  #freed = false;
  #token = {};

  /** `new WaterSurface(cols, rows)` (seed defaults) or `new WaterSurface({ cols, rows, ... })`. */
  constructor(cols, rows) {
    const lib = new.target.lib;
    this.#lib = lib;
    if (cols === FROM_HANDLE) {
      this.#adopt(rows);
      return;
    }
    const given = typeof cols === "object" && cols !== null ? cols : { cols, rows };
    const s = lib.scratch;
    lib.writeParams(s, given);
    lib.check(lib.x.sw_surface_create(s, s + PARAMS_SIZE));
    this.#adopt(lib.u32(s + PARAMS_SIZE));
  }

  #adopt(handle) {
    const lib = this.#lib;
    this.#handle = handle;
    this.#buffers = new Buffers(lib);
    const buffers = this.#buffers;
    lib.finalizers.register(
      this,
      () => {
        lib.x.sw_surface_destroy(handle);
        buffers.release();
      },
      this.#token,
    );
  }

  /** A surface restored from a snapshot (`save()`), its bodies included. */
  static load(bytes) {
    const lib = this.lib;
    const handle = lib.withInput(asBytes(bytes), (p, n) => {
      lib.check(lib.x.sw_surface_load(p, n, lib.scratch));
      return lib.u32(lib.scratch);
    });
    return new this(FROM_HANDLE, handle);
  }

  /** Frees the surface and its buffers. Twice is harmless; later calls throw. */
  free() {
    if (this.#freed) return;
    this.#freed = true;
    this.#lib.finalizers.unregister(this.#token);
    this.#lib.x.sw_surface_destroy(this.#handle);
    this.#buffers.release();
  }

  [Symbol.dispose]() {
    this.free();
  }

  // A buffer of this surface; after free(), the library's refusal of the handle instead.
  #buffer(name, bytes) {
    if (this.#freed) this.#call("sw_surface_node_count", this.#lib.scratch);
    return this.#buffers.get(name, bytes);
  }

  #call(name, ...args) {
    this.#lib.check(this.#lib.x[name](this.#handle, ...args));
  }

  // A call with one out-parameter in the scratch memory; `read(address)` reads it.
  #out(name, read, ...args) {
    const s = this.#lib.scratch;
    this.#call(name, ...args, s);
    return read(s);
  }

  #f32 = (p) => this.#lib.view().getFloat32(p, true);
  #u32 = (p) => this.#lib.u32(p);
  #f32x3 = (p) => Array.from(this.#lib.f32(p, 3));

  /** The surface's parameters (an object of the fields `new` takes). */
  get params() {
    const s = this.#lib.scratch;
    this.#lib.view().setUint32(s, PARAMS_SIZE, true);
    this.#call("sw_surface_params", s);
    return readParams.call(this.#lib, s);
  }
  get cols() {
    return this.params.cols;
  }
  get rows() {
    return this.params.rows;
  }
  /** Nodes, cols × rows: the length of every per-node buffer. */
  get nodeCount() {
    return this.#out("sw_surface_node_count", this.#u32);
  }

  /**
   * Advances the water by `seconds` of the caller's clock on the fixed-step clock; returns
   * the steps taken. `disturbances` (Rain, Wake) act before every step.
   */
  advance(seconds, disturbances = []) {
    if (disturbances.length === 0) return this.#out("sw_surface_advance", this.#u32, seconds);
    const lib = this.#lib;
    const handles = Uint32Array.from(disturbances, (d) => d.id);
    return lib.withInput(handles, (p, n) => {
      lib.check(lib.x.sw_surface_advance_with(this.#handle, seconds, p, n, lib.scratch));
      return lib.u32(lib.scratch);
    });
  }
  /** Takes `n` steps (default 1). */
  step(n = 1) {
    this.#call("sw_surface_step", n);
  }
  /** The most steps one advance takes, and whether a longer frame's rest carries over. */
  setStepCap(maxSteps, carry = false) {
    this.#call("sw_surface_set_step_cap", maxSteps, carry ? 1 : 0);
  }
  /** How far the clock is past the last step, a fraction of a step in [0, 1). */
  get interpolation() {
    return this.#out("sw_surface_interpolation", this.#f32);
  }

  /** Adds height · exp(−d²/radius²) around world (x, z). */
  dropAt(x, z, height, radius) {
    this.#call("sw_surface_drop_at", x, z, height, radius);
  }
  /** Pushes the water at (x, z) with a force in the lattice's units, for the next step. */
  addForceAt(x, z, fx, fy, fz) {
    this.#call("sw_surface_add_force_at", x, z, fx, fy, fz);
  }

  heightAt(x, z) {
    return this.#out("sw_surface_height_at", this.#f32, x, z);
  }
  normalAt(x, z) {
    return this.#out("sw_surface_normal_at", this.#f32x3, x, z);
  }
  velocityAt(x, z) {
    return this.#out("sw_surface_velocity_at", this.#f32x3, x, z);
  }

  /**
   * The water at many points (`xz`: x, z pairs): a Float32Array of 7 numbers per point
   * (height, normal x y z, velocity x y z). A point off the water is refused.
   */
  sample(xz) {
    const lib = this.#lib;
    const points = Float32Array.from(xz);
    const count = points.length >> 1;
    const out = this.#buffer("sample", Math.max(count, 1) * SAMPLE_FLOATS * 4);
    lib.withInput(points, (p, n) => {
      this.#call("sw_surface_sample", p, n / 2, out, count);
    });
    return lib.f32(out, count * SAMPLE_FLOATS).slice();
  }

  /** Interleaved positions (x, y, z per node) copied into `out` (3 × nodeCount floats). */
  writePositions(out) {
    const p = this.#buffer("copy", out.length * 4);
    this.#call("sw_surface_write_positions", p, out.length);
    out.set(this.#lib.f32(p, out.length));
  }

  /**
   * The positions (x, y, z per node) as a Float32Array over wasm memory, written now. Valid
   * until the next call into the library (one that grows memory detaches it): ask again
   * each frame instead of keeping it.
   */
  positions() {
    const n = 3 * this.nodeCount;
    const p = this.#buffer("positions", n * 4);
    this.#call("sw_surface_write_positions", p, n);
    return this.#lib.f32(p, n);
  }
  /** Unit normals (x, y, z per node), a view like `positions()`. */
  normals() {
    const n = 3 * this.nodeCount;
    const p = this.#buffer("normals", n * 4);
    this.#call("sw_surface_write_normals", p, n);
    return this.#lib.f32(p, n);
  }
  /**
   * The bottom's texture coordinates seen through the water (u, v per node) from
   * `view = { eye: [x, y, z], depth, ior }`, a view like `positions()`.
   */
  refractionUvs(view) {
    const lib = this.#lib;
    const n = 2 * this.nodeCount;
    const p = this.#buffer("uvs", n * 4);
    writeRefraction(lib, lib.scratch, view);
    this.#call("sw_surface_write_refraction_uvs", lib.scratch, p, n);
    return lib.f32(p, n);
  }
  /** Packed vertices (position, normal, refraction uv: 8 floats per node), a view. */
  vertices(view) {
    const lib = this.#lib;
    const nodes = this.nodeCount;
    const p = this.#buffer("vertices", nodes * 32);
    writeRefraction(lib, lib.scratch, view);
    this.#call("sw_surface_write_vertices", lib.scratch, p, nodes);
    return lib.f32(p, nodes * 8);
  }

  /** LOD parameters: `{ patchCells, levels, firstRange, hysteresis }` (defaults for the rest). */
  setLodParams(given) {
    const lib = this.#lib;
    const s = lib.scratch;
    lib.callStruct("sw_lod_params_default", LOD_SIZE, () => 0);
    const d = lib.view();
    if (given.patchCells !== undefined) d.setUint32(s + 4, given.patchCells, true);
    if (given.levels !== undefined) d.setUint32(s + 8, given.levels, true);
    if (given.firstRange !== undefined) d.setFloat32(s + 12, given.firstRange, true);
    if (given.hysteresis !== undefined) d.setFloat32(s + 16, given.hysteresis, true);
    this.#call("sw_surface_set_lod_params", s);
  }
  /** Chooses each patch's detail for the eye; whether the indices changed. */
  updateLod(eyeX, eyeY, eyeZ) {
    return this.#out("sw_surface_update_lod", this.#u32, eyeX, eyeY, eyeZ) === 1;
  }
  /** The LOD triangle indices (3 per triangle) as a Uint32Array view, like `positions()`. */
  lodIndices() {
    const lib = this.#lib;
    const count = this.#out("sw_surface_lod_indices", this.#u32, 0, 0);
    const p = this.#buffer("indices", count * 4);
    this.#call("sw_surface_lod_indices", p, count, lib.scratch);
    return new Uint32Array(lib.memory.buffer, p, count);
  }

  /** The state's hash (XXH3-64): equal states, equal hashes, on every build and platform. */
  stateHash() {
    return this.#out("sw_surface_state_hash", (p) => this.#lib.view().getBigUint64(p, true));
  }
  /**
   * A snapshot of the whole state, written into `buf` when it is large enough (the result
   * is the part of `buf` used), else into a new Uint8Array.
   */
  saveInto(buf) {
    const lib = this.#lib;
    const size = this.#out("sw_surface_save", this.#u32, 0, 0);
    const p = this.#buffer("save", size);
    this.#call("sw_surface_save", p, size, lib.scratch);
    const out = buf && buf.length >= size ? buf.subarray(0, size) : new Uint8Array(size);
    out.set(lib.bytes(p, size));
    return out;
  }
  save() {
    return this.saveInto();
  }
  /** Replaces the state with a snapshot's (its size and bodies too), keeping the SIMD level and LOD parameters. */
  restore(bytes) {
    const data = asBytes(bytes);
    if (this.#freed) this.#call("sw_surface_node_count", this.#lib.scratch);
    this.#lib.withInput(data, (p, n) => this.#call("sw_surface_restore", p, n));
  }

  /** Kinetic, potential and total energy (a diagnostic). */
  get energy() {
    return this.#out("sw_surface_energy", (p) => {
      const d = this.#lib.view();
      return { kinetic: d.getFloat64(p, true), potential: d.getFloat64(p + 8, true), total: d.getFloat64(p + 16, true) };
    });
  }
  /** The SIMD level this surface runs ("simd128" or "portable"). */
  get simdLevel() {
    const level = this.#out("sw_surface_simd_level", this.#u32);
    return this.#lib.string(this.#lib.x.sw_simd_level_name(level));
  }

  /** Moves the window by whole cells. */
  shift(dcols, drows) {
    this.#call("sw_surface_shift", dcols, drows);
  }
  /** Keeps world (x, z) near the window's middle; returns the shift made, [dcols, drows]. */
  follow(x, z) {
    return this.#out("sw_surface_follow", (p) => Array.from(new Int32Array(this.#lib.memory.buffer, p, 2)), x, z);
  }
  /** World x, z of node (0, 0). */
  get origin() {
    return this.#out("sw_surface_origin", (p) => Array.from(this.#lib.f32(p, 2)));
  }

  // Floating bodies.

  /** Adds a body (from `sw.sphere`, `sw.box` or `hull.floater`); returns its id. */
  addFloater(body) {
    const lib = this.#lib;
    const s = lib.scratch;
    lib.writeFloater(s, body);
    const id = s + FLOATER_SIZE + 4; // 8-aligned
    if (body.shape === "hull") {
      if (!body.hull) throw new Error("a hull body needs its hull (make it with hull.floater)");
      this.#call("sw_surface_add_hull_floater", body.hull.handle, s, id);
    } else {
      this.#call("sw_surface_add_floater", s, id);
    }
    return Number(lib.view().getBigUint64(id, true));
  }
  /** Body `id` as it is now. */
  floater(id) {
    const s = this.#lib.scratch;
    this.#lib.view().setUint32(s, FLOATER_SIZE, true);
    this.#call("sw_surface_floater", BigInt(id), s);
    return readFloater.call(this.#lib, s);
  }
  /** Replaces body `id`'s state with `fields` over its current state. */
  setFloater(id, fields) {
    const body = { ...this.floater(id), ...fields };
    const s = this.#lib.scratch;
    this.#lib.writeFloater(s, body);
    this.#call("sw_surface_set_floater", BigInt(id), s);
  }
  /** Pushes body `id` through its centre of mass for the next step. */
  pushFloater(id, force) {
    const [fx, fy, fz] = vec(force, 3, "force");
    this.#call("sw_surface_push_floater", BigInt(id), fx, fy, fz);
  }
  /** Pushes body `id` at a world point (a force and a torque) for the next step. */
  pushFloaterAt(id, force, point) {
    const [fx, fy, fz] = vec(force, 3, "force");
    const [x, y, z] = vec(point, 3, "point");
    this.#call("sw_surface_push_floater_at", BigInt(id), fx, fy, fz, x, y, z);
  }
  removeFloater(id) {
    this.#call("sw_surface_remove_floater", BigInt(id));
  }
  get floaterCount() {
    return this.#out("sw_surface_floater_count", this.#u32);
  }
  floaterIds() {
    const lib = this.#lib;
    const count = this.floaterCount;
    const p = this.#buffer("ids", count * 8);
    this.#call("sw_surface_floater_ids", p, count, lib.scratch);
    return Array.from(new BigUint64Array(lib.memory.buffer, p, count), Number);
  }
  /** `{ gravity, density }` of the world the bodies float in. */
  get buoyancy() {
    const s = this.#lib.scratch;
    this.#lib.view().setUint32(s, BUOYANCY_SIZE, true);
    this.#call("sw_surface_buoyancy", s);
    const d = this.#lib.view();
    return { gravity: d.getFloat32(s + 4, true), density: d.getFloat32(s + 8, true) };
  }
  set buoyancy(b) {
    const current = this.buoyancy;
    const s = this.#lib.scratch;
    const d = this.#lib.view();
    d.setUint32(s, BUOYANCY_SIZE, true);
    d.setFloat32(s + 4, b.gravity ?? current.gravity, true);
    d.setFloat32(s + 8, b.density ?? current.density, true);
    this.#call("sw_surface_set_buoyancy", s);
  }
  /**
   * The water's push `{ force, torque }` (world frame, torque about the centre of mass) on a
   * body another engine owns, over its next `seconds`; the water gets the opposite.
   */
  bodyForces(body, seconds) {
    const lib = this.#lib;
    const s = lib.scratch;
    lib.writeFloater(s, body);
    const out = s + FLOATER_SIZE;
    lib.view().setUint32(out, FORCES_SIZE, true);
    if (body.shape === "hull") {
      if (!body.hull) throw new Error("a hull body needs its hull (make it with hull.floater)");
      this.#call("sw_surface_hull_body_forces", body.hull.handle, s, seconds, out);
    } else {
      this.#call("sw_surface_body_forces", s, seconds, out);
    }
    const f = lib.f32(out + 4, 6);
    return { force: [f[0], f[1], f[2]], torque: [f[3], f[4], f[5]] };
  }
}

const FROM_HANDLE = Symbol("handle");

/**
 * A closed triangle mesh for floating bodies: `vertices` x, y, z per vertex (the body's
 * frame, centre of mass at the origin), `triangles` three indices each, wound outward.
 */
class Hull {
  #lib;
  #token = {};
  handle = 0;

  constructor(vertices, triangles) {
    const lib = new.target.lib;
    this.#lib = lib;
    const xyz = Float32Array.from(vertices);
    const tri = Uint32Array.from(triangles);
    if (xyz.length % 3 !== 0 || tri.length % 3 !== 0) {
      throw new Error("vertices and triangles must hold multiples of 3 numbers");
    }
    lib.withInput(xyz, (pv, nv) =>
      lib.withInput(tri, (pt, nt) => {
        lib.check(lib.x.sw_hull_create(pv, nv / 3, pt, nt / 3, lib.scratch));
      }),
    );
    const handle = lib.u32(lib.scratch);
    this.handle = handle;
    lib.finalizers.register(this, () => lib.x.sw_hull_destroy(handle), this.#token);
  }

  /** The enclosed volume, cubic world units. */
  get volume() {
    const s = this.#lib.scratch;
    this.#lib.check(this.#lib.x.sw_hull_volume(this.handle, s));
    return this.#lib.view().getFloat32(s, true);
  }

  /** A body of this hull at rest, upright, the hull's inertia for `mass`. */
  floater(mass, position) {
    const lib = this.#lib;
    const [x, y, z] = vec(position, 3, "position");
    const s = lib.scratch;
    lib.view().setUint32(s, FLOATER_SIZE, true);
    lib.check(lib.x.sw_floater_hull(this.handle, mass, x, y, z, s));
    const body = readFloater.call(lib, s);
    Object.defineProperty(body, "hull", { value: this, enumerable: false });
    return body;
  }

  /** Frees the mesh handle (bodies made of it keep the mesh). Twice is harmless. */
  free() {
    this.#lib.finalizers.unregister(this.#token);
    this.#lib.x.sw_hull_destroy(this.handle);
  }
  [Symbol.dispose]() {
    this.free();
  }
}

/**
 * Rain (the library's `disturb::Rain`): `rate` drops per second at random places, the same
 * ones for the same `seed`. Pass it to `advance(seconds, [rain])`.
 */
class Rain {
  #lib;
  #rate;
  id = 0;
  constructor(rate, seed = 1, { radius = [1.5, 3], depth = 0.6 } = {}) {
    const lib = new.target.lib;
    this.#lib = lib;
    const s = lib.scratch;
    lib.check(lib.x.sw_rain_create(rate, BigInt(seed), radius[0], radius[1], depth, s));
    const id = lib.u32(s);
    this.id = id;
    this.#rate = rate;
    lib.finalizers.register(this, () => lib.x.sw_disturbance_destroy(id), this);
  }
  /** Drops per second (0 stops the rain). */
  get rate() {
    return this.#rate;
  }
  set rate(rate) {
    this.#lib.check(this.#lib.x.sw_rain_set_rate(this.id, rate));
    this.#rate = rate;
  }
  free() {
    this.#lib.finalizers.unregister(this);
    this.#lib.x.sw_disturbance_destroy(this.id);
  }
  [Symbol.dispose]() {
    this.free();
  }
}

/**
 * A wake (the library's `disturb::Wake`): an object moving along the closed path `path`
 * (`[[x, z], ...]` or x, z pairs) at `speed` world units per second, pressing the water
 * down under it. Pass it to `advance(seconds, [wake])`.
 */
class Wake {
  #lib;
  id = 0;
  constructor(path, { speed = 60, radius = 2.5, strength = 1.5 } = {}) {
    const lib = new.target.lib;
    this.#lib = lib;
    const xz = Float32Array.from(path.flat ? path.flat() : path);
    lib.withInput(xz, (p, n) => {
      lib.check(lib.x.sw_wake_create(p, n >> 1, speed, radius, strength, lib.scratch));
    });
    const id = lib.u32(lib.scratch);
    this.id = id;
    lib.finalizers.register(this, () => lib.x.sw_disturbance_destroy(id), this);
  }
  free() {
    this.#lib.finalizers.unregister(this);
    this.#lib.x.sw_disturbance_destroy(this.id);
  }
  [Symbol.dispose]() {
    this.free();
  }
}
