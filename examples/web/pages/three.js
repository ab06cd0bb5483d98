// three.js on WebGLRenderer (README.md, "three.js"): pages/three-common.js does the work.
import * as THREE from 'three';
import { requireWebGL2 } from './common.js';
import { renderVisibilityWith } from './three-common.js';

const shaderErrors = [];

const kWebGL = {
  label: '', // the renderer string stays `three.js VERSION`, as before WebGPU
  async create() {
    const info = requireWebGL2();
    const renderer = new THREE.WebGLRenderer({ antialias: false });
    renderer.shadowMap.enabled = true;
    renderer.toneMapping = THREE.NoToneMapping;
    renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
    // A program that fails to link is reported here (three.js only logs it and draws nothing).
    renderer.debug.onShaderError = (gl, program, vs, fs) => {
      const log = (gl.getShaderInfoLog(fs) || gl.getShaderInfoLog(vs) || gl.getProgramInfoLog(program) || 'no log').trim();
      shaderErrors.push(log.split('\n')[0]);
    };
    return { renderer, info };
  },
  createTarget(width, height) {
    return new THREE.WebGLRenderTarget(width, height, {
      type: THREE.FloatType, format: THREE.RGBAFormat, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
      depthBuffer: true, generateMipmaps: false,
    });
  },
  shaderErrors: () => shaderErrors[0],
  shaderChunks: true, // THREE.ShaderChunk: what @pmndrs/vanilla's pcss patches
  async read(renderer, target, width, height) {
    const rgba = new Float32Array(4 * width * height);
    renderer.readRenderTargetPixels(target, 0, 0, width, height, rgba);
    return rgba;
  },
};

window.renderVisibility = (job) => renderVisibilityWith(job, kWebGL);
