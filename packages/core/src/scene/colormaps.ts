/**
 * Colour maps of a slice (the slice renderer and a scene's slicePlane): tables of sRGB-encoded RGB at N equally spaced points (entry i
 * at i / (N − 1)), read with linear interpolation between entries like the 1D transfer function.
 * Values copied from matplotlib (matplotlib.org, _cm_listed.py and _cm.py): 'viridis' (van der Walt
 * & Smith 2015, CC0, its 256-entry table), 'hot' (matplotlib's piecewise-linear segments, sampled
 * at 256 points), 'coolwarm' (Moreland 2009, "Diverging Color Maps for Scientific Visualization",
 * ISVC, its 33-point table CoolWarmFloat33). 'grey' is the windowed value itself (no table).
 */
/** The named colour maps; 'grey' is the windowed value itself (no table). */
export const COLORMAP_NAMES = ['grey', 'viridis', 'hot', 'coolwarm'] as const;
export type ColormapName = (typeof COLORMAP_NAMES)[number];

// matplotlib's 256-entry viridis table (_cm_listed.py) as RGB uint16 little-endian, value × 65535
// (within 8e-6 of its 6-digit numbers), base64: 1.2 kB gzip less in the viewer bundle than the
// decimal list. Decoded on first use.
const VIRIDIS_U16_BASE64 =
  'WkQ/AVRUvUR1At5VG0W+A2RXdEUbBeZYyEWLBmRaGEYQCN1bY0aqCVJdqUZOC8Ne6kbjDC5gJ0drDpVhX0fpD/dikUdeEVRk' +
  'v0fLEqxl6EczFP9mDUiWFUxoLEj0FpRpRkhPGNZqXEimGRJsbUj7GklteEhNHHpuf0idHaVvgUjrHspwf0g3IOhxd0iCIQFz' +
  'a0jMIhN0WkgUJB91REhaJSV2KUigJiR3CkjlJx1450coKQ95v0drKvt5kkesK+F6YUftLL97LEcsLph88kZrL2l9tEaoMDV+' +
  'c0blMfp+LUYhM7h/40VbNHCAlkWVNSKBRUXNNs6B8UQEOHOCmUQ6ORKDPkRvOqyD4EOjOz+Ef0PVPM2EG0MGPlWFtUI2P9iF' +
  'S0JkQFWG4EGRQcyGckG9Qj+HAkHnQ6yHkEAQRRWIHEA4RnmIpj9eR9iILz+CSDOJtj6lSYmJPD7GStyJwT3mSyqKRj0FTXSK' +
  'yTwhTruKSzw9T/6KzTtXUD2LTztvUXqL0DqGUrOLUTqbU+mL0jmvVByMUznCVU2M1DjTVnqMVTjjV6aM1zfxWM+MWTf+WfWM' +
  '3DYJWxqNXzYUXDyN4zUdXV2NaDUlXnyN7jQrX5mNdDQxYLSN/DM1Yc2NhDM4YuaNDjM6Y/yNmDI7ZBKOJDI7ZSaOsDE6ZjmO' +
  'PjE4Z0uOzTA1aFuOXTAxaWuO7i8sanmOgC8na4eOFC8hbJOOqC4abZ+OPi4SbqmO1C0Kb7OOay0BcLyOBC34cMSOnSzuccuO' +
  'NyzkctGO0ivZc9aObivNdNqOCivBdd6Opyq1duCORSqpd+KO4ymceOKOgimPeeKOISmBeuCOwShze92OYShmfNmOAShYfdSO' +
  'oidJfs6OQyc7f8aO5CYsgL2OhSYegbOOJyYPgqeOySUAg5qObCXyg4uODyXjhHuOsiTUhWmOViTFhlWO+iO2hz+OnyOniCeO' +
  'RSOZiQ6O6yKKivKNlCJ7i9SNPSJsjLSN6CFdjZKNlCFPjm2NQyFAj0aN9CAykB2NqCAjkfGMXyAUksKMGiAGk5CM2B/3k1yM' +
  'mx/plCWMYx/aleuLMB/Mlq2LAx+9l22L3R6vmCqLvh6gmeOKpx6RmpmKmB6Cm0uKkh5znPqJlh5knaaJpB5Vnk6Jvh5Fn/KI' +
  '4h42oJKIEx8moS+IUB8WosiHmh8Fo1yH8R/1o+2GVyDkpHqGyiDSpQOGTCHApoiF3CGupwiFeyKcqISEKSOJqfyD5SN1qm+D' +
  'ryRhq96CiCVMrEmCcCY3ra+BZSchrhGBaSgLr26Aeinzr8Z/mCrbsBp/wyvCsWl++yypsrR9Py6Os/l8jy9ztDp86zBXtXZ7' +
  'UjI6tq56xDMbt+B5QTX8tw55yDbcuDZ4Wji6uVp39TmYunl2mjt0u5N1Rz1PvKh0/j4ovbdzvkABvsJyhkLYvshxVkStv8lw' +
  'LkaCwMVvD0hUwbtu9kklwq1t5kv1wpls3E3Dw4Fr2k+PxGNq31FaxUFp6lMjxhlo/FXqxuxmFVivx7plNFpzyINkWVw0yUdj' +
  'hF70yQZitmCxysBg7WJty3VfKmUnzCVebGfezNBctGmTzXZbAmxGzhZaVG73zrJYrHCmz0lXCXNS0NtVa3X80GlU0nek0fFS' +
  'PXpJ0nVRrXzs0vRPIn+N025OmoEq1ORMGITG1FZLmYZf1cJJHon11StIp4uJ1o9GNI4a1+9ExJCp10xDWJM12KRB7pW+2Pk/' +
  'iJhF2Us+JZvJ2Zk8xZ1K2uQ6Z6DJ2i05C6NF23Q3sqW/27k1W6g23P0zBaur3EAysa0d3YMwXrCN3ccuDLP73Qwtu7Vm3lQr' +
  'a7jO3qApG7s13/Eny72Z30kme8D836okKsNc4BYj2cW74JAhh8gY4RogM8tz4bke3s3N4W4dh9Al4kAcLtN84jEb09XS4kca' +
  'dtgn44YZFtt64/MYst3N45AYTOAg5GIY4uJy5GoYdOXD5KkYA+gU5R8Zjupl5cgZFO235aQalu8I5q4bFPJZ5uMcjvSr5j4e' +
  'Avf+5rofcvlR51Yh3vuk5wwjRf7559kk';

