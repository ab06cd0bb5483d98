// Filament's shadows as its npm wasm build ships them (README.md, "Filament"): the glb through
// gltfio, the glb's own materials made white dielectrics with roughness 1, no indirect light, no
// post-processing (no tone mapping, no sRGB encode), one light at a time, rendered into an RGBA32F
// render target with the light's shadow caster flag on and off. The driver divides.
//
// What 1.53.4's build can and cannot reach from JavaScript (README.md has the messages):
// View.setShadowType is not bound (only PCF, the default, renders), and LightManager's shadow
// options throw an embind UnboundTypeError (no map size, bias, cascades or contact shadows). The
// page asks the build at run time, so a build that binds them renders those modes.
import { floatsToBase64, requireWebGL2, readSettings, resolveJob } from './common.js';

// Filament's JS API has no readPixels: the page notes the GL texture Filament allocates as the
// float target (texStorage2D of RGBA32F on the bound TEXTURE_2D, with its size) and reads it back
// through a framebuffer of its own. Installed before Filament creates its context.
const kGL = WebGL2RenderingContext;
const glAllocations = [];
{
  const bound = new WeakMap();
  const bindTexture = kGL.prototype.bindTexture;
  kGL.prototype.bindTexture = function (target, texture) {
    bound.set(this, texture);
    return bindTexture.call(this, target, texture);
  };
  const texStorage2D = kGL.prototype.texStorage2D;
  kGL.prototype.texStorage2D = function (target, levels, format, width, height) {
    glAllocations.push({ gl: this, texture: bound.get(this), format, width, height, layers: 1 });
    return texStorage2D.call(this, target, levels, format, width, height);
  };
  const texStorage3D = kGL.prototype.texStorage3D;
  kGL.prototype.texStorage3D = function (target, levels, format, width, height, depth) {
    glAllocations.push({ gl: this, texture: bound.get(this), format, width, height, layers: depth });
    return texStorage3D.call(this, target, levels, format, width, height, depth);
  };
}

// Bytes a texel of the GL formats Filament's shadow maps use.
const kTexelBytes = {
  [kGL.DEPTH_COMPONENT16]: 2, [kGL.DEPTH_COMPONENT24]: 4, [kGL.DEPTH_COMPONENT32F]: 4, [kGL.DEPTH24_STENCIL8]: 4,
  [kGL.DEPTH32F_STENCIL8]: 8, [kGL.RG16F]: 4, [kGL.RG32F]: 8, [kGL.RGBA16F]: 8, [kGL.RGBA32F]: 16, [kGL.R32F]: 4,
  [kGL.RGBA8]: 4,
};

// A spot's or point's falloff, in units of the distance from the light to the scene's farthest
// corner (README.md, "Filament": at 1.01 no pixel was lit; from about 10 on the image is the same).
const kFalloffScale = 10;

// The GL formats of Filament's shadow maps (depth for PCF, DPCF, PCSS; RG for VSM): the other
// textures a first frame allocates (its lookup tables) are not shadows.
const kShadowFormats = new Set([kGL.DEPTH_COMPONENT16, kGL.DEPTH_COMPONENT24, kGL.DEPTH_COMPONENT32F,
  kGL.DEPTH24_STENCIL8, kGL.DEPTH32F_STENCIL8, kGL.RG16F, kGL.RG32F]);

// Modes: View.ShadowType values, and `contact` (PCF with the light's screenSpaceContactShadows).
const kModes = { pcf: 'PCF', vsm: 'VSM', dpcf: 'DPCF', pcss: 'PCSS', contact: 'PCF' };
const kDefaultMode = 'pcf'; // View's default shadowType
// `--set` names: LightManager.ShadowOptions fields.
const kSettingKinds = {
  mapSize: 'integer', shadowCascades: 'integer', constantBias: 'number', normalBias: 'number',
  shadowFar: 'number', shadowNearHint: 'number', shadowFarHint: 'number', stable: 'boolean',
  polygonOffsetConstant: 'number', polygonOffsetSlope: 'number', stepCount: 'integer', maxShadowDistance: 'number',
};

