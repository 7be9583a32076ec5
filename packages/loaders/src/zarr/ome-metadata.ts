/**
 * OME-NGFF "multiscales" metadata → what vpt needs to read a volume: which array axes are
 * x, y, z, channel and time, and each level's path, voxel spacing and origin in one unit.
 * Pure functions over the parsed JSON attributes, for v0.4 (Zarr v2: `.zattrs` holds
 * `multiscales`) and v0.5 (Zarr v3: `zarr.json` holds `attributes.ome.multiscales`);
 * v0.3's axes given as bare names are read too.
 * Spec: https://ngff.openmicroscopy.org/0.4/ and /0.5/ ("multiscales", "axes",
 * "coordinateTransformations").
 */
import { LoaderError } from '../errors.js';

export type Vec3 = [number, number, number];

export interface OmeAxis {
  name: string;
  type?: string;
  unit?: string;
}

export interface OmeDataset {
  /** Array path inside the group. */
  path: string;
  /** Voxel size along x, y, z (the dataset's scale composed with the multiscale's). */
  spacing: Vec3;
  /** Position of voxel (0, 0, 0)'s centre along x, y, z. */
  origin: Vec3;
}

export interface OmeMultiscale {
  /** "0.4", "0.5", … as the metadata says (absent in some v0.4 writers: "0.4" assumed). */
  version: string;
  name?: string;
  axes: OmeAxis[];
  /** Array dimension of each role; c and t only when the image has them. Other axes are read at index 0. */
  axisIndex: { x: number; y: number; z: number; c?: number; t?: number };
  /** Finest first, as NGFF requires. */
  datasets: OmeDataset[];
  /** The unit spacing and origin are in (the x axis's unit; the others converted to it), if any. */
  unit?: string;
  /** omero channel display windows, by channel index, when present: [start, end]. */
  windows: ([number, number] | undefined)[];
  /** omero channel labels and display colours (`RRGGBB` hex, sRGB), by channel index, where given. */
  channelInfo: { label?: string; color?: string }[];
  /**
   * A label image's `image-label` metadata (NGFF "labels"), when the group has it: per label
   * value its display colour (RGBA bytes) and name (from `properties`). Entries that are not an
   * integer value in [0, 65535] with four bytes are skipped with a warning.
   */
  imageLabel?: ImageLabelEntry[];
  warnings: string[];
}

export interface ImageLabelEntry {
  id: number;
  rgba?: [number, number, number, number];
  name?: string;
}

/** Metres per unit for the NGFF spatial units vpt converts between (UDUNITS-2 names). */
const METRES: Record<string, number> = {
  angstrom: 1e-10,
  picometer: 1e-12,
  nanometer: 1e-9,
  micrometer: 1e-6,
  millimeter: 1e-3,
  centimeter: 1e-2,
  decimeter: 1e-1,
  meter: 1,
  kilometer: 1e3,
  inch: 0.0254,
  foot: 0.3048,
};

type Json = Record<string, unknown>;

function isObject(v: unknown): v is Json {
  return typeof v === 'object' && v !== null && !Array.isArray(v);
}

/**
 * Find the multiscales entry in a group's attributes (v0.5's `ome` wrapper or v0.4's top
 * level) and parse it. Errors are LoaderError 'bad-header' naming the field.
 */
