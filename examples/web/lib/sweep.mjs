// examples/web/sweep: every engine's defaults and settings grids (grids.json) on a few scenes, as
// a sweep spec whose `images` entries join the built-in techniques in one report (README.md).
import fs from 'node:fs';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { kEngines } from './args.mjs';
import { kWebRoot, findChromium, launchBrowser } from './browser.mjs';
import { main as renderMain } from './render.mjs';
import { readGrids, expandGrid, shortestNumber } from './grids.mjs';

export const kSweepUsage = `usage: sweep OUT [--engines ${kEngines.join(',')}] [--width W --height H] [--grids FILE]
             [--technique SETTING]... [--tool PATH] [--jobs N] [--frames N] [--force] [--no-sweep] [SCENE ...]`;
const kDefaultScenes = ['terrain_sun', 'spot_objects', 'contact_box', 'alpha_grate', 'penumbra_square', 'soft_chair', 'sphere_light'];

function parseSweepArgs(argv) {
  const o = { engines: ['three'], width: 160, height: 120, grids: path.join(kWebRoot, 'grids.json'), techniques: [],
    jobs: 1, frames: 3, force: false, sweep: true, scenes: [] };
  const value = (i, a) => { if (i + 1 >= argv.length) throw new Error(`${a} needs a value`); return argv[i + 1]; };
  const int = (a, t) => { if (!/^[0-9]+$/.test(t) || +t < 1 || +t > 16384) throw new Error(`${a}: "${t}" is not an integer in 1..16384`); return +t; };
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    if (a === '--force') o.force = true;
    else if (a === '--no-sweep') o.sweep = false;
    else if (a === '--engines') o.engines = value(i++, a).split(',');
    else if (a === '--width') o.width = int(a, value(i++, a));
    else if (a === '--height') o.height = int(a, value(i++, a));
    else if (a === '--jobs') o.jobs = int(a, value(i++, a));
    else if (a === '--frames') o.frames = int(a, value(i++, a));
    else if (a === '--grids') o.grids = value(i++, a);
    else if (a === '--technique') o.techniques.push(value(i++, a));
    else if (a === '--tool') o.tool = value(i++, a);
    else if (a.startsWith('--')) throw new Error(`unknown option ${a}`);
    else if (!o.out) o.out = a;
    else o.scenes.push(a);
  }
  if (!o.out) throw new Error('OUT is required');
  for (const e of o.engines) if (!kEngines.includes(e)) throw new Error(`--engines: ${e} is not one of ${kEngines.join(', ')}`);
  if (!o.scenes.length) o.scenes = kDefaultScenes.map((s) => path.resolve(kWebRoot, `../../scenes/${s}.scene.json`));
  o.tool = o.tool || process.env.SHADOW_ORACLE || path.resolve(kWebRoot, '../../build/cli/shadow-oracle');
  return o;
}

const stem = (scene) => path.basename(scene).split('.')[0];

function exportScenes(o) {
  const views = {};
  for (const scene of o.scenes) {
    const dir = path.join(o.out, 'exports', stem(scene));
    if (o.force || !fs.existsSync(path.join(dir, 'scene.glb'))) {
      fs.rmSync(dir, { recursive: true, force: true });
      const r = spawnSync(o.tool, ['export', scene, '--out', dir, '--width', String(o.width), '--height', String(o.height)], { stdio: ['ignore', 'ignore', 'inherit'] });
      if (r.status !== 0) throw new Error(`shadow-oracle export ${scene} failed`);
    }
    views[scene] = JSON.parse(fs.readFileSync(path.join(dir, 'view.json'), 'utf8'));
  }
  return views;
}

// The image of one setting: renders/{scene}/NAME/KEY_{KEY}/.../ENGINE-MODE.exr, the values as
// the sweep prints them, so that the spec's path pattern finds it.
function imagePath(entry, engine, settings, scenePart) {
  const dirs = Object.entries(settings).map(([k, v]) => `${k}_${v === null ? `{${k}}` : shortestNumber(v)}`);
  return path.join('renders', scenePart, entry.name, ...dirs, `${engine}-${entry.preset || entry.mode || 'default'}.exr`);
}

