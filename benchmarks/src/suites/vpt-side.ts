/**
 * Side by side with the original VPT (`pnpm bench --vpt DIR`): the anchor scene
 * (vpt-side/anchor-scene.ts) rendered by VPT's renderers and by vpt's in ONE page of one
 * Chromium, in interleaved rounds (VPT, vpt, VPT, vpt…), each against its own converged
 * reference. Reported per pair as ratios vpt / VPT (median and range over the rounds): ms
 * per iteration and the time to HDR 30 and 35 dB (linear radiance clamped to [0, 1], peak 1).
 * Method: docs/benchmarks.md, "Side by side with VPT".
 */
import os from 'node:os';
import type { Page } from 'puppeteer-core';
import { median } from '../metrics.js';
import {
  ANCHOR_ALBEDO,
  ANCHOR_CAMERA_Z,
  ANCHOR_EXTINCTION,
  ANCHOR_FOVY,
  VPT_SKY_ROWS,
} from '../vpt-side/anchor-scene.js';
import type { SideEngineConfig, SidePoint, SideSceneConfig } from '../vpt-side/side-page.js';
import { formatRatio, ratioSummary, sideIterationsTo, sideTimeTo } from '../vpt-side/side-metrics.js';

export const SIDE_TARGETS_DB = [30, 35];

/** What one engine renders for a pair, with the length of its reference and of its curves. */
interface SideEngine {
  config: SideEngineConfig;
  referenceIterations: number;
  maxIterations: number;
}

export interface SidePair {
  /** A short name for files. */
  id: string;
  name: string;
  /**
   * The renderers' estimates are running means of independent iterations, so the
   * reference's own noise can be taken out of the MSE (side-metrics.ts). Not for MIP,
   * whose running maximum is not a mean.
   */
  mean: boolean;
  vptRef: SideEngine;
  vpt: SideEngine;
}

/** The pairs of the comparison; `scale` shortens every run (the --quick smoke test). */
export function sidePairs(scale = 1): SidePair[] {
  const it = (n: number) => Math.max(4, Math.round(n * scale));
  return [
    {
      id: 'multiple',
      mean: true,
      name: 'multiple scattering (VPT MCM, 8 bounces / vpt MCRT maxDepth 8)',
      vptRef: {
        config: { engine: 'vpt-ref', renderer: 'mcm', props: {} },
        referenceIterations: it(2048),
        maxIterations: it(640),
      },
      vpt: {
        config: { engine: 'vpt', renderer: 'mcrt', params: { scattering: 'multiple', maxDepth: 8 } },
        referenceIterations: it(256),
        maxIterations: it(64),
      },
    },
    {
      id: 'single',
      mean: true,
      name: 'single scattering (VPT MCS, extinction 100 / vpt MCRT single)',
      vptRef: {
        config: { engine: 'vpt-ref', renderer: 'mcs', props: { extinction: ANCHOR_EXTINCTION } },
        referenceIterations: it(512),
        maxIterations: it(128),
      },
      vpt: {
        config: { engine: 'vpt', renderer: 'mcrt', params: { scattering: 'single' } },
        referenceIterations: it(512),
        maxIterations: it(128),
      },
    },
    {
      id: 'eam',
      mean: true,
      name: 'EAM (VPT 64 slices / vpt defaults)',
      vptRef: {
        config: { engine: 'vpt-ref', renderer: 'eam', props: {} },
        referenceIterations: it(256),
        maxIterations: it(64),
      },
      vpt: {
        config: { engine: 'vpt', renderer: 'eam', params: {} },
        referenceIterations: it(256),
        maxIterations: it(64),
      },
    },
    {
      id: 'mip',
      mean: false,
      name: 'MIP (VPT 64 steps / vpt defaults)',
      vptRef: {
        config: { engine: 'vpt-ref', renderer: 'mip', props: {} },
        referenceIterations: it(256),
        maxIterations: it(64),
      },
      vpt: {
        config: { engine: 'vpt', renderer: 'mip', params: {} },
        referenceIterations: it(256),
        maxIterations: it(64),
      },
    },
  ];
}

