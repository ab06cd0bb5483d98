// The command line of examples/web/render (README.md). Bad usage throws UsageError: one line, exit 2.
export class UsageError extends Error {}

export const kEngines = ['three', 'babylon', 'playcanvas', 'filament', 'three-webgpu', 'babylon-webgpu', 'galacean'];
/** The engines whose pages need Chromium's WebGPU flags (browser.mjs, kWebGPUArgs). */
export const isWebGPUEngine = (engine) => engine.endsWith('-webgpu');
// --preset: `default` is the engine's API defaults plus the minimum steps to get any shadow;
// `typical` what its own editor, components or official examples set (README.md, "Presets").
export const kPresets = ['default', 'typical'];

export const kUsage = `usage: render SCENE --engine ${kEngines.join('|')} [--mode MODE | --preset ${kPresets.join('|')}] [--set KEY=VALUE]...
              [--width W --height H] --out DIR [--tool PATH] [--export-dir DIR] [--chromium PATH]
              [--timeout SECONDS] [--quiet]`;

/** A --set value: a number where it reads as one, true/false as booleans, else the string. */
export function parseSettingValue(text) {
  if (text === 'true') return true;
  if (text === 'false') return false;
  if (text.trim() !== '' && Number.isFinite(Number(text))) return Number(text);
  return text;
}

function positiveInt(option, text, max) {
  if (!/^[0-9]+$/.test(text) || +text < 1 || +text > max) throw new UsageError(`${option}: "${text}" is not an integer in 1..${max}`);
  return +text;
}

export function parseArgs(argv) {
  const o = { settings: {}, mode: null, preset: null, width: null, height: null, timeoutS: 180, quiet: false };
  const positional = [];
  const takes = new Set(['--engine', '--mode', '--preset', '--set', '--width', '--height', '--out', '--tool', '--export-dir', '--chromium', '--timeout']);
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    if (a === '--help' || a === '-h') return { help: true };
    if (a === '--quiet') { o.quiet = true; continue; }
    if (!a.startsWith('--')) { positional.push(a); continue; }
    if (!takes.has(a)) throw new UsageError(`unknown option ${a}`);
    if (i + 1 >= argv.length) throw new UsageError(`${a} needs a value`);
    const v = argv[++i];
    if (a === '--engine') o.engine = v;
    else if (a === '--mode') o.mode = v;
    else if (a === '--preset') o.preset = v;
    else if (a === '--set') {
      const eq = v.indexOf('=');
      if (eq < 1) throw new UsageError(`--set ${v}: expected KEY=VALUE`);
      const key = v.slice(0, eq);
      if (!/^[A-Za-z0-9_.-]{1,64}$/.test(key)) throw new UsageError(`--set ${v}: the key must be 1 to 64 of A-Z a-z 0-9 _ . -`);
      if (key in o.settings) throw new UsageError(`--set ${key} given twice`);
      o.settings[key] = parseSettingValue(v.slice(eq + 1));
    } else if (a === '--width') o.width = positiveInt(a, v, 8192);
    else if (a === '--height') o.height = positiveInt(a, v, 8192);
    else if (a === '--timeout') o.timeoutS = positiveInt(a, v, 3600);
    else if (a === '--out') o.out = v;
    else if (a === '--tool') o.tool = v;
    else if (a === '--export-dir') o.exportDir = v;
    else if (a === '--chromium') o.chromium = v;
  }
  if (positional.length !== 1) throw new UsageError(`expected one SCENE, got ${positional.length}`);
  o.scene = positional[0];
  if (!o.engine) throw new UsageError('--engine is required');
  if (!kEngines.includes(o.engine)) throw new UsageError(`--engine ${o.engine}: not one of ${kEngines.join(', ')}`);
  if (o.mode !== null && !/^[A-Za-z0-9_.-]{1,64}$/.test(o.mode)) throw new UsageError(`--mode ${o.mode}: 1 to 64 of A-Z a-z 0-9 _ . -`);
  if (o.preset !== null && !kPresets.includes(o.preset)) throw new UsageError(`--preset ${o.preset}: not one of ${kPresets.join(', ')}`);
  if (o.preset !== null && o.mode !== null) throw new UsageError('--mode and --preset exclude each other (a preset names its mode)');
  if (!o.out) throw new UsageError('--out is required');
  if ((o.width === null) !== (o.height === null)) throw new UsageError('--width and --height go together');
  return o;
}
