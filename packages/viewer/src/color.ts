/**
 * Colour conversions for the editors: transfer-function colours are linear RGB and may
 * exceed 1 (emission brighter than white); a colour picker shows sRGB in [0, 1]. A colour
 * is shown as its hue (divided by `intensity` = max(1, largest component)) and that
 * intensity as a separate number.
 */
export type Rgb = [number, number, number];

/** sRGB transfer function (IEC 61966-2-1). */
export function linearToSrgb(c: number): number {
  const x = Math.min(1, Math.max(0, c));
  return x <= 0.0031308 ? 12.92 * x : 1.055 * Math.pow(x, 1 / 2.4) - 0.055;
}

export function srgbToLinear(c: number): number {
  return c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4);
}

export function intensityOf(c: readonly number[]): number {
  return Math.max(1, c[0], c[1], c[2]);
}

/** `#rrggbb` of a linear colour, divided by its intensity. */
export function linearToHex(c: readonly number[]): string {
  const k = intensityOf(c);
  return (
    '#' +
    c
      .slice(0, 3)
      .map((v) =>
        Math.round(linearToSrgb(v / k) * 255)
          .toString(16)
          .padStart(2, '0'),
      )
      .join('')
  );
}

/** A linear colour from `#rrggbb` and an intensity multiplier. */
export function hexToLinear(hex: string, intensity = 1): Rgb {
  const m = /^#?([0-9a-f]{2})([0-9a-f]{2})([0-9a-f]{2})$/i.exec(hex.trim());
  if (!m) return [intensity, intensity, intensity];
  return [1, 2, 3].map((i) => round4(srgbToLinear(parseInt(m[i], 16) / 255) * intensity)) as Rgb;
}

/** CSS colour for a linear colour (display only: clipped at its intensity). */
export function cssColor(c: readonly number[], alpha = 1): string {
  const k = intensityOf(c);
  const [r, g, b] = c.slice(0, 3).map((v) => Math.round(linearToSrgb(v / k) * 255));
  return `rgba(${r}, ${g}, ${b}, ${alpha})`;
}

export function round4(x: number): number {
  return Math.round(x * 1e4) / 1e4;
}
