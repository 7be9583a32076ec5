/** Readouts the panels and the stats line share. */

/**
 * The panel's error readout: the same estimate the stats line shows; "estimating…" while a
 * renderer that keeps half accumulations (MCRT) has none yet, "n/a" only for one that keeps none.
 */
export function errorReadout(
  s: { error: number | null; samples: number } | null,
  renderer: { halfAccumulations?: readonly [number, number] } | null,
): string {
  if (s?.error != null) return `${(s.error * 100).toFixed(2)} %`;
  if (renderer?.halfAccumulations) return s && s.samples >= 2 ? 'estimating…' : '— (needs 2 samples)';
  return 'n/a for this renderer';
}
