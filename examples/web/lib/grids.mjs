// grids.json: each engine's modes and settings grids for the sweep (README.md, "sweep").
import fs from 'node:fs';

/** The C library's "%.{digits}g", which the sweep's labels and image paths use. */
function cFormatG(v, digits) {
  if (v === 0) return Object.is(v, -0) ? '-0' : '0';
  const [mantissa, expText] = v.toExponential(digits - 1).split('e');
  const exp = Number(expText);
  const strip = (s) => (s.includes('.') ? s.replace(/0+$/, '').replace(/\.$/, '') : s);
  if (exp < -4 || exp >= digits) return `${strip(mantissa)}e${exp < 0 ? '-' : '+'}${String(Math.abs(exp)).padStart(2, '0')}`;
  return strip(v.toFixed(Math.max(0, digits - 1 - exp)));
}

/** A number as the sweep prints it in a label (raster_compare/pipeline/sweep_spec.cpp, shortestNumber). */
export function shortestNumber(v) {
  if (Number.isInteger(v) && Math.abs(v) < 1e15) return v.toFixed(0);
  for (let digits = 1; digits <= 17; ++digits) {
    const text = cFormatG(v, digits);
    if (Number(text) === v) return text;
  }
  return String(v);
}

function fail(file, field, why) {
  throw new Error(`${file}: ${field}: ${why}`);
}

/** The checked entries of `engine` in the grids file. */
export function readGrids(file, engine) {
  let doc;
  try {
    doc = JSON.parse(fs.readFileSync(file, 'utf8'));
  } catch (e) {
    fail(file, '(file)', e.message);
  }
  if (doc.grids_format !== 1) fail(file, 'grids_format', 'must be 1');
  const entries = doc.engines && doc.engines[engine];
  if (!Array.isArray(entries) || !entries.length) fail(file, `engines.${engine}`, 'no entries for this engine');
  const names = new Set();
  entries.forEach((e, i) => {
    const f = `engines.${engine}[${i}]`;
    if (typeof e.name !== 'string' || !/^[A-Za-z0-9_.-]{1,64}$/.test(e.name)) fail(file, `${f}.name`, 'must be 1 to 64 of A-Z a-z 0-9 _ - .');
    if (names.has(e.name)) fail(file, `${f}.name`, `"${e.name}" twice`);
    names.add(e.name);
    if (e.mode !== undefined && e.mode !== null && typeof e.mode !== 'string') fail(file, `${f}.mode`, 'must be a string or null');
    if (e.preset !== undefined && !['default', 'typical'].includes(e.preset)) fail(file, `${f}.preset`, 'must be default or typical');
    if (e.preset !== undefined && e.mode) fail(file, `${f}.preset`, 'a preset names its mode: give preset or mode, not both');
    for (const [k, v] of Object.entries(e.grid || {})) {
      if (!Array.isArray(v) || !v.length || !v.every(Number.isFinite)) fail(file, `${f}.grid.${k}`, 'must be a non-empty list of numbers');
    }
  });
  return entries;
}

/** The grid's settings, its last key varying fastest (the sweep's order): [{key: value}]. */
export function expandGrid(grid) {
  let settings = [{}];
  for (const [key, values] of Object.entries(grid || {})) {
    // Rounded to 15 significant digits, as the sweep rounds its grids (docs/sweep.md).
    settings = settings.flatMap((s) => values.map((v) => ({ ...s, [key]: Number(v.toPrecision(15)) })));
  }
  return settings;
}
