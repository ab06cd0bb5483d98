// PlayCanvas's shadows as a user ships them (README.md, "PlayCanvas"): the glb through its own
// container (glTF) loader, every mesh instance a white StandardMaterial, no ambient, no skybox,
// no tone mapping or gamma, one light at a time, rendered into an RGBA32F render target with the
// light's castShadows on and off. The driver divides.
import * as pc from 'playcanvas';
import { floatsToBase64, requireWebGL2, readSettings, medianMs, resolveJob, renderEachLight } from './common.js';

// Modes: the light's shadowType (32-bit maps: PCF, PCSS; VSM at 16 and 32 bits); `cascades` is
// PCF3 with PlayCanvas's largest cascade count, directional lights only. `clustered`: the mode
// runs on PlayCanvas 2's default clustered lighting, whose spot and omni shadows come from one
// atlas filtered by scene.lighting.shadowType (PCF1/3/5 only: the clustered shader chunk's
// CLUSTER_SHADOW_TYPE_PCF*), set to the mode's; VSM and PCSS need forward lighting.
const kModes = {
  pcf1: { shadowType: pc.SHADOW_PCF1_32F, clustered: true },
  pcf3: { shadowType: pc.SHADOW_PCF3_32F, clustered: true },
  pcf5: { shadowType: pc.SHADOW_PCF5_32F, clustered: true },
  vsm16: { shadowType: pc.SHADOW_VSM_16F, clustered: false },
  vsm32: { shadowType: pc.SHADOW_VSM_32F, clustered: false },
  pcss: { shadowType: pc.SHADOW_PCSS_32F, clustered: false },
  cascades: { shadowType: pc.SHADOW_PCF3_32F, numCascades: 4, clustered: true },
};
const kDefaultMode = 'pcf3'; // the Light's shadowType default, SHADOW_PCF3_32F
// --preset (README.md, "Presets"): `default` is the light component's defaults on clustered
// lighting (PCF3, shadowBias 0.05, normalOffsetBias 0, 1024 maps, a 2048 atlas for local
// lights); `typical` what the Editor and @playcanvas/web-components set on a new light
// (web-components src/components/light-component.ts: shadowBias 0.2, normalOffsetBias 0.05,
// shadowResolution 1024, shadowType pcf3-32f), the same on every kind of light.
const kTypical = { shadowBias: 0.2, normalOffsetBias: 0.05, shadowResolution: 1024 };
const kPresets = {
  default: { mode: 'pcf3', settings: {} },
  typical: { mode: 'pcf3', settings: { directional: kTypical, spot: kTypical, point: kTypical } },
};
// `--set` names: the light component's own properties.
const kSettingKinds = {
  shadowBias: 'number', normalOffsetBias: 'number', shadowResolution: 'integer', numCascades: 'integer',
  cascadeDistribution: 'number', shadowDistance: 'number', penumbraSize: 'number', penumbraFalloff: 'number',
  shadowSamples: 'integer', shadowBlockerSamples: 'integer', vsmBlurSize: 'integer', vsmBias: 'number',
  // The scene's, not the light's: clustered lighting off (forward), and the clustered atlas's size.
  clusteredLighting: 'boolean', shadowAtlasResolution: 'integer',
};
const kSceneSettings = ['clusteredLighting', 'shadowAtlasResolution'];
const kMaxResolution = 8192;

function parseSettings(settings, modeName) {
  if (!Object.hasOwn(kModes, modeName)) throw new Error(`unknown mode "${modeName}" for playcanvas (known: ${Object.keys(kModes).join(', ')})`);
  const s = readSettings(settings, kSettingKinds, `playcanvas mode ${modeName}`);
  if (s.shadowResolution !== undefined && (s.shadowResolution < 16 || s.shadowResolution > kMaxResolution)) {
    throw new Error(`setting shadowResolution=${s.shadowResolution}: outside 16..${kMaxResolution}`);
  }
  if (s.numCascades !== undefined && (s.numCascades < 1 || s.numCascades > 4)) throw new Error(`setting numCascades=${s.numCascades}: outside 1..4`);
  if (s.vsmBlurSize !== undefined && (s.vsmBlurSize < 1 || s.vsmBlurSize > 25)) throw new Error(`setting vsmBlurSize=${s.vsmBlurSize}: outside 1..25`);
  for (const k of ['shadowSamples', 'shadowBlockerSamples']) {
    if (s[k] !== undefined && (s[k] < 1 || s[k] > 64)) throw new Error(`setting ${k}=${s[k]}: outside 1..64`);
  }
  if (s.shadowDistance !== undefined && !(s.shadowDistance > 0)) throw new Error(`setting shadowDistance=${s.shadowDistance}: not > 0`);
  if (s.clusteredLighting === true && !kModes[modeName].clustered) {
    throw new Error(`setting clusteredLighting=true: mode ${modeName} needs forward lighting (clustered shadows are PCF1/3/5 only)`);
  }
  if (s.shadowAtlasResolution !== undefined && (s.shadowAtlasResolution < 32 || s.shadowAtlasResolution > kMaxResolution)) {
    throw new Error(`setting shadowAtlasResolution=${s.shadowAtlasResolution}: outside 32..${kMaxResolution}`);
  }
  return s;
}

