/** The tone-mapping operators, and the integer each one has in the TONEMAP_OPERATOR define. */
export const TONE_MAP_OPERATORS = ['clamp', 'reinhard', 'aces', 'pbr-neutral'] as const;

export type ToneMapOperator = (typeof TONE_MAP_OPERATORS)[number];

export const TONE_MAP_OPERATOR_ID: Readonly<Record<ToneMapOperator, number>> = {
  clamp: 0,
  reinhard: 1,
  aces: 2,
  'pbr-neutral': 3,
};

/** Name of the compile-time define that selects the operator. */
export const TONE_MAP_DEFINE = 'TONEMAP_OPERATOR';

export function isToneMapOperator(value: unknown): value is ToneMapOperator {
  return typeof value === 'string' && (TONE_MAP_OPERATORS as readonly string[]).includes(value);
}

/**
 * ACES input ceiling. The fitted curve reaches 1 at x ≈ 7.25 and is clamped there, so
 * any ceiling above that leaves the output unchanged; it keeps x*x finite in f32 for
 * huge HDR values (x > 1.8e19 would give inf/inf = NaN).
 */
export const ACES_INPUT_MAX = 64;
