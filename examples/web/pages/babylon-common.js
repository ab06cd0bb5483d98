// Babylon.js's shadows as a user ships them (README.md, "Babylon.js"), on either of its engines
// (pages/babylon.js: WebGL2 Engine; pages/babylon-webgpu.js: WebGPUEngine, each a backend): the glb through Babylon's
// own glTF loader in a right-handed scene, every mesh a white Lambert StandardMaterial, no
// ambient, no environment, no image processing, one light at a time, rendered into an RGBA float
// RenderTargetTexture with the light's shadow generator on (light.shadowEnabled) and off. The
// driver divides.
// The modules this page uses, not @babylonjs/core/index.js: its 3,000 files take a minute to load
// over HTTP on a loaded 2-core machine.
import { Engine } from '@babylonjs/core/Engines/engine.js';
import { Constants } from '@babylonjs/core/Engines/constants.js';
import { Scene } from '@babylonjs/core/scene.js';
import { SceneLoader } from '@babylonjs/core/Loading/sceneLoader.js';
import { Camera } from '@babylonjs/core/Cameras/camera.js';
import { Matrix, Vector3 } from '@babylonjs/core/Maths/math.vector.js';
import { Color3, Color4 } from '@babylonjs/core/Maths/math.color.js';
import { Material } from '@babylonjs/core/Materials/material.js';
import { StandardMaterial } from '@babylonjs/core/Materials/standardMaterial.js';
import { RenderTargetTexture } from '@babylonjs/core/Materials/Textures/renderTargetTexture.js';
import { Texture } from '@babylonjs/core/Materials/Textures/texture.js';
import { ShadowGenerator, CascadedShadowGenerator } from '@babylonjs/core/Lights/Shadows/index.js';
import { DirectionalLight } from '@babylonjs/core/Lights/directionalLight.js';
import { PointLight } from '@babylonjs/core/Lights/pointLight.js';
import '@babylonjs/loaders/glTF/index.js';
import { floatsToBase64, channelTopDown, readSettings, medianMsAsync, resolveJob, mergeLightParams, renderEachLight,
  distanceToBox, farthestCornerDistance } from './common.js';

// Modes: the generator's own filter switches. `default` is a bare ShadowGenerator.
const kModes = {
  'default': () => {},
  'poisson': (g) => { g.usePoissonSampling = true; },
  'esm': (g) => { g.useExponentialShadowMap = true; },
  'blur-esm': (g) => { g.useBlurExponentialShadowMap = true; },
  'close-esm': (g) => { g.useCloseExponentialShadowMap = true; },
  'pcf-low': (g) => pcf(g, ShadowGenerator.QUALITY_LOW),
  'pcf-medium': (g) => pcf(g, ShadowGenerator.QUALITY_MEDIUM),
  'pcf-high': (g) => pcf(g, ShadowGenerator.QUALITY_HIGH),
  'pcss': (g) => { g.useContactHardeningShadow = true; },
  'cascaded': () => {},
};
// Babylon.js's filter setter turns PCF and PCSS into Poisson sampling on a point light (a cube
// map: shadowGenerator.js, "PCF on cubemap would also be expensive"): these modes refuse points.
const kPoissonOnCubes = ['pcf-low', 'pcf-medium', 'pcf-high', 'pcss'];
// --preset (README.md, "Presets"): `default` is a bare ShadowGenerator (FILTER_NONE, bias
// 0.00005, a half-float map of the documentation's 1024); `typical` what Babylon's shadows
// documentation (doc.babylonjs.com/features/featuresDeepDive/lights/shadows) sets: 1024 maps,
// usePercentageCloserFiltering (its filteringQuality default, QUALITY_HIGH) where Babylon runs it
// (Poisson sampling on a point light's cube, as the filter setter turns it), and the
// troubleshooting section's shadowGenerator.bias = 0.01.
const kPresets = {
  default: { mode: 'default', settings: {} },
  typical: {
    mode: { directional: 'pcf-high', spot: 'pcf-high', point: 'poisson' },
    settings: { directional: { bias: 0.01 }, spot: { bias: 0.01 }, point: { bias: 0.01 } },
  },
};
function pcf(g, quality) {
  g.usePercentageCloserFiltering = true;
  g.filteringQuality = quality;
}