export interface SideOptions {
  /** URL path where the VPT build is served (with a trailing slash). */
  vptBase: string;
  /** URL of the N³ anchor volume. */
  volumeUrl: string;
  volumeSide: number;
  size: number;
  rounds: number;
  /** Shortens references and curves (1 = the full run). */
  scale: number;
  budgetMs: number;
  /** Only the pairs with these ids (multiple, single, eam, mip); all when absent. */
  pairs?: string[];
  /** Per vpt renderer name (mcrt, eam, mip), parameters merged into its configuration (an estimator or a step to compare). */
  rendererParams?: Record<string, Record<string, unknown>>;
  log: (line: string) => void;
  /** Keeps a reference image (base64 sRGB RGBA8, top row first) to look at. */
  saveImage?: (name: string, rgba8Base64: string, size: number) => void;
}

interface EngineRound {
  msPerIteration: number;
  points: SidePoint[];
  timeToDb: Record<string, number | null>;
  /** Iterations to each target: how much one iteration buys, whatever the load. */
  iterationsToDb: Record<string, number | null>;
}

export interface SidePairResult {
  name: string;
  vptRef: { config: SideEngineConfig; referenceIterations: number; rounds: EngineRound[] };
  vpt: { config: SideEngineConfig; referenceIterations: number; rounds: EngineRound[] };
  ratios: Record<string, { median: number; min: number; max: number; rounds: number } | null>;
}

export interface SideResults {
  size: number;
  volumeSide: number;
  rounds: number;
  loadAverage: { start: number[]; end: number[] };
  volumeMean: number;
  pairs: SidePairResult[];
}

async function side<T>(page: Page, fn: string, ...args: unknown[]): Promise<T> {
  return page.evaluate(
    (fn, args) => (window as unknown as { side: Record<string, (...a: unknown[]) => unknown> }).side[fn](...args),
    fn,
    args,
  ) as Promise<T>;
}

export async function vptSide(page: Page, o: SideOptions): Promise<SideResults> {
  const scene: SideSceneConfig = {
    volumeUrl: o.volumeUrl,
    n: o.volumeSide,
    extinction: ANCHOR_EXTINCTION,
    albedo: [...ANCHOR_ALBEDO],
    cameraZ: ANCHOR_CAMERA_Z,
    fovy: ANCHOR_FOVY,
    skyRows: VPT_SKY_ROWS,
  };
  const start = os.loadavg();
  const init = await side<{ mean: number }>(page, 'init', o.vptBase, scene);
  o.log(`vpt-side: anchor volume ${o.volumeSide}³, mean ${init.mean.toFixed(2)}/255; load average ${fmtLoad(start)}`);
  const pairs: SidePairResult[] = [];
  for (const pair of sidePairs(o.scale)) {
    if (o.pairs && !o.pairs.includes(pair.id)) continue;
    const extra = pair.vpt.config.engine === 'vpt' ? o.rendererParams?.[pair.vpt.config.renderer] : undefined;
    if (extra && pair.vpt.config.engine === 'vpt')
      pair.vpt.config = { ...pair.vpt.config, params: { ...pair.vpt.config.params, ...extra } };
    const engines = { vptRef: pair.vptRef, vpt: pair.vpt };
    const result: SidePairResult = {
      name: pair.name,
      vptRef: { config: pair.vptRef.config, referenceIterations: pair.vptRef.referenceIterations, rounds: [] },
      vpt: { config: pair.vpt.config, referenceIterations: pair.vpt.referenceIterations, rounds: [] },
      ratios: {},
    };
    for (const [key, e] of Object.entries(engines)) {
      await side(page, 'open', key, e.config, o.size);
      o.log(`vpt-side: ${pair.name}: ${key} reference, ${e.referenceIterations} it`);
      await side(page, 'reference', key, key, e.referenceIterations);
      if (o.saveImage)
        o.saveImage(`${pair.id}-${key}-reference`, await side<string>(page, 'referenceImage', key), o.size);
    }
    for (let round = 0; round < o.rounds; round++) {
      for (const [key, e] of Object.entries(engines) as [keyof typeof engines, SideEngine][]) {
        const samples = await side<number[]>(page, 'msPerIteration', key, o.scale < 1 ? 1 : 4, 3);
        const points = await side<SidePoint[]>(page, 'curve', key, key, 1 + round, e.maxIterations, o.budgetMs);
        const timeToDb = Object.fromEntries(
          SIDE_TARGETS_DB.map((db) => [db, sideTimeTo(points, pair.mean ? e.referenceIterations : Infinity, db)]),
        );
        const iterationsToDb = Object.fromEntries(
          SIDE_TARGETS_DB.map((db) => [db, sideIterationsTo(points, pair.mean ? e.referenceIterations : Infinity, db)]),
        );
        result[key].rounds.push({ msPerIteration: median(samples), points, timeToDb, iterationsToDb });
        o.log(
          `vpt-side: ${pair.name}: round ${round + 1} ${key}: ${median(samples).toFixed(1)} ms/it, ` +
            SIDE_TARGETS_DB.map((db) => `${db} dB ${fmtMs(timeToDb[db])}`).join(', '),
        );
      }
    }
    for (const key of Object.keys(engines)) await side(page, 'close', key);
    result.ratios['ms per iteration'] = ratioSummary(
      result.vpt.rounds.map((r) => r.msPerIteration),
      result.vptRef.rounds.map((r) => r.msPerIteration),
    );
    for (const db of SIDE_TARGETS_DB)
      result.ratios[`time to ${db} dB`] = ratioSummary(
        result.vpt.rounds.map((r) => r.timeToDb[db]),
        result.vptRef.rounds.map((r) => r.timeToDb[db]),
      );
    pairs.push(result);
  }
  return {
    size: o.size,
    volumeSide: o.volumeSide,
    rounds: o.rounds,
    loadAverage: { start, end: os.loadavg() },
    volumeMean: init.mean,
    pairs,
  };
}

