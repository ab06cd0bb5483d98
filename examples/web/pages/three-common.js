// three.js's shadows as a user ships them (README.md, "three.js"), for both of its renderers: the
// glb through GLTFLoader, every mesh white Lambert, one light at a time, rendered into a float
// target with each mesh's receiveShadow on (shadowed) and off (unshadowed). The driver divides.
// `three.js` runs it on WebGLRenderer, `three-webgpu.js` on WebGPURenderer (the page's import map
// makes 'three' three.webgpu.js there); each passes a backend (renderVisibilityWith).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { floatsToBase64, channelTopDown, readSettings, medianMsAsync, resolveJob, mergeLightParams, renderEachLight,
  distanceToBox, farthestCornerDistance } from './common.js';

// Modes: three.js's renderer.shadowMap.type values, and the CSM add-on (directional lights only).
const kModes = {
  basic: { type: THREE.BasicShadowMap, typeName: 'BasicShadowMap', settings: ['bias', 'normalBias', 'mapSize', 'shadowSide', 'fitCamera'] },
  pcf: { type: THREE.PCFShadowMap, typeName: 'PCFShadowMap', settings: ['bias', 'normalBias', 'mapSize', 'radius', 'shadowSide', 'fitCamera'] },
  vsm: { type: THREE.VSMShadowMap, typeName: 'VSMShadowMap', settings: ['bias', 'normalBias', 'mapSize', 'radius', 'blurSamples', 'shadowSide', 'fitCamera'] },
  csm: { type: THREE.PCFShadowMap, typeName: 'PCFShadowMap', settings: ['bias', 'normalBias', 'mapSize', 'cascades', 'shadowSide'] },
  // The soft shadows React Three Fiber users add (drei's <SoftShadows/>): @pmndrs/vanilla's pcss()
  // patches three's shadowmap_pars_fragment chunk; its defaults size 25, focus 0, samples 10.
  'pmndrs-pcss': { type: THREE.PCFShadowMap, typeName: 'PCFShadowMap + @pmndrs/vanilla pcss', pmndrs: true,
    settings: ['bias', 'normalBias', 'mapSize', 'shadowSide', 'fitCamera', 'size', 'focus', 'samples'] },
};
// --preset (README.md, "Presets"): `default` is three.js's defaults (PCFShadowMap, bias 0, a 512
// map; a spot's or point's shadow camera near 0.5, far 500); `typical` what three.js's official
// examples set per light: webgl_lights_hemisphere.html (directional: 2048 map, bias -0.0001),
// webgl_lights_spotlight.html (spot: 1024 map, bias -0.003, the shadow camera's near and far set
// around the scene, 2 and 10 there) and webgl_shadowmap_pointlight.html (point: bias -0.005, the
// light's distance, and so the shadow camera's far, set to the scene, 20 there).
const kPresets = {
  default: { mode: 'pcf', settings: {} },
  typical: {
    mode: 'pcf',
    settings: {
      directional: { mapSize: 2048, bias: -0.0001 },
      spot: { mapSize: 1024, bias: -0.003, fitCamera: true },
      point: { bias: -0.005, fitCamera: true },
    },
  },
};
const kDefaultMode = 'pcf'; // WebGLRenderer's shadowMap.type default
const kSettingKinds = {
  bias: 'number', normalBias: 'number', mapSize: 'integer', radius: 'number', blurSamples: 'integer',
  cascades: 'integer', shadowSide: ['front', 'back', 'double'], fitCamera: 'boolean',
  size: 'number', focus: 'number', samples: 'integer',
};
const kSides = { front: THREE.FrontSide, back: THREE.BackSide, double: THREE.DoubleSide };
const kMaxMapSize = 8192;

async function threeVersion() {
  const r = await fetch('/web/node_modules/three/package.json');
  return r.ok ? (await r.json()).version : `r${THREE.REVISION}`;
}

function parseSettings(settings, modeName) {
  const mode = kModes[modeName];
  const kinds = Object.fromEntries(mode.settings.map((k) => [k, kSettingKinds[k]]));
  const s = readSettings(settings, kinds, `three.js mode ${modeName}`);
  if (s.mapSize !== undefined && (s.mapSize < 1 || s.mapSize > kMaxMapSize)) throw new Error(`setting mapSize=${s.mapSize}: outside 1..${kMaxMapSize}`);
  if (s.blurSamples !== undefined && (s.blurSamples < 1 || s.blurSamples > 64)) throw new Error(`setting blurSamples=${s.blurSamples}: outside 1..64`);
  if (s.cascades !== undefined && (s.cascades < 1 || s.cascades > 4)) throw new Error(`setting cascades=${s.cascades}: outside 1..4`);
  return s;
}

