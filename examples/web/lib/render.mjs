// examples/web/render: one engine, one mode, one scene -> DIR/ENGINE-MODE.exr and its cost file
// (README.md). Steps: `shadow-oracle export`, a local HTTP server, chromium on pages/ENGINE.html,
// V from the page's shadowed and unshadowed renders, the EXR and cost file written atomically.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync, spawnSync } from 'node:child_process';
import { parseArgs, UsageError, kUsage, isWebGPUEngine } from './args.mjs';
import { serve } from './server.mjs';
import { findChromium, launchBrowser, runPage, kWebRoot } from './browser.mjs';
import { decodeFloats, visibility, checkParams } from './visibility.mjs';
import { encodeExr } from './exr.mjs';

function findTool(given) {
  if (given) return given;
  if (process.env.SHADOW_ORACLE) return process.env.SHADOW_ORACLE;
  const built = path.resolve(kWebRoot, '../../build/cli/shadow-oracle');
  return fs.existsSync(built) ? built : 'shadow-oracle';
}

/** Runs `shadow-oracle export` into a fresh folder unless --export-dir names one already made. */
function exportScene(o, log) {
  if (o.exportDir) return { dir: path.resolve(o.exportDir), temporary: false };
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'so-web-export-'));
  const size = o.width ? ['--width', String(o.width), '--height', String(o.height)] : [];
  const tool = findTool(o.tool);
  const r = spawnSync(tool, ['export', o.scene, '--out', dir, ...size], { encoding: 'utf8' });
  if (r.error || r.status !== 0) {
    fs.rmSync(dir, { recursive: true, force: true });
    const why = r.error ? r.error.message : (r.stderr.trim().split('\n').pop() || `exit ${r.status}`);
    throw new Error(`shadow-oracle export failed (${tool}): ${why}`);
  }
  log(r.stdout.trim());
  return { dir, temporary: true };
}

function readView(dir, o) {
  const file = path.join(dir, 'view.json');
  let view;
  try {
    view = JSON.parse(fs.readFileSync(file, 'utf8'));
  } catch (e) {
    throw new Error(`${file}: ${e.message}`);
  }
  if (view.view_format !== 1) throw new Error(`${file}: view_format: ${view.view_format}, this driver reads 1`);
  if (!fs.existsSync(path.join(dir, 'scene.glb'))) throw new Error(`${dir}: no scene.glb`);
  const { width, height } = view.camera;
  if (o.width && (width !== o.width || height !== o.height)) {
    throw new Error(`${file}: camera is ${width} x ${height}, --width/--height ask ${o.width} x ${o.height}`);
  }
  return view;
}

/** Checks the page's result and turns it into the EXR's channels and the cost file. */
function assemble(result, view, o, browserVersion) {
  if (!result || typeof result !== 'object') throw new Error('the page returned no result object');
  const { width, height } = view.camera;
  const channels = {};
  let frameMs = 0;
  for (const light of view.lights) {
    const r = result.lights && result.lights[light.name];
    if (!r) throw new Error(`the page returned nothing for light "${light.name}"`);
    const what = `light "${light.name}"`;
    const shadowed = decodeFloats(r.shadowed, width * height, `${what} shadowed`);
    const unshadowed = decodeFloats(r.unshadowed, width * height, `${what} unshadowed`);
    channels[`${light.name}.V`] = visibility(shadowed, unshadowed, what);
    if (!(r.frameMs >= 0)) throw new Error(`${what}: frameMs is not a number >= 0`);
    frameMs += r.frameMs;
  }
  if (typeof result.renderer !== 'string' || !result.renderer) throw new Error('result.renderer: missing');
  if (!(result.memoryBytes >= 0)) throw new Error('result.memoryBytes: not a number >= 0');
  const cost = {
    // The page's milliseconds are SwiftShader's (software WebGL2 in headless Chromium), not a GPU's
    // and not llvmpipe's: the renderer string says so wherever the row is shown.
    renderer: `${result.renderer} (${browserVersion}, SwiftShader${isWebGPUEngine(o.engine) ? ' Vulkan via WebGPU' : ''})`,
    frame_ms: frameMs,
    memory_bytes: Math.round(result.memoryBytes),
    params: checkParams({ mode: result.mode || o.mode || 'default', ...(o.preset ? { preset: o.preset } : {}), ...result.params }),
  };
  return { channels, cost };
}