function initFilament(assets) {
  return new Promise((resolve) => Filament.init(assets, resolve));
}

/** The inverse of a column-major 4 x 4 rigid transform (view.json's view_gl): world from view. */
function rigidInverse(m) {
  const out = new Array(16).fill(0);
  for (let r = 0; r < 3; ++r) {
    for (let c = 0; c < 3; ++c) out[4 * c + r] = m[4 * r + c];
    out[12 + r] = -(m[4 * r] * m[12] + m[4 * r + 1] * m[13] + m[4 * r + 2] * m[14]);
  }
  out[15] = 1;
  return out;
}

function farthestCorner(p, bounds) {
  let far = 0;
  for (let i = 0; i < 8; ++i) {
    const c = [i & 1 ? bounds.max[0] : bounds.min[0], i & 2 ? bounds.max[1] : bounds.min[1], i & 4 ? bounds.max[2] : bounds.min[2]];
    far = Math.max(far, Math.hypot(c[0] - p[0], c[1] - p[1], c[2] - p[2]));
  }
  return far;
}

class FilamentScene {
  constructor(job) {
    const F = Filament;
    const canvas = document.getElementById('canvas');
    canvas.width = job.width;
    canvas.height = job.height;
    this.job = job;
    this.engine = F.Engine.create(canvas);
    this.scene = this.engine.createScene();
    this.renderer = this.engine.createRenderer();
    this.camera = this.engine.createCamera(F.EntityManager.get().create());
    this.view = this.engine.createView();
    this.swapChain = this.engine.createSwapChain();
    this.view.setCamera(this.camera);
    this.view.setScene(this.scene);
    this.view.setViewport([0, 0, job.width, job.height]);
    this.view.setPostProcessingEnabled(false); // no tone mapping, no sRGB encode, no dithering, no AA
    const c = job.view.camera;
    this.camera.setCustomProjection(c.proj_gl, c.near, c.far); // view.json's OpenGL projection as it is
    this.camera.setModelMatrix(rigidInverse(c.view_gl));
    this.camera.setExposureDirect(1.0);
    this.lm = this.engine.getLightManager();
  }

  /** The float target (RGBA32F colour, 32-bit depth) the view renders into. */
  createTarget() {
    const F = Filament;
    const { width, height } = this.job;
    const texture = (format, usage) => F.Texture.Builder().width(width).height(height).levels(1)
      .sampler(F.Texture$Sampler.SAMPLER_2D).format(format).usage(usage).build(this.engine);
    const first = glAllocations.length;
    const colour = texture(F.Texture$InternalFormat.RGBA32F, 0x11); // COLOR_ATTACHMENT | SAMPLEABLE
    const depth = texture(F.Texture$InternalFormat.DEPTH32F, 0x12); // DEPTH_ATTACHMENT | SAMPLEABLE
    this.view.setRenderTarget(F.RenderTarget.Builder().texture(F.RenderTarget$AttachmentPoint.COLOR, colour)
      .texture(F.RenderTarget$AttachmentPoint.DEPTH, depth).build(this.engine));
    this.renderer.setClearOptions({ clearColor: [0, 0, 0, 0], clear: true });
    this.targetAllocation = null; // Filament allocates GL textures lazily: found after a frame
    this.allocationsBefore = first;
  }

  async load() {
    const asset = this.engine.createAssetLoader().createAsset(Filament.assets[this.job.glbUrl]);
    if (!asset) throw new Error(`gltfio cannot parse ${this.job.glbUrl}`);
    await new Promise((resolve) => asset.loadResources(resolve, null, this.job.glbUrl));
    const rm = this.engine.getRenderableManager();
    for (const e of asset.getRenderableEntities()) {
      const inst = rm.getInstance(e);
      rm.setCastShadows(inst, true);
      rm.setReceiveShadows(inst, true);
      const n = rm.getPrimitiveCount(inst);
      for (let i = 0; i < n; ++i) whiten(rm.getMaterialInstanceAt(inst, i));
      inst.delete();
    }
    this.scene.addEntities(asset.getRenderableEntities());
    this.scene.addEntities(asset.getLightEntities()); // each at intensity 0 until its turn
    for (const e of asset.getLightEntities()) {
      const li = this.lm.getInstance(e);
      this.lm.setIntensity(li, 0);
      this.lm.setShadowCaster(li, false);
      li.delete();
    }
    this.asset = asset;
  }

