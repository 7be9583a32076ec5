export { ExposureStep, MAX_EXPOSURE_STOPS, EXPOSURE_OUTPUT_MAX } from './exposure.js';
export { ToneMapStep, TONE_MAP_OPERATORS, isToneMapOperator, type ToneMapOperator } from './tone-mapping.js';
export { SrgbEncodeStep } from './srgb.js';
export {
  DenoiseStep,
  DENOISE_DEFAULTS,
  DENOISE_PARAM_NAMES,
  checkDenoiseParams,
  type DenoiseParams,
} from './denoise.js';
export {
  defaultPostChain,
  postStepFromJSON,
  postChainFromJSON,
  postStepToJSON,
  postChainToJSON,
  type PostStepJSON,
  type DefaultPostChainOptions,
} from './chain.js';
export {
  exposureRef,
  toneMapRef,
  srgbEncodeRef,
  srgbOetfRef,
  reinhardRef,
  acesRef,
  pbrNeutralRef,
  postStepRef,
  postChainRef,
  type Rgb,
} from './reference.js';
export { denoiseRef, type DenoiseInputs } from './denoise-reference.js';