function decodeUnorm16(base64: string): number[] {
  const bytes = atob(base64);
  const out: number[] = [];
  for (let i = 0; i + 1 < bytes.length; i += 2)
    out.push((bytes.charCodeAt(i) | (bytes.charCodeAt(i + 1) << 8)) / 65535);
  return out;
}

// matplotlib's 'hot' segments (_cm.py: x, value), sampled at 256 points below: the same numbers as
// its listed table to 5e-9, without shipping 768 of them.
const HOT_SEGMENTS: readonly (readonly [number, number])[][] = [
  [
    [0, 0.0416],
    [0.365079, 1],
    [1, 1],
  ],
  [
    [0, 0],
    [0.365079, 0],
    [0.746032, 1],
    [1, 1],
  ],
  [
    [0, 0],
    [0.746032, 0],
    [1, 1],
  ],
];

function piecewiseLinear(segments: readonly (readonly [number, number])[], x: number): number {
  for (let k = 1; k < segments.length; k++) {
    const [x0, y0] = segments[k - 1];
    const [x1, y1] = segments[k];
    if (x <= x1) return y0 + ((y1 - y0) * (x - x0)) / (x1 - x0);
  }
  return segments[segments.length - 1][1];
}

const HOT: number[] = [];
for (let i = 0; i < 256; i++) for (const channel of HOT_SEGMENTS) HOT.push(piecewiseLinear(channel, i / 255));

// prettier-ignore
const COOLWARM = [
  0.2298057, 0.29871797, 0.75368315,
  0.26623388, 0.35309484, 0.80146676,
  0.30386891, 0.4065353, 0.84495867,
  0.34280448, 0.45875762, 0.8837259,
  0.38301334, 0.50941904, 0.91738782,
  0.42436961, 0.55814809, 0.94561959,
  0.46666708, 0.60456257, 0.96815491,
  0.5096352, 0.64828077, 0.98478814,
  0.55295316, 0.68892933, 0.99537561,
  0.59626216, 0.72614911, 0.9998362,
  0.63917621, 0.75959995, 0.99815118,
  0.68129128, 0.78896471, 0.99036323,
  0.72219329, 0.81395274, 0.97657471,
  0.76146495, 0.83430288, 0.95694527,
  0.79869164, 0.84978614, 0.93168865,
  0.83346656, 0.86020798, 0.90106884,
  0.8653952, 0.86541021, 0.86539556,
  0.89778718, 0.84893705, 0.82088055,
  0.92412759, 0.82738488, 0.77450847,
  0.94446852, 0.80092744, 0.72673615,
  0.95885295, 0.76976775, 0.67800794,
  0.96732803, 0.73413281, 0.62875176,
  0.96995414, 0.69426668, 0.57937545,
  0.96681118, 0.65042116, 0.53026376,
  0.95800306, 0.60284243, 0.48177591,
  0.94366087, 0.55175097, 0.43424368,
  0.92394492, 0.49730856, 0.38797023,
  0.89904617, 0.43955947, 0.3432296,
  0.86918685, 0.37831309, 0.30026718,
  0.83462054, 0.31287445, 0.2593012,
  0.79563175, 0.24128379, 0.22052563,
  0.75253493, 0.15724607, 0.18411512,
  0.70567316, 0.01555616, 0.15023281,
];

let viridis: readonly number[] | undefined;
const TABLES: Readonly<Record<Exclude<ColormapName, 'grey'>, () => readonly number[]>> = {
  viridis: () => (viridis ??= decodeUnorm16(VIRIDIS_U16_BASE64)),
  hot: () => HOT,
  coolwarm: () => COOLWARM,
};

/**
 * A colour map's table as RGBA float32 texels (a = 1), one row of N texels: the `colormap`
 * auxiliary texture and the CPU expectation of tests. 'grey' has none (the kernel writes the value).
 */
export function colormapTable(name: Exclude<ColormapName, 'grey'>): Float32Array {
  const rgb = TABLES[name]();
  const n = rgb.length / 3;
  const out = new Float32Array(n * 4);
  for (let i = 0; i < n; i++) {
    out.set([rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 1], 4 * i);
  }
  return out;
}