function covers(entry, view) {
  return !entry.lights || view.lights.every((l) => entry.lights.includes(l.type));
}

/**
 * Renders one entry's grid on every scene it covers, in one browser (`shared.browser`, started
 * again after a failed render, which may have left a page hanging); returns the scenes where all
 * of it rendered.
 */
async function renderEntry(o, engine, entry, views, shared) {
  const done = [];
  for (const scene of o.scenes) {
    if (!covers(entry, views[scene])) continue;
    let ok = true;
    for (const settings of expandGrid(entry.grid)) {
      const exr = path.join(o.out, imagePath(entry, engine, settings, stem(scene)));
      if (!o.force && fs.existsSync(exr)) continue;
      const sets = Object.entries({ ...entry.set, ...settings }).flatMap(([k, v]) => ['--set', `${k}=${v}`]);
      const mode = entry.preset ? ['--preset', entry.preset] : entry.mode ? ['--mode', entry.mode] : [];
      const rc = await renderMain([scene, '--engine', engine, ...mode, ...sets, '--quiet',
        '--export-dir', path.join(o.out, 'exports', stem(scene)), '--out', path.dirname(exr)], shared);
      if (rc !== 0) { // render said why on stderr
        ok = false;
        await shared.browser.close().catch(() => {});
        shared.browser = await launchBrowser(shared.chromium);
      }
    }
    if (ok) done.push(scene);
    else process.stderr.write(`sweep: ${entry.name} left out on ${stem(scene)} (a setting failed to render)\n`);
  }
  return done;
}

function writeSpec(o, images) {
  const rel = (p) => path.relative(o.out, p);
  const spec = {
    sweep_format: 1, name: 'web-engines', scenes: o.scenes.map(rel), width: o.width, height: o.height, frames: o.frames,
    techniques: o.techniques.map((t) => {
      const [name, params] = t.split(':');
      // KEY=V or KEY=V1|V2|...: a list, swept (the matched baselines: slope-bias:resolution=512|1024|2048).
      const value = (v) => (v.includes('|') ? v.split('|').map(Number) : Number(v));
      return { name, params: Object.fromEntries((params ? params.split(',') : []).map((kv) => kv.split('=')).map(([k, v]) => [k, value(v)])) };
    }),
    images: images.map(({ engine, entry, scenes }) => ({
      name: entry.name,
      path: imagePath(entry, engine, Object.fromEntries(Object.keys(entry.grid || {}).map((k) => [k, null])), '{scene}'),
      ...(entry.grid ? { params: entry.grid } : {}),
      scenes: scenes.map(rel),
    })),
  };
  if (!spec.techniques.length) delete spec.techniques;
  const file = path.join(o.out, 'spec.json');
  fs.writeFileSync(file, JSON.stringify(spec, null, 1) + '\n');
  return file;
}

export async function sweepMain(argv) {
  let o;
  try {
    o = parseSweepArgs(argv);
  } catch (e) {
    process.stderr.write(`sweep: error: ${e.message}\n${kSweepUsage}\n`);
    return 2;
  }
  try {
    o.out = path.resolve(o.out);
    o.scenes = o.scenes.map((s) => path.resolve(s));
    fs.mkdirSync(o.out, { recursive: true });
    const views = exportScenes(o);
    const images = [];
    const chromium = findChromium(process.env.CHROMIUM);
    const shared = { chromium, browser: await launchBrowser(chromium) };
    try {
      for (const engine of o.engines) {
        for (const entry of readGrids(o.grids, engine)) {
          const scenes = await renderEntry(o, engine, entry, views, shared);
          if (scenes.length) images.push({ engine, entry, scenes });
        }
      }
    } finally {
      await shared.browser.close().catch(() => {});
    }
    if (!images.length) throw new Error('no engine rendered any scene');
    const spec = writeSpec(o, images);
    process.stderr.write(`sweep: ${spec}\n`);
    if (!o.sweep) return 0;
    const r = spawnSync(o.tool, ['sweep', spec, '--out', path.join(o.out, 'sweep'), '--jobs', String(o.jobs)], { stdio: 'inherit' });
    return r.status === 0 ? 0 : 1;
  } catch (e) {
    process.stderr.write(`sweep: error: ${e.message}\n`);
    return 1;
  }
}
