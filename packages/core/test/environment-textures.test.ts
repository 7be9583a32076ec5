import { describe, expect, it } from 'vitest';
import { buildEnvironmentSampling, environmentTextures, type LatLongEnvironment } from '../src/index.js';

const env = (scale = 1): LatLongEnvironment => ({
  type: 'latlong',
  width: 4,
  height: 2,
  data: new Float32Array(4 * 2 * 3).map((_, i) => 1 + (i % 5)),
  scale,
});

describe('environment textures (the ENVIRONMENT_MAP chunk inputs)', () => {
  it('names, sizes and fills the three textures from the sampling tables, built only when a texture is made', () => {
    const e = env();
    let built = 0;
    const textures = environmentTextures(e, () => (built++, buildEnvironmentSampling(e)));
    expect(built).toBe(0);
    const made = textures.map((t) => t.create!());
    const tables = buildEnvironmentSampling(e);
    expect(textures.map((t) => t.name)).toEqual(['envMap', 'envMarginal', 'envConditional']);
    expect(made.map((d) => [d.width, d.height, d.format])).toEqual([
      [4, 2, 'rgba32float'],
      [3, 1, 'r32float'],
      [5, 2, 'r32float'],
    ]);
    expect(made.map((d) => Array.from(d.data as Float32Array))).toEqual([
      Array.from(tables.map),
      Array.from(tables.marginal),
      Array.from(tables.conditional),
    ]);
    expect(built).toBe(3);
  });
  it('keys change with the image (by identity) and its scale, not with a copy of the same description', () => {
    const e = env();
    const key = (x: LatLongEnvironment) => environmentTextures(x, () => buildEnvironmentSampling(x))[0].key;
    expect(key({ ...e })).toBe(key(e));
    expect(key({ ...e, scale: 2 })).not.toBe(key(e));
    expect(key({ ...e, data: e.data.slice() })).not.toBe(key(e));
  });
});
