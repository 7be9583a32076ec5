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
export { slicePlane, type SlicePlane } from './plane.js';
export {
  windowMapping,
  windowCoefficients,
  checkedWindowCoefficients,
  volumeRange,
  type WindowCoefficients,
} from './window-mapping.js';
export { COLORMAP_NAMES, colormapTable, type ColormapName } from './colormaps.js';
