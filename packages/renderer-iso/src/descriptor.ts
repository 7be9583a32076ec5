/**
 * ISO described as data (core's RendererDescriptor): its parameters, defaults, uniforms and
 * viewer look. Side-effect free and kernel free, so user interfaces import it alone
 * (`@vpt/renderer-iso/descriptor`).
 */
import {
  constantDefault,
  defineRenderer,
  samplerParam,
  stepInVoxels,
  VptError,
  type ParamsOf,
  type Sampler,
  type RendererParamSpec,
  type TransferFunction,
} from '@vpt/core';

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

export const MAX_ISO_SURFACES = 4;
export const MAX_ISO_LIGHTS = 4;

const DEFAULT_SURFACE: Required<IsoSurface> = { value: 0.5, color: [1, 1, 1], opacity: 1 };

/** The first isosurface's fields, edited in place by the quality panel (the renderer takes a list). */
const firstSurface = (p: Record<string, unknown>): IsoSurface =>
  (p.surfaces as IsoSurface[] | undefined)?.[0] ?? DEFAULT_SURFACE;
const withFirstSurface = (p: Record<string, unknown>, patch: Partial<IsoSurface>) => {
  const surfaces = [...((p.surfaces as IsoSurface[] | undefined) ?? [DEFAULT_SURFACE])];
  surfaces[0] = { ...surfaces[0], ...patch };
  return { ...p, surfaces };
};
const SURFACE_CONTROLS: readonly RendererParamSpec[] = [
  {
    name: 'isoValue',
    label: 'Iso value',
    min: 0,
    max: 1,
    step: 0.01,
    placeholder: String(DEFAULT_SURFACE.value),
    read: (p) => firstSurface(p).value,
    write: (p, v) => withFirstSurface(p, { value: v as number }),
  },
  {
    name: 'isoColor',
    label: 'Surface colour',
    kind: 'color',
    read: (p) => firstSurface(p).color,
    write: (p, v) => withFirstSurface(p, { color: v as IsoSurface['color'] }),
  },
];

const bad = (m: string): never => {
  throw new VptError('invalid-scene', `IsoRenderer: ${m}`);
};
const finite = (x: unknown): x is number => typeof x === 'number' && Number.isFinite(x);
/** The keys of an IsoSurface (an unknown one, such as "colour", is a typo to report, as elsewhere). */
const SURFACE_KEYS: readonly string[] = ['value', 'color', 'opacity'];