/** The camera of view.json's OpenGL matrices as they are; nothing re-derives them from a fov. */
function makeCamera(view, backend) {
  const c = view.camera;
  const camera = new THREE.PerspectiveCamera(c.vfov_deg, c.width / c.height, c.near, c.far);
  camera.projectionMatrix.fromArray(c.proj_gl);
  if (backend.clipDepthZeroToOne) {
    // WebGPU's clip depth is 0..1, OpenGL's -1..1: z' = (z + w) / 2, the same frustum.
    camera.projectionMatrix.premultiply(new THREE.Matrix4().set(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0.5, 0.5, 0, 0, 0, 1));
    camera.coordinateSystem = THREE.WebGPUCoordinateSystem;
  }
  camera.projectionMatrixInverse.copy(camera.projectionMatrix).invert();
  camera.updateProjectionMatrix = () => {}; // the CSM add-on calls it: keep the file's projection
  camera.matrixAutoUpdate = false;
  camera.matrixWorldAutoUpdate = false;
  camera.matrixWorldInverse.fromArray(c.view_gl);
  camera.matrixWorld.copy(camera.matrixWorldInverse).invert();
  return camera;
}

/** Every mesh white Lambert, flat shaded (the geometric normal), keeping its side and alpha test. */
function whiteLambert(scene) {
  const materials = [];
  scene.traverse((o) => {
    if (!o.isMesh) return;
    const old = o.material;
    const cutout = old.alphaTest > 0;
    o.material = new THREE.MeshLambertMaterial({
      color: 0xffffff, flatShading: true, side: old.side, alphaTest: old.alphaTest,
      map: cutout ? old.map : null, opacity: cutout ? old.opacity : 1,
    });
    o.castShadow = true;
    materials.push(o.material);
  });
  return materials;
}

function findLight(scene, name) {
  const found = [];
  scene.traverse((o) => { if (o.isLight && (o.name === name || (o.parent && o.parent.name === name))) found.push(o); });
  if (found.length !== 1) throw new Error(`the glb has ${found.length} KHR_lights_punctual lights named "${name}", expected 1`);
  return found[0];
}

/**
 * A directional light's shadow camera fitted to the scene's bounds, as a user would: the light
 * placed outside the bounds along its direction, the orthographic box the bounds' eight corners in
 * its view (three.js's own default box is 10 x 10 units around the light's position).
 */
function fitDirectional(scene, light, bounds) {
  const from = light.getWorldPosition(new THREE.Vector3());
  const dir = light.target.getWorldPosition(new THREE.Vector3()).sub(from).normalize();
  const box = new THREE.Box3(new THREE.Vector3(...bounds.min), new THREE.Vector3(...bounds.max));
  const center = box.getCenter(new THREE.Vector3());
  const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-6);
  scene.attach(light);
  scene.attach(light.target);
  light.position.copy(center).addScaledVector(dir, -2 * radius);
  light.target.position.copy(center);
  const cam = light.shadow.camera;
  cam.position.copy(light.position);
  cam.lookAt(center);
  cam.updateMatrixWorld();
  const ls = new THREE.Box3();
  for (let i = 0; i < 8; ++i) {
    const p = new THREE.Vector3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z);
    ls.expandByPoint(p.applyMatrix4(cam.matrixWorldInverse));
  }
  const pad = 1e-4 * radius;
  Object.assign(cam, { left: ls.min.x - pad, right: ls.max.x + pad, bottom: ls.min.y - pad, top: ls.max.y + pad, near: -ls.max.z - pad, far: -ls.min.z + pad });
  cam.updateProjectionMatrix();
  return dir;
}

/**
 * @pmndrs/vanilla 1.25.0's pcss() on three's shader chunks, once per page (the chunks are global),
 * with the light's size, focus and samples (its defaults 25, 0, 10).
 */
async function patchPmndrsPcss(ctx, s) {
  if (ctx.pmndrs) return;
  if (!ctx.backend.shaderChunks) throw new Error('pmndrs-pcss: @pmndrs/vanilla patches WebGLRenderer\'s shader chunks; this renderer has none');
  const { pcss } = await import('@pmndrs/vanilla/core/pcss.js');
  ctx.pmndrs = { size: s.size ?? 25, focus: s.focus ?? 0, samples: s.samples ?? 10 };
  pcss(ctx.pmndrs);
}

