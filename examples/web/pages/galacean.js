// Galacean's shadows as a user ships them (README.md, "Galacean"): the glb through its own glTF
// loader, every mesh renderer a white BlinnPhongMaterial with no specular, no ambient, no
// background, no post-processing, one light at a time, rendered into an RGBA32F render target with
// the light's shadowType on and off. The driver divides.
//
// Galacean 1.6 shadows one light: the scene's sun, a directional light (CascadedShadowCasterPass
// runs for `scene._lightManager._sunlight` only; spot and point lights never cast). A job with a
// spot or point light is refused with that reason, as the other pages refuse a mode that cannot
// shadow a light, rather than an unshadowed image graded as if the engine had tried.
import * as G from '@galacean/engine';
import { floatsToBase64, requireWebGL2, readSettings, medianMs, resolveJob, farthestCornerDistance } from './common.js';

// Modes: the light's shadowType; `cascades2`/`cascades4` are SoftLow with the scene's
// shadowCascades (TwoCascades, FourCascades) and Galacean's own split ratios.
const kModes = {
  hard: { shadowType: G.ShadowType.Hard, cascades: G.ShadowCascadesMode.NoCascades },
  'soft-low': { shadowType: G.ShadowType.SoftLow, cascades: G.ShadowCascadesMode.NoCascades },
  'soft-high': { shadowType: G.ShadowType.SoftHigh, cascades: G.ShadowCascadesMode.NoCascades },
  cascades2: { shadowType: G.ShadowType.SoftLow, cascades: G.ShadowCascadesMode.TwoCascades },
  cascades4: { shadowType: G.ShadowType.SoftLow, cascades: G.ShadowCascadesMode.FourCascades },
};
// A light's shadowType defaults to None: a user must pick one to get any shadow, and Hard is the
// first that draws (README.md, "Presets").
const kDefaultMode = 'hard';
// --preset (README.md, "Presets"): `typical` is Galacean's own shadow examples
// (galacean/engine examples/shadow-basic.ts: `directLight.shadowType = ShadowType.SoftLow`,
// scene.shadowDistance set to the scene's size, resolution, biases and cascades left at their
// defaults); only directional lights have a row.
const kPresets = {
  default: { mode: 'hard', settings: {} },
  typical: { mode: 'soft-low', settings: {} },
};
// `--set` names: the light's and the scene's own properties; shadowResolution is the
// ShadowResolution enum's name (Low 512, Medium 1024, High 2048, VeryHigh 4096).
const kResolutions = { Low: 512, Medium: 1024, High: 2048, VeryHigh: 4096 };
const kSettingKinds = {
  shadowBias: 'number', shadowNormalBias: 'number', shadowStrength: 'number', shadowNearPlaneOffset: 'number',
  shadowResolution: Object.keys(kResolutions), shadowDistance: 'number', shadowFadeBorder: 'number',
};
const kSceneSettings = ['shadowResolution', 'shadowDistance', 'shadowFadeBorder'];

function parseSettings(settings, modeName) {
  if (!Object.hasOwn(kModes, modeName)) throw new Error(`unknown mode "${modeName}" for galacean (known: ${Object.keys(kModes).join(', ')})`);
  const s = readSettings(settings, kSettingKinds, `galacean mode ${modeName}`);
  for (const k of ['shadowBias', 'shadowNormalBias', 'shadowNearPlaneOffset']) {
    if (s[k] !== undefined && !(s[k] >= 0)) throw new Error(`setting ${k}=${s[k]}: not >= 0`);
  }
  for (const k of ['shadowStrength', 'shadowFadeBorder']) {
    if (s[k] !== undefined && !(s[k] >= 0 && s[k] <= 1)) throw new Error(`setting ${k}=${s[k]}: outside 0..1`);
  }
  if (s.shadowDistance !== undefined && !(s.shadowDistance > 0)) throw new Error(`setting shadowDistance=${s.shadowDistance}: not > 0`);
  return s;
}

/** Galacean shadows directional lights only (above): any other light in the job is refused. */
function refuseLocalLights(view, names) {
  for (const name of names) {
    const l = view.lights.find((x) => x.name === name);
    const type = l ? l.type : 'unknown';
    if (type !== 'directional') {
      throw new Error(`galacean ${G.version} casts shadows from the scene's directional sun light only: light "${name}" ` +
        `(${type} in view.json) would render with no shadow at all, so no image is made for it`);
    }
  }
}