/** The surfaces with defaults filled in, each checked; throws VptError('invalid-scene') naming the surface. */
export function resolveIsoSurfaces(given: unknown): Required<IsoSurface>[] {
  const surfaces = (given ?? [DEFAULT_SURFACE]) as IsoSurface[];
  if (!Array.isArray(surfaces) || surfaces.length < 1 || surfaces.length > MAX_ISO_SURFACES) {
    bad(
      `surfaces must be an array of 1 to ${MAX_ISO_SURFACES} isosurfaces, got ${Array.isArray(surfaces) ? surfaces.length : JSON.stringify(surfaces)}`,
    );
  }
  return surfaces.map((s, i): Required<IsoSurface> => {
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
}

/** The default surface's albedo: a warm bone white. */
const DEFAULT_SURFACE_COLOR: [number, number, number] = [0.92, 0.88, 0.8];

/**
 * The isovalue the viewer's automatic function suggests: halfway between where it starts (the
 * median of the foreground) and its 90th percentile, the outer surface of the object rather
 * than its densest core; null for a function that is not 1D with two points.
 */
function isoValueOf(tf: TransferFunction): number | null {
  if (tf.dimensions !== '1d' || tf.points.length < 2) return null;
  return Math.round(((tf.points[0].value + tf.points[1].value) / 2) * 1000) / 1000;
}

export const ISO_DESCRIPTOR = defineRenderer({
  name: 'iso',
  label: 'Isosurface',
  owner: 'ISO',
  params: {
    /** 1 to 4 surfaces. Default: one white surface at 0.5. */
    surfaces: {
      kind: 'custom',
      default: [DEFAULT_SURFACE] as IsoSurface[],
      defaultText: 'one white surface at 0.5',
      controls: SURFACE_CONTROLS,
    },
    /** Ray-march step in world units (box longest side = 1). Default: half a voxel. Crossings closer than a step can be missed. */
    stepSize: {
      kind: 'step',
      ...stepInVoxels(0.5),
      ui: { label: 'Step size', min: 0.0005, max: 0.05, step: 0.0005 },
      uniform: { type: 'f32' },
    },
    /** Weight of the normalized Blinn-Phong lobe in [0, 1] (the Lambert part gets 1 - specular). Default 0.1. */
    specular: {
      kind: 'number',
      min: 0,
      max: 1,
      default: 0.1,
      ui: { label: 'Specular', step: 0.05 },
      uniform: { type: 'f32' },
    },
    /** Blinn-Phong exponent (> 0). Default 40. */
    shininess: {
      kind: 'number',
      min: 0,
      exclusiveMin: true,
      max: 1e4,
      default: 40,
      ui: { label: 'Shininess', min: 1, max: 1000, step: 1 },
      uniform: { type: 'f32' },
    },
    /** Trace a shadow ray toward each directional light. Default true. */
    shadows: { kind: 'boolean', default: true, ui: { label: 'Shadows' } },
    /** Occlude environment light by the surfaces (ambient occlusion). Default true. */
    ambientOcclusion: { kind: 'boolean', default: true, ui: { label: 'Ambient occlusion' } },
    /** Occluders farther than this (world units) do not block environment light. Default: unlimited. */
    aoRadius: {
      kind: 'number',
      min: 0,
      exclusiveMin: true,
      allowInfinity: true,
      unit: 'world units',
      default: Infinity,
      defaultText: 'unlimited',
      // The kernels compare distances against it: "unlimited" is a radius beyond any box.
      uniform: { type: 'f32', pack: (r) => (Number.isFinite(r) ? r : 1e30) },
    },
    /**
     * Angular radius (radians, < π/2) of every directional light, sampled uniformly over its cone
     * with the same irradiance: > 0 gives penumbrae. Default 0 (an ideal directional light).
     */
    lightAngularRadius: {
      kind: 'number',
      min: 0,
      max: Math.PI / 2,
      exclusiveMax: true,
      unit: 'radians',
      default: 0,
    },
    /** Jitter rays inside each pixel (antialiasing). false: pixel-centre rays, for exact depth read-outs. Default true. */
    jitter: { kind: 'boolean', default: true },
    /**
     * What the HDR output holds: 'shaded' (default) the converged image (rgb, a = coverage);
     * 'depth' (t, t, t, 1) with t the distance along the unit camera ray to the nearest surface
     * hit so far; 'normal' (n, 1) its viewer-facing unit normal; (0, 0, 0, 0) where nothing was hit.
     */
    output: { kind: 'enum', values: ['shaded', 'depth', 'normal'], default: 'shaded' },
    /**
     * Skip the majorant-grid cells whose value range holds none of the visible iso values (default
     * true). No crossing is lost, so the image is the same bits either way; false is the plain march.
     */
    emptySpaceSkipping: { kind: 'boolean', default: true },
    /**
     * 'blue-noise': the pixel jitter, the camera march's offset and the environment (AO) sample are
     * a rank-1 sequence rotated per pixel by a blue-noise mask (core's shaders/blue-noise.ts);
     * 'pcg': the PCG stream. Default blue noise: 1.3–1.9× fewer iterations to 35 dB
     * (docs/benchmarks.md, "Blue-noise sampling").
     */
    sampler: samplerParam('blue-noise'),
  },
  check: (p) => void resolveIsoParams(p),
  writesGuides: true,
  needs: { transferFunction: false, lights: true, environment: true },
  look: {
    densityScale: 20,
    environment: [0.1, 0.11, 0.14],
    keyLight: [2.6, 2.5, 2.3],
    params: (tf, channels) => {
      // A multichannel volume: one surface per drawn channel (surface k lies on drawn channel
      // k), at that channel's own isovalue, in its colour, as a microscopist reads them apart.
      if (channels?.length) {
        const surfaces = channels.map((c) => ({
          value: isoValueOf(c.transferFunction) ?? 0.5,
          color: c.color ? ([...c.color] as [number, number, number]) : DEFAULT_SURFACE_COLOR,
          opacity: 1,
        }));
        return { surfaces, specular: 0.15, shininess: 30 };
      }
      const value = tf ? isoValueOf(tf) : null;
      if (value === null) return {};
      return { surfaces: [{ value, color: DEFAULT_SURFACE_COLOR, opacity: 1 }], specular: 0.15, shininess: 30 };
    },
  },
});

export type IsoParams = ParamsOf<typeof ISO_DESCRIPTOR>;

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
  sampler: Sampler;
}

const DEFAULT = <K extends keyof IsoParams>(key: K) => constantDefault(ISO_DESCRIPTOR, key) as Required<IsoParams>[K];

/** Defaults filled in and every value checked; throws VptError('invalid-scene') naming the parameter. */
export function resolveIsoParams(p: IsoParams): ResolvedIsoParams {
  const resolved = resolveIsoSurfaces(p.surfaces);
  if (p.stepSize !== undefined && !(finite(p.stepSize) && p.stepSize >= 1e-4 && p.stepSize <= 1))
    bad(`stepSize must be in [1e-4, 1] world units, got ${p.stepSize}`);
  const specular = p.specular ?? DEFAULT('specular');
  if (!(finite(specular) && specular >= 0 && specular <= 1)) bad(`specular must be in [0, 1], got ${p.specular}`);
  const shininess = p.shininess ?? DEFAULT('shininess');
  if (!(finite(shininess) && shininess > 0 && shininess <= 1e4))
    bad(`shininess must be in (0, 10000], got ${p.shininess}`);
  const aoRadius = p.aoRadius ?? DEFAULT('aoRadius');
  if (!(aoRadius > 0) || Number.isNaN(aoRadius))
    bad(`aoRadius must be positive (Infinity for unlimited), got ${p.aoRadius}`);
  const lightAngularRadius = p.lightAngularRadius ?? DEFAULT('lightAngularRadius');
  if (!(finite(lightAngularRadius) && lightAngularRadius >= 0 && lightAngularRadius < Math.PI / 2))
    bad(`lightAngularRadius must be in [0, π/2) radians, got ${p.lightAngularRadius}`);
  const output = p.output ?? DEFAULT('output');
  if (!ISO_DESCRIPTOR.params.output.values.includes(output))
    bad(`output must be one of ${ISO_DESCRIPTOR.params.output.values.join(', ')}, got ${JSON.stringify(p.output)}`);
  // The enum's values are checked by validateParams (the descriptor's spec).
  const sampler = p.sampler ?? DEFAULT('sampler');
  for (const k of ['shadows', 'ambientOcclusion', 'jitter', 'emptySpaceSkipping'] as const) {
    if (p[k] !== undefined && typeof p[k] !== 'boolean') bad(`${k} must be true or false, got ${JSON.stringify(p[k])}`);
  }
  return {
    surfaces: resolved,
    stepSize: p.stepSize ?? null,
    specular,
    shininess,
    shadows: p.shadows ?? DEFAULT('shadows'),
    ambientOcclusion: p.ambientOcclusion ?? DEFAULT('ambientOcclusion'),
    aoRadius,
    lightAngularRadius,
    jitter: p.jitter ?? DEFAULT('jitter'),
    output,
    emptySpaceSkipping: p.emptySpaceSkipping ?? DEFAULT('emptySpaceSkipping'),
    sampler,
  };
}

/** The package's descriptor under the name every renderer package uses (the generated loaders read it). */
export { ISO_DESCRIPTOR as descriptor };
