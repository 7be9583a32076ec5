import { describe, expect, it } from 'vitest';
import { loadVolumeSource } from '../src/loading/volume-source.js';

// Issue 28: an error from the element must not suggest `options.raw`, which no attribute reaches.
describe("the element's load errors for headerless data", () => {
  it('unrecognised bytes suggest a sidecar or a file name, not options.raw', async () => {
    const bytes = new Uint8Array(64).fill(7).buffer;
    const e = await loadVolumeSource(bytes, { worker: false } as never).then(
      () => new Error('it loaded'),
      (x: unknown) => x as Error,
    );
    expect(e).toBeInstanceOf(Error);
    expect(e.message).not.toMatch(/options\.raw/);
    expect(e.message).toMatch(/JSON sidecar/);
  });

  it('a .raw file without dims in its name or a sidecar says the same', async () => {
    const file = new File([new Uint8Array(64)], 'scan.raw');
    const e = await loadVolumeSource(file, { worker: false } as never).then(
      () => new Error('it loaded'),
      (x: unknown) => x as Error,
    );
    expect(e).toBeInstanceOf(Error);
    expect(e.message).not.toMatch(/options\.raw/);
    expect(e.message).toMatch(/file name \(name_128x128x84_uint8\.raw\)/);
  });
});