const fmtMs = (ms: number | null) => (ms === null ? 'not reached' : `${(ms / 1000).toFixed(2)} s`);
const fmtIt = (n: number | null) => (n === null ? '—' : n.toFixed(1));
const fmtLoad = (l: number[]) => l.map((x) => x.toFixed(2)).join(' / ');

/** The results as a markdown table (ratios vpt / VPT, median and range over the rounds). */
export function sideMarkdown(r: SideResults): string {
  const lines = [
    `Anchor scene, ${r.size}² on a ${r.volumeSide}³ volume, ${r.rounds} interleaved rounds, WebGL 2 both. ` +
      `Load average (1, 5, 15 min): ${fmtLoad(r.loadAverage.start)} at the start, ${fmtLoad(r.loadAverage.end)} at the end.`,
    '',
    '| vpt / VPT | ms per iteration | time to HDR 30 dB | time to HDR 35 dB |',
    '|---|---|---|---|',
  ];
  for (const p of r.pairs)
    lines.push(
      `| ${p.name} | ${formatRatio(p.ratios['ms per iteration'])} | ${formatRatio(p.ratios['time to 30 dB'])} | ${formatRatio(p.ratios['time to 35 dB'])} |`,
    );
  lines.push(
    '',
    '| pair | engine | ms/it (rounds) | 30 dB (s) | 35 dB (s) | iterations to 30 / 35 dB |',
    '|---|---|---|---|---|---|',
  );
  for (const p of r.pairs)
    for (const [label, e] of [
      ['VPT', p.vptRef],
      ['vpt', p.vpt],
    ] as const)
      lines.push(
        `| ${p.name} | ${label} | ${e.rounds.map((x) => x.msPerIteration.toFixed(1)).join(', ')} | ` +
          `${e.rounds.map((x) => fmtMs(x.timeToDb[30])).join(', ')} | ${e.rounds.map((x) => fmtMs(x.timeToDb[35])).join(', ')} | ` +
          `${e.rounds.map((x) => `${fmtIt(x.iterationsToDb[30])} / ${fmtIt(x.iterationsToDb[35])}`).join(', ')} |`,
      );
  return lines.join('\n');
}
