import type { TransferFunction } from '@vpt/core';

/**
 * Named transfer functions for the `transfer-function` attribute. Colours are linear
 * RGB (values above 1 emit more light than a white background returns); opacity is
 * extinction per unit density scale, so the same preset works at any `density-scale`.
 */
export const TRANSFER_FUNCTION_PRESETS: Readonly<Record<string, TransferFunction>> = {
  /** Grey, opacity and brightness growing linearly with the value. */
  ramp: {
    dimensions: '1d',
    points: [
      { value: 0, color: [1, 1, 1], opacity: 0 },
      { value: 1, color: [1, 1, 1], opacity: 1 },
    ],
  },
  /** Low values transparent, a soft warm shell around the middle, dense white highs (soft tissue → bone); colours stay ≤ 1 so EAM does not blow out to white. */
  tissue: {
    dimensions: '1d',
    points: [
      { value: 0.0, color: [0, 0, 0], opacity: 0 },
      { value: 0.15, color: [0.5, 0.2, 0.1], opacity: 0 },
      { value: 0.3, color: [0.85, 0.45, 0.3], opacity: 0.02 },
      { value: 0.5, color: [0.95, 0.7, 0.55], opacity: 0.1 },
      { value: 0.7, color: [1.0, 0.9, 0.8], opacity: 0.4 },
      { value: 1.0, color: [1, 1, 1], opacity: 1 },
    ],
  },
  /** Only the top of the range: dense white structures (bone in CT). */
  bone: {
    dimensions: '1d',
    points: [
      { value: 0, color: [0, 0, 0], opacity: 0 },
      { value: 0.55, color: [0.9, 0.85, 0.75], opacity: 0 },
      { value: 0.7, color: [1.6, 1.5, 1.3], opacity: 0.6 },
      { value: 1, color: [2.5, 2.4, 2.2], opacity: 1 },
    ],
  },
  /** Black-body-like ramp (dark red → orange → yellow-white), for emission-style data. */
  hot: {
    dimensions: '1d',
    points: [
      { value: 0.05, color: [0.2, 0, 0], opacity: 0 },
      { value: 0.35, color: [1.2, 0.15, 0], opacity: 0.15 },
      { value: 0.7, color: [2.5, 1.2, 0.1], opacity: 0.5 },
      { value: 1, color: [4, 3.5, 2.5], opacity: 1 },
    ],
  },
  /**
   * 2D: material boundaries only (high gradient magnitude), brighter for higher values;
   * homogeneous regions, whatever their value, stay clear (Kniss et al. 2002).
   */
  boundaries: {
    dimensions: '2d',
    widgets: [
      { type: 'box', min: [0.12, 0.18], max: [0.55, 1], ramp: [0.05, 0.08], color: [0.9, 0.55, 0.4], opacity: 0.15 },
      { type: 'box', min: [0.55, 0.12], max: [1, 1], ramp: [0.05, 0.08], color: [1, 0.95, 0.85], opacity: 0.8 },
    ],
  },
  /** Blue → cyan → white, moderately dense: microscopy and simulation fields. */
  cool: {
    dimensions: '1d',
    points: [
      { value: 0.05, color: [0.05, 0.1, 0.6], opacity: 0 },
      { value: 0.4, color: [0.1, 0.6, 1.2], opacity: 0.2 },
      { value: 0.8, color: [1.2, 1.8, 2.2], opacity: 0.6 },
      { value: 1, color: [3, 3, 3], opacity: 1 },
    ],
  },
};

export const DEFAULT_TRANSFER_FUNCTION = 'ramp';

export function transferFunctionPreset(name: string): TransferFunction | undefined {
  const tf = Object.hasOwn(TRANSFER_FUNCTION_PRESETS, name) ? TRANSFER_FUNCTION_PRESETS[name] : undefined;
  return tf ? structuredClone(tf) : undefined;
}
