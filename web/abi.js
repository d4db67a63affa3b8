// The C ABI seen from JavaScript, for springwater.js: the C structs' sizes and field
// offsets on wasm32 (ffi/include/springwater.h), the instance's exports and memory with
// the moves between JavaScript and wasm memory, the statuses of refused calls turned into
// Errors, and the buffers behind the zero-copy views.

// Sizes (bytes) and field offsets of the C structs on wasm32 (ffi/include/springwater.h).
export const PARAMS_SIZE = 60;
export const PARAMS_FIELDS = [
  ["cols", 4, "u32"], ["rows", 8, "u32"], ["spacing", 12], ["mass", 16], ["stiffness", 20],
  ["viscosity", 24], ["dt", 28], ["restRatio", 32], ["timeScale", 36],
  ["accelerationX", 40], ["accelerationY", 44], ["accelerationZ", 48],
  ["boundary", 52, "boundary"], ["absorbingWidth", 56, "u32"],
];
export const BOUNDARIES = ["pinned", "free", "absorbing"];
export const SHAPES = ["sphere", "box", "hull"];
export const FLOATER_SIZE = 172;
export const FLOATER_FIELDS = [
  ["radius", 8, 1], ["halfExtents", 12, 3], ["mass", 24, 1], ["drag", 28, 1],
  ["position", 32, 3], ["velocity", 44, 3], ["push", 56, 3], ["waterForce", 68, 3],
  ["orientation", 80, 4], ["angularVelocity", 96, 3], ["pushTorque", 108, 3],
  ["waterTorque", 120, 3], ["inertia", 136, 9],
];
export const REFRACTION_SIZE = 24;
export const LOD_SIZE = 20;
export const BUOYANCY_SIZE = 12;
export const FORCES_SIZE = 28;
export const SAMPLE_FLOATS = 7; // height, normal xyz, velocity xyz
export const SCRATCH_BYTES = 1024; // out-parameters and structs of one call at a time
export const MESSAGE_BYTES = 1024;

// The instance's exports and memory, and the moves between JavaScript and wasm memory.
export class Lib {
  constructor(exports) {
    this.x = exports;
    this.memory = exports.memory;
    this.scratch = this.alloc(SCRATCH_BYTES);
    this.message = this.alloc(MESSAGE_BYTES);
    // Surfaces and hulls dropped without free(): freed when collected.
    this.finalizers = new FinalizationRegistry((release) => release());
    const params = this.callStruct("sw_params_default", PARAMS_SIZE, (p) => this.u32(p));
    if (params !== PARAMS_SIZE) {
      throw new Error(`SwParams is ${params} bytes in this build, ${PARAMS_SIZE} expected`);
    }
  }

  alloc(bytes) {
    const p = this.x.sw_wasm_alloc(bytes);
    if (p === 0 && bytes > 0) throw new Error(`cannot allocate ${bytes} bytes of wasm memory`);
    return p;
  }

  free(p) {
    this.x.sw_wasm_free(p);
  }

  // Views over the memory, made again after it grows (growing detaches the old buffer).
  f32(p, n) {
    return new Float32Array(this.memory.buffer, p, n);
  }
  u32(p) {
    return new DataView(this.memory.buffer).getUint32(p, true);
  }
  bytes(p, n) {
    return new Uint8Array(this.memory.buffer, p, n);
  }
  view() {
    return new DataView(this.memory.buffer);
  }

  string(p) {
    const all = new Uint8Array(this.memory.buffer);
    let end = p;
    while (all[end] !== 0) end++;
    return new TextDecoder().decode(all.subarray(p, end));
  }

  // Throws the library's message for a refused call.
  check(status) {
    if (status >= 0) return;
    const needed = this.x.sw_last_error(this.message, MESSAGE_BYTES);
    const text = this.string(this.message);
    const name = this.string(this.x.sw_status_name(status));
    const error = new Error(text || `${name} (${needed})`);
    error.code = name;
    error.status = status;
    throw error;
  }

  // Calls a function that returns a struct (its address is the call's first argument on
  // wasm32) and reads it with `read(address)`.
  callStruct(name, size, read, ...args) {
    const p = this.scratch;
    this.bytes(p, size).fill(0);
    this.x[name](p, ...args);
    return read.call(this, p);
  }

  // Copies `data` (a typed array) into fresh wasm memory, runs `f(address, length)` and
  // frees it.
  withInput(data, f) {
    const bytes = data.byteLength;
    const p = bytes > 0 ? this.alloc(bytes) : 0;
    try {
      if (bytes > 0) this.bytes(p, bytes).set(new Uint8Array(data.buffer, data.byteOffset, bytes));
      return f(p, data.length);
    } finally {
      if (p !== 0) this.free(p);
    }
  }

