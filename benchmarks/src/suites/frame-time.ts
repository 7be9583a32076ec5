import { scenes } from '../configs.js';
import { median, spread } from '../metrics.js';
import { bench, type SuiteContext } from './types.js';

export interface FrameTimeRow {
  table: 'by-volume' | 'by-framebuffer';
  label: string;
  backend: string;
  volumeSize: number;
  size: number;
  medianMs: number;
  minMs: number;
  maxMs: number;
  samples: number[];
}

/**
 * The paper's Table 1: ms per iteration by volume size (at a fixed framebuffer size) and by
 * framebuffer size (at 128³). Each sample is a batch of iterations bracketed by GPU syncs
 * (blocking 1-texel readback on WebGL 2, onSubmittedWorkDone on WebGPU).
 */
export async function frameTime(s: SuiteContext): Promise<FrameTimeRow[]> {
  const rows: FrameTimeRow[] = [];
  const p = s.preset;
  const run = async (table: FrameTimeRow['table'], volumeSize: number, size: number) => {
    const spec = scenes(volumeSize).cloud;
    for (const backend of s.backends) {
      for (const config of s.renderers) {
        s.log(`frame-time: ${table} ${config.label} ${backend} volume ${volumeSize}³ at ${size}²`);
        const r = await bench<{ samples: number[] }>(s.page, 'frameTime', { ...config, backend }, spec, size, size, p.frameIterations, p.frameRepeats);
        const sp = spread(r.samples);
        rows.push({ table, label: config.label, backend, volumeSize, size, medianMs: median(r.samples), minMs: sp.min, maxMs: sp.max, samples: r.samples });
      }
    }
  };
  for (const v of p.frameVolumeSizes) await run('by-volume', v, p.frameSizeAtVolume);
  for (const f of p.frameSizes) await run('by-framebuffer', 128, f);
  return rows;
}