  findLight(name) {
    const found = this.asset.getEntitiesByName(name).filter((e) => this.lm.hasComponent(e));
    if (found.length !== 1) throw new Error(`the glb has ${found.length} KHR_lights_punctual lights named "${name}", expected 1`);
    return found[0];
  }

  /** Filament skips a frame when the previous one is not done: renders until n frames were drawn. */
  async frames(n) {
    const times = [];
    for (let tries = 0; tries < 1000 && times.length < n; ++tries) {
      const t0 = performance.now();
      if (this.renderer.beginFrame(this.swapChain)) {
        this.renderer.renderView(this.view);
        this.renderer.endFrame();
        this.engine.execute();
        this.gl().finish(); // the frame done, for its time
        times.push(performance.now() - t0);
      } else {
        this.engine.execute(); // runs the backend's work, whose fences let the next frame begin
      }
      await new Promise((r) => setTimeout(r, 2));
    }
    if (times.length < n) throw new Error(`Filament drew ${times.length} of ${n} frames in 1000 tries`);
    return times;
  }

  gl() {
    return glAllocations.length ? glAllocations[0].gl : document.getElementById('canvas').getContext('webgl2');
  }

  read() {
    const { width, height } = this.job;
    if (!this.targetAllocation) {
      this.targetAllocation = glAllocations.slice(this.allocationsBefore)
        .find((a) => a.format === kGL.RGBA32F && a.width === width && a.height === height);
      if (!this.targetAllocation) throw new Error('the float target\'s GL texture was not seen (texStorage2D RGBA32F)');
    }
    const { gl, texture } = this.targetAllocation;
    const previous = gl.getParameter(gl.FRAMEBUFFER_BINDING);
    const fb = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
    const rgba = new Float32Array(4 * width * height);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.FLOAT, rgba);
    gl.bindFramebuffer(gl.FRAMEBUFFER, previous); // Filament caches its GL state: put it back
    gl.deleteFramebuffer(fb);
    const out = new Float32Array(width * height);
    for (let y = 0; y < height; ++y) {
      const src = (height - 1 - y) * width; // GL rows run bottom to top
      for (let x = 0; x < width; ++x) out[y * width + x] = rgba[4 * (src + x)];
    }
    return out;
  }
}

/** gltfio's ubershader instance as a white dielectric, rough, not emissive (the same for every light). */
function whiten(mi) {
  const set = (name, fn) => { try { fn(); } catch (e) { /* the variant lacks the parameter */ } };
  set('baseColorFactor', () => mi.setFloat4Parameter('baseColorFactor', [1, 1, 1, 1]));
  set('metallicFactor', () => mi.setFloatParameter('metallicFactor', 0));
  set('roughnessFactor', () => mi.setFloatParameter('roughnessFactor', 1));
  set('emissiveFactor', () => mi.setFloat3Parameter('emissiveFactor', [0, 0, 0]));
}

/** The mode and settings, or a clear Error where this build cannot set them. */
function applyMode(fs, li, modeName, s) {
  const view = fs.view;
  if (modeName !== kDefaultMode && modeName !== 'contact') {
    if (typeof view.setShadowType !== 'function') {
      throw new Error(`mode ${modeName}: filament 1.53.4's wasm build has no View.setShadowType binding (filament.d.ts declares View$ShadowType, but View has no setter), so only its default PCF renders`);
    }
    view.setShadowType(Filament[`View$ShadowType`][kModes[modeName]]);
  }
  const options = { ...s };
  if (modeName === 'contact') options.screenSpaceContactShadows = true;
  if (Object.keys(options).length > 0) {
    try {
      fs.lm.setShadowOptions(li, options);
    } catch (e) {
      throw new Error(`${modeName === 'contact' ? 'mode contact (screenSpaceContactShadows)' : `settings ${Object.keys(s).join(', ')}`}: LightManager.setShadowOptions fails in filament 1.53.4's wasm build: ${e.message}`);
    }
  }
}

