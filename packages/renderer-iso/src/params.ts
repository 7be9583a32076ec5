import { constantDefault, paramSpecsOf, VptError, type ParamSpecs } from '@vpt/core';
import {
  ISO_DESCRIPTOR,
  MAX_ISO_LIGHTS,
  MAX_ISO_SURFACES,
  resolveIsoSurfaces,
  type IsoOutput,
  type IsoParams,
  type IsoSurface,
} from './descriptor.js';

export { MAX_ISO_LIGHTS, MAX_ISO_SURFACES, type IsoOutput, type IsoParams, type IsoSurface };

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

const OUTPUTS = ISO_DESCRIPTOR.params.output.values;
const DEFAULT = <K extends keyof IsoParams>(key: K) => constantDefault(ISO_DESCRIPTOR, key) as Required<IsoParams>[K];

/** ISO's parameters and their ranges (core's validateParams; resolveIsoParams adds the surface rules). */
export const ISO_PARAM_SPECS: ParamSpecs = paramSpecsOf(ISO_DESCRIPTOR);

/** Defaults filled in and every value checked; throws VptError('invalid-scene') naming the parameter. */
export function resolveIsoParams(p: IsoParams): ResolvedIsoParams {
  const bad = (m: string): never => {
    throw new VptError('invalid-scene', `IsoRenderer: ${m}`);
  };
  const finite = (x: unknown): x is number => typeof x === 'number' && Number.isFinite(x);
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
  if (!OUTPUTS.includes(output)) bad(`output must be one of ${OUTPUTS.join(', ')}, got ${JSON.stringify(p.output)}`);
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
  };
}
