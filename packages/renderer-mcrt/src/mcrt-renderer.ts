import {
  BaseRenderer,
  validateParams,
  buildEnvironmentSampling,
  environmentTextures,
  environmentTexturesKey,
  objectId,
  COPY_ACCUMULATION_RENDER,
  rasterizeTransferFunction,
  TF_RESOLUTION,
  type AuxiliaryTexture,
  type EnvironmentSamplingTables,
  type KernelSource,
  type LatLongEnvironment,
  type Scene,
  type UniformField,
  type UniformValues,
  type Volume,
  type VolumeBinding,
  volumeValueMapping,
  buildMajorantGrid,
  volumeCellRanges,
  scalarSceneOf,
  gridGeometry,
  majorantGridTextures,
  type MajorantGrid,
  paramUniformFields,
  paramUniformValues,
} from '@vpt/core';
import { blueNoiseTexture } from '@vpt/core/blue-noise';
// The CPU grid of what the kernel draws: the channels' sum, plus the labels' (label volumes' subpath).
import { sceneMajorantGrid } from '@vpt/core/labels';
import { MCRT_DESCRIPTOR } from './descriptor.js';
import { activeLights, computeFeatures, featureKey, MAX_LIGHTS, type McrtFeatures } from './features.js';
import { generateKernel, INTEGRATE_HALVES } from './kernel-sources.js';
import { MCRT_PARAM_SPECS, resolveParams, type McrtParams, type ResolvedMcrtParams } from './params.js';
import { extinctionCap } from './extinction-cap.js';
import { chooseEstimator, GridStatisticsMemo, type EstimatorChoice } from './estimator-choice.js';

export const MCRT_PARAM_FIELDS: readonly UniformField[] = [
  // phaseG (the anisotropy), maxDepth, rouletteDepth
  ...paramUniformFields(MCRT_DESCRIPTOR),
  { name: 'globalMajorant', type: 'f32' },
  { name: 'globalMinorant', type: 'f32' },
  /** σ_max: the medium's extinction and the grid's bounds are min(σ, σ_max) (extinction-cap.ts). */
  { name: 'extinctionMax', type: 'f32' },
  /** Majorant-grid cells per axis and the slice atlas's column count (atlasTexel in tracking.*.ts). */
  { name: 'gridCells', type: 'ivec4' },
  /** Lights in use; read only by the generic kernel (specialised kernels loop to LIGHT_COUNT). */
  { name: 'lightCount', type: 'i32' },
  { name: 'lightDirection', type: 'vec4', count: MAX_LIGHTS },
  { name: 'lightIrradiance', type: 'vec4', count: MAX_LIGHTS },
];

/**
 * Monte Carlo volumetric path tracer (docs/design.md). HDR = estimated radiance,
 * a = 1 if the camera ray had a real collision (its mean is the opacity along the ray).
 * Accumulates the running mean of all iterations and of the even and odd ones
 * (`halfAccumulations`), so RenderContext.estimateError() works.
 *
 * The generate kernel is specialised to the scene: `features()` derives the flag set and
 * `kernels.generate` is that variant's source (the context reads `kernels` right after
 * calling `features()` for the same scene), cached by flag set.
 */
export class McrtRenderer extends BaseRenderer<McrtParams> {
  readonly name = MCRT_DESCRIPTOR.name;
  readonly frameFormats = ['rgba32float'] as const;
  readonly accumulationFormats = ['rgba32float', 'rgba32float', 'rgba32float'] as const;
  readonly halfAccumulations = [1, 2] as const;
  readonly writesGuides = MCRT_DESCRIPTOR.writesGuides;
  /**
   * No normal test in temporal reuse: one sample's first collision in a medium has a gradient
   * normal that turns from sample to sample, and the test rejected history taps at random
   * (docs/benchmarks.md, "Orbit: a sharper and decorrelated history").
   */
  readonly temporalNormalTest = false;
  /** Draws a scene's slicePlane (core's scene/slice-plane.ts) under VPT_SLICE_PLANE. */
  readonly drawsSlicePlane = true;
  /** Draws a scene's labels (core's scene/labels.ts) under VPT_LABELS: their opacity joins the medium (transferAt). */
  readonly drawsLabels = true;
  readonly paramFields = MCRT_PARAM_FIELDS;
  private resolved: ResolvedMcrtParams;
  private current: McrtFeatures | null = null;
  private readonly variants = new Map<string, KernelSource>();
  private gridMemo: { key: string; grid: MajorantGrid } | null = null;
  private envMemo: { key: string; tables: EnvironmentSamplingTables } | null = null;
  private constantMapMemo: { key: string; map: LatLongEnvironment } | null = null;
  private readonly gridStats = new GridStatisticsMemo();
  private choiceMemo: { scene: Scene; params: ResolvedMcrtParams; choice: EstimatorChoice | null } | null = null;

