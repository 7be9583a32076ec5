/**
 * A scene's label volume (segmentation): an integer volume of label ids (0 = background) on the
 * image's grid, drawn with a label table (per id a linear RGB colour, an opacity in the
 * transfer function's units and a visible flag). Labels are read NEAREST, never interpolated
 * between ids: the voxel holding a point gives its id, the table its colour and opacity.
 *
 * How the renderers draw them (docs/architecture.md, "Label volumes"): EAM and MCRT see the
 * image and the labels as one mixture (σ = opacity_image + opacity_label, colour / albedo the
 * σ-weighted mean: transferAt in the LABELS chunk), the majorant grid bounds the sum; MIP shows
 * the colour of the most opaque visible label on the ray over the grey maximum; the slice
 * renderer and the slice plane overlay the label colour with its opacity.
 */
import { VptError } from '../errors.js';
import type { BackendCapabilities, TextureDescriptor } from '../gpu/backend.js';
import { checkNumber } from '../validation/checks.js';
import { MAX_EXTINCTION, MAX_OPACITY } from '../validation/limits.js';
import { volumeBox, type Volume } from './volume.js';
import type { AuxiliaryTexture, VolumeBinding } from '../renderer.js';
import type { Scene } from './scene.js';
import { rasterizeTransferFunction, TF_RESOLUTION, type TransferFunction } from './transfer-function.js';
import { scalarSceneOf, type ChannelSettings } from './channels.js';
import {
  buildMajorantGrid,
  channelMajorantGrid,
  gridCells,
  volumeCellRanges,
  type MajorantGrid,
} from '../majorant/majorant-grid.js';
import { atlasTexture } from '../majorant/grid-textures.js';
import { registerLabelSupport } from './label-support.js';
import { downsampleLabels, labelBytesPerVoxel } from './label-downsample.js';
import * as glslLabels from '../shaders/labels.glsl.js';
import * as wgslLabels from '../shaders/labels.wgsl.js';

export { downsampleLabels, labelBytesPerVoxel };

/**
 * Enable label volumes (scene/label-support.ts): call once before setting a scene with `labels`
 * (the headless page does at load). Kept out of bundles that never call it.
 */
export function enableLabels(): void {
  registerLabelSupport({
    validateSceneLabels,
    labelTextures,
    labelScaleOf,
    majorantGridTexture: labelMajorantGridTexture,
    downsampleLabels,
    labelBytesPerVoxel,
    chunks: { glsl: glslLabels.LABELS, wgsl: wgslLabels.LABELS },
  });
}

export interface LabelEntry {
  /** The label id in the volume (1 … 255 for uint8, 1 … 65535 for uint16); 0 is the background. */
  id: number;
  name?: string;
  /** Linear RGB in [0, 1]; absent: the default palette's colour for the id (defaultLabelColor). */
  color?: [number, number, number];
  /** Extinction per unit densityScale, as a transfer function's opacity (default 1). */
  opacity?: number;
  /** Drawn when true (default true); a hidden label renders as if its voxels were background. */
  visible?: boolean;
}

export interface SceneLabels {
  /** uint8 or uint16 label ids, one channel, the image volume's dims. */
  volume: Volume;
  /** One entry per drawn id; ids not listed (and 0) are background. */
  table: LabelEntry[];
}

/** Label-table texture width: id → texel (id mod 256, floor(id / 256)), so 65535 ids fit in 256 × 256. */
export const LABEL_TABLE_WIDTH = 256;

/**
 * The default palette: matplotlib's tab20 (Vega category20; a qualitative palette of 20
 * distinct colours), as sRGB bytes, converted to linear RGB by defaultLabelColor. Id k takes
 * entry (k − 1) mod 20.
 */
export const LABEL_PALETTE_SRGB: readonly (readonly [number, number, number])[] = [
  [31, 119, 180],
  [255, 127, 14],
  [44, 160, 44],
  [214, 39, 40],
  [148, 103, 189],
  [140, 86, 75],
  [227, 119, 194],
  [127, 127, 127],
  [188, 189, 34],
  [23, 190, 207],
  [174, 199, 232],
  [255, 187, 120],
  [152, 223, 138],
  [255, 152, 150],
  [197, 176, 213],
  [196, 156, 148],
  [247, 182, 210],
  [199, 199, 199],
  [219, 219, 141],
  [158, 218, 229],
];

