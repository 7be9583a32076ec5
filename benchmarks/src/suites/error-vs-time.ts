import { estimatorScenes, scenes, type Backend, type RendererConfig, type SceneSpec } from '../configs.js';
import { timeToPsnr, type CurvePoint } from '../metrics.js';
import { gpuProcessPid, processCpuMs } from '../process-cpu-time.js';
import { bench, type SuiteContext } from './types.js';

export const TARGETS_DB = [25, 30, 35, 40];

export interface ErrorCurveResult {
  scene: string;
  label: string;
  backend: string;
  size: number;
  referenceIterations: number;
  /** The reference's own estimated RMSE (from its half-accumulations), subtracted in quadrature from the curve; null when the renderer has no estimate. */
  referenceRmse: number | null;
  points: CurvePoint[];
  timeToDb: Record<string, number | null>;
  timeToDbLdr: Record<string, number | null>;
  /** What the renderer chose for the scene (RenderContext.stats.renderer; MCRT: the estimator). */
  rendererStats?: Record<string, string>;
  /** Estimator study: ms per iteration measured round-robin with the scene's other configurations (one sample per round). */
  interleavedMsPerIteration?: number[];
  /** The same batches' CPU ms per iteration in the browser's GPU process (Linux; 10 ms ticks per batch, so use sums or means). */
  interleavedGpuProcessCpuMsPerIteration?: number[];
}

/**
 * Error vs wall-clock time: each configuration renders progressively against a converged
 * reference made by the same renderer with an independent seed (so the curve measures
 * noise, not a bias between renderers).
 */
export async function errorVsTime(s: SuiteContext): Promise<ErrorCurveResult[]> {
  const out: ErrorCurveResult[] = [];
  const size = s.preset.errorSize;
  const all = [...s.renderers, ...s.mcrtVariants];
  const study = s.preset.estimatorStudy ? estimatorScenes(s.preset.cloudSize) : {};
  for (const [sceneName, sceneSpec] of Object.entries({
    ...scenes(s.preset.cloudSize),
    ...study,
    ...s.fetchedScenes,
  })) {
    if (s.preset.errorScenes && !s.preset.errorScenes.includes(sceneName)) continue;
    // The reference sets its own seed; the curves take the preset's when one is given.
    const spec = s.preset.curveSeed === undefined ? sceneSpec : { ...sceneSpec, seed: s.preset.curveSeed };
    for (const backend of s.backends) {
      for (const config of all) {
        // Variants on the procedural scene only, except in the estimator study.
        if (sceneName !== 'cloud' && !s.preset.estimatorStudy && s.mcrtVariants.includes(config)) continue;
        const refIterations = s.preset.referenceIterations[config.renderer];
        // One reference per configuration, made on the first backend: the backends give
        // bit-identical images (tests/*parity*), so it is the reference for both.
        const refConfig = referenceConfig(config, all);
        const refKey = referenceKey(sceneName, refConfig.label, size);
        s.log(
          `error-vs-time: ${sceneName} ${config.label} ${backend} (reference: ${refConfig.label}, ${refIterations} it)`,
        );
        const ref = await renderReference(s, refKey, refConfig, s.backends[0], spec, size, refIterations);
        const points = await errorCurve(s, config, backend, spec, size, refKey, !!config.halves);
        const rendererStats = await bench<Record<string, string>>(
          s.page,
          'rendererStats',
          { ...config, backend },
          spec,
        );
        out.push({
          rendererStats,
          scene: sceneName,
          label: config.label,
          backend,
          size,
          referenceIterations: refIterations,
          referenceRmse: ref.rmse ?? null,
          points,
          timeToDb: Object.fromEntries(TARGETS_DB.map((d) => [d, timeToPsnr(points, d)])),
          timeToDbLdr: Object.fromEntries(TARGETS_DB.map((d) => [d, timeToPsnr(points, d, 'psnrLdr')])),
        });
      }
    }
  }
  if (s.preset.estimatorStudy) await interleavedCosts(s, out);
  return out;
}