export function parseOmeMultiscales(attributes: unknown, name: string): OmeMultiscale {
  const bad = (m: string): never => {
    throw new LoaderError('bad-header', `${name}: OME-Zarr metadata: ${m}`);
  };
  if (!isObject(attributes)) bad('the group has no attributes');
  const attrs = attributes as Json;
  const ome = isObject(attrs.ome) ? attrs.ome : attrs;
  const list = ome.multiscales;
  if (list === undefined)
    bad('no "multiscales" in the group attributes (is this an OME-Zarr image? a plate or label group is not)');
  if (!Array.isArray(list) || list.length === 0 || !isObject(list[0]))
    bad('"multiscales" must be a non-empty array of objects');
  const ms = (list as Json[])[0];
  const version = String(ms.version ?? (isObject(attrs.ome) ? attrs.ome.version : undefined) ?? '0.4');
  const warnings: string[] = [];
  if ((list as unknown[]).length > 1) warnings.push('the group holds several multiscale images; the first is loaded');

  const datasetsJson = ms.datasets;
  if (!Array.isArray(datasetsJson) || datasetsJson.length === 0)
    bad('"multiscales[0].datasets" must be a non-empty array');
  const axes = parseAxes(ms.axes, (datasetsJson as unknown[]).length, bad);
  const ndim = axes.length;
  const space = axes
    .map((a, i) => (a.type === 'space' || (!a.type && /^[xyz]$/.test(a.name)) ? i : -1))
    .filter((i) => i >= 0);
  if (space.length !== 3)
    throw new LoaderError(
      'unsupported',
      `${name}: the image has ${space.length} space axes (${axes.map((a) => a.name).join(', ')}); vpt renders 3D volumes`,
    );
  // Space axes by name when they are x/y/z, else in order (NGFF orders them z, y, x).
  const byName = (n: string) => space.find((i) => axes[i].name.toLowerCase() === n);
  const x = byName('x') ?? space[2],
    y = byName('y') ?? space[1],
    z = byName('z') ?? space[0];
  if (new Set([x, y, z]).size !== 3) bad(`the space axes ${space.map((i) => axes[i].name).join(', ')} are ambiguous`);
  const axisIndex: OmeMultiscale['axisIndex'] = { x, y, z };
  axes.forEach((a, i) => {
    if (space.includes(i)) return;
    if (a.type === 'time' || (!a.type && a.name === 't')) {
      if (axisIndex.t === undefined) axisIndex.t = i;
    } else if (a.type === 'channel' || (!a.type && a.name === 'c')) {
      if (axisIndex.c === undefined) axisIndex.c = i;
    } else {
      warnings.push(`axis "${a.name}" (${a.type ?? 'no type'}) is read at index 0`);
    }
  });

  // Spatial units: the x axis's unit, the others converted to it.
  const units = [x, y, z].map((i) => axes[i].unit);
  const unit = units[0] ?? units.find((u) => u !== undefined);
  const toUnit = [x, y, z].map((i) => {
    const u = axes[i].unit;
    if (!unit || !u || u === unit) return 1;
    if (METRES[u] === undefined || METRES[unit] === undefined) {
      warnings.push(`axis ${axes[i].name} is in ${u}, axis x in ${unit}; not converted (unknown unit)`);
      return 1;
    }
    return METRES[u] / METRES[unit];
  });

  const outer = readTransforms(ms.coordinateTransformations, ndim, 'multiscales[0].coordinateTransformations', bad);
  const datasets = (datasetsJson as unknown[]).map((d, k): OmeDataset => {
    const where = `multiscales[0].datasets[${k}]`;
    if (!isObject(d) || typeof d.path !== 'string' || d.path === '') bad(`${where}.path must be a non-empty string`);
    const ds = d as Json;
    const own = readTransforms(ds.coordinateTransformations, ndim, `${where}.coordinateTransformations`, bad);
    // Dataset transforms first, then the multiscale's: x' = (i·s_d + t_d)·s_m + t_m.
    const scale = own.scale.map((s, i) => s * outer.scale[i]);
    const translation = own.translation.map((t, i) => t * outer.scale[i] + outer.translation[i]);
    const pick = (v: number[]) => [x, y, z].map((i, k3) => v[i] * toUnit[k3]) as Vec3;
    const spacing = pick(scale);
    if (!spacing.every((s) => Number.isFinite(s) && s > 0))
      bad(`${where}: the scale along x, y, z must be positive, got ${spacing.join(', ')}`);
    const origin = pick(translation);
    if (!origin.every(Number.isFinite)) bad(`${where}: the translation must be finite numbers`);
    return { path: (ds.path as string).replace(/^\/+|\/+$/g, ''), spacing, origin };
  });
  return {
    version,
    name: typeof ms.name === 'string' ? ms.name : undefined,
    axes,
    axisIndex,
    datasets,
    unit,
    windows: omeroWindows(ome.omero ?? attrs.omero),
    channelInfo: omeroChannelInfo(ome.omero ?? attrs.omero),
    ...(ome['image-label'] !== undefined ? { imageLabel: imageLabelOf(ome['image-label'], warnings) } : {}),
    warnings,
  };
}

