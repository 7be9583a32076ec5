import { VptError } from '../errors.js';
import type { BackendOptions, GpuBackend } from './backend.js';
import { createWebGL2Backend } from './webgl2/webgl2-backend.js';
import { createWebGPUBackend, isWebGPUAvailable } from './webgpu/webgpu-backend.js';

/**
 * Create a backend. 'auto' tries WebGPU first (when the browser exposes an adapter)
 * and falls back to WebGL 2; an explicit choice never falls back.
 */
export async function createBackend(options: BackendOptions = {}): Promise<GpuBackend> {
  const pref = options.backend ?? 'auto';
  if (pref !== 'auto' && pref !== 'webgl2' && pref !== 'webgpu') {
    throw new VptError('no-backend', `Unknown backend "${pref}" (use 'auto', 'webgl2' or 'webgpu')`);
  }
  if (options.gl && options.device)
    throw new VptError('no-backend', 'Give a shared WebGL 2 context (gl) or a shared GPUDevice (device), not both');
  if (options.gl) {
    if (pref === 'webgpu') throw new VptError('no-backend', 'A shared WebGL 2 context (gl) needs the WebGL 2 backend');
    return createWebGL2Backend(options.gl.canvas, options.gl);
  }
  const canvas = options.canvas ?? makeCanvas();
  if (options.device) {
    if (pref === 'webgl2') throw new VptError('no-backend', 'A shared GPUDevice (device) needs the WebGPU backend');
    return createWebGPUBackend(canvas, options);
  }
  if (pref === 'webgpu') return createWebGPUBackend(canvas, options);
  if (pref === 'webgl2') return createWebGL2Backend(canvas);
  if (await isWebGPUAvailable()) {
    try {
      return await createWebGPUBackend(canvas, options);
    } catch {
      // An adapter that fails to give a device: fall through to WebGL 2.
    }
  }
  try {
    return createWebGL2Backend(canvas);
  } catch (e) {
    if (e instanceof VptError && e.code === 'missing-extension') throw e;
    throw new VptError('no-backend', 'This browser offers neither WebGPU nor WebGL 2; vpt needs one of them.', {
      cause: e,
    });
  }
}

function makeCanvas(): HTMLCanvasElement | OffscreenCanvas {
  if (typeof document !== 'undefined') return document.createElement('canvas');
  if (typeof OffscreenCanvas !== 'undefined') return new OffscreenCanvas(1, 1);
  throw new VptError('no-backend', 'No canvas available (not running in a browser)');
}