function srgbToLinear(b: number): number {
  const c = b / 255;
  return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
}

/** The default colour of a label id (linear RGB): the palette's entry (id − 1) mod 20. */
export function defaultLabelColor(id: number): [number, number, number] {
  const e = LABEL_PALETTE_SRGB[(((id - 1) % 20) + 20) % 20];
  return [srgbToLinear(e[0]), srgbToLinear(e[1]), srgbToLinear(e[2])];
}

/** The largest id a label volume's type holds. */
export function maxLabelId(type: Volume['type']): number {
  return type === 'uint8' ? 255 : 65535;
}

/** A table for every non-zero id present in a label volume: palette colours, opacity 1, visible. */
export function defaultLabelTable(volume: Volume, names: Readonly<Record<number, string>> = {}): LabelEntry[] {
  const seen = new Uint8Array(maxLabelId(volume.type) + 1);
  for (let i = 0; i < volume.data.length; i++) seen[volume.data[i]] = 1;
  const out: LabelEntry[] = [];
  for (let id = 1; id < seen.length; id++)
    if (seen[id])
      out.push({
        id,
        ...(names[id] ? { name: names[id] } : {}),
        color: defaultLabelColor(id),
        opacity: 1,
        visible: true,
      });
  return out;
}

/** The entry's drawn opacity: 0 when hidden. */
export function labelOpacity(e: LabelEntry): number {
  return e.visible === false ? 0 : (e.opacity ?? 1);
}

/** The largest opacity a visible label of the table draws (0 without one). */
export function maxLabelOpacity(table: readonly LabelEntry[]): number {
  return table.reduce((m, e) => Math.max(m, labelOpacity(e)), 0);
}

const ENTRY_FIELDS = ['id', 'name', 'color', 'opacity', 'visible'];

/**
 * Check a scene's labels against its image volume; throws VptError('invalid-scene') naming the
 * field (`Scene: labels.volume.type`, `Scene: labels.table[2].color[1]`…). `imageMaxOpacity`:
 * the image's largest drawn opacity, since the mixture's extinction is the sum.
 */
