/**
 * @vpt/viewer: `import '@vpt/viewer'` defines <vpt-viewer>, <vpt-tf-editor> and <vpt-tf2d-editor> (this
 * module's only side effect) and exports their classes and the pieces an application
 * may want on its own (renderer registry, presets, histogram, exporters).
 */
import { VptTfEditor } from './tf-editor-1d.js';
import { VptTf2dEditor } from './tf-editor-2d.js';
import {
  VptViewer,
  type ViewerChangeDetail,
  type ViewerConvergedDetail,
  type ViewerErrorDetail,
  type ViewerHoverDetail,
  type ViewerLoadDetail,
  type ViewerProgressDetail,
} from './viewer-element.js';

export { VptViewer, VptTfEditor, VptTf2dEditor };
export type {
  ViewerErrorDetail,
  ViewerProgressDetail,
  ViewerConvergedDetail,
  ViewerLoadDetail,
  ViewerChangeDetail,
  ViewerHoverDetail,
  HoveredLabel,
  ProbeReading,
  PanelName,
} from './viewer-element.js';
export {
  paneGeometries,
  voxelAt,
  screenPoint,
  probeValue,
  VIEWER_LAYOUTS,
  type PaneGeometry,
  type PaneName,
  type ViewerLayout,
  type Voxel,
} from './slice-panes.js';
export type { RefinementStats } from './session.js';
export {
  registerRenderer,
  rendererEntries,
  rendererEntry,
  createRenderer,
  type RendererEntry,
  type RendererConstructor,
  type RendererParamSpec,
} from './renderer-registry.js';
export { TRANSFER_FUNCTION_PRESETS, transferFunctionPreset } from './presets.js';
export { parseTransferFunction, parseCamera, parseLights, parseEnvironment } from './attributes.js';
export {
  valueHistogram,
  gradientSamples,
  valueGradientHistogram,
  type Histogram1D,
  type Histogram2D,
  type GradientSamples,
} from './histogram.js';
export { encodePfm, encodeExr, encodePngBlob } from './export.js';
export { fitCamera, anatomicalFrame, type AnatomicalFrame, type OrientedVolume } from './camera-fit.js';
export {
  autoTransferFunction,
  asAlbedo,
  isoValueOf,
  keyLight,
  rendererLook,
  defaultRendererParams,
  type RendererLook,
  type Palette,
} from './defaults.js';
export { volumeLoader } from './loading/volume-source.js';
export type { VolumeSource, LoadOptions, LoadedVolumeLike, ViewerChannel } from './loading/types.js';

/** Define the custom elements once (a second copy of the package on the page is ignored, not an error). */
function define(name: string, ctor: CustomElementConstructor): void {
  if (typeof customElements !== 'undefined' && !customElements.get(name)) customElements.define(name, ctor);
}
define('vpt-viewer', VptViewer);
define('vpt-tf-editor', VptTfEditor);
define('vpt-tf2d-editor', VptTf2dEditor);

declare global {
  /**
   * The element's events, typed: `el.addEventListener('vpt-progress', (e) => e.detail.phase)`
   * compiles in strict mode. The `vpt-` prefix keeps them apart from native events
   * (`progress`, `error`, `load` and `change` exist on HTMLElement with other types).
   */
  interface HTMLElementEventMap {
    'vpt-load': CustomEvent<ViewerLoadDetail>;
    'vpt-progress': CustomEvent<ViewerProgressDetail>;
    'vpt-converged': CustomEvent<ViewerConvergedDetail>;
    'vpt-error': CustomEvent<ViewerErrorDetail>;
    'vpt-change': CustomEvent<ViewerChangeDetail>;
    'vpt-hover': CustomEvent<ViewerHoverDetail>;
  }
  interface HTMLElementTagNameMap {
    'vpt-viewer': VptViewer;
    'vpt-tf-editor': VptTfEditor;
    'vpt-tf2d-editor': VptTf2dEditor;
  }
}
