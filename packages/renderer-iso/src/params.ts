import { paramSpecsOf, type ParamSpecs } from '@vpt/core';
import { ISO_DESCRIPTOR } from './descriptor.js';

export {
  MAX_ISO_LIGHTS,
  MAX_ISO_SURFACES,
  resolveIsoParams,
  type IsoOutput,
  type IsoParams,
  type IsoSurface,
  type ResolvedIsoParams,
} from './descriptor.js';

/** ISO's parameters and their ranges (core's validateParams; resolveIsoParams adds the surface rules). */
export const ISO_PARAM_SPECS: ParamSpecs = paramSpecsOf(ISO_DESCRIPTOR);