  constructor(params: McrtParams = {}) {
    validateParams(MCRT_DESCRIPTOR.owner, MCRT_PARAM_SPECS, params);
    const resolved = resolveParams(params);
    super(params, MCRT_PARAM_SPECS, MCRT_DESCRIPTOR.owner);
    this.resolved = resolved;
  }

  /** Merge and validate new parameters (VptError 'invalid-scene' on a bad value); resets accumulation. */
  override setParams(params: Partial<McrtParams>): void {
    const resolved = resolveParams({ ...this.getParams(), ...params });
    super.setParams(params);
    this.resolved = resolved;
  }

  /** The parameters with defaults filled in. */
  get resolvedParams(): ResolvedMcrtParams {
    return { ...this.resolved };
  }

  get kernels(): { readonly generate: KernelSource; readonly integrate: KernelSource; readonly render: KernelSource } {
    return { generate: this.variant(this.current), integrate: INTEGRATE_HALVES, render: COPY_ACCUMULATION_RENDER };
  }

  /** The generate kernel for a feature set (the last features() result when omitted). */
  variant(features: McrtFeatures | null = this.current): KernelSource {
    const f = features ?? DEFAULT_FEATURES;
    const key = featureKey(f);
    let k = this.variants.get(key);
    if (!k) {
      k = generateKernel(f);
      this.variants.set(key, k);
    }
    return k;
  }

  override features(scene: Scene): Record<string, boolean | number> {
    const f = computeFeatures(scene, this.paramsFor(scene));
    this.current = f;
    return { ...f };
  }

  paramValues(scene: Scene): UniformValues {
    const p = this.paramsFor(scene);
    // With the grid the bounds live on the GPU; one global bound is computed here only without it.
    const onGpu = computeFeatures(scene, p).MAJORANT_GRID;
    const grid = onGpu ? null : this.majorantGrid(scene);
    const cap = extinctionCap(scene);
    const lights = activeLights(scene);
    const dirs = new Float32Array(4 * MAX_LIGHTS),
      irr = new Float32Array(4 * MAX_LIGHTS);
    lights.forEach((l, i) => {
      dirs.set(l.direction, 4 * i);
      irr.set(l.irradiance, 4 * i);
    });
    return {
      ...paramUniformValues(MCRT_DESCRIPTOR, p),
      globalMajorant: grid ? Math.min(grid.globalMajorant, cap) : 0,
      globalMinorant: grid ? Math.min(grid.globalMinorant, cap) : 0,
      extinctionMax: cap,
      gridCells: this.gridGeometry(scene),
      lightCount: lights.length,
      lightDirection: dirs,
      lightIrradiance: irr,
    };
  }

  // Without a binding (a caller outside RenderContext): the exact path's r32float of data values.
  auxiliaryTextures(
    scene: Scene,
    volume: VolumeBinding = {
      ...volumeValueMapping(scene.volume, { decodeScale: 1, decodeOffset: 0 }),
      format: 'r32float',
      key: '',
    },
  ): readonly AuxiliaryTexture[] {
    const aux: AuxiliaryTexture[] = [];
    const f = computeFeatures(scene, this.paramsFor(scene));
    if (f.MAJORANT_GRID) aux.push(...this.majorantGridTextures(scene, volume));
    if (f.ENV_MAP) {
      const env = this.environmentMap(scene);
      aux.push(...environmentTextures(env, () => this.environmentTables(env, environmentTexturesKey(env))));
    }
    if (f.BLUE_NOISE) aux.push(blueNoiseTexture());
    return aux;
  }

  /** The majorant grid as GPU-made auxiliary textures (core's majorantGridTextures); only the grid is bound. */
  private majorantGridTextures(scene: Scene, volume: VolumeBinding): AuxiliaryTexture[] {
    return majorantGridTextures(scene, volume, this.cellSize(scene), 'majorants');
  }

  /** The majorant grid of a scene computed on the CPU (cached by volume, TF, density scale and cell size): the reference the GPU build is tested against, and the global bounds without a grid. */
  majorantGrid(given: Scene): MajorantGrid {
    const cellSize = this.cellSize(given);
    // One drawn channel: the scalar scene it draws (the same bound, bit for bit).
    const scene = scalarSceneOf(given) ?? given;
    const labels = scene.labels ? `|${objectId(scene.labels.volume)}|${JSON.stringify(scene.labels.table)}` : '';
    const key = `${objectId(scene.volume as Volume)}|${cellSize}|${scene.densityScale}|${JSON.stringify(scene.channels ?? scene.transferFunction)}${labels}`;
    if (this.gridMemo?.key !== key && (scene.channels || scene.labels)) {
      // Channels and labels: the CPU grid of what the kernel draws (the sum of the channels', plus the labels').
      this.gridMemo = { key, grid: sceneMajorantGrid(scene, cellSize) };
    } else if (this.gridMemo?.key !== key) {
      const ranges = volumeCellRanges(scene.volume, cellSize);
      const tf = rasterizeTransferFunction(scene.transferFunction, TF_RESOLUTION);
      this.gridMemo = { key, grid: buildMajorantGrid(ranges, tf, scene.densityScale) };
    }
    return this.gridMemo.grid;
  }

