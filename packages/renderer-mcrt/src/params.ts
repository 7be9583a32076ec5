import { paramSpecsOf, type ParamSpecs } from '@vpt/core';
import { MCRT_DESCRIPTOR } from './descriptor.js';

export {
  MCRT_DEFAULTS,
  MAX_ANISOTROPY,
  MAX_LIGHT_SAMPLES,
  FIXED_TRACKING,
  FIXED_ENVIRONMENT_SAMPLING,
  resolveMcrtParams as resolveParams,
  type McrtParams,
  type ResolvedMcrtParams,
  type TrackingMode,
  type EnvironmentSampling,
} from './descriptor.js';

/** MCRT's parameters and their ranges (core's validateParams; resolveParams adds the rules across them). */
export const MCRT_PARAM_SPECS: ParamSpecs = paramSpecsOf(MCRT_DESCRIPTOR);
