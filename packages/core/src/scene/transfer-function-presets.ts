import { VptError } from '../errors.js';
import type { TransferFunction2D, TransferWidget } from './transfer-function.js';
import { normalizationRange, type Volume } from './volume.js';

/**
 * 2D transfer-function presets (value × gradient magnitude) for common kinds of data, tuned
 * for densityScale 1 (opacities are extinctions per world unit). Both axes are fitted to the
 * volume, so one preset serves many datasets:
 *  - CT presets are written in Hounsfield units and HU/mm, mapped through the volume's
 *    normalization range (any CT volume stored in HU, whatever its range) and fixed with
 *    `gradientMax`, so an extreme edge (metal, the table) does not rescale the gradient axis.
 *  - MRI and microscopy intensities have no absolute scale: values sit at quantiles of the
 *    volume's foreground (voxels above 5 % of the range, sampled at most ~2^20), and the
 *    gradient axis spans a fixed fraction of the value range per voxel.
 * Boundaries between materials trace arches in value × gradient space (Kindlmann & Durkin
 * 1998); the widgets pick the arches' high-gradient parts for surfaces, or low-gradient
 * interiors for tissue.
 */
export type TransferFunctionPresetName = 'ct-bone' | 'ct-soft-tissue' | 'mri-brain' | 'microscopy';

export const TRANSFER_FUNCTION_PRESETS: readonly TransferFunctionPresetName[] = [
  'ct-bone',
  'ct-soft-tissue',
  'mri-brain',
  'microscopy',
];

/** HU range assumed by the CT presets when no volume is given (12-bit CT). */
const DEFAULT_HU_RANGE: [number, number] = [-1024, 3071];

/**
 * The preset `name` fitted to `volume` (see above). Without a volume, CT presets assume
 * values normalized from [-1024, 3071] HU and 1 mm voxels, the others a foreground spread over [0, 1].
 */
export function transferFunctionPreset(name: TransferFunctionPresetName, volume?: Volume): TransferFunction2D {
  switch (name) {
    case 'ct-bone':
      return mirrorIfInverted(ctBone(huScale(volume)), volume);
    case 'ct-soft-tissue':
      return mirrorIfInverted(ctSoftTissue(huScale(volume)), volume);
    case 'mri-brain':
      return mriBrain(relativeScale(volume));
    case 'microscopy':
      return microscopy(relativeScale(volume));
    default:
      throw new VptError(
        'invalid-scene',
        `Unknown transfer-function preset "${name as string}" (${TRANSFER_FUNCTION_PRESETS.join(', ')})`,
      );
  }
}

interface Scale {
  /** Data value (HU for CT, a foreground quantile in [0, 1] otherwise) → normalized value. */
  v(x: number): number;
  /** The gradientMax of the preset, in the volume's data units per spacing unit. */
  gradientMax: number;
}

const clamp01 = (x: number) => Math.min(1, Math.max(0, x));

/**
 * CT: HU → normalized value of the range taken ascending; the gradient axis spans 0..1000
 * HU/mm. With an inverted range (LO > HI) the widgets are then mirrored (mirrorIfInverted),
 * since the normalized value is 1 − that: bone stays bone.
 */
function huScale(volume?: Volume): Scale {
  const [a, b] = volume ? normalizationRange(volume) : DEFAULT_HU_RANGE;
  const lo = Math.min(a, b),
    hi = Math.max(a, b);
  return { v: (hu) => clamp01((hu - lo) / (hi - lo)), gradientMax: 1000 };
}

/** Mirror the widgets along the value axis (v → 1 − v) when the volume's range is inverted. */
function mirrorIfInverted(tf: TransferFunction2D, volume?: Volume): TransferFunction2D {
  if (!volume) return tf;
  const [lo, hi] = normalizationRange(volume);
  if (lo < hi) return tf;
  const widgets = tf.widgets.map((w): TransferWidget =>
    w.type === 'box'
      ? { ...w, min: [1 - w.max[0], w.min[1]], max: [1 - w.min[0], w.max[1]] }
      : { ...w, center: [1 - w.center[0], w.center[1]] },
  );
  return { ...tf, widgets };
}

/**
 * Intensity data: q → the q-quantile of the foreground's normalized values; the gradient axis
 * spans a quarter of the value range per (smallest) voxel.
 */