/**
 * The estimator study's cost side: per scene and backend, every configuration's ms per
 * iteration measured round-robin (preset.costRounds rounds of preset.costBatch-iteration
 * batches, the order reversed every other round: A B C, C B A, …) at the curves' size, so the
 * comparison does not depend on how the machine's load moved while the curves ran one after
 * another. Time to a target is then iterations to it (from the curve: variance, independent of
 * the load) × this cost. Each batch is timed twice: the wall clock, and the CPU time the GPU
 * process spent on it (SwiftShader runs the kernels there; process-cpu-time.ts), which the
 * other processes of a loaded machine do not inflate.
 */
async function interleavedCosts(s: SuiteContext, out: ErrorCurveResult[]): Promise<void> {
  const all = [...s.renderers, ...s.mcrtVariants];
  const specs = { ...scenes(s.preset.cloudSize), ...estimatorScenes(s.preset.cloudSize), ...s.fetchedScenes };
  const gpuPid = gpuProcessPid(s.page.browser().process()?.pid);
  const iterations = s.preset.costBatch ?? 2;
  for (const sceneName of [...new Set(out.map((r) => r.scene))])
    for (const backend of s.backends) {
      const rows = out.filter((r) => r.scene === sceneName && r.backend === backend);
      const configs = rows.map((r) => ({ ...all.find((c) => c.label === r.label)!, backend }));
      s.log(
        `error-vs-time: ${sceneName} ${backend}: interleaved ms per iteration of ${configs.length} configurations${gpuPid ? ` (and GPU process ${gpuPid}'s CPU time)` : ''}`,
      );
      await bench(
        s.page,
        'costOpen',
        configs,
        specs[sceneName as keyof typeof specs],
        s.preset.errorSize,
        s.preset.errorSize,
      );
      const wall: number[][] = rows.map(() => []),
        cpu: number[][] = rows.map(() => []);
      for (let round = 0; round < (s.preset.costRounds ?? 5); round++)
        for (let k = 0; k < rows.length; k++) {
          const i = round % 2 ? rows.length - 1 - k : k;
          const cpu0 = gpuPid ? processCpuMs(gpuPid) : 0;
          const ms = await bench<number>(s.page, 'costBatch', i, iterations);
          if (gpuPid) cpu[i].push((processCpuMs(gpuPid) - cpu0) / iterations);
          wall[i].push(ms / iterations);
        }
      await bench(s.page, 'costClose');
      rows.forEach((r, i) => {
        r.interleavedMsPerIteration = wall[i];
        if (gpuPid) r.interleavedGpuProcessCpuMsPerIteration = cpu[i];
      });
    }
}

/** The configuration whose converged image is `config`'s reference (its referenceGroup, else itself). */
export function referenceConfig(config: RendererConfig, all: readonly RendererConfig[]): RendererConfig {
  return (config.referenceGroup && all.find((c) => c.label === config.referenceGroup)) || config;
}

/** Render a converged reference in the page and keep it there under `refKey`; returns its own RMSE estimate. */
export function renderReference(
  s: SuiteContext,
  refKey: string,
  config: RendererConfig,
  backend: Backend,
  spec: SceneSpec,
  size: number,
  iterations: number,
): Promise<{ rmse: number | null }> {
  return bench(s.page, 'reference', refKey, { ...config, backend }, spec, size, size, iterations);
}

/** The PSNR/RMSE curve of `config` against the reference kept under `refKey`, at the preset's checkpoints and budget. */
export function errorCurve(
  s: SuiteContext,
  config: RendererConfig,
  backend: Backend,
  spec: SceneSpec,
  size: number,
  refKey: string,
  halves: boolean,
): Promise<CurvePoint[]> {
  return bench(
    s.page,
    'errorCurve',
    { ...config, backend },
    spec,
    size,
    size,
    refKey,
    s.preset.curveIterations,
    s.preset.curveBudgetMs,
    halves,
  );
}

/** References live in the page by this key, so suites that need the same one share it. */
export const referenceKey = (scene: string, label: string, size: number) => `${scene}|${label}|${size}`;