async function renderOneLight(fs, name, modeName, s) {
  const { lm } = fs;
  const entity = fs.findLight(name);
  const li = lm.getInstance(entity);
  lm.setIntensity(li, 1);
  // gltfio gives a light without a glTF range a falloff of 10 units. Filament lights a spot only
  // over part of its falloff radius here (README.md): the page sets 10 x the distance to the
  // scene's farthest corner, beyond which the image no longer changes.
  if (lm.getType(li) !== Filament.LightManager$Type.DIRECTIONAL && lm.getType(li) !== Filament.LightManager$Type.SUN) {
    const tm = fs.engine.getTransformManager();
    const ti = tm.getInstance(entity);
    const w = tm.getWorldTransform(ti);
    ti.delete();
    lm.setFalloff(li, kFalloffScale * farthestCorner([w[12], w[13], w[14]], fs.job.view.scene.bounds));
  }
  applyMode(fs, li, modeName, s);
  const before = glAllocations.length;
  lm.setShadowCaster(li, true);
  // The first frame compiles the shadow variants; the median of the other three is the time.
  const times = (await fs.frames(4)).slice(1);
  const shadowed = fs.read();
  // The shadow maps Filament allocated for this light's frames; its frame graph may hand a later
  // light the same texture again, which then counts as the last one allocated.
  const { width, height } = fs.job;
  let bytes = glAllocations.slice(before)
    .filter((a) => kShadowFormats.has(a.format) && !(a.width === width && a.height === height)) // not the target's depth

    .reduce((sum, a) => sum + a.width * a.height * a.layers * (kTexelBytes[a.format] || 4), 0);
  if (bytes === 0) bytes = fs.lastShadowBytes || 0;
  fs.lastShadowBytes = bytes;
  lm.setShadowCaster(li, false);
  await fs.frames(2);
  const unshadowed = fs.read();
  lm.setIntensity(li, 0);
  li.delete();
  times.sort((a, b) => a - b);
  return { bytes, shadowed, unshadowed, frameMs: times[1] };
}

window.renderVisibility = async (job) => {
  const glRenderer = requireWebGL2();
  // --preset: `typical` is `default` here, for the want of a binding: the shadow options a
  // Filament user or sample sets (mapSize, biases, shadow type) cannot be set from 1.53.4's wasm
  // build (README.md, "Filament"), so what its users get is its defaults.
  const resolved = resolveJob(job, { default: { mode: kDefaultMode }, typical: { mode: kDefaultMode } }, kDefaultMode, 'filament');
  const modeName = resolved.modeFor('directional');
  if (!Object.hasOwn(kModes, modeName)) throw new Error(`unknown mode "${modeName}" for filament (known: ${Object.keys(kModes).join(', ')})`);
  const s = readSettings(resolved.settingsFor('directional'), kSettingKinds, `filament mode ${modeName}`);
  if (s.mapSize !== undefined && (s.mapSize < 16 || s.mapSize > 8192)) throw new Error(`setting mapSize=${s.mapSize}: outside 16..8192`);
  if (!job.view.scene || !job.view.scene.bounds) throw new Error('view.json has no scene.bounds');
  await initFilament([job.glbUrl]);
  const fs = new FilamentScene(job);
  await fs.load();
  fs.createTarget();
  const lights = {};
  let memoryBytes = 0;
  for (const name of job.lights) {
    const r = await renderOneLight(fs, name, modeName, s);
    lights[name] = { shadowed: floatsToBase64(r.shadowed), unshadowed: floatsToBase64(r.unshadowed), frameMs: r.frameMs };
    memoryBytes += r.bytes;
  }
  const params = { shadowType: kModes[modeName], screenSpaceContactShadows: modeName === 'contact', ...s };
  return { renderer: 'filament 1.53.4', glRenderer, mode: modeName, params, memoryBytes, lights };
};
