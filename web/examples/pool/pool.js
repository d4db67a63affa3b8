// The pool: springwater's surface drawn by three.js, the tiled bottom seen through it by the
// library's refraction coordinates. Click or tap to drop, R for rain, drag to orbit.
// `?simd=portable` loads the portable build. The page exposes `window.pool` for the
// browser test (examples/browser-test.mjs).
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";
import { load } from "springwater";

const COLS = 128;
const ROWS = 128;
const DEPTH = 8; // the bottom, below the calm surface
const WIDTH = COLS - 1; // world units at the default spacing of 1
const LENGTH = ROWS - 1;

const hud = document.getElementById("hud");
const query = new URLSearchParams(location.search);
const sw = await load(query.get("simd") ? { simd: query.get("simd") } : {});
const water = new sw.WaterSurface(COLS, ROWS);
const rain = new sw.Rain(0, 1);

// three.js: renderer, camera, orbit controls.
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(Math.min(devicePixelRatio, 2));
renderer.setSize(innerWidth, innerHeight);
document.body.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2630);
const camera = new THREE.PerspectiveCamera(50, innerWidth / innerHeight, 0.5, 1000);
camera.position.set(WIDTH / 2, 62, LENGTH + 48);
const controls = new OrbitControls(camera, renderer.domElement);
controls.target.set(WIDTH / 2, -4, LENGTH / 2 + 8);
controls.maxPolarAngle = 1.45;
controls.update();
addEventListener("resize", () => {
  camera.aspect = innerWidth / innerHeight;
  camera.updateProjectionMatrix();
  renderer.setSize(innerWidth, innerHeight);
});

// The bottom: pale tiles with grout, a darker border row and a lane line down the middle.
function tiles() {
  const canvas = document.createElement("canvas");
  const n = 24;
  const px = 24;
  canvas.width = canvas.height = n * px;
  const g = canvas.getContext("2d");
  let seed = 12345;
  const random = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
  for (let i = 0; i < n; i++) {
    for (let j = 0; j < n; j++) {
      const edge = i === 0 || j === 0 || i === n - 1 || j === n - 1;
      const lane = i === n / 2;
      const shade = 0.93 + 0.07 * random();
      const [r, gr, b] = edge ? [70, 120, 150] : lane && j > 1 && j < n - 2 ? [60, 85, 120] : [205, 228, 236];
      g.fillStyle = `rgb(${r * shade},${gr * shade},${b * shade})`;
      g.fillRect(i * px, j * px, px, px);
    }
  }
  g.strokeStyle = "rgba(90,110,120,0.55)";
  g.lineWidth = 2;
  for (let k = 0; k <= n; k++) {
    g.beginPath();
    g.moveTo(k * px, 0);
    g.lineTo(k * px, n * px);
    g.moveTo(0, k * px);
    g.lineTo(n * px, k * px);
    g.stroke();
  }
  const texture = new THREE.CanvasTexture(canvas);
  texture.colorSpace = THREE.SRGBColorSpace;
  texture.anisotropy = 4;
  return texture;
}

// The water: positions, normals and refraction UVs from the library each frame; the
// triangles from its LOD index buffer.
const nodes = water.nodeCount;
const geometry = new THREE.BufferGeometry();
geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * nodes), 3));
geometry.setAttribute("normal", new THREE.BufferAttribute(new Float32Array(3 * nodes), 3));
geometry.setAttribute("uv", new THREE.BufferAttribute(new Float32Array(2 * nodes), 2));
for (const name of ["position", "normal", "uv"]) geometry.attributes[name].setUsage(THREE.DynamicDrawUsage);
const material = new THREE.ShaderMaterial({
  uniforms: { tiles: { value: tiles() }, sun: { value: new THREE.Vector3(0.4, 0.8, -0.45).normalize() } },
  vertexShader: `
    varying vec2 vBottom;
    varying vec3 vNormal;
    varying vec3 vWorld;
    void main() {
      vBottom = uv;
      vNormal = normal;
      vWorld = (modelMatrix * vec4(position, 1.0)).xyz;
      gl_Position = projectionMatrix * viewMatrix * vec4(vWorld, 1.0);
    }`,
  fragmentShader: `
    uniform sampler2D tiles;
    uniform vec3 sun;
    varying vec2 vBottom;
    varying vec3 vNormal;
    varying vec3 vWorld;
    void main() {
      vec3 n = normalize(vNormal);
      vec3 v = normalize(cameraPosition - vWorld);
      vec2 uv = clamp(vBottom, 0.0, 1.0);
      vec3 bottom = texture2D(tiles, vec2(uv.x, 1.0 - uv.y)).rgb;
      vec3 through = bottom * vec3(0.72, 0.9, 0.95);
      float cosi = max(dot(n, v), 0.0);
      float fresnel = 0.02 + 0.98 * pow(1.0 - cosi, 5.0);
      vec3 r = reflect(-v, n);
      vec3 sky = mix(vec3(0.45, 0.6, 0.75), vec3(0.85, 0.92, 1.0), clamp(r.y, 0.0, 1.0));
      float glint = pow(max(dot(r, sun), 0.0), 120.0) * 1.5;
      // Slopes facing the sun lighter, slopes away darker: the rings show.
      float shade = clamp(1.0 + 6.0 * (dot(n, sun) - sun.y), 0.55, 1.6);
      gl_FragColor = vec4(mix(through * shade, sky, fresnel) + glint, 1.0);
      #include <colorspace_fragment>
    }`,
});
const surface = new THREE.Mesh(geometry, material);
surface.frustumCulled = false;
scene.add(surface);

