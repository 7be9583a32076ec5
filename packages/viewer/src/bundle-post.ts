/**
 * @vpt/post as the one-file bundle exposes it (its `post`): all of it but the CPU twins of the
 * post steps (`*Ref`, `denoiseRef`), which verify the GPU steps in tests and cost ~2.5 kB gzip
 * up front. A module's own export shadows a star re-export of the same name (ES module
 * semantics), so Rollup drops them; pages that need them import @vpt/post itself.
 */
export * from '@vpt/post';
// Not in the one-file bundle: import these from @vpt/post.
export const exposureRef = undefined;
export const toneMapRef = undefined;
export const srgbEncodeRef = undefined;
export const srgbOetfRef = undefined;
export const reinhardRef = undefined;
export const acesRef = undefined;
export const pbrNeutralRef = undefined;
export const postStepRef = undefined;
export const postChainRef = undefined;
export const denoiseRef = undefined;
