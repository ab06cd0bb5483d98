// Babylon.js on its WebGL2 Engine (README.md, "Babylon.js"): pages/babylon-common.js does the work.
import { Engine } from '@babylonjs/core/Engines/engine.js';
import { requireWebGL2 } from './common.js';
import { renderVisibilityWith } from './babylon-common.js';

const kWebGL = {
  label: '', // the renderer string stays `babylon.js VERSION`, as before WebGPU
  async createEngine(canvas) {
    const info = requireWebGL2();
    const engine = new Engine(canvas, false, { antialias: false, stencil: false, adaptToDeviceRatio: false });
    if (engine.webGLVersion < 2) throw new Error(`Babylon.js got WebGL ${engine.webGLVersion}, not WebGL2`);
    return { engine, info };
  },
  async finish(engine) {
    engine._gl.finish();
  },
};

window.renderVisibility = (job) => renderVisibilityWith(job, kWebGL);