// The deck around the pool.
const deck = new THREE.Shape();
deck.moveTo(-12, -12).lineTo(WIDTH + 12, -12).lineTo(WIDTH + 12, LENGTH + 12).lineTo(-12, LENGTH + 12);
const hole = new THREE.Path();
hole.moveTo(0, 0).lineTo(0, LENGTH).lineTo(WIDTH, LENGTH).lineTo(WIDTH, 0);
deck.holes.push(hole);
const deckMesh = new THREE.Mesh(new THREE.ShapeGeometry(deck), new THREE.MeshLambertMaterial({ color: 0xc9bfa8, side: THREE.DoubleSide }));
deckMesh.rotation.x = Math.PI / 2;
deckMesh.position.y = 0.6;
scene.add(deckMesh);
scene.add(new THREE.HemisphereLight(0xddeeff, 0x405060, 1.6));
const light = new THREE.DirectionalLight(0xffffff, 1.8);
light.position.set(40, 80, -40);
scene.add(light);

// Boats of the shipped hull (assets/boat.obj: 6 long, bow +x, origin on the keel) at twice
// its size, their centre of mass put 0.7 above the keel.
async function boatMesh() {
  const text = await (await fetch("/assets/boat.obj")).text();
  const vertices = [];
  const triangles = [];
  for (const line of text.split("\n")) {
    const [kind, ...rest] = line.trim().split(/\s+/);
    if (kind === "v") vertices.push(...rest.map(Number));
    if (kind === "f") triangles.push(...rest.map((f) => parseInt(f, 10) - 1));
  }
  for (let i = 0; i < vertices.length; i++) vertices[i] = 2 * vertices[i] - (i % 3 === 1 ? 0.7 : 0);
  return { vertices, triangles };
}
const mesh = await boatMesh();
const hull = new sw.Hull(mesh.vertices, mesh.triangles);
const boatGeometry = new THREE.BufferGeometry();
boatGeometry.setAttribute("position", new THREE.BufferAttribute(Float32Array.from(mesh.vertices), 3));
boatGeometry.setIndex(mesh.triangles);
boatGeometry.computeVertexNormals();
const boats = [
  { colour: 0xd24d3e, centre: [36, 36], turn: 1 },
  { colour: 0xf2f2ea, centre: [91, 88], turn: -1 },
  { colour: 0x3e7bd2, centre: [36, 91], turn: 1 },
].map((b, k) => {
  const radius = 16;
  const start = k * 2.4;
  const body = hull.floater(0.45 * hull.volume, [b.centre[0] + radius * Math.sin(start), 0, b.centre[1] + radius * Math.cos(start)]);
  const id = water.addFloater(body);
  const object = new THREE.Mesh(boatGeometry, new THREE.MeshLambertMaterial({ color: b.colour }));
  scene.add(object);
  return { ...b, id, radius, object };
});
hull.free();