  paramsDefault() {
    return this.callStruct("sw_params_default", PARAMS_SIZE, readParams);
  }

  // Writes the params struct at `p`: the library's defaults with `given`'s fields over them.
  writeParams(p, given) {
    const base = this.paramsDefault();
    for (const key of Object.keys(given)) {
      if (!(key in base)) throw new Error(`unknown parameter ${key}`);
    }
    const params = { ...base, ...given };
    const d = this.view();
    d.setUint32(p, PARAMS_SIZE, true);
    for (const [key, at, kind] of PARAMS_FIELDS) {
      const value = params[key];
      if (kind === "boundary") {
        const code = BOUNDARIES.indexOf(value);
        if (code < 0) throw new Error(`boundary is ${value}, expected one of ${BOUNDARIES.join(", ")}`);
        d.setInt32(p + at, code, true);
      } else if (kind === "u32") {
        if (!Number.isInteger(value) || value < 0 || value > 0xffffffff) {
          throw new Error(`${key} is ${value}, expected a whole number from 0 to 4294967295`);
        }
        d.setUint32(p + at, value, true);
      } else {
        d.setFloat32(p + at, value, true);
      }
    }
  }

  writeFloater(p, body) {
    const d = this.view();
    d.setUint32(p, FLOATER_SIZE, true);
    const shape = SHAPES.indexOf(body.shape);
    if (shape < 0) throw new Error(`shape is ${body.shape}, expected one of ${SHAPES.join(", ")}`);
    d.setInt32(p + 4, shape, true);
    for (const [key, at, n] of FLOATER_FIELDS) {
      const value = body[key];
      if (n === 1) {
        d.setFloat32(p + at, value ?? 0, true);
      } else {
        const v = value ?? new Array(n).fill(0);
        if (v.length !== n) throw new Error(`${key} has ${v.length} numbers, expected ${n}`);
        for (let k = 0; k < n; k++) d.setFloat32(p + at + 4 * k, v[k], true);
      }
    }
    d.setInt32(p + 132, body.hasInertia ? 1 : 0, true);
  }
}

export function readParams(p) {
  const d = this.view();
  const out = {};
  for (const [key, at, kind] of PARAMS_FIELDS) {
    if (kind === "boundary") out[key] = BOUNDARIES[d.getInt32(p + at, true)] ?? "unknown";
    else if (kind === "u32") out[key] = d.getUint32(p + at, true);
    else out[key] = d.getFloat32(p + at, true);
  }
  return out;
}

export function readFloater(p) {
  const d = this.view();
  const out = { shape: SHAPES[d.getInt32(p + 4, true)] ?? "unknown" };
  for (const [key, at, n] of FLOATER_FIELDS) {
    if (n === 1) out[key] = d.getFloat32(p + at, true);
    else out[key] = Array.from({ length: n }, (_, k) => d.getFloat32(p + at + 4 * k, true));
  }
  out.hasInertia = d.getInt32(p + 132, true) === 1;
  return out;
}

export function vec(v, n, what) {
  if (v == null || v.length !== n) throw new Error(`${what} must hold ${n} numbers`);
  return v;
}

export function writeRefraction(lib, p, view = {}) {
  const base = lib.callStruct("sw_refraction_default", REFRACTION_SIZE, function (q) {
    const d = this.view();
    return { depth: d.getFloat32(q + 16, true), ior: d.getFloat32(q + 20, true) };
  });
  const [ex, ey, ez] = vec(view.eye ?? [0, 0, 0], 3, "eye");
  const d = lib.view();
  d.setUint32(p, REFRACTION_SIZE, true);
  d.setFloat32(p + 4, ex, true);
  d.setFloat32(p + 8, ey, true);
  d.setFloat32(p + 12, ez, true);
  d.setFloat32(p + 16, view.depth ?? base.depth, true);
  d.setFloat32(p + 20, view.ior ?? base.ior, true);
}

// The per-surface buffers that back the zero-copy views, grown when a call needs more.
export class Buffers {
  constructor(lib) {
    this.lib = lib;
    this.parts = new Map(); // name -> { p, bytes }
  }
  get(name, bytes) {
    const have = this.parts.get(name);
    if (have && have.bytes >= bytes) return have.p;
    if (have) this.lib.free(have.p);
    const p = this.lib.alloc(Math.max(bytes, 8));
    this.parts.set(name, { p, bytes });
    return p;
  }
  release() {
    for (const { p } of this.parts.values()) this.lib.free(p);
    this.parts.clear();
  }
}

export function asBytes(bytes) {
  if (bytes instanceof Uint8Array) return bytes;
  if (bytes instanceof ArrayBuffer) return new Uint8Array(bytes);
  if (ArrayBuffer.isView(bytes)) return new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  throw new Error("expected a Uint8Array, an ArrayBuffer or a typed array");
}