// `--set` names: the generator's own properties, plus its constructor's mapSize and
// usefullFloatFirst (a 32-bit float map instead of Babylon's default half float).
const kSettingKinds = {
  mapSize: 'integer', usefullFloatFirst: 'boolean', bias: 'number', normalBias: 'number',
  depthScale: 'number', frustumEdgeFalloff: 'number', forceBackFacesOnly: 'boolean',
  contactHardeningLightSizeUVRatio: 'number', blurScale: 'integer', blurKernel: 'integer',
  blurBoxOffset: 'integer', useKernelBlur: 'boolean',
  numCascades: 'integer', lambda: 'number', stabilizeCascades: 'boolean', cascadeBlendPercentage: 'number',
};
const kCascadedOnly = ['numCascades', 'lambda', 'stabilizeCascades', 'cascadeBlendPercentage'];
// Babylon's constructor has no default map size; its documentation's examples use 1024.
const kDefaultMapSize = 1024;
const kMaxMapSize = 8192;

function parseSettings(settings, modeName) {
  if (!Object.hasOwn(kModes, modeName)) throw new Error(`unknown mode "${modeName}" for babylon (known: ${Object.keys(kModes).join(', ')})`);
  const s = readSettings(settings, kSettingKinds, `babylon mode ${modeName}`);
  const mapSize = s.mapSize === undefined ? kDefaultMapSize : s.mapSize;
  if (mapSize < 16 || mapSize > kMaxMapSize) throw new Error(`setting mapSize=${mapSize}: outside 16..${kMaxMapSize}`);
  for (const k of kCascadedOnly) {
    if (s[k] !== undefined && modeName !== 'cascaded') throw new Error(`setting ${k}: for mode cascaded only`);
  }
  if (s.numCascades !== undefined && (s.numCascades < 2 || s.numCascades > 4)) {
    throw new Error(`setting numCascades=${s.numCascades}: outside 2..4 (CascadedShadowGenerator's range)`);
  }
  if (s.blurScale !== undefined && (s.blurScale < 1 || s.blurScale > 8)) throw new Error(`setting blurScale=${s.blurScale}: outside 1..8`);
  if (s.blurKernel !== undefined && (s.blurKernel < 1 || s.blurKernel > 64)) throw new Error(`setting blurKernel=${s.blurKernel}: outside 1..64`);
  return { ...s, mapSize };
}


/**
 * The camera of view.json's OpenGL matrices as they are: Babylon's row-vector matrices, stored
 * row-major, are the same 16 numbers as OpenGL's column-major ones, and a right-handed Babylon
 * scene on WebGL has OpenGL's view space (looking down -z) and clip depth (-1..1).
 */
function createCamera(scene, c) {
  const viewFromWorld = Matrix.FromArray(c.view_gl);
  const projection = Matrix.FromArray(c.proj_gl);
  if (scene.getEngine().isNDCHalfZRange) {
    // WebGPU's clip depth is 0..1, OpenGL's -1..1: z' = (z + w) / 2, the same frustum (Babylon's
    // row vectors: the OpenGL matrix times this one).
    projection.multiplyToRef(Matrix.FromValues(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0.5, 0, 0, 0, 0.5, 1), projection);
  }
  const camera = new Camera('view.json', Vector3.FromArray(c.eye), scene);
  camera._getViewMatrix = () => viewFromWorld.clone(); // Camera's hook for a derived camera's view
  camera.minZ = c.near;
  camera.maxZ = c.far;
  camera.freezeProjectionMatrix(projection);
  scene.activeCamera = camera;
  return camera;
}

/** White Lambert in place of a glTF material, keeping what shapes the shadow: side, two-sided lighting and alpha test. */
function whiteMaterial(scene, original) {
  const m = new StandardMaterial(`white ${original ? original.name : ''}`, scene);
  m.diffuseColor = Color3.White();
  m.specularColor = Color3.Black();
  m.emissiveColor = Color3.Black();
  m.ambientColor = Color3.Black();
  if (!original) return m;
  m.backFaceCulling = original.backFaceCulling;
  m.sideOrientation = original.sideOrientation;
  // The loader lights a doubleSided material's back faces with the flipped normal: the oracle's
  // two-sided cos, not 0 (a back face seen from the camera would read as shadow).
  m.twoSidedLighting = original.twoSidedLighting === true;
  if (original.transparencyMode === Material.MATERIAL_ALPHATEST && original.albedoTexture) {
    // The cutout's alpha, tested against alphaCutOff, as opacityTexture: the base colour texture's
    // RGB as diffuseTexture would tint the unshadowed render (black in the holes). Babylon's shadow
    // generator reads material.getAlphaTestTexture() for its alpha test, the diffuse texture for a
    // StandardMaterial (the albedo for the loader's own PBRMaterial, what a user gets): a cutout in
    // opacityTexture alone is drawn opaque into the map. kCutoutsInMap makes the generator read it.
    m.opacityTexture = original.albedoTexture;
    m.transparencyMode = Material.MATERIAL_ALPHATEST;
    m.alphaCutOff = original.alphaCutOff;
  }
  return m;
}

