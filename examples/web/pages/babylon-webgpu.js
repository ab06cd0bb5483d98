// Babylon.js on its WebGPUEngine (README.md, "Babylon.js on WebGPU"): its own shader generation
// (WGSL) on Chromium's WebGPU adapter (SwiftShader's Vulkan), through the same page as the WebGL2
// Engine's (pages/babylon-common.js): the float RenderTargetTexture read back with readPixels.
import { WebGPUEngine } from '@babylonjs/core/Engines/webgpuEngine.js';
import { renderVisibilityWith } from './babylon-common.js';

const kWebGPU = {
  label: 'WebGPU',
  async createEngine(canvas) {
    if (!navigator.gpu) throw new Error('WebGPU is not available in this browser (chromium needs --enable-unsafe-webgpu and the Vulkan flags: README.md)');
    const adapter = await navigator.gpu.requestAdapter();
    if (!adapter) throw new Error('navigator.gpu.requestAdapter() returned no adapter (chromium needs the Vulkan flags: README.md)');
    const engine = new WebGPUEngine(canvas, { antialias: false, stencil: false, adaptToDeviceRatio: false });
    try {
      await engine.initAsync();
    } catch (e) {
      throw new Error(`Babylon.js's WebGPUEngine.initAsync failed: ${e && e.message ? e.message : e}`);
    }
    const info = adapter.info || {};
    return { engine, info: `WebGPU adapter: ${info.vendor || '?'} ${info.architecture || '?'}` };
  },
  async finish(engine) {
    await engine.flushFramebuffer?.();
    await new Promise((r) => requestAnimationFrame(r)); // the queue's work is submitted per frame
  },
};

window.renderVisibility = (job) => renderVisibilityWith(job, kWebGPU);
