// Compile test, checked by `pnpm run typecheck` (strict): <vpt-viewer>'s events are typed
// through HTMLElementEventMap, so listeners get their `detail` without casts; the lines
// marked as expected errors fail the typecheck if the typing ever loosens.
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
// @ts-expect-error no such field on the load event
el.addEventListener('vpt-load', (e) => console.log(e.detail.nope));
// The native events keep their own types.
el.addEventListener('error', (e) => console.log(e.type));
export {};