const hasGeometry = (m) => m.getTotalVertices && m.getTotalVertices() > 0;

async function loadScene(engine, job) {
  const scene = new Scene(engine);
  scene.useRightHandedSystem = true; // glTF's handedness: the loader adds no mirroring root
  scene.clearColor = new Color4(0, 0, 0, 0);
  scene.ambientColor = Color3.Black();
  scene.environmentTexture = null;
  scene.fogEnabled = false;
  scene.imageProcessingConfiguration.isEnabled = false; // no tone mapping, exposure or gamma
  SceneLoader.ShowLoadingScreen = false;
  try {
    await SceneLoader.AppendAsync('', job.glbUrl, scene, undefined, '.glb');
  } catch (e) {
    throw new Error(`Babylon's glTF loader cannot load ${job.glbUrl}: ${e.message || e}`);
  }
  const white = new Map();
  for (const mesh of scene.meshes.filter(hasGeometry)) {
    const key = mesh.material || null;
    if (!white.has(key)) white.set(key, whiteMaterial(scene, key));
    mesh.material = white.get(key);
    mesh.receiveShadows = true;
  }
  for (const c of scene.cameras.slice()) c.dispose();
  for (const l of scene.lights) l.setEnabled(false);
  createCamera(scene, job.view.camera);
  return scene;
}

/** The loader names a light by its KHR_lights_punctual name, else by its node's. */
function findLight(scene, name) {
  const found = scene.lights.filter((l) => l.name === name || (l.parent && l.parent.name === name));
  if (found.length !== 1) throw new Error(`the glb has ${found.length} KHR_lights_punctual lights named "${name}", expected 1`);
  return found[0];
}

/**
 * A spot's or a point light's shadow depth range fitted to the scene's box as seen from the
 * light, as a user sets shadowMinZ/shadowMaxZ (Babylon's default is the camera's near and far
 * planes, meant for the camera: casters nearer the light than the camera's near are clipped).
 */
function fitLocalDepth(light, bounds) {
  const p = light.getAbsolutePosition().asArray();
  const far = 1.01 * farthestCornerDistance(p, bounds);
  // No caster is nearer the light than the box: half that distance keeps a PCF map's non-linear
  // depth usable (a near of far / 1000 squeezes it against 1, where any bias removes the shadow).
  light.shadowMinZ = Math.max(0.5 * distanceToBox(p, bounds), 0.01 * far);
  light.shadowMaxZ = far;
}

function createGenerator(scene, light, modeName, s, bounds) {
  const isDirectional = light instanceof DirectionalLight;
  if (modeName === 'cascaded' && !isDirectional) {
    throw new Error(`cascaded: CascadedShadowGenerator shadows directional lights only; light "${light.name}" is a ${light.getClassName()}`);
  }
  if (isDirectional) {
    // Fitted to the scene as a user would: Babylon's own autoUpdateExtends (the casters' bounds
    // in light space, padded by shadowOrthoScale 0.1) plus autoCalcShadowZBounds for the depth.
    light.autoUpdateExtends = true;
    light.autoCalcShadowZBounds = true;
  } else {
    fitLocalDepth(light, bounds); // spot and point lights alike
  }
  if (light instanceof PointLight && kPoissonOnCubes.includes(modeName)) {
    throw new Error(`${modeName}: Babylon.js runs Poisson sampling instead on a point light's cube map (shadowGenerator.js), so a ${modeName} row would be mislabelled; light "${light.name}" is a point light (use --mode poisson)`);
  }
  const useFloat = s.usefullFloatFirst === true;
  const gen = modeName === 'cascaded'
    ? new CascadedShadowGenerator(s.mapSize, light, useFloat)
    : new ShadowGenerator(s.mapSize, light, useFloat);
  kModes[modeName](gen);
  // The generator's alpha test through the white material's opacityTexture, where the page put the
  // glTF cutout (whiteMaterial): the texture a user's glTF material gives getAlphaTestTexture().
  gen.useOpacityTextureForTransparentShadow = true;
  for (const [key, value] of Object.entries(s)) {
    if (key !== 'mapSize' && key !== 'usefullFloatFirst') gen[key] = value;
  }
  for (const m of scene.meshes.filter(hasGeometry)) gen.addShadowCaster(m, false);
  return gen;
}

