// Debian's chromium through puppeteer-core: one page, one job, its result or one clear Error.
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';

// The flags that give WebGL2 on SwiftShader headless here (/work/shared/notes/wave4.md): without
// --enable-unsafe-swiftshader Chromium still falls back but warns that a later version will refuse.
export const kChromiumArgs = ['--no-sandbox', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'];
// WebGPU on SwiftShader's Vulkan (/work/shared/notes/wave5.md, "WebGPU headless"): without the
// Vulkan flags navigator.gpu.requestAdapter() returns no adapter. Only the WebGPU engines' pages
// get them, so the WebGL pages run as they always have.
export const kWebGPUArgs = ['--enable-unsafe-webgpu', '--enable-features=Vulkan', '--use-vulkan=swiftshader',
  '--use-webgpu-adapter=swiftshader', '--use-angle=swiftshader'];

export function findChromium(given) {
  if (given) {
    if (!fs.existsSync(given)) throw new Error(`no chromium at ${given}`);
    return given;
  }
  if (process.env.CHROMIUM) return process.env.CHROMIUM;
  for (const name of ['chromium', 'chromium-browser', 'google-chrome']) {
    try {
      return execFileSync('sh', ['-c', `command -v ${name}`], { encoding: 'utf8' }).trim();
    } catch { /* next */ }
  }
  throw new Error('no chromium found (apt-get install chromium, or --chromium PATH / CHROMIUM=PATH)');
}

async function loadPuppeteer() {
  try {
    return (await import('puppeteer-core')).default;
  } catch {
    throw new Error('puppeteer-core is missing: run `npm ci` in examples/web');
  }
}

function firstLine(message) {
  return String(message).split('\n')[0].replace(/^(Error|TypeError|ReferenceError): /, '');
}

/** Debian's chromium, headless, with WebGL2 on SwiftShader (and WebGPU where `webgpu`). */
export async function launchBrowser(chromium, webgpu = false) {
  const puppeteer = await loadPuppeteer();
  try {
    return await puppeteer.launch({ executablePath: chromium, headless: true, args: [...kChromiumArgs, ...(webgpu ? kWebGPUArgs : [])] });
  } catch (e) {
    throw new Error(`cannot start ${chromium}: ${firstLine(e.message)}`);
  }
}

/**
 * Loads pageUrl in a new page of `browser`, waits for window.renderVisibility, runs it on job
 * and closes the page. Rejects with one clear line.
 */
export async function runPage({ browser, pageUrl, job, timeoutS, log }) {
  const pageErrors = [];
  let timer;
  let page = null;
  try {
    page = await browser.newPage();
    page.on('pageerror', (e) => pageErrors.push(firstLine(e.message)));
    page.on('console', (m) => {
      if (m.type() === 'error') pageErrors.push(firstLine(m.text()));
      else if (!m.text().includes('GL Driver Message')) log(`page: ${m.text()}`); // SwiftShader's readback stall notes
    });
    page.on('requestfailed', (r) => pageErrors.push(`request failed: ${r.url()}`));
    const work = (async () => {
      const response = await page.goto(pageUrl, { waitUntil: 'load', timeout: timeoutS * 1000 });
      if (!response || !response.ok()) throw new Error(`cannot load ${pageUrl} (HTTP ${response ? response.status() : 'none'})`);
      await page.waitForFunction(() => typeof window.renderVisibility === 'function', { timeout: 30000 }).catch(() => {
        throw new Error(`the page defines no window.renderVisibility${pageErrors.length ? ': ' + pageErrors[0] : ''}`);
      });
      const result = await page.evaluate((j) => window.renderVisibility(j), job);
      return { result, browserVersion: await browser.version() };
    })();
    const timeout = new Promise((_, reject) => {
      timer = setTimeout(() => reject(new Error(`timed out after ${timeoutS} s`)), timeoutS * 1000);
    });
    return await Promise.race([work, timeout]);
  } catch (e) {
    throw new Error(firstLine(e.message));
  } finally {
    clearTimeout(timer);
    if (page) await Promise.race([page.close().catch(() => {}), new Promise((r) => setTimeout(r, 5000))]);
  }
}

export const kWebRoot = path.resolve(path.dirname(new URL(import.meta.url).pathname), '..');