  /** The `gridCells` uniform: cells per axis and the slice atlas's column count. */
  private gridGeometry(scene: Scene): [number, number, number, number] {
    return gridGeometry(scene.volume.dims, this.cellSize(scene));
  }

  /**
   * The parameters for a scene: with `estimator: 'auto'` the environment sampling, tracking,
   * majorant grid and light samples the caller left unset are chosen for it (estimator-choice.ts).
   */
  paramsFor(scene: Scene): ResolvedMcrtParams {
    const m = this.choiceMemo;
    if (m && m.scene === scene && m.params === this.resolved) return this.applyChoice(m.choice);
    let choice: EstimatorChoice | null = null;
    if (this.resolved.estimator === 'auto') {
      const set = this.getParams();
      const given = <T>(v: T | 'auto' | undefined) => (v === 'auto' ? undefined : v);
      choice = chooseEstimator(
        scene,
        {
          tracking: given(set.tracking),
          environmentSampling: given(set.environmentSampling),
          majorantGrid: set.majorantGrid,
          lightSamples: set.lightSamples,
          anisotropy: this.resolved.anisotropy,
          singleScattering: this.resolved.scattering === 'single',
        },
        () => this.gridStats.get(scene, this.resolved.majorantCellSize),
      );
    }
    this.choiceMemo = { scene, params: this.resolved, choice };
    return this.applyChoice(choice);
  }

  private applyChoice(choice: EstimatorChoice | null): ResolvedMcrtParams {
    if (!choice) return this.resolved;
    const { tracking, environmentSampling, majorantGrid, lightSamples } = choice;
    return { ...this.resolved, tracking, environmentSampling, majorantGrid, lightSamples };
  }

  /**
   * What the renderer chose for the last scene it was given (RenderContext.stats.renderer):
   * `estimator` ('auto' or 'fixed'), the tracking, environment sampling, grid and light samples in use,
   * and with 'auto' the reason for each.
   */
  stats(): Record<string, string> {
    const m = this.choiceMemo;
    if (!m) return { estimator: this.resolved.estimator };
    const p = this.applyChoice(m.choice);
    const out: Record<string, string> = {
      estimator: p.estimator,
      tracking: p.tracking,
      environmentSampling: p.environmentSampling,
      majorantGrid: p.majorantGrid ? 'grid' : 'global',
      lightSamples: String(p.lightSamples),
    };
    if (m.choice) for (const [k, reason] of Object.entries(m.choice.reasons)) out[`${k}Reason`] = reason;
    return out;
  }

  /** Majorant-grid cell edge in voxels: the generic kernel always walks a grid, of one cell when the grid is off. */
  private cellSize(scene: Scene): number {
    const p = this.paramsFor(scene);
    return !p.specialize && !p.majorantGrid ? Math.max(...scene.volume.dims) : p.majorantCellSize;
  }

  /** The lat-long map the kernel samples: the scene's, or (generic kernel) a constant sky as a constant map. */
  private environmentMap(scene: Scene): LatLongEnvironment {
    const env = scene.environment;
    if (env.type === 'latlong') return env;
    const key = JSON.stringify(env.radiance);
    if (this.constantMapMemo?.key !== key) {
      const [w, h] = CONSTANT_MAP_SIZE;
      const data = new Float32Array(w * h * 3);
      for (let k = 0; k < w * h; k++) data.set(env.radiance, 3 * k);
      this.constantMapMemo = { key, map: { type: 'latlong', width: w, height: h, data } };
    }
    return this.constantMapMemo.map;
  }

  private environmentTables(env: LatLongEnvironment, key: string): EnvironmentSamplingTables {
    if (this.envMemo?.key !== key) this.envMemo = { key, tables: buildEnvironmentSampling(env) };
    return this.envMemo.tables;
  }
}

const DEFAULT_FEATURES: McrtFeatures = {
  ENV_MAP: false,
  ENV_LIGHT: true,
  LIGHT_COUNT: 0,
  SINGLE_SCATTERING: false,
  LIGHT_SAMPLES: 1,
  MAJORANT_GRID: true,
  TRACKING: 2,
  ENV_SAMPLING: 2,
  MIS_POWER: true,
  DEBUG_OUTPUT: 0,
  GENERIC: false,
  BLUE_NOISE: false,
};

/** A constant sky as a map for the generic kernel: small, since every texel is the same. */
const CONSTANT_MAP_SIZE = [16, 8] as const;
