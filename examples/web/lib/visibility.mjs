// From a page's two renders of one light to V, and the checks on what a page returns.
import { Buffer } from 'node:buffer';

// Where the unshadowed render is below this fraction of its brightest pixel the surface faces away
// from the light, lies outside a spot's cone or is background: V = 0 there, the oracle's own
// convention for those pixels (its `cos` mask; docs/external.md). Blender's script uses the same.
export const kUnshadowedFloor = 1e-6;

export function decodeFloats(base64, count, what) {
  if (typeof base64 !== 'string') throw new Error(`${what}: not a base64 string`);
  const bytes = Buffer.from(base64, 'base64');
  if (bytes.length !== 4 * count) throw new Error(`${what}: ${bytes.length} bytes, expected ${4 * count} (${count} floats)`);
  const out = new Float32Array(count);
  for (let i = 0; i < count; ++i) out[i] = bytes.readFloatLE(4 * i);
  return out;
}

/** V = shadowed / unshadowed, clamped to [0, 1], where unshadowed is not tiny; 0 elsewhere. */
export function visibility(shadowed, unshadowed, what) {
  let peak = 0;
  for (const u of unshadowed) {
    if (!Number.isFinite(u)) throw new Error(`${what}: the unshadowed render has a non-finite value`);
    if (u > peak) peak = u;
  }
  const v = new Float32Array(unshadowed.length);
  const floor = peak * kUnshadowedFloor;
  let lit = 0;
  for (let i = 0; i < v.length; ++i) {
    if (!(unshadowed[i] > floor)) continue;
    if (!Number.isFinite(shadowed[i])) throw new Error(`${what}: the shadowed render has a non-finite value at pixel ${i}`);
    v[i] = Math.min(1, Math.max(0, shadowed[i] / unshadowed[i]));
    ++lit;
  }
  if (lit === 0) throw new Error(`${what}: the light reaches no pixel even unshadowed (a wrong camera or light?)`);
  return v;
}

/** The cost file's params: scalar values with names compare accepts (docs/external.md). */
export function checkParams(params) {
  if (params === null || typeof params !== 'object' || Array.isArray(params)) throw new Error('result.params: not an object');
  for (const [k, v] of Object.entries(params)) {
    if (!/^.{1,64}$/.test(k)) throw new Error(`result.params: name "${k}" is not 1 to 64 characters`);
    if (!['number', 'string', 'boolean'].includes(typeof v) || (typeof v === 'number' && !Number.isFinite(v))) {
      throw new Error(`result.params.${k}: not a finite number, string or boolean`);
    }
  }
  return params;
}