function writeAtomically(files) {
  const temps = files.map(([file, bytes]) => {
    const tmp = `${file}.tmp-${process.pid}`;
    fs.writeFileSync(tmp, bytes);
    return [tmp, file];
  });
  for (const [tmp, file] of temps) fs.renameSync(tmp, file);
}

/** One render; `shared.browser`, where given, is used and left open (a sweep's), else one is started. */
async function render(o, log, shared) {
  const modeName = o.preset || o.mode || 'default'; // the image's name: ENGINE-PRESET or ENGINE-MODE
  fs.mkdirSync(o.out, { recursive: true });
  const exrPath = path.join(o.out, `${o.engine}-${modeName}.exr`);
  // A failed run leaves no image at all, not the last run's under this run's name.
  for (const stale of [exrPath, `${exrPath}.json`]) fs.rmSync(stale, { force: true });
  const pageFile = path.join(kWebRoot, 'pages', `${o.engine}.html`);
  if (!fs.existsSync(pageFile)) throw new Error(`no page ${pageFile} for this engine`);
  // A sweep's shared browser has no WebGPU flags: a WebGPU engine gets a browser of its own.
  const useShared = shared && shared.browser && !isWebGPUEngine(o.engine);
  const browser = useShared ? shared.browser : await launchBrowser(findChromium(o.chromium), isWebGPUEngine(o.engine));
  let exported = null;
  let server = null;
  try {
    exported = exportScene(o, log);
    server = await serve({ web: kWebRoot, scene: exported.dir });
    const view = readView(exported.dir, o);
    const job = {
      glbUrl: `${server.url}/scene/scene.glb`, view, width: view.camera.width, height: view.camera.height,
      mode: o.mode, preset: o.preset, settings: o.settings, lights: view.lights.map((l) => l.name),
    };
    const pageUrl = `${server.url}/web/pages/${o.engine}.html`;
    const { result, browserVersion } = await runPage({ browser, pageUrl, job, timeoutS: o.timeoutS, log });
    const { channels, cost } = assemble(result, view, o, browserVersion);
    const exr = encodeExr(view.camera.width, view.camera.height, channels, {
      'shadowOracle/renderer': cost.renderer, 'shadowOracle/sceneHash': view.scene.hash || '',
    });
    writeAtomically([[`${exrPath}.json`, JSON.stringify(cost, null, 2) + '\n'], [exrPath, exr]]);
    log(`${o.engine} ${modeName}: ${exrPath} (${Object.keys(channels).join(', ')}; frame ${cost.frame_ms.toFixed(1)} ms on SwiftShader)`);
  } finally {
    if (server) await server.close();
    if (exported && exported.temporary) fs.rmSync(exported.dir, { recursive: true, force: true });
    if (!useShared) await browser.close().catch(() => {});
  }
}

/** The command: exit 0, 1 (a failed render, one line on stderr) or 2 (bad usage). */
export async function main(argv, shared = null) {
  let o;
  try {
    o = parseArgs(argv);
  } catch (e) {
    if (!(e instanceof UsageError)) throw e;
    process.stderr.write(`render: error: ${e.message}\n${kUsage}\n`);
    return 2;
  }
  if (o.help) {
    process.stdout.write(kUsage + '\n');
    return 0;
  }
  const log = o.quiet ? () => {} : (s) => { if (s) process.stderr.write(s + '\n'); };
  try {
    await render(o, log, shared);
    return 0;
  } catch (e) {
    const message = String(e && e.message ? e.message : e).split('\n')[0]; // one line, whatever threw
    process.stderr.write(`render: ${o.engine} ${o.preset || o.mode || 'default'} ${o.scene}: ${message}\n`);
    return 1;
  }
}