function createApp(width, height, modeName, s) {
  const canvas = document.getElementById('canvas');
  canvas.width = width;
  canvas.height = height;
  const app = new pc.Application(canvas, { graphicsDeviceOptions: { antialias: false, alpha: false, deviceTypes: [pc.DEVICETYPE_WEBGL2] } });
  if (!app.graphicsDevice.isWebGL2) throw new Error('PlayCanvas did not get a WebGL2 device');
  app.setCanvasResolution(pc.RESOLUTION_FIXED, width, height);
  app.autoRender = false;
  // PlayCanvas 2's default, clustered lighting, wherever the mode runs on it: spot and omni
  // shadows then come from one shared atlas (scene.lighting.shadowAtlasResolution, 2048) filtered
  // by scene.lighting.shadowType, while each light's own biases still apply (the clustered
  // light data packs shadowBias and normalOffsetBias). Directional lights are never clustered.
  const clustered = kModes[modeName].clustered && s.clusteredLighting !== false;
  app.scene.clusteredLightingEnabled = clustered;
  if (clustered) {
    app.scene.lighting.shadowsEnabled = true;
    app.scene.lighting.shadowType = kModes[modeName].shadowType;
    if (s.shadowAtlasResolution !== undefined) app.scene.lighting.shadowAtlasResolution = s.shadowAtlasResolution;
  }
  app.scene.ambientLight = new pc.Color(0, 0, 0);
  app.scene.skyboxIntensity = 0;
  app.scene.exposure = 1;
  app.start();
  return app;
}

/**
 * The camera of view.json's OpenGL matrices as they are, through PlayCanvas's custom-matrix
 * hooks: pc.Mat4 is column-major, as view.json. The entity also carries the view's position,
 * rotation, vertical fov and aspect: PlayCanvas fits a directional light's shadow (and its
 * cascades) to the frustum of the camera entity (getFrustumCorners reads fov and aspectRatio),
 * not to the projection hook's matrix.
 */
function createCamera(app, c) {
  const projection = new pc.Mat4().set(c.proj_gl);
  const worldFromView = new pc.Mat4().set(c.view_gl).invert();
  const entity = new pc.Entity('view.json');
  entity.addComponent('camera', {
    clearColor: new pc.Color(0, 0, 0, 0), nearClip: c.near, farClip: c.far,
    toneMapping: pc.TONEMAP_NONE, gammaCorrection: pc.GAMMA_NONE,
  });
  entity.camera.calculateProjection = (m) => m.copy(projection);
  entity.camera.calculateTransform = (m) => m.copy(worldFromView);
  entity.setPosition(c.eye[0], c.eye[1], c.eye[2]);
  entity.setRotation(new pc.Quat().setFromMat4(worldFromView));
  entity.camera.fov = (2 * Math.atan(1 / c.proj_gl[5]) * 180) / Math.PI; // proj_gl[5] = 1 / tan(fovY / 2)
  entity.camera.horizontalFov = false;
  entity.camera.aspectRatioMode = pc.ASPECT_MANUAL;
  entity.camera.aspectRatio = c.proj_gl[5] / c.proj_gl[0];
  app.root.addChild(entity);
  return entity;
}

function loadContainer(app, url) {
  return new Promise((resolve, reject) => {
    const asset = new pc.Asset('scene.glb', 'container', { url });
    asset.on('load', () => resolve(asset.resource));
    asset.on('error', (err) => reject(new Error(`PlayCanvas's glTF loader cannot load ${url}: ${err}`)));
    app.assets.add(asset);
    app.assets.load(asset);
  });
}