async function createEngine(width, height) {
  const canvas = document.getElementById('canvas');
  canvas.width = width;
  canvas.height = height;
  const engine = await G.WebGLEngine.create({
    canvas, graphicDeviceOptions: { webGLMode: G.WebGLMode.WebGL2, antialias: false, alpha: false },
  });
  const scene = engine.sceneManager.activeScene;
  const ambient = scene.ambientLight;
  ambient.diffuseMode = G.DiffuseMode.SolidColor;
  ambient.diffuseSolidColor.set(0, 0, 0, 1);
  ambient.diffuseIntensity = 0;
  ambient.specularIntensity = 0;
  scene.background.mode = G.BackgroundMode.SolidColor;
  scene.background.solidColor.set(0, 0, 0, 0);
  return engine;
}

/**
 * The camera of view.json's OpenGL matrices as they are: the entity's world matrix is
 * inverse(view_gl) (Galacean's Matrix is column-major, as view.json) and the projection a custom
 * matrix. The fov, aspect, near and far are set too: Galacean fits the sun's shadow (and its
 * cascades) to the camera frustum from those, not from the projection matrix.
 */
function createCamera(scene, c, target) {
  const entity = scene.createRootEntity('view.json');
  const worldFromView = new G.Matrix();
  worldFromView.copyFromArray(c.view_gl);
  worldFromView.invert();
  entity.transform.worldMatrix = worldFromView;
  const camera = entity.addComponent(G.Camera);
  camera.nearClipPlane = c.near;
  camera.farClipPlane = c.far;
  camera.fieldOfView = (2 * Math.atan(1 / c.proj_gl[5]) * 180) / Math.PI; // proj_gl[5] = 1 / tan(fovY / 2)
  camera.aspectRatio = c.proj_gl[5] / c.proj_gl[0];
  const projection = new G.Matrix();
  projection.copyFromArray(c.proj_gl);
  camera.projectionMatrix = projection;
  camera.msaaSamples = G.MSAASamples.None;
  camera.enableHDR = false;
  camera.enablePostProcess = false;
  camera.renderTarget = target;
  return camera;
}

/**
 * White Lambert in place of a glTF material, keeping what shapes the shadow: the face culling
 * (a double-sided material lights its back faces with the flipped normal, phong_frag's
 * getNormal(gl_FrontFacing)) and the alpha test. Galacean's shadow caster pass has a render state
 * of its own (ShaderPool.init: `new RenderState()`, back faces culled) whatever the material's
 * renderFace: a double-sided caster whose front faces look away from the sun casts nothing
 * (README.md, "Galacean").
 */
function whiteMaterial(engine, original) {
  const m = new G.BlinnPhongMaterial(engine);
  m.baseColor.set(1, 1, 1, 1);
  m.specularColor.set(0, 0, 0, 1);
  m.emissiveColor.set(0, 0, 0, 1);
  m.renderFace = original.renderFace;
  if (original.alphaCutoff > 0 && original.baseTexture) {
    m.baseTexture = original.baseTexture;
    m.alphaCutoff = original.alphaCutoff;
  }
  return m;
}

function whiteRenderers(engine, root) {
  const white = new Map();
  const renderers = [];
  root.getComponentsIncludeChildren(G.MeshRenderer, renderers);
  for (const r of renderers) {
    r.castShadows = true;
    r.receiveShadows = true;
    for (let i = 0; i < r.materialCount; ++i) {
      const original = r.getMaterial(i);
      if (!white.has(original)) white.set(original, whiteMaterial(engine, original));
      r.setMaterial(i, white.get(original));
    }
  }
}

/** The loader puts each KHR_lights_punctual light on the entity of its node, named after it. */
function findLight(root, name) {
  const lights = [];
  root.getComponentsIncludeChildren(G.DirectLight, lights);
  const found = lights.filter((l) => l.entity.name === name);
  if (found.length !== 1) throw new Error(`the glb has ${found.length} directional lights named "${name}", expected 1`);
  return found[0];
}

/**
 * The light set up as a user would: the sun, its shadowType the mode's, and the scene's
 * shadowDistance (50 by default, from the camera) reaching the scene's farthest corner, as
 * Galacean's examples set it to their scene's size.
 */
function setUpLight(scene, light, mode, s, view) {
  scene.sun = light;
  scene.shadowCascades = mode.cascades;
  scene.shadowDistance = 1.01 * farthestCornerDistance(view.camera.eye, view.scene.bounds);
  for (const [k, v] of Object.entries(s)) {
    if (k === 'shadowResolution') scene.shadowResolution = G.ShadowResolution[v];
    else if (kSceneSettings.includes(k)) scene[k] = v;
    else light[k] = v;
  }
  light.color.set(1, 1, 1, 1);
  light.enabled = true;
}

