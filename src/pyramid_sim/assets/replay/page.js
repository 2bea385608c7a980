// The replay page's own code: unpack three.js and the run's data (both gzipped in the page),
// build the scene from the geoms, and set every body's pose from the slider's frame.
const inflate = async (id) => {
  const text = document.getElementById(id).textContent.trim();
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("gzip"));
  return new Response(stream).arrayBuffer();
};
const source = async (id) => new TextDecoder().decode(await inflate(id));
const moduleUrl = (code) => URL.createObjectURL(new Blob([code], { type: "text/javascript" }));

// three.js as its package ships it: three.module.js imports three.core.js, the controls
// import "three"; each is loaded from a blob URL, its import rewritten to the other's.
const coreUrl = moduleUrl(await source("three-core"));
const threeUrl = moduleUrl((await source("three-module")).replaceAll("./three.core.js", coreUrl));
const controlsCode = (await source("orbit-controls")).replace("from 'three'", `from '${threeUrl}'`);
const THREE = await import(threeUrl);
const { OrbitControls } = await import(moduleUrl(controlsCode));

const header = JSON.parse(document.getElementById("replay-header").textContent);
const buffer = await inflate("replay-data");
const arrays = {};
for (const [name, [kind, offset, length]] of Object.entries(header.arrays)) {
  const Type = { f4: Float32Array, i2: Int16Array, u2: Uint16Array, i4: Int32Array, i1: Int8Array }[kind];
  arrays[name] = new Type(buffer, offset, length);
}
// Poses are stored frame to frame as differences (mod 2^16): summed back here.
const frames = header.frames;
const bodies = header.bodies;
for (const name of ["pos", "quat"]) {
  const a = arrays[name];
  const stride = a.length / frames;
  for (let i = stride; i < a.length; i++) a[i] = a[i] + a[i - stride];
}

THREE.Object3D.DEFAULT_UP.set(0, 0, 1);
const view = document.getElementById("view");
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.shadowMap.enabled = true;
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xdfe3e8);
const camera = new THREE.PerspectiveCamera(45, 1, 0.02, 60);
const c = arrays.camera;
camera.position.set(c[0], c[1], c[2]);
const controls = new OrbitControls(camera, renderer.domElement);
controls.target.set(c[3], c[4], c[5]);
controls.update();

scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f96, 2.0));
const sun = new THREE.DirectionalLight(0xffffff, 2.2);
sun.position.set(1.2, -1.5, 3.5);
sun.target.position.set(0.5, 0, 0.7);
sun.castShadow = true;
sun.shadow.mapSize.set(2048, 2048);
Object.assign(sun.shadow.camera, { left: -1.5, right: 1.5, top: 1.5, bottom: -1.5, near: 0.5, far: 8 });
scene.add(sun, sun.target);

const meshes = [];
let vert = 0, face = 0;
for (let m = 0; m < arrays.mesh_vertnum.length; m++) {
  const nv = arrays.mesh_vertnum[m], nf = arrays.mesh_facenum[m];
  const g = new THREE.BufferGeometry();
  const position = Float32Array.from(arrays.mesh_vert.subarray(3 * vert, 3 * (vert + nv)), (v) => v * header.mesh_unit);
  g.setAttribute("position", new THREE.BufferAttribute(position, 3));
  g.setIndex(new THREE.BufferAttribute(arrays.mesh_face.slice(3 * face, 3 * (face + nf)), 1));
  g.computeVertexNormals();
  meshes.push(g);
  vert += nv;
  face += nf;
}

function shape(type, s, mesh) {
  switch (type) {
    case 0: return new THREE.PlaneGeometry(2 * (s[0] || 4), 2 * (s[1] || 4));
    case 2: return new THREE.SphereGeometry(s[0], 24, 16);
    case 3: return new THREE.CapsuleGeometry(s[0], 2 * s[1], 8, 16).rotateX(Math.PI / 2);
    case 4: return new THREE.SphereGeometry(1, 24, 16).scale(s[0], s[1], s[2]);
    case 5: return new THREE.CylinderGeometry(s[0], s[0], 2 * s[1], 32).rotateX(Math.PI / 2);
    case 6: return new THREE.BoxGeometry(2 * s[0], 2 * s[1], 2 * s[2]);
    case 7: return meshes[mesh];
    default: return null;
  }
}

