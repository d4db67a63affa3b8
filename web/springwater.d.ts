// TypeScript declarations of the springwater package (springwater.js).

/** The model's parameters; `load()`'s `defaultParams()` gives the seed's defaults. */
export interface Params {
  cols: number;
  rows: number;
  /** Rest distance between neighbouring nodes, world units. */
  spacing: number;
  mass: number;
  stiffness: number;
  viscosity: number;
  /** Timestep of one step, model time. */
  dt: number;
  restRatio: number;
  /** Model time per second of the caller's clock. */
  timeScale: number;
  accelerationX: number;
  accelerationY: number;
  accelerationZ: number;
  boundary: "pinned" | "free" | "absorbing";
  absorbingWidth: number;
}

export type Vec3 = [number, number, number];

/** A floating body as plain data (`sphere`, `box`, `Hull.floater`, `floater(id)`). */
export interface Floater {
  shape: "sphere" | "box" | "hull";
  radius: number;
  halfExtents: number[];
  mass: number;
  drag: number;
  position: number[];
  velocity: number[];
  push: number[];
  /** Read only: the water's force during the last step. */
  waterForce: number[];
  /** Unit quaternion x, y, z, w, body to world. */
  orientation: number[];
  angularVelocity: number[];
  pushTorque: number[];
  /** Read only: the water's torque during the last step. */
  waterTorque: number[];
  /** Column by column; used on input only when `hasInertia`. */
  inertia: number[];
  hasInertia: boolean;
  /** The mesh of a hull body (set by `Hull.floater`). */
  readonly hull?: Hull;
}

export interface BodyForces {
  force: Vec3;
  torque: Vec3;
}

/** The eye and the bottom for refraction texture coordinates. */
export interface RefractionView {
  eye: Vec3 | number[];
  /** Depth of the flat bottom below the rest surface (library default if left out). */
  depth?: number;
  /** Index of refraction (1.333 if left out). */
  ior?: number;
}

export interface LodParams {
  patchCells?: number;
  levels?: number;
  firstRange?: number;
  hysteresis?: number;
}

export interface Energy {
  kinetic: number;
  potential: number;
  total: number;
}

/** A refused call's error: `message` is the library's; `code` its status name. */
export interface SpringwaterError extends Error {
  code: string;
  status: number;
}

export declare class WaterSurface {
  /** A flat surface at rest with the seed's defaults. */
  constructor(cols: number, rows: number);
  /** A flat surface at rest: the defaults with `params` over them. */
  constructor(params: Partial<Params>);
  /** A surface restored from a snapshot. */
  static load(bytes: Uint8Array | ArrayBuffer | ArrayBufferView): WaterSurface;
  /** Frees the surface; twice is harmless, later calls throw. */
  free(): void;
  [Symbol.dispose](): void;

  readonly params: Params;
  readonly cols: number;
  readonly rows: number;
  readonly nodeCount: number;

  /** Seconds of the caller's clock on the fixed-step clock; the steps taken. */
  advance(seconds: number, disturbances?: Array<Rain | Wake>): number;
  step(n?: number): void;
  setStepCap(maxSteps: number, carry?: boolean): void;
  readonly interpolation: number;

  dropAt(x: number, z: number, height: number, radius: number): void;
  addForceAt(x: number, z: number, fx: number, fy: number, fz: number): void;
  heightAt(x: number, z: number): number;
  normalAt(x: number, z: number): Vec3;
  velocityAt(x: number, z: number): Vec3;
  /** 7 floats per point: height, normal x y z, velocity x y z. */
  sample(xz: ArrayLike<number>): Float32Array;

  /** Interleaved positions copied into `out` (3 × nodeCount floats). */
  writePositions(out: Float32Array): void;
  /** A view over wasm memory, valid until the next call into the library. */
  positions(): Float32Array;
  normals(): Float32Array;
  refractionUvs(view: RefractionView): Float32Array;
  /** Position, normal, uv: 8 floats per node. */
  vertices(view: RefractionView): Float32Array;

  setLodParams(params: LodParams): void;
  updateLod(eyeX: number, eyeY: number, eyeZ: number): boolean;
  lodIndices(): Uint32Array;

  /** Equal to Rust's `Surface::state_hash`. */
  stateHash(): bigint;
  saveInto(buf?: Uint8Array): Uint8Array;
  save(): Uint8Array;
  restore(bytes: Uint8Array | ArrayBuffer | ArrayBufferView): void;

  readonly energy: Energy;
  readonly simdLevel: string;
  shift(dcols: number, drows: number): void;
  follow(x: number, z: number): [number, number];
  readonly origin: [number, number];

  addFloater(body: Floater): number;
  floater(id: number): Floater;
  setFloater(id: number, fields: Partial<Floater>): void;
  pushFloater(id: number, force: Vec3 | number[]): void;
  pushFloaterAt(id: number, force: Vec3 | number[], point: Vec3 | number[]): void;
  removeFloater(id: number): void;
  readonly floaterCount: number;
  floaterIds(): number[];
  buoyancy: { gravity: number; density: number };
  bodyForces(body: Floater, seconds: number): BodyForces;
}

export declare class Hull {
  /** x, y, z per vertex; three indices per triangle, wound outward. */
  constructor(vertices: ArrayLike<number>, triangles: ArrayLike<number>);
  readonly handle: number;
  readonly volume: number;
  floater(mass: number, position: Vec3 | number[]): Floater;
  free(): void;
  [Symbol.dispose](): void;
}

export declare class Rain {
  constructor(rate: number, seed?: number | bigint, options?: { radius?: [number, number]; depth?: number });
  readonly id: number;
  rate: number;
  free(): void;
  [Symbol.dispose](): void;
}

export declare class Wake {
  constructor(
    path: Array<[number, number]> | ArrayLike<number>,
    options?: { speed?: number; radius?: number; strength?: number },
  );
  readonly id: number;
  free(): void;
  [Symbol.dispose](): void;
}

export interface Springwater {
  /** The build loaded: "simd128" or "portable". */
  readonly simd: "simd128" | "portable";
  readonly version: string;
  readonly WaterSurface: typeof WaterSurface;
  readonly Hull: typeof Hull;
  readonly Rain: typeof Rain;
  readonly Wake: typeof Wake;
  defaultParams(): Params;
  sphere(radius: number, mass: number, position: Vec3 | number[]): Floater;
  box(halfExtents: Vec3 | number[], mass: number, position: Vec3 | number[]): Floater;
  /** The wasm memory's size in bytes. */
  readonly memoryBytes: number;
}

export interface LoadOptions {
  /** Force a build; by default SIMD128 where the engine validates it. */
  simd?: "simd128" | "portable";
  /** The module's bytes, a Response or a URL instead of the packaged file. */
  wasm?: BufferSource | Response | URL | string;
}

export declare function load(options?: LoadOptions): Promise<Springwater>;
export declare function hasSimd128(): boolean;
