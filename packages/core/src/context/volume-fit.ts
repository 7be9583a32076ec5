import type { MultiscaleSource } from '../bricking/source.js';
import { VptError } from '../errors.js';
import type { Renderer } from '../renderer.js';
import { downsampleChannels, downsampleVolume, fitFactors } from '../scene/downsample.js';
import type { Scene } from '../scene/scene.js';
import { TF_RESOLUTION } from '../scene/transfer-function.js';
import { enabledChannels } from '../scene/channels.js';
import { channelCount, voxelCount } from '../scene/volume.js';
import type { VolumeOptions } from './context-options.js';
import { sameVoxels, type BrickPlan, type SceneResources } from './scene-resources.js';

/**
 * The GPU memory budget's fit of a scene's volume: each side within the 3D texture limit
 * and the whole within maxGpuBytes, by integer box-average downsampling (scene/downsample.ts)
 * or, with bricking, by a brick atlas with a page table (bricking/); and the multiscale
 * sources that back stand-in volumes (RenderContext.setVolumeSource).
 */

/** Something the context changed to make a scene fit or could not load, reported through onWarning (and console.warn without a listener). */
export type RenderWarning = VolumeDownsampledWarning | BrickLoadWarning;

/** A brick of a streamed volume (setVolumeSource) could not be read; a coarser level keeps serving its region. */
export interface BrickLoadWarning {
  code: 'brick-load-failed';
  message: string;
}

export interface VolumeDownsampledWarning {
  code: 'volume-downsampled';
  message: string;
  /** Integer box-average factors per axis. */
  factors: [number, number, number];
  from: [number, number, number];
  to: [number, number, number];
}

/**
 * Bytes a volume (with its gradient) or a brick atlas may take at this size, renderer and
 * post chain: maxGpuBytes less the render targets (16 bytes a texel: frames, two sets of
 * accumulations, the HDR image, one target per post step) and the transfer function.
 */
export function volumeBudgetBytes(
  maxGpuBytes: number,
  width: number,
  height: number,
  renderer: Pick<Renderer, 'frameFormats' | 'accumulationFormats'>,
  postSteps: number,
): number {
  const pixels = width * height;
  const targetBytes =
    pixels * 16 * (renderer.frameFormats.length + 2 * renderer.accumulationFormats.length + 1 + postSteps);
  return maxGpuBytes - targetBytes - TF_RESOLUTION * 16 * 256;
}

/** The share of maxGpuBytes the render targets may take; the rest is the volume's (maxRenderPixels). */
export const RENDER_TARGET_BUDGET_SHARE = 0.5;

/**
 * The most pixels a render size may have within the GPU memory budget: the render targets
 * (16 bytes a texel: frames with the guide frames when guides are kept, two sets of
 * accumulations, the guides' two, the HDR image, one target per post step) plus the
 * canvas's two 8-bit buffers may take RENDER_TARGET_BUDGET_SHARE of maxGpuBytes.
 */
export function maxRenderPixels(
  maxGpuBytes: number,
  renderer: Pick<Renderer, 'frameFormats' | 'accumulationFormats'>,
  postSteps: number,
  guides: boolean,
): number {
  const accumulation = renderer.accumulationFormats.length;
  const texels =
    renderer.frameFormats.length +
    2 * accumulation +
    1 +
    postSteps +
    (guides ? 2 /* guide frames */ + 2 * 3 /* guide accumulations, 3 targets each */ : 0);
  return Math.max(1, Math.floor((maxGpuBytes * RENDER_TARGET_BUDGET_SHARE) / (16 * texels + 8)));
}

/** What the fit reads of the context at the time of each fit. */
export interface VolumeFitHost {
  readonly resources: Pick<SceneResources, 'planUpload' | 'wantsGradient'>;
  readonly maxGpuBytes: number;
  /** The device's 3D texture limit (maxTextureDimension3D). */
  max3D(): number;
  /** The render size now. */
  size(): { width: number; height: number };
  /** volumeBudgetBytes for the current size, renderer and post chain. */
  budgetBytes(): number;
  /**
   * The scene's label volume as the renderer draws it (null: none, or a renderer that does not
   * draw labels) and its GPU bytes per voxel, with the label support's downsampler.
   */
  labels(
    scene: Scene,
  ): { bytesPerVoxel: number; downsample: (v: Scene['volume'], f: [number, number, number]) => Scene['volume'] } | null;
  warn(warning: RenderWarning): void;
}

export class VolumeFit {
  // The last fit: a scene volume → the volume actually uploaded (itself when it fits).
  // With labels, their source volume and the one uploaded (the same grid's factors, by majority vote).
  private fitted: {
    source: Scene['volume'];
    key: string;
    volume: Scene['volume'];
    bricks: BrickPlan | null;
    labels?: { source: Scene['volume']; volume: Scene['volume'] };
  } | null = null;
  // Volumes backed by a multiscale source (setVolumeSource): the scene's volume is a stand-in.
  private readonly volumeSources = new WeakMap<Scene['volume'], MultiscaleSource>();

