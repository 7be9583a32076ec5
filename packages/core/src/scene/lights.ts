import { VptError } from '../errors.js';
import type { Vec3 } from './camera.js';
import { checkNumbers, checkObject, fail, LATLONG_SIDE_RULE } from '../validation/checks.js';
import { FLOAT32_MAX, MAX_SCENE_LIGHTS, MAX_RADIANCE } from '../validation/limits.js';

/** A distant light: irradiance E (linear RGB) measured perpendicular to the beam. */
export interface DirectionalLight {
  type: 'directional';
  /** Points from the scene TOWARD the light (light travels along -direction). */
  direction: Vec3;
  irradiance: Vec3;
}
export type Light = DirectionalLight;

/** Background radiance: constant, or an equirectangular (lat-long) HDR image. */
export type Environment =
  | { type: 'constant'; radiance: Vec3 }
  | {
      type: 'latlong';
      width: number;
      height: number;
      /** RGB float, row 0 at the top (+y up is the image's top) */ data: Float32Array;
      scale?: number;
    };

/**
 * Lights: at most MAX_SCENE_LIGHTS, each with a finite non-zero direction and an irradiance in
 * [0, MAX_RADIANCE] (float32 arithmetic in the kernels stays finite; see limits.ts).
 */
export function validateLights(lights: readonly Light[]): void {
  if (!Array.isArray(lights)) fail('lights', 'must be an array');
  if (lights.length > MAX_SCENE_LIGHTS)
    fail(
      'lights',
      `${lights.length} lights exceed the limit of ${MAX_SCENE_LIGHTS} (MAX_SCENE_LIGHTS)`,
      'limit-exceeded',
    );
  lights.forEach((l, i) => {
    const field = `Light ${i}`;
    checkObject(field, l);
    if (l.type !== 'directional')
      throw new VptError(
        'invalid-scene',
        `Light ${i}: unknown type "${(l as { type: string }).type}" (supported: directional)`,
      );
    const d = checkNumbers(`${field}: direction`, l.direction, 3, { min: -FLOAT32_MAX, max: FLOAT32_MAX });
    if (Math.hypot(...d) < 1e-9)
      throw new VptError('invalid-scene', `Light ${i}: direction must be finite and non-zero`);
    checkNumbers(`${field}: irradiance`, l.irradiance, 3, {
      min: 0,
      max: MAX_RADIANCE,
      unit: 'MAX_RADIANCE keeps float32 kernel arithmetic finite',
    });
  });
}

/**
 * Environment: constant radiance, or a lat-long image of integer width × height
 * (≤ MAX_TEXTURE_SIDE_2D − 1, the conditional CDF texture is one wider) whose texels × scale
 * lie in [0, MAX_RADIANCE].
 */
export function validateEnvironment(env: Environment): void {
  checkObject('Environment', env);
  if (env.type === 'constant') {
    checkNumbers('Environment: radiance', env.radiance, 3, {
      min: 0,
      max: MAX_RADIANCE,
      unit: 'MAX_RADIANCE keeps float32 kernel arithmetic finite',
    });
  } else if (env.type === 'latlong') {
    const { width, height } = env;
    checkNumbers('Environment: lat-long [width, height]', [width, height], 2, LATLONG_SIDE_RULE);
    if (!(env.data instanceof Float32Array) || env.data.length !== width * height * 3)
      throw new VptError(
        'invalid-scene',
        `Environment: lat-long image needs width*height*3 = ${width * height * 3} floats in a Float32Array, got ${env.data instanceof Float32Array ? env.data.length : typeof env.data}`,
      );
    const scale = env.scale ?? 1;
    checkNumbers('Environment: scale', [scale], 1, { min: 0, max: MAX_RADIANCE });
    for (let i = 0; i < env.data.length; i++) {
      const x = env.data[i];
      if (!Number.isFinite(x) || x < 0)
        throw new VptError(
          'invalid-scene',
          `Environment: texel ${Math.floor(i / 3)} is not a finite non-negative radiance`,
        );
      if (x * scale > MAX_RADIANCE)
        throw new VptError(
          'invalid-scene',
          `Environment: texel ${Math.floor(i / 3)} radiance ${x} × scale ${scale} exceeds the limit ${MAX_RADIANCE} (MAX_RADIANCE keeps float32 kernel arithmetic finite)`,
        );
    }
  } else {
    throw new VptError(
      'invalid-scene',
      `Environment: unknown type "${(env as { type: string }).type}" (supported: constant, latlong)`,
    );
  }
}
