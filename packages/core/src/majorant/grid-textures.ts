import type { AuxiliaryTexture, VolumeBinding } from '../renderer.js';
import type { Scene } from '../scene/scene.js';
import { TF_RESOLUTION } from '../scene/transfer-function.js';
import type { Volume } from '../scene/volume.js';
import { sliceAtlasLayout } from '../shaders/slice-atlas.js';
import * as glslAtlas from '../shaders/slice-atlas.glsl.js';
import * as wgslAtlas from '../shaders/slice-atlas.wgsl.js';
import { UniformLayout, type UniformField } from '../uniforms/layout.js';
import { buildMajorantGrid, channelMajorantGrid, gridCells, summedChannelGrid } from './majorant-grid.js';
import { scalarSceneOf } from '../scene/channels.js';
import { labelSupport } from '../scene/label-support.js';
import { rasterizeTransferFunction } from '../scene/transfer-function.js';
import { atlasTexel } from '../shaders/slice-atlas.js';
import * as glslBuild from './majorant-build.glsl.js';
import * as wgslBuild from './majorant-build.wgsl.js';

/**
 * What a kernel reads from the grid: `'ranges'` binds `majorantRanges` (per cell, the min
 * and max volume texel its points can blend; map with valueScale / valueOffset: MIP, ISO);
 * `'majorants'` binds `majorantGrid` (per cell, the max and min of densityScale·opacity:
 * MCRT's majorants, EAM's empty cells).
 */
export type MajorantGridOutput = 'ranges' | 'majorants';

/** The `gridCells` uniform every kernel that walks the grid declares (cells per axis, slice-atlas columns). */
export const GRID_CELLS_FIELD: UniformField = { name: 'gridCells', type: 'ivec4' };

/** Default cell edge in voxels for the ray marches' empty-space skipping (MCRT's own default is the same). */
export const DEFAULT_SKIP_CELL_SIZE = 8;

/** The `gridCells` uniform value for a volume and cell edge: cells per axis and the slice atlas's column count. */
export function gridGeometry(dims: readonly number[], cellSize: number): [number, number, number, number] {
  const cells = gridCells(dims, cellSize);
  return [...cells, sliceAtlasLayout(cells).columns];
}

// Stable ids for the volume objects whose identity keys the textures.
const ids = new WeakMap<object, number>();
let nextId = 1;
function objectId(o: object): number {
  let i = ids.get(o);
  if (i === undefined) {
    i = nextId++;
    ids.set(o, i);
  }
  return i;
}

/**
 * The majorant grid as GPU-made auxiliary textures, no voxel loop on the CPU: the per-cell
 * value ranges (once per volume and cell size), and for `'majorants'` each TF column's
 * opacity bounds (on a TF change) and the grid itself (on a volume, TF or density change).
 * All use the slice-atlas layout of the cell counts; only the output named by `output` is
 * bound to the kernel. The CPU twin is majorant-grid.ts.
 */
