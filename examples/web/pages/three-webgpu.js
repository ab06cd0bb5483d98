// three.js on WebGPURenderer (README.md, "three.js on WebGPU"): its node-based shadows (ShadowNode,
// ShadowFilterNode) on Chromium's WebGPU adapter (SwiftShader's Vulkan), through the same page as
// WebGLRenderer's (pages/three-common.js). The import map makes 'three' three.webgpu.js, so the
// scene's Lambert materials become node materials. Read back from the float render target with
// readRenderTargetPixelsAsync (copyTextureToBuffer + mapAsync): a WebGPU canvas can come back
// blank headless.
import * as THREE from 'three';
import { renderVisibilityWith } from './three-common.js';

async function requireWebGPU() {
  if (!navigator.gpu) throw new Error('WebGPU is not available in this browser (chromium needs --enable-unsafe-webgpu --enable-features=Vulkan --use-vulkan=swiftshader --use-webgpu-adapter=swiftshader)');
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) throw new Error('navigator.gpu.requestAdapter() returned no adapter (chromium needs the Vulkan flags: README.md)');
  const info = adapter.info || {};
  return `WebGPU adapter: ${info.vendor || '?'} ${info.architecture || '?'}`;
}

const kWebGPU = {
  label: 'WebGPU',
  async create() {
    const info = await requireWebGPU();
    const renderer = new THREE.WebGPURenderer({ antialias: false });
    await renderer.init();
    if (!renderer.backend || !renderer.backend.isWebGPUBackend) {
      throw new Error('WebGPURenderer fell back to WebGL2: no WebGPU device here, so this would not be the WebGPU row');
    }
    renderer.shadowMap.enabled = true;
    renderer.toneMapping = THREE.NoToneMapping;
    renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
    return { renderer, info };
  },
  createTarget(width, height) {
    return new THREE.RenderTarget(width, height, {
      type: THREE.FloatType, format: THREE.RGBAFormat, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
      depthBuffer: true, generateMipmaps: false,
    });
  },
  async read(renderer, target, width, height) {
    const data = await renderer.readRenderTargetPixelsAsync(target, 0, 0, width, height);
    if (!(data instanceof Float32Array) || data.length < 4 * width * height) {
      throw new Error(`the float target read back as ${data && data.constructor.name} of ${data && data.length} values`);
    }
    // WebGPU's rows come top first, WebGL's bottom first: give the common code WebGL's order.
    const rgba = new Float32Array(4 * width * height);
    const rowFloats = data.length / height; // rows padded to 256 bytes where the width asks for it
    for (let y = 0; y < height; ++y) rgba.set(data.subarray(y * rowFloats, y * rowFloats + 4 * width), (height - 1 - y) * 4 * width);
    return rgba;
  },
  // The notes' trial: toggling castShadow between frames takes effect on WebGPU; receiveShadow, a
  // node material's build-time switch, does not (both renders came back shadowless).
  toggleCastShadow: true,
  clipDepthZeroToOne: true, // view.json's proj_gl is OpenGL's; WebGPU clips depth to 0..1
  refuses: { csm: 'the CSM add-on patches WebGLRenderer\'s shader chunks; WebGPURenderer has CSMShadowNode instead, not wired here' },
};

window.renderVisibility = (job) => renderVisibilityWith(job, kWebGPU);
