/**
 * @vpt/core as the one-file bundle exposes it (its `core`): all of it but `reference`, the CPU
 * reference renderers, which verify the GPU renderers in tests and cost ~1.6 kB gzip up front.
 * A module's own export shadows a star re-export of the same name (ES module semantics), so
 * Rollup drops the CPU twins; pages that need them import @vpt/core itself.
 */
export * from '@vpt/core';
/** Not in the one-file bundle: import `reference` from @vpt/core. */
export const reference = undefined;