export function majorantGridTextures(
  scene: Scene,
  volume: VolumeBinding,
  cellSize: number,
  output: MajorantGridOutput,
): AuxiliaryTexture[] {
  // Labels add their extinction: the grid is built on the CPU (labels.ts labelMajorantGridTexture, registered by enableLabels).
  if (scene.labels && output === 'majorants') return [labelSupport().majorantGridTexture(scene, volume, cellSize)];
  // One drawn channel is an r-format texture and a one-row TF: the GPU build below reads it as a scalar volume.
  if (scene.channels && scene.channels.filter((c) => c.enabled !== false).length > 1)
    return [channelGridTexture(scene, cellSize, output, volume.channelCellRanges ? volume : null)];
  // A bricked channel scene of one drawn channel: its grid is the scalar scene's it draws.
  if (volume.cellRanges)
    return [brickedGridTexture(scalarSceneOf(scene) ?? scene, volume, cellSize, output, volume.cellRanges)];
  const map = { valueScale: volume.valueScale, valueOffset: volume.valueOffset };
  const geometry = gridGeometry(scene.volume.dims, cellSize);
  const layout = sliceAtlasLayout(geometry.slice(0, 3));
  const volumeId = objectId(scene.volume as Volume);
  const ranges: AuxiliaryTexture = {
    name: 'majorantRanges',
    dimension: '2d',
    bind: output === 'ranges',
    key: `${volumeId}|${cellSize}|${volume.format}|${volume.key.split('|')[0]}`,
    render: {
      label: 'majorant grid value ranges',
      width: layout.width,
      height: layout.height,
      format: 'rgba32float',
      glsl: glslAtlas.SLICE_ATLAS + glslBuild.cellRanges,
      wgsl: wgslAtlas.SLICE_ATLAS + wgslBuild.cellRanges,
      uniforms: BUILD_UNIFORMS,
      values: { gridCells: geometry, gridDensity: 0, ...map },
      inputs: [{ name: 'volume', dimension: '3d' }],
    },
  };
  if (output === 'ranges') return [ranges];
  const tfKey = JSON.stringify(scene.channels ?? scene.transferFunction);
  return [
    ranges,
    {
      name: 'opacityBounds',
      dimension: '2d',
      bind: false,
      key: tfKey,
      render: {
        label: 'transfer function opacity bounds',
        width: TF_RESOLUTION,
        height: 1,
        format: 'rgba32float',
        glsl: glslBuild.opacityBounds,
        wgsl: wgslBuild.opacityBounds,
        uniforms: BUILD_UNIFORMS,
        values: { gridCells: [0, 0, 0, 0], gridDensity: 0, ...map },
        inputs: [{ name: 'transferFunction', dimension: '2d' }],
      },
    },
    {
      name: 'majorantGrid',
      dimension: '2d',
      key: `${volumeId}|${cellSize}|${scene.densityScale}|${tfKey}|${volume.key}`,
      render: {
        label: 'majorant grid',
        width: layout.width,
        height: layout.height,
        format: 'rgba32float',
        glsl: glslAtlas.SLICE_ATLAS + glslBuild.majorantGrid,
        wgsl: wgslAtlas.SLICE_ATLAS + wgslBuild.majorantGrid,
        uniforms: BUILD_UNIFORMS,
        values: { gridCells: geometry, gridDensity: scene.densityScale, ...map },
        inputs: [
          { name: 'majorantRanges', dimension: '2d' },
          { name: 'opacityBounds', dimension: '2d' },
        ],
      },
    },
  ];
}

/**
 * A bricked volume's grid, built on the CPU from the value ranges the brick cache reports
 * per cell (resident bricks' data, a coarser level's bounds elsewhere: VolumeBinding.cellRanges),
 * since the volume texture is then a brick atlas the GPU build cannot read as voxels. Keyed
 * on the binding's key, which changes with the residency. `'ranges'` stores the ranges back
 * in texel units (the kernels map them with valueScale / valueOffset and take both ends);
 * `'majorants'` the grid buildMajorantGrid makes of them.
 */
