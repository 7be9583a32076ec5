export { IsoRenderer, ISO_PARAM_FIELDS } from './iso-renderer.js';
export { ISO_DESCRIPTOR, descriptor, resolveIsoSurfaces } from './descriptor.js';
export {
  ISO_PARAM_SPECS,
  MAX_ISO_LIGHTS,
  MAX_ISO_SURFACES,
  resolveIsoParams,
  type IsoOutput,
  type IsoParams,
  type IsoSurface,
  type ResolvedIsoParams,
} from './params.js';
