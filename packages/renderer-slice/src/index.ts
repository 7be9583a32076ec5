export { SliceRenderer, SLICE_PARAM_SPECS, SLICE_UNIFORM_FIELDS } from './slice-renderer.js';
export {
  SLICE_DESCRIPTOR,
  descriptor,
  SLICE_COLORMAPS,
  SLICE_OWNER,
  resolveSliceParams,
  type SliceParams,
  type ResolvedSliceParams,
  type SliceAxis,
  type SliceSampling,
  type SliceColormap,
} from './descriptor.js';
// The plane, the window and the colour maps are core's (shared with a scene's slicePlane).
export {
  slicePlane,
  type SlicePlane,
  windowMapping,
  windowCoefficients,
  checkedWindowCoefficients,
  volumeRange,
  type WindowCoefficients,
  COLORMAP_NAMES,
  colormapTable,
  type ColormapName,
} from '@vpt/core';
