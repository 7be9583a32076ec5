// Issue 28: the headerless-raw error told a <vpt-viewer> user to pass options.raw, which no
// element attribute reaches. It now names every way to give the dims: a sidecar (the way for
// an element's src and for scene files), the file-name pattern, and options.raw from code.
import { describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';
import { expectLoaderError } from './helpers.js';

describe('headerless raw data', () => {
  it('the error names the sidecar, the file-name pattern and, for code, options.raw', async () => {
    const e = await expectLoaderError(loadVolume(new File([new Uint8Array(64)], 'scan.raw')), 'bad-header');
    expect(e.message).toMatch(/scan\.raw: raw data has no header/);
    expect(e.message).toMatch(/JSON sidecar beside it .*"dims": \[NX, NY, NZ\].*<vpt-viewer src>/);
    expect(e.message).toMatch(/name_NXxNYxNZ_uint8\.raw/);
    expect(e.message).toMatch(/from code loadVolume\(…, \{ raw: \{ dims, type \} \}\)/);
  });
});