export function validateLabels(labels: unknown, image: Volume, densityScale: number, imageMaxOpacity: number): void {
  const bad = (msg: string): never => {
    throw new VptError('invalid-scene', `Scene: labels${msg}`);
  };
  if (!labels || typeof labels !== 'object' || Array.isArray(labels))
    bad(` must be { volume, table }, got ${JSON.stringify(labels)}`);
  const l = labels as SceneLabels;
  for (const k of Object.keys(l)) if (k !== 'volume' && k !== 'table') bad(`: unknown field "${k}" (volume, table)`);
  const v = l.volume;
  if (!v || typeof v !== 'object') bad('.volume is missing (a uint8 or uint16 label volume)');
  if (v.type !== 'uint8' && v.type !== 'uint16')
    bad(
      `.volume.type must be "uint8" or "uint16" (integer label ids, read nearest), got ${JSON.stringify(v.type)}: a label volume is never interpolated or normalized`,
    );
  if ((v.channels ?? 1) !== 1) bad(`.volume.channels must be 1 (one id per voxel), got ${v.channels}`);
  if (!Array.isArray(v.dims) || v.dims.length !== 3 || !v.dims.every((d) => Number.isInteger(d) && d >= 1))
    bad(`.volume.dims must be three positive integers, got ${JSON.stringify(v.dims)}`);
  if (
    !Array.isArray(v.spacing) ||
    v.spacing.length !== 3 ||
    !v.spacing.every((x) => typeof x === 'number' && Number.isFinite(x) && x > 0)
  )
    bad(`.volume.spacing must be three positive numbers, got ${JSON.stringify(v.spacing)}`);
  if (v.dims.some((d, i) => d !== image.dims[i]))
    bad(
      `.volume.dims [${v.dims.join(', ')}] differ from the image volume's dims [${image.dims.join(', ')}] (a label volume lies on the image's grid)`,
    );
  const want = v.dims[0] * v.dims[1] * v.dims[2];
  const Arr = v.type === 'uint8' ? Uint8Array : Uint16Array;
  if (!(v.data instanceof Arr) || v.data.length !== want)
    bad(`.volume.data must be a ${Arr.name} of ${want} ids (NX·NY·NZ), got ${v.data?.length ?? 'none'}`);
  const lb = volumeBox(v).size,
    ib = volumeBox(image).size;
  if (lb.some((s, i) => Math.abs(s - ib[i]) > 1e-6 * Math.max(...ib)))
    bad(
      `.volume.spacing [${v.spacing.join(', ')}] gives another box than the image volume's spacing [${image.spacing.join(', ')}]`,
    );
  if (!Array.isArray(l.table)) bad(`.table must be an array of label entries, got ${JSON.stringify(l.table)}`);
  const top = maxLabelId(v.type);
  const ids = new Set<number>();
  l.table.forEach((e, i) => {
    const at = `.table[${i}]`;
    if (!e || typeof e !== 'object' || Array.isArray(e))
      bad(`${at} must be an object { id, name?, color, opacity, visible }`);
    for (const k of Object.keys(e))
      if (!ENTRY_FIELDS.includes(k)) bad(`${at}: unknown field "${k}" (${ENTRY_FIELDS.join(', ')})`);
    if (typeof e.id !== 'number' || !Number.isInteger(e.id) || e.id < 1 || e.id > top)
      bad(
        `${at}.id must be an integer in [1, ${top}] (a ${v.type} label volume; 0 is the background), got ${JSON.stringify(e.id)}`,
      );
    if (ids.has(e.id)) bad(`${at}.id ${e.id} is listed twice`);
    ids.add(e.id);
    if (e.name !== undefined && typeof e.name !== 'string') bad(`${at}.name must be a string`);
    if (e.color !== undefined) {
      if (!Array.isArray(e.color) || e.color.length !== 3)
        bad(`${at}.color must be [r, g, b] (linear RGB in [0, 1]), got ${JSON.stringify(e.color)}`);
      e.color.forEach((x, j) => checkNumber(`Scene: labels${at}.color[${j}]`, x, { min: 0, max: 1 }));
    }
    if (e.opacity !== undefined)
      checkNumber(`Scene: labels${at}.opacity`, e.opacity, { min: 0, max: MAX_OPACITY, unit: 'MAX_OPACITY' });
    if (e.visible !== undefined && typeof e.visible !== 'boolean')
      bad(`${at}.visible must be true or false, got ${JSON.stringify(e.visible)}`);
  });
  const sum = imageMaxOpacity + maxLabelOpacity(l.table);
  if (densityScale * sum > MAX_EXTINCTION)
    throw new VptError(
      'invalid-scene',
      `Scene: densityScale ${densityScale} × (the image's largest opacity + the labels' largest opacity) ${sum} = ${densityScale * sum} exceeds the limit ${MAX_EXTINCTION} (MAX_EXTINCTION)`,
    );
}

/** A scene's labels against its image: the mixture's extinction bound counts the image's largest drawn opacity. */
export function validateSceneLabels(s: Scene): void {
  const tf = s.transferFunction;
  const imageMax = s.channels
    ? s.channels
        .filter((c) => c.enabled !== false && c.transferFunction.dimensions !== '2d')
        .reduce(
          (m, c) =>
            m + Math.max(...(c.transferFunction as { points: { opacity: number }[] }).points.map((p) => p.opacity)),
          0,
        )
    : tf.dimensions === '2d'
      ? Math.max(...tf.widgets.map((w) => w.opacity))
      : Math.max(...tf.points.map((p) => p.opacity));
  validateLabels(s.labels, s.volume, s.densityScale, imageMax);
}

