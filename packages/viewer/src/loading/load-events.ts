/**
 * The details of the events loading fires (`vpt-load`, and `vpt-progress` while loading or
 * refining), declared for the element in HTMLElementEventMap (index.ts).
 */
import type { Volume } from '@vpt/core';
import type { RefinementStats } from '../session.js';

export type ViewerProgressDetail =
  { phase: 'loading'; stage: string; loaded: number; total?: number } | ({ phase: 'refining' } & RefinementStats);
export interface ViewerLoadDetail {
  volume: Volume;
  format: string;
  dims: [number, number, number];
  type: string;
  /**
   * For a multiscale store (OME-Zarr) loaded level by level: the level now shown (0 =
   * finest), how many the store has, its dims, and whether it is the last one coming.
   */
  level?: {
    index: number;
    count: number;
    dims: [number, number, number];
    final: boolean;
    /** Level 0 streamed as bricks (it does not fit the budget): `volume` is the stand-in level the cache starts from. */
    bricked?: boolean;
  };
}