/**
 * A spot's or point light's shadow camera near and far around the scene's box (`fitCamera`), as
 * three.js's examples set them for theirs: far just past the farthest corner, near half the way to
 * the box (a hundredth of far where the light is inside it). three.js's own are 0.5 and 500.
 */
function fitLocalCamera(light, bounds) {
  const p = light.getWorldPosition(new THREE.Vector3()).toArray();
  const far = 1.01 * farthestCornerDistance(p, bounds);
  const cam = light.shadow.camera;
  cam.near = Math.max(0.5 * distanceToBox(p, bounds), 0.01 * far);
  cam.far = far;
  cam.updateProjectionMatrix();
}

function applyShadowSettings(shadow, s) {
  if (s.bias !== undefined) shadow.bias = s.bias;
  if (s.normalBias !== undefined) shadow.normalBias = s.normalBias;
  if (s.mapSize !== undefined) shadow.mapSize.set(s.mapSize, s.mapSize);
  if (s.radius !== undefined) shadow.radius = s.radius;
  if (s.blurSamples !== undefined) shadow.blurSamples = s.blurSamples;
}

/** Bytes of the maps three.js r187 allocates (WebGLShadowMap.js) for one light's shadow. */
function shadowBytes(modeName, light, shadow, cascades) {
  const texels = shadow.mapSize.x * shadow.mapSize.y;
  if (modeName === 'vsm') return 12 * texels; // RG16F map + 32-bit float depth + RG16F blur pass
  const perTexel = 8; // RGBA8 colour attachment + 32-bit depth texture
  if (light.isPointLight) return 6 * perTexel * texels; // a cube
  return (modeName === 'csm' ? cascades : 1) * perTexel * texels;
}

function effectiveParams(modeName, shadow, s, cascades, light) {
  const p = { shadowMap: kModes[modeName].typeName, mapSize: shadow.mapSize.x, bias: shadow.bias, normalBias: shadow.normalBias };
  if (!light.isDirectionalLight && modeName !== 'csm') Object.assign(p, { near: shadow.camera.near, far: shadow.camera.far });
  if (modeName === 'pcf' || modeName === 'vsm') p.radius = shadow.radius;
  if (modeName === 'vsm') p.blurSamples = shadow.blurSamples;
  if (modeName === 'csm') p.cascades = cascades;
  if (kModes[modeName].pmndrs) Object.assign(p, { size: s.size ?? 25, focus: s.focus ?? 0, samples: s.samples ?? 10 });
  p.shadowSide = s.shadowSide || 'default';
  return p;
}

class LightRender {
  constructor(backend, renderer, scene, camera, light, width, height) {
    Object.assign(this, { backend, renderer, scene, camera, light, width, height });
    this.target = backend.createTarget(width, height);
  }

  frame(receive, before) {
    const byLight = this.backend.toggleCastShadow; // the node materials do not rebuild on receiveShadow
    if (byLight) this.light.castShadow = receive;
    this.scene.traverse((o) => { if (o.isMesh) o.receiveShadow = byLight || receive; });
    if (before) before();
    this.renderer.setRenderTarget(this.target);
    this.renderer.render(this.scene, this.camera);
  }

  async read() {
    const rgba = await this.backend.read(this.renderer, this.target, this.width, this.height);
    return channelTopDown(rgba, this.width, this.height, 0);
  }

  /** Shadowed and unshadowed radiance, and the shadowed frame's median time (compile excluded). */
  async run(before) {
    this.frame(true, before);
    const shadowed = await this.read();
    const failed = this.backend.shaderErrors && this.backend.shaderErrors();
    if (failed) throw new Error(`a shader failed to compile: ${failed}`);
    const frameMs = await medianMsAsync(async () => {
      this.frame(true, before);
      await this.backend.read(this.renderer, this.target, 1, 1); // waits for the frame
    });
    this.frame(false, before);
    return { shadowed, unshadowed: await this.read(), frameMs };
  }
}