/** White Lambert in place of a glTF material, keeping what shapes the shadow: cull mode, two-sided lighting and alpha test. */
function whiteMaterial(original) {
  const m = new pc.StandardMaterial();
  m.diffuse = new pc.Color(1, 1, 1);
  m.specular = new pc.Color(0, 0, 0);
  m.emissive = new pc.Color(0, 0, 0);
  m.ambient = new pc.Color(0, 0, 0);
  m.useSkybox = false;
  m.useFog = false;
  m.cull = original.cull;
  // The loader lights a doubleSided material's back faces with the flipped normal: the oracle's
  // two-sided cos, not 0 (a back face seen from the camera would read as shadow).
  m.twoSidedLighting = original.twoSidedLighting === true;
  if (original.alphaTest > 0 && original.opacityMap) {
    m.opacityMap = original.opacityMap;
    m.opacityMapChannel = original.opacityMapChannel;
    m.opacityMapUv = original.opacityMapUv;
    m.alphaTest = original.alphaTest;
  }
  m.update();
  return m;
}

function whiteMeshes(root) {
  const white = new Map();
  for (const r of root.findComponents('render')) {
    r.castShadows = true;
    r.receiveShadows = true;
    for (const mi of r.meshInstances) {
      if (!white.has(mi.material)) white.set(mi.material, whiteMaterial(mi.material));
      mi.material = white.get(mi.material);
    }
  }
}

/** The loader puts each KHR_lights_punctual light on an entity named after its node. */
function findLight(root, name) {
  const found = root.findComponents('light').filter((l) => l.entity.name === name);
  if (found.length !== 1) throw new Error(`the glb has ${found.length} KHR_lights_punctual lights named "${name}", expected 1`);
  return found[0];
}

function farthestCorner(p, bounds) {
  let far = 0;
  for (let i = 0; i < 8; ++i) {
    const c = [i & 1 ? bounds.max[0] : bounds.min[0], i & 2 ? bounds.max[1] : bounds.min[1], i & 4 ? bounds.max[2] : bounds.min[2]];
    far = Math.max(far, Math.hypot(c[0] - p.x, c[1] - p.y, c[2] - p.z));
  }
  return far;
}

/**
 * The light set up as a user would: a directional light's shadowDistance reaches the scene's
 * farthest corner from the camera (PlayCanvas fits a directional map to the camera's frustum up
 * to shadowDistance, 40 units by default); a spot or omni whose glTF gave no range (the loader's
 * 9999, its shadow camera's far plane) gets the scene's farthest corner from the light.
 */
function setUpLight(light, modeName, s, view) {
  const mode = kModes[modeName];
  if (modeName === 'cascades' && light.type !== 'directional') {
    throw new Error(`cascades: PlayCanvas cascades shadow directional lights only; light "${light.entity.name}" is ${light.type}`);
  }
  if (light.type === 'directional') {
    light.shadowDistance = view.camera.far;
  } else if (light.range >= 9999) {
    light.range = 1.01 * farthestCorner(light.entity.getPosition(), view.scene.bounds);
  }
  light.shadowType = mode.shadowType;
  if (mode.numCascades) light.numCascades = mode.numCascades;
  for (const [k, v] of Object.entries(s)) if (!kSceneSettings.includes(k)) light[k] = v;
  light.shadowUpdateMode = pc.SHADOWUPDATE_REALTIME;
  light.intensity = 1;
  light.enabled = true;
}

/** A clustered spot or omni light: its shadow is a tile of the scene's atlas. */
const inAtlas = (light, scene) => scene.clusteredLightingEnabled && light.type !== 'directional';

function effectiveParams(light, scene) {
  const atlas = inAtlas(light, scene);
  const p = { lighting: scene.clusteredLightingEnabled ? 'clustered' : 'forward',
    shadowType: pc.shadowTypeInfo.get(atlas ? scene.lighting.shadowType : light.shadowType).name,
    shadowResolution: atlas ? scene.lighting.shadowAtlasResolution : light.shadowResolution,
    shadowBias: light.shadowBias, normalOffsetBias: light.normalOffsetBias };
  if (light.type === 'directional') Object.assign(p, { shadowDistance: light.shadowDistance, numCascades: light.numCascades, cascadeDistribution: light.cascadeDistribution });
  const kind = pc.shadowTypeInfo.get(light.shadowType);
  if (kind.vsm) Object.assign(p, { vsmBlurSize: light.vsmBlurSize, vsmBias: light.vsmBias });
  if (kind.pcss) Object.assign(p, { penumbraSize: light.penumbraSize, penumbraFalloff: light.penumbraFalloff, shadowSamples: light.shadowSamples, shadowBlockerSamples: light.shadowBlockerSamples });
  return p;
}