/** The label-table texture's texels: RGBA float (rgb, opacity) per id at (id mod 256, id / 256); hidden ids and 0 are 0. */
export function labelTableData(labels: SceneLabels): { width: number; height: number; data: Float32Array } {
  const top = labels.table.reduce((m, e) => Math.max(m, e.id), 0);
  const width = LABEL_TABLE_WIDTH;
  const height = Math.max(1, Math.ceil((top + 1) / width));
  const data = new Float32Array(4 * width * height);
  for (const e of labels.table) {
    const a = labelOpacity(e);
    if (a <= 0) continue;
    const c = e.color ?? defaultLabelColor(e.id);
    data.set([c[0], c[1], c[2], a], 4 * e.id);
  }
  return { width, height, data };
}

/**
 * The label volume's texture: uint8 → r8unorm (the array as is), uint16 → r16unorm where the
 * device has 16-bit norm formats, else r32float holding the ids. Kernels read it with
 * texelFetch only and recover the id as round(texel · labelScale): exact for every id.
 */
export function labelVolumeTexture(
  volume: Volume,
  caps: BackendCapabilities,
): { desc: TextureDescriptor; labelScale: number } {
  const base = { dimension: '3d' as const, width: volume.dims[0], height: volume.dims[1], depth: volume.dims[2] };
  if (volume.type === 'uint8')
    return { desc: { ...base, format: 'r8unorm', data: volume.data, label: 'label volume' }, labelScale: 255 };
  if (caps.norm16)
    return { desc: { ...base, format: 'r16unorm', data: volume.data, label: 'label volume' }, labelScale: 65535 };
  return {
    desc: { ...base, format: 'r32float', data: Float32Array.from(volume.data), label: 'label volume' },
    labelScale: 1,
  };
}

/** The label texture's texel → id factor (the `labelScale` uniform), as labelVolumeTexture plans it. */
export function labelScaleOf(volume: Pick<Volume, 'type'>, caps: BackendCapabilities): number {
  return volume.type === 'uint8' ? 255 : caps.norm16 ? 65535 : 1;
}

/** The id of the voxel holding world point p (the kernels' labelIdAt, CPU twin): floor of the box coordinate, clamped. */
export function labelIdAt(volume: Volume, p: readonly number[]): number {
  const box = volumeBox(volume);
  const i = [0, 1, 2].map((a) => {
    const tc = (p[a] - box.min[a]) / box.size[a];
    return Math.min(volume.dims[a] - 1, Math.max(0, Math.floor(tc * volume.dims[a])));
  });
  return volume.data[i[0] + volume.dims[0] * (i[1] + volume.dims[1] * i[2])];
}

/** (linear rgb, opacity) the table draws for an id: zero for 0, unlisted and hidden ids. */
export function labelEntryOf(labels: SceneLabels, id: number): [number, number, number, number] {
  const e = id > 0 ? labels.table.find((t) => t.id === id) : undefined;
  if (!e || labelOpacity(e) <= 0) return [0, 0, 0, 0];
  const c = e.color ?? defaultLabelColor(e.id);
  return [c[0], c[1], c[2], labelOpacity(e)];
}

/**
 * Per majorant-grid cell (x fastest; cells over the box in texture coordinates, as
 * majorant-grid.ts), the largest densityScale · opacity of a visible label among the voxels a
 * point of the cell can read (nearest: floor(tc · N), padded by one voxel against rounding).
 */
export function labelCellMajorants(
  labels: SceneLabels,
  cells: readonly [number, number, number],
  densityScale: number,
): Float32Array {
  const { dims, data } = labels.volume;
  const { data: table } = labelTableData(labels);
  const range = (c: number, G: number, N: number): [number, number] => [
    Math.max(0, Math.floor((c * N) / G) - 1),
    Math.min(N - 1, Math.floor(((c + 1) * N) / G) + 1),
  ];
  const out = new Float32Array(cells[0] * cells[1] * cells[2]);
  // Per voxel opacity along x, reduced per cell column first.
  const [nx, ny, nz] = dims;
  const rx = Array.from({ length: cells[0] }, (_, c) => range(c, cells[0], nx));
  const ry = Array.from({ length: cells[1] }, (_, c) => range(c, cells[1], ny));
  const rz = Array.from({ length: cells[2] }, (_, c) => range(c, cells[2], nz));
  const ax = new Float32Array(cells[0] * ny * nz);
  for (let z = 0; z < nz; z++)
    for (let y = 0; y < ny; y++) {
      const row = nx * (y + ny * z);
      for (let c = 0; c < cells[0]; c++) {
        let m = 0;
        for (let x = rx[c][0]; x <= rx[c][1]; x++) {
          const id = data[row + x];
          const a = id > 0 && 4 * id + 3 < table.length ? table[4 * id + 3] : 0;
          if (a > m) m = a;
        }
        ax[c + cells[0] * (y + ny * z)] = m;
      }
    }
  for (let cz = 0; cz < cells[2]; cz++)
    for (let cy = 0; cy < cells[1]; cy++)
      for (let cx = 0; cx < cells[0]; cx++) {
        let m = 0;
        for (let z = rz[cz][0]; z <= rz[cz][1]; z++)
          for (let y = ry[cy][0]; y <= ry[cy][1]; y++) m = Math.max(m, ax[cx + cells[0] * (y + ny * z)]);
        out[cx + cells[0] * (cy + cells[1] * cz)] = Math.fround(m * densityScale * (1 + 1e-5));
      }
  return out;
}