  constructor(
    private readonly options: VolumeOptions,
    private readonly host: VolumeFitHost,
  ) {}

  /** The brick plan of the last fit (null: the volume is one texture). */
  get bricks(): BrickPlan | null {
    return this.fitted?.bricks ?? null;
  }

  /** Forget the last fit (the scene it was made for was not kept). */
  forget(): void {
    this.fitted = null;
  }

  /** RenderContext.setVolumeSource: checks the source and remembers it for `standIn`. */
  setVolumeSource(standIn: Scene['volume'], source: MultiscaleSource): void {
    const l = source?.levels;
    const ok =
      Array.isArray(l) &&
      l.length > 0 &&
      l.every(
        (v) =>
          [v.dims, v.spacing, v.origin].every((a) => Array.isArray(a) && a.length === 3 && a.every(Number.isFinite)) &&
          v.dims.every((d) => Number.isInteger(d) && d >= 1) &&
          v.spacing.every((x) => x > 0),
      ) &&
      typeof source.readRegion === 'function';
    if (!ok)
      throw new VptError(
        'invalid-scene',
        'setVolumeSource: the source needs levels (level 0 finest) with positive integer dims, positive spacing, an origin each, and readRegion()',
      );
    if (source.type !== standIn.type)
      throw new VptError(
        'invalid-scene',
        `setVolumeSource: the stand-in volume is ${standIn.type}, the source ${source.type}; they must match`,
      );
    this.volumeSources.set(standIn, source);
  }

  /**
   * The scene with a volume that fits the device: each side within the 3D texture limit and
   * the whole within maxGpuBytes (volume + gradient at this scene's sampling, plus the render
   * targets and the TF); otherwise downsampled by integer box averages (scene/downsample.ts)
   * with a warning naming the factors. The fit is kept per source volume, so setting the same
   * volume again neither recomputes nor warns again.
   */
  fitScene(scene: Scene): Scene {
    const host = this.host;
    const { width, height } = host.size();
    const sampling = scene.sampling ?? this.options.sampling;
    const gradient = host.resources.wantsGradient(scene);
    const channels = scene.channels ? enabledChannels(scene.channels) : undefined;
    // A label volume drawn on the image's grid takes its bytes from the same budget (labels.ts).
    const labels = host.labels(scene);
    const key = `${sampling}|${gradient}|${width}x${height}${channels ? `|channels ${channels.join(',')}` : ''}${labels ? `|labels ${labels.bytesPerVoxel}` : ''}`;
    const f = this.fitted;
    // The last fit holds for these labels too: none then and now, or the same label volume.
    const sameLabels = f !== null && (f.labels?.source ?? null) === (labels ? scene.labels!.volume : null);
    if (f && sameLabels && f.key === key && f.source === scene.volume) {
      return withFitted(scene, f.volume, f.labels);
    }
    if (f && sameLabels && f.key === key && f.bricks && !f.bricks.source && sameVoxels(f.source, scene.volume)) {
      this.fitted = { ...f, source: scene.volume, volume: scene.volume };
      return withFitted(scene, scene.volume, f.labels);
    }
    if (f && sameLabels && f.key === key && sameVoxels(f.source, scene.volume) && f.volume !== f.source) {
      // The same voxels with another value range: keep the downsampled copy, take the new range.
      const volume = { ...f.volume, valueRange: scene.volume.valueRange };
      this.fitted = { source: scene.volume, key, volume, bricks: null, labels: f.labels };
      return withFitted(scene, volume, f.labels);
    }
    // With channels the texture holds every drawn channel, so the budget counts them all.
    const upload = host.resources.planUpload(scene.volume, sampling, channels);
    const imagePerVoxel = upload.bytesPerVoxel + (gradient ? (sampling === 'exact' ? 4 : 2) : 0);
    const perVoxel = imagePerVoxel + (labels?.bytesPerVoxel ?? 0);
    const budget = host.budgetBytes();
    const max3D = host.max3D();
    const from = [...scene.volume.dims] as [number, number, number];
    const factors = fitFactors(from, perVoxel, budget, max3D);
    if (!factors) {
      throw new VptError(
        'limit-exceeded',
        `maxGpuBytes (${host.maxGpuBytes} bytes) leaves no room for a volume next to the ${width} x ${height} render targets`,
      );
    }
    // Bricks instead of a downsampled copy: the full data stays available to the view.
    // A channel scene's TFs are 1D (scene.transferFunction is not drawn); its atlas holds the
    // drawn channels as components (the channel texture's format), so the budget counts them all
    // (at most MAX_BRICKED_CHANNELS = MAX_ENABLED_CHANNELS: validateChannels refuses more).
    const brickable = (channels !== undefined || scene.transferFunction.dimensions !== '2d') && !gradient;
    const source = this.volumeSources.get(scene.volume);
    const bricking = this.options.bricking;
    if (source && (source.channels ?? 1) !== channelCount(scene.volume))
      throw new VptError(
        'invalid-scene',
        `setVolumeSource: the source has ${source.channels ?? 1} channel(s) per voxel (MultiscaleSource.channels), the stand-in volume ${channelCount(scene.volume)}; they must match`,
      );
    if (brickable && (source || bricking === 'force' || (bricking === 'auto' && factors.some((f) => f > 1)))) {
      // Labels beside a brick atlas stay one texture: whole while they fit half the budget,
      // else downsampled to that half; the atlas has what they leave.
      let fittedLabels: { source: Scene['volume']; volume: Scene['volume'] } | undefined;
      let labelBytes = 0;
      if (labels) {
        const lv = scene.labels!.volume;
        const lf = fitFactors(from, labels.bytesPerVoxel, budget / 2, max3D) ?? [1, 1, 1];
        const volume = lf.some((x) => x > 1) ? labels.downsample(lv, lf) : lv;
        if (volume !== lv)
          this.warnDownsampled(
            from,
            lf,
            volume,
            'label volume',
            `${voxelCount(from)} label voxels take more than half of the GPU memory budget of ${host.maxGpuBytes} bytes beside a brick atlas`,
          );
        fittedLabels = { source: lv, volume };
        labelBytes = voxelCount(volume.dims) * labels.bytesPerVoxel;
      }
      const bricks: BrickPlan = {
        capacityBytes: budget - labelBytes,
        brickSize: this.options.brickSize,
        uploadsPerFrame: this.options.brickUploadsPerFrame,
        lod: this.options.brickLod,
        onFailure: (message) => host.warn({ code: 'brick-load-failed', message }),
        ...(source ? { source } : {}),
      };
      const volume = source ? standInWithLevel0Box(scene.volume, source) : scene.volume;
      this.fitted = { source: scene.volume, key, volume, bricks, labels: fittedLabels };
      return withFitted(scene, volume, fittedLabels);
    }
    let volume = scene.volume;
    let fittedLabels = labels ? { source: scene.labels!.volume, volume: scene.labels!.volume } : undefined;
    if (factors.some((f) => f > 1)) {
      volume = channels ? downsampleChannels(scene.volume, factors) : downsampleVolume(scene.volume, factors);
      const over3D = from.some((d) => d > max3D);
      const bytes = labels ? `${imagePerVoxel} + ${labels.bytesPerVoxel} (labels)` : `${perVoxel}`;
      const why = over3D
        ? `a side exceeds this device's 3D texture limit of ${max3D} (maxTextureDimension3D)`
        : `${voxelCount(from)} voxels x ${bytes} bytes${channels ? ` (${channels.length} channels)` : ''} exceed the GPU memory budget of ${host.maxGpuBytes} bytes (maxGpuBytes)`;
      // The label volume lies on the image's grid: the same factors, by majority vote.
      if (labels && fittedLabels)
        fittedLabels = { ...fittedLabels, volume: labels.downsample(fittedLabels.source, factors) };
      this.warnDownsampled(from, factors, volume, labels ? 'Volume and label volume' : 'Volume', why);
    }
    this.fitted = { source: scene.volume, key, volume, bricks: null, labels: fittedLabels };
    return withFitted(scene, volume, fittedLabels);
  }