/** NGFF `image-label`: `colors` [{ "label-value", "rgba" }] and `properties` [{ "label-value", "name"? }]. */
function imageLabelOf(json: unknown, warnings: string[]): ImageLabelEntry[] {
  if (!isObject(json)) {
    warnings.push('"image-label" is not an object; its colours are ignored');
    return [];
  }
  const byId = new Map<number, ImageLabelEntry>();
  const id = (e: unknown): number | null => {
    const v = isObject(e) ? e['label-value'] : undefined;
    return typeof v === 'number' && Number.isInteger(v) && v >= 0 && v <= 65535 ? v : null;
  };
  const entry = (k: number) => byId.get(k) ?? byId.set(k, { id: k }).get(k)!;
  let skipped = 0;
  for (const c of Array.isArray(json.colors) ? json.colors : []) {
    const k = id(c);
    const rgba = isObject(c) ? c.rgba : undefined;
    if (
      k === null ||
      !Array.isArray(rgba) ||
      rgba.length !== 4 ||
      !rgba.every((x) => typeof x === 'number' && Number.isInteger(x) && x >= 0 && x <= 255)
    ) {
      skipped++;
      continue;
    }
    entry(k).rgba = rgba as [number, number, number, number];
  }
  for (const p of Array.isArray(json.properties) ? json.properties : []) {
    const k = id(p);
    const name = isObject(p) ? p.name : undefined;
    if (k === null) {
      skipped++;
      continue;
    }
    if (typeof name === 'string' && name) entry(k).name = name;
  }
  if (skipped) warnings.push(`${skipped} "image-label" entries are not a label value with four RGBA bytes; skipped`);
  return [...byId.values()].sort((a, b) => a.id - b.id);
}

function parseAxes(json: unknown, _levels: number, bad: (m: string) => never): OmeAxis[] {
  if (json === undefined) bad('"multiscales[0].axes" is missing (OME-NGFF before v0.3 is not read)');
  if (!Array.isArray(json) || json.length < 2 || json.length > 5) bad('"multiscales[0].axes" must list 2 to 5 axes');
  const axes = (json as unknown[]).map((a, i): OmeAxis => {
    if (typeof a === 'string')
      return { name: a, type: /^[xyz]$/.test(a) ? 'space' : a === 't' ? 'time' : a === 'c' ? 'channel' : undefined };
    if (!isObject(a) || typeof a.name !== 'string') bad(`axes[${i}] must have a "name"`);
    const ax = a as Json;
    return {
      name: ax.name as string,
      ...(typeof ax.type === 'string' ? { type: ax.type } : {}),
      ...(typeof ax.unit === 'string' ? { unit: ax.unit } : {}),
    };
  });
  if (new Set(axes.map((a) => a.name)).size !== axes.length) bad('axis names must be unique');
  return axes;
}

/** One list of coordinateTransformations → its scale and translation (identity where absent). */
function readTransforms(
  json: unknown,
  ndim: number,
  where: string,
  bad: (m: string) => never,
): { scale: number[]; translation: number[] } {
  const scale = new Array<number>(ndim).fill(1);
  const translation = new Array<number>(ndim).fill(0);
  if (json === undefined) return { scale, translation };
  if (!Array.isArray(json)) bad(`${where} must be an array`);
  for (const [k, t] of (json as unknown[]).entries()) {
    if (!isObject(t)) bad(`${where}[${k}] must be an object`);
    const tr = t as Json;
    if (tr.type === 'identity') continue;
    if (tr.type !== 'scale' && tr.type !== 'translation')
      throw new LoaderError(
        'unsupported',
        `${where}[${k}]: transformation type ${JSON.stringify(tr.type)} is not read (scale, translation)`,
      );
    if (tr.path !== undefined)
      throw new LoaderError('unsupported', `${where}[${k}]: a ${tr.type} stored in a file ("path") is not read`);
    const v = tr[tr.type as string];
    if (!Array.isArray(v) || v.length !== ndim || !v.every((n) => typeof n === 'number' && Number.isFinite(n)))
      bad(`${where}[${k}].${tr.type} must be ${ndim} finite numbers (one per axis)`);
    const target = tr.type === 'scale' ? scale : translation;
    (v as number[]).forEach((n, i) => {
      if (tr.type === 'scale') target[i] *= n;
      else target[i] += n;
    });
  }
  return { scale, translation };
}

function omeroChannelInfo(omero: unknown): { label?: string; color?: string }[] {
  if (!isObject(omero) || !Array.isArray(omero.channels)) return [];
  return (omero.channels as unknown[]).map((ch) => {
    const c = isObject(ch) ? ch : {};
    return {
      ...(typeof c.label === 'string' && c.label ? { label: c.label.slice(0, 200) } : {}),
      ...(typeof c.color === 'string' && /^[0-9a-f]{6}$/i.test(c.color) ? { color: c.color } : {}),
    };
  });
}

function omeroWindows(omero: unknown): ([number, number] | undefined)[] {
  if (!isObject(omero) || !Array.isArray(omero.channels)) return [];
  return (omero.channels as unknown[]).map((ch) => {
    const w = isObject(ch) && isObject(ch.window) ? ch.window : undefined;
    const start = w?.start,
      end = w?.end;
    return typeof start === 'number' &&
      typeof end === 'number' &&
      Number.isFinite(start) &&
      Number.isFinite(end) &&
      start !== end
      ? [start, end]
      : undefined;
  });
}