// Stable ids for the volume objects whose identity keys the label textures and grid.
const ids = new WeakMap<object, number>();
let nextId = 1;
function objectId(o: object): number {
  let i = ids.get(o);
  if (i === undefined) ids.set(o, (i = nextId++));
  return i;
}

/**
 * The label textures a scene binds when its renderer draws labels (RenderContext adds them as
 * auxiliary textures): `labelVolume` (3D, uploaded when the label volume object changes) and
 * `labelTable` (2D, when the table changes; a visibility toggle re-uploads 4 bytes per id, never the volume).
 */
export function labelTextures(
  labels: SceneLabels,
  caps: BackendCapabilities,
): { name: string; dimension: '2d' | '3d'; key: string; create: () => TextureDescriptor }[] {
  const id = objectId(labels.volume);
  return [
    {
      name: 'labelVolume',
      dimension: '3d',
      key: `labels ${id}|${caps.norm16 ? 'norm16' : 'float'}`,
      create: () => labelVolumeTexture(labels.volume, caps).desc,
    },
    {
      name: 'labelTable',
      dimension: '2d',
      key: `label table ${JSON.stringify(labels.table)}`,
      create: () => {
        const t = labelTableData(labels);
        return {
          dimension: '2d',
          width: t.width,
          height: t.height,
          format: 'rgba32float',
          data: t.data,
          label: 'label table',
        };
      },
    },
  ];
}

/**
 * A loaded volume as a label volume: uint8 / uint16 as they are; any other type (a NIfTI
 * segmentation stored as int16, int32 or float, a scaled one) converted to the smallest of
 * uint8 / uint16 that holds its values, which must all be integers in [0, 65535] (no
 * normalization, no rounding). Throws VptError('invalid-scene') naming `field` otherwise.
 * The value range is dropped: ids are never mapped.
 */
export function toLabelVolume(v: Volume, field = 'labels.volume'): Volume {
  const { valueRange: _drop, ...rest } = v;
  void _drop;
  if ((v.channels ?? 1) !== 1)
    throw new VptError('invalid-scene', `${field}: a label volume has one id per voxel, got ${v.channels} channels`);
  if (v.type === 'uint8' || v.type === 'uint16') return rest;
  let max = 0;
  for (let i = 0; i < v.data.length; i++) {
    const x = v.data[i];
    if (!(Number.isInteger(x) && x >= 0 && x <= 65535))
      throw new VptError(
        'invalid-scene',
        `${field}: voxel ${i} holds ${x}, not a label id (an integer in [0, 65535]); a ${v.type} volume is a label volume only when every value is one`,
      );
    if (x > max) max = x;
  }
  return max <= 255
    ? { ...rest, type: 'uint8', data: Uint8Array.from(v.data) }
    : { ...rest, type: 'uint16', data: Uint16Array.from(v.data) };
}

/**
 * A table with a file's label colours applied (OME-Zarr's `image-label`: per id RGBA bytes,
 * display sRGB, and a name): the colour converted to linear RGB, the opacity alpha / 255 (an
 * alpha of 0 hides the label), the name where given. Ids the file lists but the table lacks are
 * added; the others keep their entries.
 */
