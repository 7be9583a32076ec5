/**
 * Progressive loading of multiscale volumes (OME-Zarr): which levels the viewer shows, in
 * which order. The coarsest level comes first (it loads in a fraction of a second), then,
 * when the level that fits the memory budget would take long, the finest level expected
 * to load within about half a second, then that target. Each step replaces the volume
 * (accumulation restarts only then). Pure functions: the element does the loading.
 */
import { fitFactors } from '@vpt/core';

export type Dims = [number, number, number];

/** A multiscale store whose level is left to the viewer: an `.zarr` URL without `level=` in its fragment. */
export function isProgressiveSource(source: unknown): source is string {
  if (typeof source !== 'string' || !/\.zarr\/?([?#].*)?$/i.test(source)) return false;
  const hash = source.indexOf('#');
  return hash < 0 || !new URLSearchParams(source.slice(hash + 1)).has('level');
}

/** The source with `level=<level>` added to its fragment (channel and time kept). */
export function sourceAtLevel(source: string, level: number | 'coarsest'): string {
  const hash = source.indexOf('#');
  const params = new URLSearchParams(hash < 0 ? '' : source.slice(hash + 1));
  params.set('level', String(level));
  return `${hash < 0 ? source : source.slice(0, hash)}#${params}`;
}

const voxels = (d: Dims) => d[0] * d[1] * d[2];

/**
 * The finest level (lowest index) whose volume fits `budgetBytes` at `bytesPerVoxel` and
 * the 3D texture limit as it is (core's fitFactors gives [1, 1, 1]); the coarsest when none does.
 */
export function finestFittingLevel(
  levels: readonly Dims[],
  bytesPerVoxel: number,
  budgetBytes: number,
  max3D: number,
): number {
  for (let k = 0; k < levels.length; k++) {
    const f = fitFactors(levels[k], bytesPerVoxel, budgetBytes, max3D);
    if (f && f.every((x) => x === 1)) return k;
  }
  return levels.length - 1;
}

/** How long the first image may take, and how long a step may take before a finer intermediate level is shown first. */
export const FIRST_IMAGE_MS = 500;
export const DIRECT_STEP_MS = 1500;

/**
 * The levels to load after the coarsest one (shown first), finest last. `rate` is what the
 * coarsest level's load measured, in voxels per ms (latency included, so estimates err
 * slow). If the target would take longer than DIRECT_STEP_MS, the finest level between
 * them expected within FIRST_IMAGE_MS goes first.
 */
export function refinementPlan(levels: readonly Dims[], target: number, voxelsPerMs: number): number[] {
  const coarsest = levels.length - 1;
  if (target >= coarsest) return [];
  const estimate = (k: number) => voxels(levels[k]) / Math.max(voxelsPerMs, 1e-9);
  const plan: number[] = [];
  if (estimate(target) > DIRECT_STEP_MS) {
    for (let k = target + 1; k < coarsest; k++) {
      if (estimate(k) <= FIRST_IMAGE_MS) {
        plan.push(k);
        break;
      }
    }
  }
  plan.push(target);
  return plan;
}