  private warnDownsampled(
    from: [number, number, number],
    factors: [number, number, number],
    volume: Scene['volume'],
    what: string,
    why: string,
  ): void {
    this.host.warn({
      code: 'volume-downsampled',
      factors,
      from,
      to: [...volume.dims] as [number, number, number],
      message: `${what} [${from.join(', ')}] downsampled by [${factors.join(', ')}] to [${volume.dims.join(', ')}]: ${why}`,
    });
  }
}

/** The scene as fitted: its volume, and its label volume where the fit made one (the table as given). */
function withFitted(
  scene: Scene,
  volume: Scene['volume'],
  labels: { source: Scene['volume']; volume: Scene['volume'] } | undefined,
): Scene {
  const newLabels = labels !== undefined && scene.labels !== undefined && labels.volume !== scene.labels.volume;
  if (volume === scene.volume && !newLabels) return scene;
  const out = { ...scene, volume };
  if (newLabels) out.labels = { ...scene.labels!, volume: labels!.volume };
  return out;
}

/**
 * The stand-in of a streamed volume as the scene renders it: its voxels, with the spacing
 * stretched so that its box is the source's level 0 (a coarser level's box can be a little
 * larger or smaller, its sides rounded to whole voxels), and the source's value range.
 */
function standInWithLevel0Box(standIn: Scene['volume'], source: MultiscaleSource): Scene['volume'] {
  const l0 = source.levels[0];
  const spacing = [0, 1, 2].map((a) => (l0.dims[a] * l0.spacing[a]) / standIn.dims[a]) as [number, number, number];
  const valueRange = source.valueRange ?? standIn.valueRange;
  return { ...standIn, spacing, ...(valueRange ? { valueRange: [valueRange[0], valueRange[1]] } : {}) };
}