// The helmsman, once a frame: thrust along the heading and a turning couple that keeps each
// boat on its circle. Pushes last one step, so they are scaled by the steps of the frame.
function steer(steps) {
  for (const b of boats) {
    const body = water.floater(b.id);
    const [qx, qy, qz, qw] = body.orientation;
    const heading = new THREE.Vector3(1, 0, 0).applyQuaternion(new THREE.Quaternion(qx, qy, qz, qw));
    heading.y = 0;
    heading.normalize();
    const out = new THREE.Vector3(body.position[0] - b.centre[0], 0, body.position[2] - b.centre[1]);
    const off = (out.length() - b.radius) / b.radius;
    out.normalize();
    const wanted = new THREE.Vector3(0, 1, 0).cross(out).multiplyScalar(b.turn).addScaledVector(out, -Math.max(-1, Math.min(1, off))).normalize();
    const sine = heading.clone().cross(wanted).y;
    const error = heading.dot(wanted) >= 0 ? sine : Math.sign(sine) || 1;
    const speed = 8;
    const along = body.velocity[0] * heading.x + body.velocity[2] * heading.z;
    const thrust = body.mass * (body.drag * speed + 4 * (speed - along)) * steps;
    water.pushFloater(b.id, [heading.x * thrust, 0, heading.z * thrust]);
    const yaw = body.inertia[4];
    const moment = yaw * (12 * error + 8 * ((b.turn * speed) / b.radius - body.angularVelocity[1])) * steps;
    const arm = 3;
    const f = moment / (2 * arm);
    const [px, py, pz] = body.position;
    // +f across the heading at the bow, −f at the stern: a couple about +y.
    const side = [-heading.z * f, 0, heading.x * f];
    water.pushFloaterAt(b.id, side.map((v) => -v), [px + heading.x * arm, py, pz + heading.z * arm]);
    water.pushFloaterAt(b.id, side, [px - heading.x * arm, py, pz - heading.z * arm]);
    b.object.position.set(px, py, pz);
    b.object.quaternion.set(qx, qy, qz, qw);
  }
}

// Click or tap: a drop where the ray meets the calm surface.
const raycaster = new THREE.Raycaster();
const calm = new THREE.Plane(new THREE.Vector3(0, 1, 0), 0);
let lastDrop = null;
let pressed = null;
renderer.domElement.addEventListener("pointerdown", (e) => (pressed = [e.clientX, e.clientY]));
renderer.domElement.addEventListener("pointerup", (e) => {
  if (!pressed || Math.hypot(e.clientX - pressed[0], e.clientY - pressed[1]) > 4) return; // a drag orbits
  const ndc = new THREE.Vector2((e.clientX / innerWidth) * 2 - 1, -(e.clientY / innerHeight) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  const hit = raycaster.ray.intersectPlane(calm, new THREE.Vector3());
  if (hit && hit.x > 1 && hit.x < WIDTH - 1 && hit.z > 1 && hit.z < LENGTH - 1) {
    water.dropAt(hit.x, hit.z, -2.5, 3);
    lastDrop = [hit.x, hit.z];
  }
});
let raining = false;
addEventListener("keydown", (e) => {
  if (e.key === "r" || e.key === "R") {
    raining = !raining;
    rain.rate = raining ? 25 : 0;
  }
});

// The frame: advance on the fixed clock, upload, draw.
let paused = false;
let stepMs = 0;
let last = performance.now();
let lodChanged = true;
function upload() {
  const eye = camera.position;
  geometry.attributes.position.array.set(water.positions());
  geometry.attributes.normal.array.set(water.normals());
  geometry.attributes.uv.array.set(water.refractionUvs({ eye: [eye.x, eye.y, eye.z], depth: DEPTH }));
  for (const name of ["position", "normal", "uv"]) geometry.attributes[name].needsUpdate = true;
  if (water.updateLod(eye.x, eye.y, eye.z) || lodChanged) {
    geometry.setIndex(new THREE.BufferAttribute(Uint32Array.from(water.lodIndices()), 1));
    lodChanged = false;
  }
}
function frame(now) {
  const seconds = Math.max(0, Math.min((now - last) / 1000, 0.1));
  last = now;
  if (!paused) {
    const t0 = performance.now();
    const steps = water.advance(seconds, [rain]);
    const t1 = performance.now();
    if (steps > 0) stepMs = 0.9 * stepMs + (0.1 * (t1 - t0)) / steps;
    steer(Math.max(steps, 1));
  }
  controls.update();
  upload();
  renderer.render(scene, camera);
  hud.textContent =
    `springwater ${sw.version}  ${sw.simd}\n` +
    `${COLS}×${ROWS}  step ${stepMs.toFixed(2)} ms\n` +
    `click: drop   R: rain ${raining ? "on" : "off"}   drag: orbit`;
  requestAnimationFrame(frame);
}
requestAnimationFrame(frame);

// For the browser test: pause, step, project a world point to the screen, run scenes.
window.pool = {
  sw,
  water,
  get lastDrop() {
    return lastDrop;
  },
  get stepMs() {
    return stepMs;
  },
  pause(on) {
    paused = on;
  },
  step(n) {
    water.step(n);
  },
  toScreen(x, y, z) {
    const p = new THREE.Vector3(x, y, z).project(camera);
    return [((p.x + 1) / 2) * innerWidth, ((1 - p.y) / 2) * innerHeight];
  },
};
window.poolReady = true;