export function withLabelColors(
  table: readonly LabelEntry[],
  colors: readonly { id: number; rgba?: readonly number[]; name?: string }[],
): LabelEntry[] {
  const out = new Map(table.map((e) => [e.id, { ...e }]));
  for (const c of colors) {
    if (c.id < 1 || c.id > 65535) continue;
    const e: LabelEntry = out.get(c.id) ?? { id: c.id, color: defaultLabelColor(c.id), opacity: 1, visible: true };
    if (c.rgba) {
      e.color = [srgbToLinear(c.rgba[0]), srgbToLinear(c.rgba[1]), srgbToLinear(c.rgba[2])];
      e.opacity = c.rgba[3] / 255;
      e.visible = c.rgba[3] > 0;
    }
    if (c.name) e.name = c.name;
    out.set(c.id, e);
  }
  return [...out.values()].sort((a, b) => a.id - b.id);
}

/**
 * A grid with a scene's labels added (scene/labels.ts): the kernels' extinction is the image's
 * plus densityScale · opacity of the visible label at the point, so each cell's majorant is the
 * image's plus the largest label opacity its points can read (labelCellMajorants: nearest, padded
 * by a voxel); the minorant stays the image's (a label adds extinction, never removes it).
 */
export function withLabelMajorants(grid: MajorantGrid, labels: SceneLabels, densityScale: number): MajorantGrid {
  const add = labelCellMajorants(labels, grid.cells, densityScale);
  const data = grid.data.slice();
  let gMax = 0;
  for (let c = 0; c < add.length; c++) {
    data[4 * c] = Math.fround(data[4 * c] + add[c]);
    if (data[4 * c] > gMax) gMax = data[4 * c];
  }
  return { cells: grid.cells, data, globalMajorant: gMax, globalMinorant: grid.globalMinorant };
}

/**
 * A scene's majorant grid on the CPU, whatever it draws: a channel scene's summed grid, else the
 * scalar one (one drawn channel: the scalar scene it draws), plus its labels when it has them.
 */
export function sceneMajorantGrid(
  given: {
    volume: Volume;
    transferFunction: TransferFunction;
    densityScale: number;
    channels?: ChannelSettings[];
    labels?: SceneLabels;
  },
  cellSize: number,
): MajorantGrid {
  const scene = scalarSceneOf(given) ?? given;
  const base = scene.channels
    ? channelMajorantGrid(scene.volume, scene.channels, scene.densityScale, cellSize)
    : buildMajorantGrid(
        volumeCellRanges(scene.volume, cellSize),
        rasterizeTransferFunction(scene.transferFunction, TF_RESOLUTION),
        scene.densityScale,
      );
  return scene.labels ? withLabelMajorants(base, scene.labels, scene.densityScale) : base;
}

/**
 * A label scene's grid (scene/labels.ts): the image's (the channels' sum, the scalar grid, or a
 * bricked volume's from its cell ranges) plus each cell's largest visible label opacity
 * (majorant-grid.ts withLabelMajorants), built on the CPU and uploaded: a table change rebuilds it.
 */
export function labelMajorantGridTexture(scene: Scene, volume: VolumeBinding, cellSize: number): AuxiliaryTexture {
  const labels = scene.labels!;
  const cells = gridCells(scene.volume.dims, cellSize);
  return {
    name: 'majorantGrid',
    dimension: '2d',
    key: `labels|${objectId(scene.volume)}|${objectId(labels.volume)}|${cellSize}|${scene.densityScale}|${JSON.stringify(scene.channels ?? scene.transferFunction)}|${JSON.stringify(labels.table)}|${volume.cellRanges ? volume.key : ''}`,
    create: () => {
      const grid = volume.cellRanges
        ? withLabelMajorants(
            buildMajorantGrid(
              volume.cellRanges(cells),
              rasterizeTransferFunction(scene.transferFunction, TF_RESOLUTION),
              scene.densityScale,
            ),
            labels,
            scene.densityScale,
          )
        : sceneMajorantGrid(scene, cellSize);
      return atlasTexture(cells, grid.data, 'majorant grid (labels)');
    },
  };
}
