import { VptError } from '../errors.js';
import type { Vec3 } from './camera.js';

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
  | { type: 'latlong'; width: number; height: number; /** RGB float, row 0 at the top (+y up is the image's top) */ data: Float32Array; scale?: number };

export function validateLights(lights: readonly Light[]): void {
  lights.forEach((l, i) => {
    if (l.type !== 'directional') throw new VptError('invalid-scene', `Light ${i}: unknown type "${(l as { type: string }).type}"`);
    if (!l.direction.every(Number.isFinite) || Math.hypot(...l.direction) < 1e-9) throw new VptError('invalid-scene', `Light ${i}: direction must be finite and non-zero`);
    if (!l.irradiance.every((x) => Number.isFinite(x) && x >= 0)) throw new VptError('invalid-scene', `Light ${i}: irradiance must be finite and non-negative`);
  });
}

export function validateEnvironment(env: Environment): void {
  if (env.type === 'constant') {
    if (!env.radiance.every((x) => Number.isFinite(x) && x >= 0)) throw new VptError('invalid-scene', 'Environment: radiance must be finite and non-negative');
  } else if (env.type === 'latlong') {
    if (!(env.width >= 1 && env.height >= 1) || env.data.length !== env.width * env.height * 3) throw new VptError('invalid-scene', `Environment: lat-long image needs width*height*3 floats`);
    for (let i = 0; i < env.data.length; i++) if (!Number.isFinite(env.data[i]) || env.data[i] < 0) throw new VptError('invalid-scene', `Environment: texel ${Math.floor(i / 3)} is not a finite non-negative radiance`);
  } else {
    throw new VptError('invalid-scene', `Environment: unknown type "${(env as { type: string }).type}"`);
  }
}