/** The settings in effect: the generator's own numbers, after Babylon's clamping. */
// ShadowGenerator.FILTER_* by value: the filter that runs, whatever was asked.
const kFilterNames = { 0: 'none', 1: 'exponential', 2: 'poisson', 3: 'blur-exponential', 4: 'close-exponential',
  5: 'blur-close-exponential', 6: 'pcf', 7: 'pcss' };

function effectiveParams(gen, s, light) {
  const p = { generator: gen.getClassName(), mapSize: s.mapSize, usefullFloatFirst: s.usefullFloatFirst === true,
    bias: gen.bias, normalBias: gen.normalBias, filter: kFilterNames[gen.filter] || String(gen.filter), depthScale: gen.depthScale,
    shadowMinZ: light.shadowMinZ === undefined ? 'camera' : light.shadowMinZ,
    shadowMaxZ: light.shadowMaxZ === undefined ? 'camera' : light.shadowMaxZ,
    forceBackFacesOnly: gen.forceBackFacesOnly };
  if (gen.usePercentageCloserFiltering || gen.useContactHardeningShadow) p.filteringQuality = gen.filteringQuality;
  if (gen.useContactHardeningShadow) p.contactHardeningLightSizeUVRatio = gen.contactHardeningLightSizeUVRatio;
  if (gen.useBlurExponentialShadowMap || gen.useBlurCloseExponentialShadowMap) {
    Object.assign(p, { blurScale: gen.blurScale, blurBoxOffset: gen.blurBoxOffset, useKernelBlur: gen.useKernelBlur, blurKernel: gen.blurKernel });
  }
  if (gen instanceof CascadedShadowGenerator) {
    Object.assign(p, { numCascades: gen.numCascades, lambda: gen.lambda, stabilizeCascades: gen.stabilizeCascades,
      cascadeBlendPercentage: gen.cascadeBlendPercentage });
  }
  return p;
}

/** Bytes a texel of an InternalTexture (Babylon's Constants.TEXTURETYPE_* and TEXTUREFORMAT_*). */
function texelBytes(t) {
  const channelBytes = { 0: 1, 1: 4, 2: 2 }[t.type] || 4;
  const channels = { 6: 1, 7: 2, 4: 3, 5: 4 }[t.format];
  return channels === undefined ? 4 : channelBytes * channels; // depth formats: 24+8 or 32 bits
}

/**
 * The bytes of every render texture allocated since `before`: the generator's map (an array of
 * layers for cascades), its depth-stencil texture, its blur targets. Textures loaded from a URL
 * (the BRDF lookup table the first frame creates) are not the shadows'.
 */
function newTextureBytes(engine, before) {
  let bytes = 0;
  for (const t of engine.getLoadedTexturesCache()) {
    if (before.has(t) || t.url) continue;
    bytes += t.width * t.height * (t.isCube ? 6 : Math.max(1, t.depth || 1)) * texelBytes(t);
  }
  return bytes;
}

class LightRender {
  constructor(scene, width, height, backend) {
    Object.assign(this, { scene, width, height, backend });
    this.target = new RenderTargetTexture('visibility', { width, height }, scene, false, true,
      Constants.TEXTURETYPE_FLOAT, false, Texture.NEAREST_SAMPLINGMODE, true);
    this.target.renderList = scene.meshes.filter(hasGeometry);
    this.target.activeCamera = scene.activeCamera;
    this.target.clearColor = new Color4(0, 0, 0, 0);
  }

  /**
   * scene.render() draws the shadow maps (and the canvas); then the float target; between the
   * engine's beginFrame and endFrame, as its render loop calls them. WebGPU needs them: endFrame
   * submits the frame's command encoders and beginFrame takes the canvas's texture of this frame.
   * Without them a submit referenced the canvas texture of an earlier frame ("Destroyed texture
   * ... used in a submit"), the whole submit was rejected with it, and the shadow maps drawn in it
   * never reached the GPU: directional and point lights read as shadowed everywhere.
   */
  frame() {
    const engine = this.scene.getEngine();
    engine.beginFrame();
    this.scene.render();
    this.target.render();
    engine.endFrame();
  }

