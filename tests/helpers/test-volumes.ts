/**
 * The synthetic volumes the browser tests render, built the same way in Node (for CPU
 * expectations) and in the page. `installTestVolumes` is typed TypeScript sent with
 * `page.evaluate(installTestVolumes)` (usePage does it), which installs `window.tv`; puppeteer
 * sends the function's compiled source, so it may use nothing from this module's scope. In
 * Node, `testVolumes({ createVolume, createProceduralVolume })` runs the same source.
 */
import type { ProceduralKind, Volume, VoxelArray, VoxelType } from '@vpt/core';

/** The part of core the builders need (window.vpt.core in the page, core's index in Node). */
export interface VolumeFactories {
  createVolume(
    dims: [number, number, number],
    type: VoxelType,
    data?: VoxelArray,
    spacing?: [number, number, number],
  ): Volume;
  createProceduralVolume(kind: ProceduralKind, size?: number): Volume;
}

/** A scalar field f(x, y, z) of physical voxel-centre coordinates (index × spacing). */
export type FieldKind = 'ramp' | 'sphere16' | 'waves' | 'probe';
export interface FieldSpec {
  kind: FieldKind;
  dims: [number, number, number];
  spacing: [number, number, number];
  range: [number, number];
}

/** Every test volume states its value range. */
export type RangedVolume = Volume & { valueRange: [number, number] };

export interface TestVolumes {
  /** value(p) = |p| at N³ voxel centres of the unit box (valueRange [0, 1]): isosurface value r is the sphere of radius r. */
  sphereDistance(n: number): RangedVolume;
  /** 1 inside |x|, |y|, |z| < half (unit box about the origin), 0 outside; valueRange [0, 1]. */
  block(n: number, half: number): RangedVolume;
  /** The 16³ blob stored as `type` with a range that maps it back to [0, 1]; `inverted` stores dense matter as low values. */
  blobAs(type: VoxelType, inverted: boolean): RangedVolume;
  /** A float32 volume of a named field (FieldKind) at the given dims and spacing. */
  field(spec: FieldSpec): RangedVolume;
}

interface TestVolumeHost {
  vpt: { core: VolumeFactories };
  tv?: TestVolumes;
}

declare global {
  interface Window {
    tv: TestVolumes;
  }
}

/** Installs `host.tv` (default: the page's window, whose `vpt.core` the builders use). */
export function installTestVolumes(host: TestVolumeHost = window as unknown as TestVolumeHost): void {
  const core = host.vpt.core;
  const ranged = (v: Volume, range: [number, number]): RangedVolume => Object.assign(v, { valueRange: range });
  const fields: Record<FieldKind, (x: number, y: number, z: number) => number> = {
    ramp: (x, y, z) => 0.3 * x - 0.2 * y + 0.5 * z,
    sphere16: (x, y, z) => Math.hypot(x - 16, y - 16, z - 16),
    waves: (x, y, z) => Math.sin(x / 7) * Math.cos(y / 9) + z / 100,
    probe: (x, y, z) => Math.sin(x / 3) + (Math.cos(y / 4) * z) / 9,
  };
  host.tv = {
    sphereDistance(n) {
      const data = new Float32Array(n * n * n);
      for (let z = 0; z < n; z++)
        for (let y = 0; y < n; y++)
          for (let x = 0; x < n; x++)
            data[x + n * (y + n * z)] = Math.hypot((x + 0.5) / n - 0.5, (y + 0.5) / n - 0.5, (z + 0.5) / n - 0.5);
      const v = core.createVolume([n, n, n], 'float32', data);
      return ranged(v, [0, 1]);
    },
    block(n, half) {
      const data = new Float32Array(n * n * n);
      for (let z = 0; z < n; z++)
        for (let y = 0; y < n; y++)
          for (let x = 0; x < n; x++) {
            const c = [x, y, z].map((i) => Math.abs((i + 0.5) / n - 0.5));
            data[x + n * (y + n * z)] = Math.max(...c) < half ? 1 : 0;
          }
      const v = core.createVolume([n, n, n], 'float32', data);
      return ranged(v, [0, 1]);
    },
    blobAs(type, inverted) {
      const blob = core.createProceduralVolume('blob', 16);
      const span = { uint8: [0, 255], uint16: [0, 60000], int16: [-15000, 15000], float32: [-300, 700] }[type];
      const [a, b] = inverted ? [span[1], span[0]] : span;
      const C = { uint8: Uint8Array, uint16: Uint16Array, int16: Int16Array, float32: Float32Array }[type];
      const data = new C(blob.data.length);
      for (let i = 0; i < data.length; i++) {
        const x = a + (b - a) * blob.data[i];
        data[i] = type === 'float32' ? x : Math.round(x);
      }
      const v = core.createVolume([...blob.dims], type, data, [...blob.spacing]);
      return ranged(v, [a, b]);
    },
    field(spec) {
      const f = fields[spec.kind];
      const [nx, ny, nz] = spec.dims;
      const data = new Float32Array(nx * ny * nz);
      for (let z = 0; z < nz; z++)
        for (let y = 0; y < ny; y++)
          for (let x = 0; x < nx; x++)
            data[x + nx * (y + ny * z)] = f(x * spec.spacing[0], y * spec.spacing[1], z * spec.spacing[2]);
      const v = core.createVolume(spec.dims, 'float32', data, spec.spacing);
      return ranged(v, spec.range);
    },
  };
}

/** The same builders in Node, over core's own factories. */
export function testVolumes(core: VolumeFactories): TestVolumes {
  const host: TestVolumeHost = { vpt: { core } };
  installTestVolumes(host);
  return host.tv!;
}
