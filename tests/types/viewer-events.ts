// Compile test, checked by `pnpm run typecheck` (strict): <vpt-viewer>'s events are typed
// through HTMLElementEventMap, so listeners get their `detail` without casts; the lines
// marked as expected errors fail the typecheck if the typing ever loosens.
import type { VptViewer } from '../../packages/viewer/src/index.js';
import '../../packages/viewer/src/index.js';

const el = document.createElement('vpt-viewer');
el.addEventListener('vpt-progress', (e) => {
  if (e.detail.phase === 'loading') console.log(e.detail.loaded, e.detail.total);
  else console.log(e.detail.samples, e.detail.error);
  // @ts-expect-error samples exists only in the refining phase
  console.log(e.detail.samples);
});
el.addEventListener('vpt-error', (e) => console.log(e.detail.code, e.detail.error.message, e.detail.source));
el.addEventListener('vpt-load', (e) => console.log(e.detail.dims[0], e.detail.format));
el.addEventListener('vpt-converged', (e) => console.log(e.detail.reason === 'target-error'));
el.addEventListener('vpt-change', (e) => console.log(e.detail.property));
// A clip change carries the Clip (or null); the other properties an unknown value.
el.addEventListener('vpt-change', (e) => {
  if (e.detail.property === 'clip') console.log(e.detail.value?.planes?.length, e.detail.value?.box?.min[0]);
  // @ts-expect-error a clip change's value is a Clip or null, not a number
  if (e.detail.property === 'clip') console.log(e.detail.value.toFixed(2));
});
// The slice panes' crosshair is a voxel index, their window [center, width] in data units.
el.addEventListener('vpt-change', (e) => {
  if (e.detail.property === 'crosshair') console.log(e.detail.value[0] + e.detail.value[2]);
  if (e.detail.property === 'window') console.log(e.detail.value[1].toFixed(1));
  // @ts-expect-error the crosshair is a voxel index, not a string
  if (e.detail.property === 'crosshair') console.log(e.detail.value.toUpperCase());
});
// The hovered label (labels-layer.ts): an id and an optional name, or null.
el.addEventListener('vpt-hover', (e) => console.log(e.detail.label?.id.toFixed(0), e.detail.label?.name?.length));
el.addEventListener('vpt-change', (e) => {
  if (e.detail.property === 'labelTable') console.log(e.detail.value[0].id);
});
// @ts-expect-error a label id is a number
el.addEventListener('vpt-hover', (e) => console.log(e.detail.label?.id.toUpperCase()));
const layout: VptViewer['layout'] = 'quad';
// @ts-expect-error not a layout
const badLayout: VptViewer['layout'] = 'triple';
console.log(layout, badLayout);
// @ts-expect-error no such field on the load event
el.addEventListener('vpt-load', (e) => console.log(e.detail.nope));
// The native events keep their own types.
el.addEventListener('error', (e) => console.log(e.type));
export {};
