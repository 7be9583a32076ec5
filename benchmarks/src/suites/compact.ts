import os from 'node:os';
import { scenes } from '../configs.js';
import { median, spread } from '../metrics.js';
import { bench, type SuiteContext } from './types.js';

export interface BytesPerVoxelRow {
  backend: string;
  type: string;
  sampling: 'fast' | 'exact';
  bytesPerVoxel: number;
  total: number;
}

export interface FastExactRow {
  renderer: string;
  backend: string;
  size: number;
  fastMs: number;
  exactMs: number;
  /** exact / fast median ms per iteration, measured alternately in one run: > 1 means the fast path is faster. */
  ratio: number;
  fastSpread: { min: number; max: number };
  exactSpread: { min: number; max: number };
}

export interface CtLoadRow {
  backend: string;
  depth: number;
  generateMs: number;
  setSceneMs: number;
  firstImageMs: number;
  loadMs: number;
  /** Peak of the page's JS heap (V8 heap + array-buffer backing stores, as DevTools reports them) during the load, MiB. */
  peakHeapMiB: number;
  /** The same before the volume was generated, MiB. */
  baseHeapMiB: number;
  gpuBytes: { volume: number; total: number };
  uploadedDims: number[];
  warnings: string[];
}

export interface CompactResults {
  loadAverage: number[];
  bytesPerVoxel: BytesPerVoxelRow[];
  fastVsExact: FastExactRow[];
  ctLoad: CtLoadRow[];
  ctSkipped: string[];
}

/**
 * Compact volumes (docs/benchmarks.md, "Compact volumes"): GPU bytes per voxel per type; ms per iteration of the fast
 * path (compact texture, hardware filter) against the exact path (r32float, manual
 * trilinear) for every renderer on the bundled head, alternately in one run (A/B, B/A);
 * load time and peak JS heap of a synthetic 512 × 512 × N int16 CT (first backend only).
 */
export async function compact(s: SuiteContext): Promise<CompactResults> {
  const loadAverage = os.loadavg();
  const bytesPerVoxel: BytesPerVoxelRow[] = [];
  for (const backend of s.backends)
    bytesPerVoxel.push(...(await bench<BytesPerVoxelRow[]>(s.page, 'bytesPerVoxel', backend, 32)));

  const fastVsExact: FastExactRow[] = [];
  const size = s.preset.compactSize;
  const head = scenes(s.preset.cloudSize).head;
  for (const backend of s.backends) {
    for (const r of s.renderers) {
      s.log(`compact: ${r.label} fast vs exact ${backend} at ${size}²`);
      const samples = { fast: [] as number[], exact: [] as number[] };
      for (let round = 0; round < 2; round++) {
        const order = round === 0 ? (['fast', 'exact'] as const) : (['exact', 'fast'] as const);
        for (const sampling of order) {
          const res = await bench<{ samples: number[] }>(
            s.page,
            'frameTime',
            { ...r, backend, sampling },
            head,
            size,
            size,
            s.preset.frameIterations,
            s.preset.frameRepeats,
          );
          samples[sampling].push(...res.samples);
        }
      }
      const fm = median(samples.fast),
        em = median(samples.exact);
      fastVsExact.push({
        renderer: r.label,
        backend,
        size,
        fastMs: fm,
        exactMs: em,
        ratio: em / fm,
        fastSpread: spread(samples.fast),
        exactSpread: spread(samples.exact),
      });
    }
  }

  const ctLoad: CtLoadRow[] = [];
  const ctSkipped: string[] = [];
  const backend = s.backends[0];
  const cdp = await s.page.target().createCDPSession();
  const heapMiB = async () => {
    const h = (await cdp.send('Runtime.getHeapUsage')) as { usedSize: number; backingStorageSize?: number };
    return (h.usedSize + (h.backingStorageSize ?? 0)) / 2 ** 20;
  };
  for (const depth of s.preset.ctDepths) {
    s.log(`compact: synthetic 512x512x${depth} int16 CT on ${backend}`);
    await cdp.send('HeapProfiler.collectGarbage');
    const baseHeapMiB = await heapMiB();
    let peak = baseHeapMiB,
      polling = true;
    const poll = (async () => {
      while (polling) {
        peak = Math.max(peak, await heapMiB());
        await new Promise((r) => setTimeout(r, 20));
      }
    })();
    try {
      const row = await bench<Omit<CtLoadRow, 'peakHeapMiB' | 'baseHeapMiB'>>(s.page, 'ctLoad', backend, depth);
      polling = false;
      await poll;
      ctLoad.push({ ...row, peakHeapMiB: Math.max(peak, await heapMiB()), baseHeapMiB });
    } catch (e) {
      polling = false;
      await poll;
      ctSkipped.push(`512x512x${depth}: ${(e as Error).message.split('\n')[0]}`);
    }
    await cdp.send('HeapProfiler.collectGarbage');
  }
  await cdp.detach();
  return { loadAverage, bytesPerVoxel, fastVsExact, ctLoad, ctSkipped };
}