  /**
   * Until every effect is compiled, and three frames more: Babylon compiles asynchronously and
   * skips what is not ready (a shadow map whose effect is not ready is not drawn at all), and the
   * blurred modes' passes run a frame behind.
   */
  async settle() {
    let ready = 0;
    for (let i = 0; i < 600 && ready < 3; ++i) {
      this.frame();
      ready = this.scene.isReady() && this.target.isReadyForRendering() ? ready + 1 : 0;
      await new Promise((r) => setTimeout(r, 5));
    }
    if (ready < 3) throw new Error('Babylon.js\'s shaders did not become ready in 600 frames');
  }

  async read() {
    const rgba = await this.target.readPixels(0, 0, null, true, true);
    if (!(rgba instanceof Float32Array)) throw new Error(`the float target read back as ${rgba && rgba.constructor.name}`);
    return channelTopDown(rgba, this.width, this.height, 0);
  }

  /** Shadowed and unshadowed radiance, and the shadowed frame's median time (compile excluded). */
  async run(light) {
    light.shadowEnabled = true;
    await this.settle();
    const shadowed = await this.read();
    const frameMs = await medianMsAsync(async () => { this.frame(); await this.backend.finish(this.scene.getEngine()); });
    light.shadowEnabled = false;
    await this.settle();
    return { shadowed, unshadowed: await this.read(), frameMs };
  }
}

const lightKind = (light) => (light instanceof DirectionalLight ? 'directional' : light instanceof PointLight ? 'point' : 'spot');

async function renderOneLight(ctx, name) {
  const { scene, engine, view, job, target } = ctx;
  const light = findLight(scene, name);
  const modeName = job.modeFor(lightKind(light));
  const s = parseSettings(job.settingsFor(lightKind(light)), modeName);
  light.setEnabled(true);
  light.intensity = 1;
  const before = new Set(engine.getLoadedTexturesCache());
  const gen = createGenerator(scene, light, modeName, s, view.scene.bounds);
  // Without this the first frames have no shadow: the map's effects compile asynchronously.
  await gen.forceCompilationAsync();
  const r = await target.run(light);
  const out = {
    bytes: newTextureBytes(engine, before),
    mode: modeName,
    params: effectiveParams(gen, s, light),
    result: { shadowed: floatsToBase64(r.shadowed), unshadowed: floatsToBase64(r.unshadowed), frameMs: r.frameMs },
  };
  gen.dispose();
  light.setEnabled(false);
  return out;
}

/**
 * The page's renderVisibility on `backend`: {label (after the version in `renderer`),
 * createEngine(canvas) -> {engine, info} (async), finish(engine): waits for the GPU (async)}.
 */
export async function renderVisibilityWith(job, backend) {
  const resolved = resolveJob(job, kPresets, 'default', 'babylon');
  for (const kind of ['directional', 'spot', 'point']) parseSettings(resolved.settingsFor(kind), resolved.modeFor(kind));
  if (!job.view.scene || !job.view.scene.bounds) throw new Error('view.json has no scene.bounds');
  const canvas = document.getElementById('canvas');
  canvas.width = job.width;
  canvas.height = job.height;
  const { engine, info } = await backend.createEngine(canvas);
  if (!engine.getCaps().textureFloatRender) throw new Error('Babylon.js finds no float render targets');
  engine.setHardwareScalingLevel(1);
  try {
    const scene = await loadScene(engine, job);
    const ctx = { scene, engine, view: job.view, job: resolved, target: new LightRender(scene, job.width, job.height, backend) };
    const { lights, memoryBytes, perLight } = await renderEachLight(job.lights, async (name) => {
      const one = await renderOneLight(ctx, name);
      return { ...one, params: { mode: one.mode, ...one.params } };
    });
    const merged = mergeLightParams(perLight);
    const mode = merged.mode;
    delete merged.mode; // the cost file's mode is the first light's; a later light's differing one stays as LIGHT.mode
    return { renderer: `babylon.js ${Engine.Version}${backend.label ? ' ' + backend.label : ''}`, glRenderer: info, mode,
      params: merged, memoryBytes, lights };
  } finally {
    engine.dispose();
  }
}