function effectiveParams(scene, light) {
  return {
    shadowType: G.ShadowType[light.shadowType], shadowCascades: scene.shadowCascades,
    shadowResolution: kResolutions[G.ShadowResolution[scene.shadowResolution]], shadowBias: light.shadowBias,
    shadowNormalBias: light.shadowNormalBias, shadowStrength: light.shadowStrength,
    shadowNearPlaneOffset: light.shadowNearPlaneOffset, shadowDistance: scene.shadowDistance,
    shadowFadeBorder: scene.shadowFadeBorder,
  };
}

class LightRender {
  constructor(engine, width, height) {
    Object.assign(this, { engine, width, height });
    this.colour = new G.Texture2D(engine, width, height, G.TextureFormat.R32G32B32A32, false, false);
    this.colour.filterMode = G.TextureFilterMode.Point;
    this.target = new G.RenderTarget(engine, width, height, this.colour, G.TextureFormat.Depth24, 1);
    this.gl = engine._hardwareRenderer.gl;
  }

  frame() {
    this.engine.update();
  }

  read() {
    this.frame(); // a first frame compiles the shaders
    this.frame();
    const rgba = new Float32Array(4 * this.width * this.height);
    this.colour.getPixelBuffer(0, 0, this.width, this.height, 0, rgba);
    // Galacean flips the projection when it renders into a render target (RenderContext
    // flipProjection), so the target's row 0 is the image's top row.
    const out = new Float32Array(this.width * this.height);
    for (let i = 0; i < out.length; ++i) out[i] = rgba[4 * i];
    return out;
  }

  run(light, shadowType) {
    light.shadowType = shadowType;
    const shadowed = this.read();
    const frameMs = medianMs(() => { this.frame(); this.gl.finish(); });
    light.shadowType = G.ShadowType.None;
    return { shadowed, unshadowed: this.read(), frameMs };
  }
}

/** Bytes of the sun's shadow map: one 32-bit depth atlas of shadowResolution^2 (cascades are tiles of it). */
const shadowBytes = (scene) => kResolutions[G.ShadowResolution[scene.shadowResolution]] ** 2 * 4;

window.renderVisibility = async (job) => {
  const glRenderer = requireWebGL2();
  refuseLocalLights(job.view, job.lights);
  const resolved = resolveJob(job, kPresets, kDefaultMode, 'galacean');
  const modeName = resolved.modeFor('directional');
  const s = parseSettings(resolved.settingsFor('directional'), modeName);
  if (!job.view.scene || !job.view.scene.bounds) throw new Error('view.json has no scene.bounds');
  const engine = await createEngine(job.width, job.height);
  try {
    const scene = engine.sceneManager.activeScene;
    const gltf = await engine.resourceManager.load({ url: job.glbUrl, type: G.AssetType.GLTF })
      .catch((e) => { throw new Error(`Galacean's glTF loader cannot load ${job.glbUrl}: ${e && e.message ? e.message : e}`); });
    const root = gltf.instantiateSceneRoot();
    scene.addRootEntity(root);
    whiteRenderers(engine, root);
    const all = [];
    for (const type of [G.DirectLight, G.SpotLight, G.PointLight]) root.getComponentsIncludeChildren(type, all);
    for (const l of all) { l.enabled = false; l.shadowType = G.ShadowType.None; }
    const cameras = [];
    root.getComponentsIncludeChildren(G.Camera, cameras);
    for (const c of cameras) c.enabled = false;
    const target = new LightRender(engine, job.width, job.height);
    createCamera(scene, job.view.camera, target.target);
    const lights = {};
    let params = null;
    let memoryBytes = 0;
    for (const name of job.lights) {
      const light = findLight(root, name);
      setUpLight(scene, light, kModes[modeName], s, job.view);
      light.shadowType = kModes[modeName].shadowType;
      params = params || effectiveParams(scene, light);
      const r = target.run(light, kModes[modeName].shadowType);
      lights[name] = { shadowed: floatsToBase64(r.shadowed), unshadowed: floatsToBase64(r.unshadowed), frameMs: r.frameMs };
      memoryBytes += shadowBytes(scene);
      light.enabled = false;
    }
    return { renderer: `galacean ${G.version}`, glRenderer, mode: modeName, params, memoryBytes, lights };
  } finally {
    engine.destroy();
  }
};
