// createBackend's choice between a shared WebGL 2 context and a shared GPUDevice: contradictory
// options are refused with a VptError naming them, before anything touches a GPU.
import { describe, expect, it } from 'vitest';
import { createBackend } from '../src/gpu/create-backend.js';
import { VptError } from '../src/errors.js';

const gl = {} as WebGL2RenderingContext;
const device = {} as GPUDevice;

async function refusal(p: Promise<unknown>): Promise<VptError> {
  const e = await p.then(
    () => null,
    (err: unknown) => err,
  );
  expect(e).toBeInstanceOf(VptError);
  return e as VptError;
}

describe('createBackend with shared contexts', () => {
  it('refuses both a gl context and a device', async () => {
    const e = await refusal(createBackend({ gl, device }));
    expect(e.code).toBe('no-backend');
    expect(e.message).toMatch(/not both/);
  });

  it('refuses a shared device with the WebGL 2 backend, and a shared gl context with WebGPU', async () => {
    expect(
      (await refusal(createBackend({ device, backend: 'webgl2', canvas: {} as OffscreenCanvas }))).message,
    ).toMatch(/GPUDevice \(device\) needs the WebGPU backend/);
    expect((await refusal(createBackend({ gl, backend: 'webgpu' }))).message).toMatch(/needs the WebGL 2 backend/);
  });
});