const groups = [];
for (let b = 0; b < bodies; b++) {
  const group = new THREE.Group();
  scene.add(group);
  groups.push(group);
}
const edgeMaterial = new THREE.LineBasicMaterial({ color: 0x3a1a12 });
const walls = [];  // thin tall boxes of the room: hidden while the camera is behind them
for (let i = 0; i < arrays.geom_type.length; i++) {
  const type = arrays.geom_type[i];
  const s = arrays.geom_size.subarray(3 * i, 3 * i + 3);
  const geometry = shape(type, s, arrays.geom_mesh[i]);
  if (geometry === null) continue;
  const rgba = arrays.geom_rgba.subarray(4 * i, 4 * i + 4);
  const material = new THREE.MeshStandardMaterial({
    color: new THREE.Color().setRGB(rgba[0], rgba[1], rgba[2], THREE.SRGBColorSpace),
    transparent: rgba[3] < 1, opacity: rgba[3], roughness: 0.7, metalness: 0.05,
    flatShading: type === 7,
  });
  const mesh = new THREE.Mesh(geometry, material);
  const p = arrays.geom_pos.subarray(3 * i, 3 * i + 3), q = arrays.geom_quat.subarray(4 * i, 4 * i + 4);
  mesh.position.set(p[0], p[1], p[2]);
  mesh.quaternion.set(q[1], q[2], q[3], q[0]);
  mesh.castShadow = type !== 0;
  mesh.receiveShadow = true;
  groups[arrays.geom_body[i]].add(mesh);
  if (type === 6 && arrays.geom_body[i] !== 0) {  // a brick's edges, so each shows in a wall
    const edges = new THREE.LineSegments(new THREE.EdgesGeometry(geometry), edgeMaterial);
    edges.position.copy(mesh.position);
    edges.quaternion.copy(mesh.quaternion);
    groups[arrays.geom_body[i]].add(edges);
  }
  const thin = Math.min(s[0], s[1], s[2]), long = Math.max(s[0], s[1], s[2]);
  if (type === 6 && arrays.geom_body[i] === 0 && thin < 0.05 && long > 1) {
    const axis = new THREE.Vector3().setComponent(s.indexOf(thin), 1).applyQuaternion(mesh.quaternion);
    walls.push([mesh, axis]);
  }
}

// The plan's goals: where each brick is to rest, outlined.
const goals = new THREE.Group();
const goalLines = new THREE.LineBasicMaterial({ color: 0xe8b400 });
for (let i = 0; i < arrays.goal.length / 7; i++) {
  const g = arrays.goal.subarray(7 * i, 7 * i + 7);
  const box = new THREE.LineSegments(new THREE.EdgesGeometry(new THREE.BoxGeometry(2 * g[4], 2 * g[5], 2 * g[6])), goalLines);
  box.position.set(g[0], g[1], g[2]);
  box.rotation.z = g[3];
  goals.add(box);
}
scene.add(goals);
const showGoals = document.getElementById("goals");
showGoals.addEventListener("change", () => { goals.visible = showGoals.checked; });

const POS = header.pos_unit, QUAT = header.quat_unit;
let frame = 0;
function setFrame(i) {
  frame = Math.max(0, Math.min(frames - 1, Math.round(i)));
  const pos = arrays.pos, quat = arrays.quat;
  for (let b = 0; b < bodies; b++) {
    const p = 3 * (frame * bodies + b), q = 4 * (frame * bodies + b);
    groups[b].position.set(pos[p] * POS, pos[p + 1] * POS, pos[p + 2] * POS);
    groups[b].quaternion.set(quat[q + 1] * QUAT, quat[q + 2] * QUAT, quat[q + 3] * QUAT, quat[q] * QUAT).normalize();
  }
  slider.value = String(frame);
  clock.textContent = `${arrays.time[frame].toFixed(1)} s / ${arrays.time[frames - 1].toFixed(1)} s`;
}

const slider = document.getElementById("slider"), clock = document.getElementById("clock");
const play = document.getElementById("play"), speed = document.getElementById("speed");
slider.max = String(frames - 1);
let playing = false, shown = 0;  // shown: the frame as a real number, while playing
const toggle = () => {
  playing = !playing;
  if (playing && frame >= frames - 1) setFrame(0);
  shown = frame;
  play.textContent = playing ? "pause" : "play";
};
play.addEventListener("click", toggle);
slider.addEventListener("input", () => { setFrame(Number(slider.value)); shown = frame; });
window.addEventListener("keydown", (e) => { if (e.code === "Space") { e.preventDefault(); toggle(); } });

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
}
window.addEventListener("resize", resize);
resize();

const centre = new THREE.Vector3(c[3], c[4], c[5]);
const toCamera = new THREE.Vector3(), toCentre = new THREE.Vector3();
let last = performance.now();
function tick(now) {
  const dt = (now - last) / 1000;
  last = now;
  if (playing) {
    shown += (dt * Number(speed.value)) / header.frame_dt;
    if (shown >= frames - 1) { shown = frames - 1; toggle(); }
    setFrame(shown);
  }
  controls.update();
  for (const [wall, axis] of walls) {  // shown only from the room's side of it
    toCamera.subVectors(camera.position, wall.position);
    toCentre.subVectors(centre, wall.position);
    wall.visible = toCamera.dot(axis) * toCentre.dot(axis) > 0;
  }
  renderer.render(scene, camera);
  requestAnimationFrame(tick);
}
setFrame(0);
document.getElementById("message").remove();
// For a test or a script: the frame shown, and where a body is on the canvas, in pixels.
const onCanvas = (name) => {
  const b = header.names.indexOf(name);
  if (b < 0) return null;
  const p = groups[b].getWorldPosition(new THREE.Vector3()).project(camera);
  return [(p.x + 1) / 2 * view.clientWidth, (1 - p.y) / 2 * view.clientHeight];
};
window.replay = { frames, setFrame, onCanvas, get frame() { return frame; }, frameDt: header.frame_dt, ready: true };
requestAnimationFrame(tick);
