/**
 * The auxiliary textures the shared ENVIRONMENT_MAP chunk (sampling.glsl.ts / .wgsl.ts) reads
 * for a lat-long environment: `envMap` (radiance and texel density), `envMarginal` and
 * `envConditional` (the importance-sampling CDFs of scene/environment-sampling.ts). Renderers
 * that bind the chunk (ISO, MCRT) list them from here, so their names and sizes live once.
 */
import type { AuxiliaryTexture } from '../renderer.js';
import type { EnvironmentSamplingTables, LatLongEnvironment } from '../scene/environment-sampling.js';

const ids = new WeakMap<object, number>();
let nextId = 1;

/** A stable number per object (by identity), for auxiliary-texture keys that must not hash voxels or pixels. */
export function objectId(o: object): number {
  let i = ids.get(o);
  if (i === undefined) {
    i = nextId++;
    ids.set(o, i);
  }
  return i;
}

/** What the environment textures depend on: the image (by identity), its scale and size. */
export function environmentTexturesKey(env: LatLongEnvironment): string {
  return `${objectId(env.data)}|${env.scale ?? 1}|${env.width}x${env.height}`;
}

/**
 * The three environment textures of `env`; `tables` builds (or returns memoised) sampling
 * tables and is called only when a texture is created, i.e. when the key changed.
 */
export function environmentTextures(
  env: LatLongEnvironment,
  tables: () => EnvironmentSamplingTables,
): AuxiliaryTexture[] {
  const key = environmentTexturesKey(env);
  const texture = (
    name: string,
    width: number,
    height: number,
    format: 'rgba32float' | 'r32float',
    data: (t: EnvironmentSamplingTables) => Float32Array,
    label: string,
  ): AuxiliaryTexture => ({
    name,
    dimension: '2d',
    key,
    create: () => ({ dimension: '2d', width, height, format, data: data(tables()), label }),
  });
  return [
    texture('envMap', env.width, env.height, 'rgba32float', (t) => t.map, 'environment map'),
    texture('envMarginal', env.height + 1, 1, 'r32float', (t) => t.marginal, 'environment marginal CDF'),
    texture(
      'envConditional',
      env.width + 1,
      env.height,
      'r32float',
      (t) => t.conditional,
      'environment conditional CDFs',
    ),
  ];
}