function brickedGridTexture(
  scene: Scene,
  volume: VolumeBinding,
  cellSize: number,
  output: MajorantGridOutput,
  cellRanges: NonNullable<VolumeBinding['cellRanges']>,
): AuxiliaryTexture {
  const cells = gridCells(scene.volume.dims, cellSize);
  const layout = sliceAtlasLayout(cells);
  const tfKey = output === 'majorants' ? `|${scene.densityScale}|${JSON.stringify(scene.transferFunction)}` : '';
  return {
    name: output === 'ranges' ? 'majorantRanges' : 'majorantGrid',
    dimension: '2d',
    key: `bricked|${cellSize}${tfKey}|${volume.key}`,
    create: () => {
      const ranges = cellRanges(cells);
      let texels: Float32Array;
      if (output === 'majorants') {
        const tf = rasterizeTransferFunction(scene.transferFunction, TF_RESOLUTION);
        texels = buildMajorantGrid(ranges, tf, scene.densityScale).data;
      } else {
        // Normalized value → texel, the inverse of sampleVolume's map (a zero scale maps every texel to the offset).
        const toTexel = (v: number) => (volume.valueScale === 0 ? 0 : (v - volume.valueOffset) / volume.valueScale);
        texels = new Float32Array(4 * ranges.vmin.length);
        for (let c = 0; c < ranges.vmin.length; c++) {
          const a = toTexel(ranges.vmin[c]),
            b = toTexel(ranges.vmax[c]);
          texels.set([Math.min(a, b), Math.max(a, b), 0, 1], 4 * c);
        }
      }
      const data = new Float32Array(4 * layout.width * layout.height);
      for (let z = 0; z < cells[2]; z++)
        for (let y = 0; y < cells[1]; y++) {
          const [ax, ay] = atlasTexel(layout, cells, 0, y, z);
          const from = 4 * cells[0] * (y + cells[1] * z);
          data.set(texels.subarray(from, from + 4 * cells[0]), 4 * (ax + layout.width * ay));
        }
      return {
        dimension: '2d',
        width: layout.width,
        height: layout.height,
        format: 'rgba32float',
        data,
        label: output === 'ranges' ? 'majorant grid value ranges (bricked)' : 'majorant grid (bricked)',
      };
    },
  };
}

/**
 * A channel scene's grid (majorant-grid.ts channelMajorantGrid: the sum of the drawn channels'
 * bounds), built on the CPU and uploaded. Only `'majorants'`: the skipping of MIP and ISO reads
 * one value range per cell, which a channel scene does not have, so they march it unskipped.
 * Bricked (`bricked` given): the sum over the drawn channels of the grids made of the brick
 * cache's per-channel cell ranges (what the resident bricks, or coarser levels, serve), keyed
 * on the binding's key, which changes with the residency.
 */
function channelGridTexture(
  scene: Scene,
  cellSize: number,
  output: MajorantGridOutput,
  bricked: VolumeBinding | null,
): AuxiliaryTexture {
  if (output !== 'majorants') throw new RangeError('a channel scene has a majorant grid, not one value range per cell');
  const channels = scene.channels!;
  const cells = gridCells(scene.volume.dims, cellSize);
  return {
    name: 'majorantGrid',
    dimension: '2d',
    key: bricked
      ? `channels bricked|${cellSize}|${scene.densityScale}|${JSON.stringify(channels)}|${bricked.key}`
      : `channels|${objectId(scene.volume as Volume)}|${cellSize}|${scene.densityScale}|${JSON.stringify(channels)}`,
    create: () =>
      atlasTexture(
        cells,
        bricked
          ? summedChannelGrid(bricked.channelCellRanges!(cells), channels, scene.densityScale).data
          : channelMajorantGrid(scene.volume, channels, scene.densityScale, cellSize).data,
        'majorant grid (channels)',
      ),
  };
}

/** A grid's RGBA texels (x fastest) laid out in the slice atlas of its cell counts, as the GPU build writes it. */
export function atlasTexture(cells: [number, number, number], texels: Float32Array, label: string) {
  const layout = sliceAtlasLayout(cells);
  const data = new Float32Array(4 * layout.width * layout.height);
  for (let z = 0; z < cells[2]; z++)
    for (let y = 0; y < cells[1]; y++) {
      const [ax, ay] = atlasTexel(layout, cells, 0, y, z);
      const from = 4 * cells[0] * (y + cells[1] * z);
      data.set(texels.subarray(from, from + 4 * cells[0]), 4 * (ax + layout.width * ay));
    }
  return {
    dimension: '2d' as const,
    width: layout.width,
    height: layout.height,
    format: 'rgba32float' as const,
    data,
    label,
  };
}

const BUILD_UNIFORMS = new UniformLayout('MajorantBuild', [
  GRID_CELLS_FIELD,
  { name: 'gridDensity', type: 'f32' },
  // Volume texel → normalized value (RenderContext's VolumeBinding; gpu/volume-format.ts).
  { name: 'valueScale', type: 'f32' },
  { name: 'valueOffset', type: 'f32' },
]);
