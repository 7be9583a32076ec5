export { SliceRenderer, SLICE_UNIFORM_FIELDS } from './slice-renderer.js';
export {
  SLICE_PARAM_TABLE,
  SLICE_PARAM_SPECS,
  SLICE_COLORMAPS,
  resolveSliceParams,
  type SliceParams,
  type SliceParamRow,
  type ResolvedSliceParams,
  type SliceAxis,
  type SliceSampling,
  type SliceColormap,
} from './params.js';
export { slicePlane, type SlicePlane } from './plane.js';
export {
  windowMapping,
  windowCoefficients,
  checkedWindowCoefficients,
  volumeRange,
  type WindowCoefficients,
} from './window-mapping.js';
export { COLORMAP_NAMES, colormapTable, type ColormapName } from './colormaps.js';
