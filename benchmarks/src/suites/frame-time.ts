import { scenes, type Backend, type RendererConfig, type SceneSpec } from '../configs.js';
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
  /** GPU time per iteration (timer queries), median and min–max; null where no timer was offered. */
  gpuMedianMs: number | null;
  gpuMinMs: number | null;
  gpuMaxMs: number | null;
  gpuTimer: string;
}

/** ms per iteration of `config` at size², the preset's batches of iterations between GPU syncs (wall clock and GPU timer). */
export function frameTimes(
  s: SuiteContext,
  config: RendererConfig,
  backend: Backend,
  spec: SceneSpec,
  size: number,
): Promise<{ samples: number[]; gpuSamples: number[]; gpuTimer: string }> {
  return bench(
    s.page,
    'frameTime',
    { ...config, backend },
    spec,
    size,
    size,
    s.preset.frameIterations,
    s.preset.frameRepeats,
  );
}

/**
 * The paper's Table 1: ms per iteration by volume size (at a fixed framebuffer size) and by
 * framebuffer size (at 128³). Each sample is a batch of iterations bracketed by GPU syncs
 * (blocking 1-texel readback on WebGL 2, onSubmittedWorkDone on WebGPU), timed by the wall
 * clock and, where offered, by GPU timer queries (EXT_disjoint_timer_query_webgl2,
 * WebGPU timestamp-query).
 */
export async function frameTime(s: SuiteContext): Promise<FrameTimeRow[]> {
  const rows: FrameTimeRow[] = [];
  const p = s.preset;
  const run = async (table: FrameTimeRow['table'], volumeSize: number, size: number) => {
    const spec = scenes(volumeSize).cloud;
    for (const backend of s.backends) {
      for (const config of s.renderers) {
        s.log(`frame-time: ${table} ${config.label} ${backend} volume ${volumeSize}³ at ${size}²`);
        const r = await frameTimes(s, config, backend, spec, size);
        const sp = spread(r.samples);
        const gp = r.gpuSamples.length ? spread(r.gpuSamples) : null;
        rows.push({
          table,
          label: config.label,
          backend,
          volumeSize,
          size,
          medianMs: median(r.samples),
          minMs: sp.min,
          maxMs: sp.max,
          samples: r.samples,
          gpuMedianMs: gp ? median(r.gpuSamples) : null,
          gpuMinMs: gp?.min ?? null,
          gpuMaxMs: gp?.max ?? null,
          gpuTimer: r.gpuTimer,
        });
      }
    }
  };
  for (const v of p.frameVolumeSizes) await run('by-volume', v, p.frameSizeAtVolume);
  for (const f of p.frameSizes) await run('by-framebuffer', 128, f);
  return rows;
}