async function renderOneLight(ctx, name) {
  const { scene, camera, view, job, materials, renderer, backend } = ctx;
  const light = findLight(scene, name);
  const typeName = light.isDirectionalLight ? 'directional' : light.isSpotLight ? 'spot' : 'point';
  const modeName = job.modeFor(typeName);
  if (backend.refuses && backend.refuses[modeName]) throw new Error(`${modeName}: ${backend.refuses[modeName]}`);
  const s = parseSettings(job.settingsFor(typeName), modeName);
  if (kModes[modeName].pmndrs) await patchPmndrsPcss(ctx, s);
  renderer.shadowMap.type = kModes[modeName].type;
  for (const m of materials) m.shadowSide = s.shadowSide ? kSides[s.shadowSide] : null;
  if (modeName === 'vsm' && light.isPointLight) throw new Error(`vsm: light "${name}" is a point light, and three.js has no VSM for point lights (it warns and draws no shadow)`);
  if (modeName === 'csm' && !light.isDirectionalLight) throw new Error(`csm: the CSM add-on shadows directional lights only; light "${name}" is a ${typeName} light`);
  light.visible = true;
  light.intensity = 1;
  let before = null;
  let shadow = light.shadow;
  let csm = null;
  if (light.isDirectionalLight) {
    const dir = fitDirectional(scene, light, view.scene.bounds);
    if (modeName === 'csm') {
      light.visible = false; // the add-on lights the scene with its own cascade lights
      // Imported here: the add-on patches WebGLRenderer's ShaderChunk, which three.webgpu.js lacks.
      const { CSM } = await import('three/addons/csm/CSM.js');
      csm = new CSM({ camera, parent: scene, lightDirection: dir, lightIntensity: 1, cascades: s.cascades, shadowMapSize: s.mapSize, shadowBias: s.bias });
      for (const cl of csm.lights) applyShadowSettings(cl.shadow, { normalBias: s.normalBias });
      for (const m of materials) csm.setupMaterial(m);
      shadow = csm.lights[0].shadow;
      before = () => csm.update();
    }
  }
  if (!csm) {
    light.castShadow = true;
    applyShadowSettings(light.shadow, s);
    if (s.fitCamera && !light.isDirectionalLight) fitLocalCamera(light, view.scene.bounds);
  }
  const r = await new LightRender(backend, renderer, scene, camera, light, view.camera.width, view.camera.height).run(before);
  const cascades = csm ? csm.cascades : 1;
  const out = {
    bytes: shadowBytes(modeName, light, shadow, cascades),
    params: effectiveParams(modeName, shadow, s, cascades, light),
    result: { shadowed: floatsToBase64(r.shadowed), unshadowed: floatsToBase64(r.unshadowed), frameMs: r.frameMs },
  };
  light.visible = false;
  light.castShadow = false;
  if (csm) csm.remove();
  return out;
}

/**
 * The page's renderVisibility on `backend`: {label (after the version in `renderer`), create() -> {renderer, info} (async; shadows
 * on, no tone mapping, linear output), createTarget(width, height), read(renderer, target, width,
 * height) -> RGBA Float32Array, rows bottom first (async), refuses: {mode: reason}, toggleCastShadow:
 * shadow on and off by the light's castShadow instead of every mesh's receiveShadow}.
 */
export async function renderVisibilityWith(job, backend) {
  const resolved = resolveJob(job, kPresets, kDefaultMode, 'three.js');
  for (const type of ['directional', 'spot', 'point']) {
    const modeName = resolved.modeFor(type);
    if (!kModes[modeName]) throw new Error(`unknown mode "${modeName}" for three.js (known: ${Object.keys(kModes).join(', ')})`);
    parseSettings(resolved.settingsFor(type), modeName); // a bad setting fails before any render
  }
  const { renderer, info } = await backend.create();
  let gltf;
  try {
    gltf = await new GLTFLoader().loadAsync(job.glbUrl);
  } catch (e) {
    throw new Error(`GLTFLoader cannot load ${job.glbUrl}: ${e.message || e}`);
  }
  // A Scene around the glTF's root Group: WebGPURenderer's shadows need one (WebGLRenderer takes either).
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  scene.background = null;
  scene.environment = null;
  scene.updateMatrixWorld(true);
  scene.traverse((o) => { if (o.isLight) o.visible = false; });
  const materials = whiteLambert(scene);
  const ctx = { scene, camera: makeCamera(job.view, backend), view: job.view, job: resolved, materials, renderer, backend };
  const { lights, memoryBytes, perLight } = await renderEachLight(job.lights, (name) => renderOneLight(ctx, name));
  renderer.dispose();
  // Every preset of this page runs one mode on every light.
  return { renderer: `three.js ${await threeVersion()}${backend.label ? ' ' + backend.label : ''}`, glRenderer: info, mode: resolved.modeFor('directional'),
    params: mergeLightParams(perLight), memoryBytes, lights };
}
