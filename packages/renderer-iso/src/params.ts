import { VptError, type ParamSpecs } from '@vpt/core';

/** One isosurface: where the normalized value crosses `value`, with its own colour and opacity. */
export interface IsoSurface {
  /** Iso value in the normalized value range [0, 1] (the same axis as the transfer function). */
  value: number;
  /** Diffuse albedo (linear RGB, each in [0, 1]). */
  color: [number, number, number];
  /**
   * Probability in [0, 1] that a ray crossing this surface stops there (stochastic
   * transparency): the converged image alpha-composites every crossing, front to back, with
   * this opacity, and shadows through the surface are attenuated by (1 - opacity) per crossing.
   * 0 hides the surface. Default 1.
   */
  opacity?: number;
}

export type IsoOutput = 'shaded' | 'depth' | 'normal';

export interface IsoParams {
  /** 1 to 4 surfaces. Default: one white surface at 0.5. */
  surfaces?: IsoSurface[];
  /** Ray-march step in world units (box longest side = 1). Default: half a voxel. Crossings closer than a step can be missed. */
  stepSize?: number;
  /** Weight of the normalized Blinn-Phong lobe in [0, 1] (the Lambert part gets 1 - specular). Default 0.1. */
  specular?: number;
  /** Blinn-Phong exponent (> 0). Default 40. */
  shininess?: number;
  /** Trace a shadow ray toward each directional light. Default true. */
  shadows?: boolean;
  /** Occlude environment light by the surfaces (ambient occlusion). Default true. */
  ambientOcclusion?: boolean;
  /** Occluders farther than this (world units) do not block environment light. Default: unlimited. */
  aoRadius?: number;
  /**
   * Angular radius (radians, < π/2) of every directional light, sampled uniformly over its cone
   * with the same irradiance: > 0 gives penumbrae. Default 0 (an ideal directional light).
   */
  lightAngularRadius?: number;
  /** Jitter rays inside each pixel (antialiasing). false: pixel-centre rays, for exact depth read-outs. Default true. */
  jitter?: boolean;
  /**
   * What the HDR output holds: 'shaded' (default) the converged image (rgb, a = coverage);
   * 'depth' (t, t, t, 1) with t the distance along the unit camera ray to the nearest surface
   * hit so far; 'normal' (n, 1) its viewer-facing unit normal; (0, 0, 0, 0) where nothing was hit.
   */
  output?: IsoOutput;
  /**
   * Skip the majorant-grid cells whose value range holds none of the visible iso values (default
   * true). No crossing is lost, so the image is the same bits either way; false is the plain march.
   */
  emptySpaceSkipping?: boolean;
}

export const MAX_ISO_SURFACES = 4;
export const MAX_ISO_LIGHTS = 4;

export interface ResolvedIsoParams {
  surfaces: Required<IsoSurface>[];
  stepSize: number | null;
  specular: number;
  shininess: number;
  shadows: boolean;
  ambientOcclusion: boolean;
  aoRadius: number;
  lightAngularRadius: number;
  jitter: boolean;
  output: IsoOutput;
  emptySpaceSkipping: boolean;
}

const OUTPUTS: readonly IsoOutput[] = ['shaded', 'depth', 'normal'];
/** The keys of an IsoSurface (an unknown one, such as "colour", is a typo to report, as elsewhere). */
const SURFACE_KEYS: readonly string[] = ['value', 'color', 'opacity'];

/** ISO's parameters and their ranges (core's validateParams; resolveIsoParams adds the surface rules). */
export const ISO_PARAM_SPECS: ParamSpecs = {
  surfaces: { kind: 'custom' },
  stepSize: { kind: 'step' },
  specular: { kind: 'number', min: 0, max: 1 },
  shininess: { kind: 'number', min: 0, exclusiveMin: true, max: 1e4 },
  shadows: { kind: 'boolean' },
  ambientOcclusion: { kind: 'boolean' },
  aoRadius: { kind: 'number', min: 0, exclusiveMin: true, allowInfinity: true, unit: 'world units' },
  lightAngularRadius: { kind: 'number', min: 0, max: Math.PI / 2, exclusiveMax: true, unit: 'radians' },
  jitter: { kind: 'boolean' },
  output: { kind: 'enum', values: OUTPUTS },
  emptySpaceSkipping: { kind: 'boolean' },
};

