/**
 * `@vpt/viewer/tf-editor`: the viewer's 1D transfer-function editor on its own, for pages
 * that draw the volume some other way (a three.js scene with @vpt/three): defines
 * <vpt-tf-editor> (this module's only side effect) without the viewer element and its
 * loaders, and exports the value histogram it draws over.
 */
import { VptTfEditor } from './tf-editor-1d.js';

export { VptTfEditor };
export { valueHistogram, type Histogram1D } from './histogram.js';

if (typeof customElements !== 'undefined' && !customElements.get('vpt-tf-editor'))
  customElements.define('vpt-tf-editor', VptTfEditor);
