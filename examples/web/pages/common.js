// Helpers every engine page shares (README.md, "Page contract"). Plain ES module, no engine code.

/** A Float32Array as base64 of its little-endian bytes (the driver's decodeFloats reads it). */
export function floatsToBase64(floats) {
  const bytes = new Uint8Array(floats.buffer, floats.byteOffset, floats.byteLength);
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

/**
 * One channel of an RGBA float readback (OpenGL order: row 0 at the bottom) as width * height
 * values with row 0 at the top, the order of the contract and of the oracle's images.
 */
export function channelTopDown(rgba, width, height, channel = 0) {
  const out = new Float32Array(width * height);
  for (let y = 0; y < height; ++y) {
    const src = (height - 1 - y) * width;
    for (let x = 0; x < width; ++x) out[y * width + x] = rgba[4 * (src + x) + channel];
  }
  return out;
}

/** Throws a clear Error where WebGL2 or float render targets are missing. */
export function requireWebGL2() {
  const gl = document.createElement('canvas').getContext('webgl2');
  if (!gl) throw new Error('WebGL2 is not available in this browser (chromium needs --enable-unsafe-swiftshader without a GPU)');
  if (!gl.getExtension('EXT_color_buffer_float')) throw new Error('WebGL2 has no EXT_color_buffer_float: float render targets cannot be read back');
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
}

/**
 * The job's settings as typed values: `known` maps a name to its kind ('number', 'integer',
 * 'boolean' or an array of allowed strings). An unknown name or a wrong value throws, naming it.
 */
export function readSettings(settings, known, engine) {
  const out = {};
  for (const [name, value] of Object.entries(settings || {})) {
    const kind = known[name];
    if (kind === undefined) throw new Error(`unknown setting "${name}" for ${engine} (known: ${Object.keys(known).join(', ')})`);
    const ok = Array.isArray(kind) ? kind.includes(value)
      : kind === 'integer' ? Number.isInteger(value)
      : kind === 'number' ? typeof value === 'number' && Number.isFinite(value)
      : typeof value === kind;
    if (!ok) throw new Error(`setting ${name}=${value}: expected ${Array.isArray(kind) ? 'one of ' + kind.join(', ') : 'a ' + kind}`);
    out[name] = value;
  }
  return out;
}

/** Milliseconds of `frame()` (which must finish its GPU work, e.g. by a readback): the median of n. */
export function medianMs(frame, n = 5) {
  const times = [];
  for (let i = 0; i < n; ++i) {
    const t0 = performance.now();
    frame();
    times.push(performance.now() - t0);
  }
  times.sort((a, b) => a - b);
  return times[n >> 1];
}

/**
 * The mode and each light's settings a job asks for. With `job.preset`, `presets[job.preset]`
 * gives `mode` (a mode name, or {directional, spot, point: mode name}) and `settings`
 * ({directional, spot, point: {name: value}}), which the job's --set override; without one,
 * `job.mode` (null: `defaultMode`) and the job's settings for every light.
 */
export function resolveJob(job, presets, defaultMode, engine) {
  const given = job.settings || {};
  if (job.preset === undefined || job.preset === null) {
    const modeName = job.mode === null ? defaultMode : job.mode;
    return { preset: null, modeFor: () => modeName, settingsFor: () => given };
  }
  if (!Object.hasOwn(presets, job.preset)) throw new Error(`unknown preset "${job.preset}" for ${engine} (known: ${Object.keys(presets).join(', ')})`);
  const p = presets[job.preset];
  return {
    preset: job.preset,
    modeFor: (type) => (typeof p.mode === 'string' ? p.mode : p.mode[type]),
    settingsFor: (type) => ({ ...((p.settings && p.settings[type]) || {}), ...given }),
  };
}

/**
 * One params object for the cost file from each light's: the first light's as they are, and
 * where a later light's value differs (a preset's per-light settings), `LIGHT.name` beside them.
 */
export function mergeLightParams(perLight) {
  const out = { ...perLight[0][1] };
  for (const [light, params] of perLight.slice(1)) {
    for (const [k, v] of Object.entries(params)) if (out[k] !== v) out[`${light}.${k}`] = v;
  }
  return out;
}

/**
 * Each light of `names` rendered in turn by `renderOne(name)`, which resolves to { result, bytes,
 * params }: the job's `lights` (name -> result), the shadow memory summed over them, and the
 * per-light params as mergeLightParams takes them.
 */
export async function renderEachLight(names, renderOne) {
  const lights = {};
  let memoryBytes = 0;
  const perLight = [];
  for (const name of names) {
    const one = await renderOne(name);
    lights[name] = one.result;
    memoryBytes += one.bytes;
    perLight.push([name, one.params]);
  }
  return { lights, memoryBytes, perLight };
}

/** The distance from point p ([x, y, z]) to the box `bounds` ({min, max}); 0 inside it. */
export function distanceToBox(p, bounds) {
  let d2 = 0;
  for (let i = 0; i < 3; ++i) {
    const d = Math.max(bounds.min[i] - p[i], 0, p[i] - bounds.max[i]);
    d2 += d * d;
  }
  return Math.sqrt(d2);
}

/** The distance from point p to the farthest corner of the box `bounds`. */
export function farthestCornerDistance(p, bounds) {
  let far = 0;
  for (let i = 0; i < 8; ++i) {
    const c = [i & 1 ? bounds.max[0] : bounds.min[0], i & 2 ? bounds.max[1] : bounds.min[1], i & 4 ? bounds.max[2] : bounds.min[2]];
    far = Math.max(far, Math.hypot(c[0] - p[0], c[1] - p[1], c[2] - p[2]));
  }
  return far;
}

/** medianMs for a `frame()` that returns a promise (a WebGPU frame ends with an async readback). */
export async function medianMsAsync(frame, n = 5) {
  const times = [];
  for (let i = 0; i < n; ++i) {
    const t0 = performance.now();
    await frame();
    times.push(performance.now() - t0);
  }
  times.sort((a, b) => a - b);
  return times[n >> 1];
}