/** Defaults filled in and every value checked; throws VptError('invalid-scene') naming the parameter. */
export function resolveIsoParams(p: IsoParams): ResolvedIsoParams {
  const bad = (m: string): never => {
    throw new VptError('invalid-scene', `IsoRenderer: ${m}`);
  };
  const finite = (x: unknown): x is number => typeof x === 'number' && Number.isFinite(x);
  const surfaces = p.surfaces ?? [{ value: 0.5, color: [1, 1, 1], opacity: 1 }];
  if (!Array.isArray(surfaces) || surfaces.length < 1 || surfaces.length > MAX_ISO_SURFACES) {
    bad(
      `surfaces must be an array of 1 to ${MAX_ISO_SURFACES} isosurfaces, got ${Array.isArray(surfaces) ? surfaces.length : JSON.stringify(surfaces)}`,
    );
  }
  const resolved = surfaces.map((s, i): Required<IsoSurface> => {
    if (!s || typeof s !== 'object') bad(`surface ${i} must be an object`);
    const unknown = Object.keys(s).filter((k) => !SURFACE_KEYS.includes(k));
    if (unknown.length) bad(`surface ${i}: unknown key "${unknown[0]}" (known: ${SURFACE_KEYS.join(', ')})`);
    if (!finite(s.value) || s.value < 0 || s.value > 1)
      bad(`surface ${i}: value must be in [0, 1] (normalized), got ${s.value}`);
    if (!Array.isArray(s.color) || s.color.length !== 3 || !s.color.every((c) => finite(c) && c >= 0 && c <= 1))
      bad(`surface ${i}: color must be three numbers in [0, 1], got ${JSON.stringify(s.color)}`);
    const opacity = s.opacity ?? 1;
    if (!finite(opacity) || opacity < 0 || opacity > 1)
      bad(`surface ${i}: opacity must be in [0, 1], got ${s.opacity}`);
    return { value: s.value, color: [s.color[0], s.color[1], s.color[2]], opacity };
  });
  if (p.stepSize !== undefined && !(finite(p.stepSize) && p.stepSize >= 1e-4 && p.stepSize <= 1))
    bad(`stepSize must be in [1e-4, 1] world units, got ${p.stepSize}`);
  const specular = p.specular ?? 0.1;
  if (!(finite(specular) && specular >= 0 && specular <= 1)) bad(`specular must be in [0, 1], got ${p.specular}`);
  const shininess = p.shininess ?? 40;
  if (!(finite(shininess) && shininess > 0 && shininess <= 1e4))
    bad(`shininess must be in (0, 10000], got ${p.shininess}`);
  const aoRadius = p.aoRadius ?? Infinity;
  if (!(aoRadius > 0) || Number.isNaN(aoRadius))
    bad(`aoRadius must be positive (Infinity for unlimited), got ${p.aoRadius}`);
  const lightAngularRadius = p.lightAngularRadius ?? 0;
  if (!(finite(lightAngularRadius) && lightAngularRadius >= 0 && lightAngularRadius < Math.PI / 2))
    bad(`lightAngularRadius must be in [0, π/2) radians, got ${p.lightAngularRadius}`);
  const output = p.output ?? 'shaded';
  if (!OUTPUTS.includes(output)) bad(`output must be one of ${OUTPUTS.join(', ')}, got ${JSON.stringify(p.output)}`);
  for (const k of ['shadows', 'ambientOcclusion', 'jitter', 'emptySpaceSkipping'] as const) {
    if (p[k] !== undefined && typeof p[k] !== 'boolean') bad(`${k} must be true or false, got ${JSON.stringify(p[k])}`);
  }
  return {
    surfaces: resolved,
    stepSize: p.stepSize ?? null,
    specular,
    shininess,
    shadows: p.shadows ?? true,
    ambientOcclusion: p.ambientOcclusion ?? true,
    aoRadius,
    lightAngularRadius,
    jitter: p.jitter ?? true,
    output,
    emptySpaceSkipping: p.emptySpaceSkipping ?? true,
  };
}