/**
 * Bytes of one light's shadow maps from its settings, as PlayCanvas 2.23 allocates them
 * (ShadowMap.create2dMap / createCubemap, ShadowRenderer.renderVsm): a PCF map is a 32-bit depth
 * texture; PCSS an R32F colour map with a 32-bit depth buffer; VSM an RGBA16F or RGBA32F map with
 * a depth buffer, and a second map of the same kind for its blur. An omni light has six faces; a
 * directional light's cascades share its one shadowResolution^2 map.
 */
function shadowBytes(light, scene) {
  if (inAtlas(light, scene)) return scene.lighting.shadowAtlasResolution ** 2 * 4; // one 32-bit depth atlas
  const kind = pc.shadowTypeInfo.get(light.shadowType);
  const perTexel = kind.pcf ? 4 : kind.pcss ? 8 : light.shadowType === pc.SHADOW_VSM_16F ? 2 * (8 + 4) : 2 * (16 + 4);
  return light.shadowResolution ** 2 * perTexel * (light.type === 'omni' ? 6 : 1);
}

class LightRender {
  constructor(app, camera, width, height) {
    Object.assign(this, { app, width, height });
    this.colour = new pc.Texture(app.graphicsDevice, {
      name: 'visibility', width, height, format: pc.PIXELFORMAT_RGBA32F, mipmaps: false,
      minFilter: pc.FILTER_NEAREST, magFilter: pc.FILTER_NEAREST,
    });
    this.target = new pc.RenderTarget({ colorBuffer: this.colour, depth: true, samples: 1 });
    camera.camera.renderTarget = this.target;
    this.gl = app.graphicsDevice.gl;
  }

  frame() {
    this.app.render();
  }

  async read() {
    this.frame(); // a first frame compiles the shaders: PlayCanvas compiles them synchronously
    this.frame();
    const rgba = await this.colour.read(0, 0, this.width, this.height, { renderTarget: this.target, immediate: true });
    if (!(rgba instanceof Float32Array)) throw new Error(`the float target read back as ${rgba && rgba.constructor.name}`);
    // A render target's row 0 is its bottom row (OpenGL), as the canvas's.
    const out = new Float32Array(this.width * this.height);
    for (let y = 0; y < this.height; ++y) {
      const src = (this.height - 1 - y) * this.width;
      for (let x = 0; x < this.width; ++x) out[y * this.width + x] = rgba[4 * (src + x)];
    }
    return out;
  }

  /** Shadowed and unshadowed radiance, and the shadowed frame's median time (compile excluded). */
  async run(light) {
    light.castShadows = true;
    const shadowed = await this.read();
    const frameMs = medianMs(() => { this.frame(); this.gl.finish(); });
    light.castShadows = false;
    return { shadowed, unshadowed: await this.read(), frameMs };
  }
}

async function renderOneLight(ctx, name) {
  const { app, root, view, modeName, s, target } = ctx;
  const light = findLight(root, name);
  setUpLight(light, modeName, s, view);
  const r = await target.run(light);
  const out = {
    bytes: shadowBytes(light, app.scene),
    params: effectiveParams(light, app.scene),
    result: { shadowed: floatsToBase64(r.shadowed), unshadowed: floatsToBase64(r.unshadowed), frameMs: r.frameMs },
  };
  light.enabled = false;
  return out;
}

window.renderVisibility = async (job) => {
  const glRenderer = requireWebGL2();
  // Every preset of this page sets one mode and the same settings on every kind of light.
  const resolved = resolveJob(job, kPresets, kDefaultMode, 'playcanvas');
  const modeName = resolved.modeFor('directional');
  const s = parseSettings(resolved.settingsFor('directional'), modeName);
  if (!job.view.scene || !job.view.scene.bounds) throw new Error('view.json has no scene.bounds');
  const app = createApp(job.width, job.height, modeName, s);
  try {
    const container = await loadContainer(app, job.glbUrl);
    const root = container.instantiateRenderEntity();
    app.root.addChild(root);
    whiteMeshes(root);
    for (const l of root.findComponents('light')) l.enabled = false;
    for (const c of root.findComponents('camera')) c.enabled = false;
    const camera = createCamera(app, job.view.camera);
    const ctx = { app, root, view: job.view, modeName, s, target: new LightRender(app, camera, job.width, job.height) };
    const { lights, memoryBytes, perLight } = await renderEachLight(job.lights, (name) => renderOneLight(ctx, name));
    // The first light's params: every light of a page's mode is set alike.
    const params = perLight.length ? perLight[0][1] : null;
    return { renderer: `playcanvas ${pc.version}`, glRenderer, mode: modeName, params, memoryBytes, lights };
  } finally {
    app.destroy();
  }
};