function relativeScale(volume?: Volume): Scale {
  if (!volume) return { v: (q) => q, gradientMax: 0.25 };
  // Normalized values already carry an inverted range's flip: the foreground is what maps high.
  const [lo, hi] = normalizationRange(volume);
  const n = volume.data.length;
  const stride = Math.max(1, Math.floor(n / (1 << 20)));
  const sample = new Float32Array(Math.ceil(n / stride));
  let k = 0;
  for (let i = 0; i < n; i += stride) {
    const x = (volume.data[i] - lo) / (hi - lo);
    if (Number.isFinite(x) && x > 0.05) sample[k++] = Math.min(1, x);
  }
  const sorted = k > 0 ? sample.subarray(0, k).sort() : Float32Array.of(0.05, 1);
  const m = sorted.length;
  return {
    v: (q) => sorted[Math.min(m - 1, Math.max(0, Math.round(q * (m - 1))))],
    gradientMax: (0.25 * Math.abs(hi - lo)) / Math.min(...volume.spacing),
  };
}

/** Bone (> ~250 HU) opaque and bone-white at any gradient; the skin surface (the air–skin arch's top) faint. */
function ctBone(s: Scale): TransferFunction2D {
  const widgets: TransferWidget[] = [
    {
      type: 'box',
      min: [s.v(300), 0],
      max: [1, 1],
      ramp: [s.v(300) - s.v(150), 0],
      color: [0.95, 0.9, 0.8],
      opacity: 150,
    },
    {
      type: 'box',
      min: [s.v(-550), 0.25],
      max: [s.v(-250), 1],
      ramp: [s.v(-250) - s.v(-400), 0.1],
      color: [0.8, 0.55, 0.45],
      opacity: 6,
    },
  ];
  return { dimensions: '2d', gradientMax: s.gradientMax, widgets };
}

/**
 * Soft tissue: the skin and lung surfaces as translucent shells (high-gradient arches from
 * air), muscle and organs (about -100..100 HU, low gradient) as a reddish fog, bone faint.
 */
function ctSoftTissue(s: Scale): TransferFunction2D {
  const widgets: TransferWidget[] = [
    {
      type: 'box',
      min: [s.v(-600), 0.2],
      max: [s.v(-300), 1],
      ramp: [s.v(-300) - s.v(-450), 0.1],
      color: [0.85, 0.6, 0.5],
      opacity: 12,
    },
    {
      type: 'box',
      min: [s.v(0), 0],
      max: [s.v(100), 0.08],
      ramp: [s.v(100) - s.v(0), 0.04],
      color: [0.8, 0.25, 0.2],
      opacity: 6,
    },
    { type: 'box', min: [s.v(300), 0], max: [1, 1], ramp: [s.v(300) - s.v(150), 0], color: [1, 1, 0.95], opacity: 20 },
  ];
  return { dimensions: '2d', gradientMax: s.gradientMax, widgets };
}

/** MRI head/brain: the bright tissue's surfaces at mid-high gradient, the brightest tissue faint inside. */
function mriBrain(s: Scale): TransferFunction2D {
  const mid = s.v(0.5),
    high = s.v(0.9);
  const widgets: TransferWidget[] = [
    {
      type: 'box',
      min: [s.v(0.2), 0.25],
      max: [1, 1],
      ramp: [Math.max(0.01, s.v(0.2) - s.v(0.05)), 0.15],
      color: [0.9, 0.75, 0.65],
      opacity: 3,
    },
    {
      type: 'gaussian',
      center: [high, 0],
      width: [Math.max(0.02, (high - mid) / 2), 0.2],
      color: [0.7, 0.5, 0.35],
      opacity: 1.5,
    },
  ];
  return { dimensions: '2d', gradientMax: s.gradientMax, widgets };
}

/** Fluorescence microscopy: bright structures (the top fifth of the foreground) with their boundaries emphasised; background clear. */
function microscopy(s: Scale): TransferFunction2D {
  const fg = s.v(0.8),
    top = s.v(0.98);
  const widgets: TransferWidget[] = [
    {
      type: 'box',
      min: [fg, 0.15],
      max: [1, 1],
      ramp: [Math.max(0.01, fg - s.v(0.6)), 0.1],
      color: [0.3, 1, 0.5],
      opacity: 150,
    },
    {
      type: 'box',
      min: [top, 0],
      max: [1, 1],
      ramp: [Math.max(0.01, top - fg), 0],
      color: [0.7, 1, 0.75],
      opacity: 60,
    },
  ];
  return { dimensions: '2d', gradientMax: s.gradientMax, widgets };
}
