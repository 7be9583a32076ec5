import type { GpuBackend, GpuTexture, PassDescriptor, RenderTarget } from '../gpu/backend.js';
import type { AuxiliaryPass, AuxiliaryTexture, Renderer, VolumeBinding } from '../renderer.js';
import type { Scene } from '../scene/scene.js';
import { rasterizeTransferFunction, TF_RESOLUTION, transferFunctionSize } from '../scene/transfer-function.js';
import {
  channelTextureData,
  planChannelUpload,
  planVolumeUpload,
  uploadsDataAsIs,
  volumeTextureData,
  volumeTextureSlab,
  volumeValueMapping,
  type VolumeSampling,
  type VolumeUpload,
} from '../gpu/volume-format.js';
import { buildGradientVolume, destroyGradientVolume, type GradientVolume } from '../gradient/gradient-volume.js';
import { BrickedVolume, type BrickChannels, type BrickingOptions } from '../bricking/bricked-volume.js';
import { inMemoryMultiscaleSource, type MultiscaleSource } from '../bricking/source.js';
import { channelVolume, interleaveChannels, normalizationRange } from '../scene/volume.js';
import {
  channelNormalizationRange,
  enabledChannels,
  rasterizeChannelTransferFunctions,
  sceneChannelVolume,
  type ChannelSettings,
} from '../scene/channels.js';
import { slicePlaneTextures } from '../scene/slice-plane.js';
import { labelSupport } from '../scene/label-support.js';

/** How RenderContext wants the scene's volume bricked (null: one texture). */
export interface BrickPlan extends BrickingOptions {
  /** Bytes for the atlas, page table and level table. */
  capacityBytes: number;
  /** Where the bricks come from (RenderContext.setVolumeSource); default: levels made from the scene's volume. */
  source?: MultiscaleSource;
  /** Called once per brick whose read failed. */
  onFailure?: (message: string) => void;
}

/**
 * The GPU resources a scene needs beside the renderer's targets, and their lifetimes: the
 * volume texture (in the format of its upload plan, gpu/volume-format.ts; rebuilt when the
 * voxels or the plan change, kept when only the value range does), the transfer function
 * (by content), the gradient-magnitude volume (when a 2D TF or the renderer asks for it,
 * until the volume changes) and the renderer's auxiliary textures (by key). RenderContext
 * owns one and asks it to sync before a frame, to release everything on dispose and to
 * forget the lost handles after a context loss.
 */
export class SceneResources {
  volumeTexture: GpuTexture | null = null;
  /** The brick cache when the volume is bricked (then volumeTexture is its atlas). */
  bricked: BrickedVolume | null = null;
  private brickPlan: BrickPlan | null = null;
  private brickKey = '';
  private volumeSource: Scene['volume'] | null = null;
  volumeUpload: VolumeUpload | null = null;
  private volumeKey = 0; // bumped on every volume upload (VolumeBinding.key)
  /** Volumes written into the texture of the one before (same dims and format) instead of a new texture. */
  volumeRewrites = 0;
  private planMemo: { volume: Scene['volume']; sampling: VolumeSampling; channels: string; plan: VolumeUpload } | null =
    null;
  // The drawn channels of the uploaded texture ('' for a scalar scene): a new selection re-uploads.
  private volumeChannels = '';
  private mappingMemo: {
    volume: Scene['volume'];
    upload: Pick<VolumeUpload, 'decodeScale' | 'decodeOffset'>;
    mapping: { valueScale: number; valueOffset: number };
    channels: Scene['channels'];
  } | null = null;
  private readonly sampling: VolumeSampling;
  private readonly allowHalfFloat: boolean;
  tfTexture: GpuTexture | null = null;
  private tfSource: string | null = null;
  // The volume's gradient magnitude (gradient/), built on the GPU the first time a 2D TF or
  // a renderer with needsGradient asks for it, kept until the volume changes.
  gradient: GradientVolume | null = null;
  private gradientSource: Scene['volume'] | null = null;
  private gradientKey = '';
  // Renderer-declared textures by name; `target` is set for GPU-made ones (AuxiliaryPass).
  readonly auxTextures = new Map<string, AuxEntry>();
  private auxFor: { scene: Scene | null; renderer: Renderer | null; version: number; volumeKey: string } = {
    scene: null,
    renderer: null,
    version: -1,
    volumeKey: '',
  };

  constructor(
    private readonly backend: GpuBackend,
    private readonly current: () => { scene: Scene | null; renderer: Renderer },
    opts: { sampling: VolumeSampling; allowHalfFloat: boolean },
  ) {
    this.sampling = opts.sampling;
    this.allowHalfFloat = opts.allowHalfFloat;
  }

  private get scene(): Scene | null {
    return this.current().scene;
  }
  private get _renderer(): Renderer {
    return this.current().renderer;
  }

  /** The texel → normalized value map of the uploaded volume (scene uniforms valueScale/valueOffset). */
  volumeMapping(scene: Scene): { valueScale: number; valueOffset: number } {
    // Memoized: normalizationRange scans int16/float32 data without a valueRange, and this runs every iteration.
    const upload = this.volumeUpload ?? EXACT_DECODE;
    const m = this.mappingMemo;
    if (m && m.volume === scene.volume && m.upload === upload && m.channels === scene.channels) return m.mapping;
    // A channel scene's scalar mapping is its first drawn channel's (the slice and guides read that one).
    const mapping = scene.channels
      ? channelMappings(scene.volume, scene.channels, upload)[0]
      : volumeValueMapping(scene.volume, upload);
    this.mappingMemo = { volume: scene.volume, upload, mapping, channels: scene.channels };
    return mapping;
  }

  /** The drawn channels' texel → normalized value maps (CHANNEL_UNIFORM_FIELDS), unused components 0. */
  channelMapping(scene: Scene): { channelScale: number[]; channelOffset: number[] } {
    const maps = channelMappings(scene.volume, scene.channels ?? [], this.volumeUpload ?? EXACT_DECODE);
    const channelScale = [0, 0, 0, 0],
      channelOffset = [0, 0, 0, 0];
    maps.forEach((m, k) => {
      channelScale[k] = m.valueScale;
      channelOffset[k] = m.valueOffset;
    });
    return { channelScale, channelOffset };
  }

  /** What auxiliary passes need to read the volume texture's texels (Renderer.auxiliaryTextures). */
  volumeBinding(scene: Scene): VolumeBinding {
    const m = this.volumeMapping(scene);
    const bricked = this.bricked;
    return {
      ...m,
      format: this.volumeUpload?.format ?? 'r32float',
      key: `${this.volumeKey}|${m.valueScale}|${m.valueOffset}${bricked ? `|bricks ${bricked.generation}` : ''}`,
      ...(bricked
        ? {
            cellRanges: (cells: readonly [number, number, number]) => bricked.cellRanges(cells),
            channelCellRanges: (cells: readonly [number, number, number]) => bricked.channelCellRanges(cells),
          }
        : {}),
    };
  }

  brickPlanNow(): BrickPlan | null {
    return this.brickPlan;
  }

  /** Brick the next volumes (RenderContext decides, per scene), or hold them in one texture (null). */
  setBrickPlan(plan: BrickPlan | null): void {
    this.brickPlan = plan;
  }

  /**
   * The brick cache for the scene's volume: kept while the voxels, format, drawn channels and
   * plan stay, else rebuilt empty. A channel scene's bricks hold its drawn channels (the atlas
   * in the channel texture's format); one drawn channel is bricked as the scalar volume holding it.
   */
  private syncBricked(volume: Scene['volume'], upload: VolumeUpload, settings?: readonly ChannelSettings[]): void {
    const plan = this.brickPlan!;
    const key = [
      upload.format,
      upload.filter,
      upload.decodeScale,
      upload.decodeOffset,
      plan.capacityBytes,
      plan.brickSize,
      plan.uploadsPerFrame,
      plan.lod,
      plan.source ? sourceId(plan.source) : 0,
      settings ? JSON.stringify(settings.map((c) => [c.enabled !== false, c.range ?? null])) : '',
    ].join('|');
    if (this.bricked && this.brickKey === key && this.volumeSource && sameVoxels(this.volumeSource, volume)) {
      this.volumeSource = volume;
      return;
    }
    const drawn = settings ? enabledChannels(settings) : null;
    // Each drawn channel's data range mapped to [0, 1] (one drawn channel: the scalar volume holding it).
    const ranges = drawn
      ? drawn.map((c) => channelNormalizationRange(volume, c, settings![c]))
      : [normalizationRange(volume)];
    const range = ranges[0];
    let source = plan.source;
    if (!source) {
      // In memory: the levels of the drawn channels alone (channel by channel box averages).
      const v = !drawn
        ? volume
        : drawn.length === 1
          ? sceneChannelVolume(volume, settings!, drawn[0])
          : interleaveChannels(drawn.map((c) => channelVolume(volume, c)));
      source = inMemoryMultiscaleSource(v, { coarsestSide: plan.brickSize });
    }
    // A multichannel source: the bricks keep the drawn channels (a streamed one holds every channel).
    const channels: BrickChannels | null =
      (source.channels ?? 1) > 1 ? { pick: plan.source ? drawn! : drawn!.map((_, k) => k), ranges } : null;
    // Made before the old volume goes: a VptError here (no room for the coarsest level) changes nothing.
    const bricked = new BrickedVolume(
      this.backend,
      source,
      upload,
      plan.capacityBytes,
      plan,
      range,
      plan.onFailure,
      channels,
    );
    this.dropVolume();
    this.bricked = bricked;
    this.brickKey = key;
    this.volumeTexture = this.bricked.atlas;
    this.volumeSource = volume;
    this.volumeUpload = upload;
    this.volumeKey++;
  }

  private dropVolume(): void {
    if (this.bricked) this.bricked.release();
    else if (this.volumeTexture) this.backend.destroyTexture(this.volumeTexture);
    this.bricked = null;
    this.brickKey = '';
    this.volumeTexture = null;
    this.dropGradient();
  }

  /**
   * The upload plan of a volume, kept per volume, sampling and drawn channels (a uint16 or
   * half-float plan scans the data once); `channels`: the drawn channels of a channel scene.
   */
  planUpload(volume: Scene['volume'], sampling: VolumeSampling, channels?: readonly number[]): VolumeUpload {
    const memo = this.planMemo;
    const key = channels ? channels.join(',') : '';
    // The plan depends on the voxels alone, not on the value range.
    if (memo && sameVoxels(memo.volume, volume) && memo.sampling === sampling && memo.channels === key)
      return memo.plan;
    const opts = { sampling, allowHalfFloat: this.allowHalfFloat };
    const plan = channels
      ? planChannelUpload(volume, this.backend.capabilities, opts, channels)
      : planVolumeUpload(volume, this.backend.capabilities, opts);
    this.planMemo = { volume, sampling, channels: key, plan };
    return plan;
  }

  private samplingOf(scene: Scene): VolumeSampling {
    return scene.sampling ?? this.sampling;
  }

  /**
   * The volume texture: the volume's own array when the format takes it as is, else converted
   * and written in slabs of about 16 M voxels, so a real-size volume never has a full-size
   * converted copy next to it in memory.
   */
  private uploadVolume(volume: Scene['volume'], upload: VolumeUpload, channels: readonly number[] | null): GpuTexture {
    const [width, height, depth] = volume.dims;
    const desc = {
      dimension: '3d' as const,
      width,
      height,
      depth,
      format: upload.format,
      filter: upload.filter,
      label: 'volume',
    };
    // The drawn channels go up in one piece (interleaved into the texture's components).
    if (channels) return this.backend.createTexture({ ...desc, data: channelTextureData(volume, upload, channels) });
    if (uploadsDataAsIs(upload) || width * height * depth <= SLAB_VOXELS)
      return this.backend.createTexture({ ...desc, data: volumeTextureData(volume, upload) });
    const texture = this.backend.createTexture(desc);
    this.writeVolume(texture, volume, upload);
    return texture;
  }

  /** Write a volume's texels into a volume texture of its dims and format, in slabs (see uploadVolume). */
  private writeVolume(texture: GpuTexture, volume: Scene['volume'], upload: VolumeUpload): void {
    const [width, height, depth] = volume.dims;
    if (uploadsDataAsIs(upload) || width * height * depth <= SLAB_VOXELS) {
      this.backend.writeTexture(texture, volumeTextureData(volume, upload));
      return;
    }
    const slabDepth = Math.max(1, Math.floor(SLAB_VOXELS / (width * height)));
    const scratch = new ArrayBuffer(slabDepth * width * height * 4); // one buffer for every slab
    for (let z = 0; z < depth; z += slabDepth) {
      const z1 = Math.min(depth, z + slabDepth);
      this.backend.writeTextureSlices(texture, z, volumeTextureSlab(volume, upload, z, z1, scratch));
    }
  }

  /** Upload the volume and transfer function when they changed (by identity / content). */
  sync(): void {
    const scene = this.scene!;
    const channels = scene.channels ? enabledChannels(scene.channels) : null;
    const channelKey = channels ? channels.join(',') : '';
    const upload = this.planUpload(scene.volume, this.samplingOf(scene), channels ?? undefined);
    if (this.brickPlan) this.syncBricked(scene.volume, upload, scene.channels);
    else if (this.bricked) this.dropVolume();
    let same =
      this.volumeUpload &&
      this.volumeUpload.format === upload.format &&
      this.volumeUpload.filter === upload.filter &&
      this.volumeUpload.decodeScale === upload.decodeScale &&
      this.volumeUpload.decodeOffset === upload.decodeOffset;
    if (
      !this.bricked &&
      this.volumeTexture &&
      same &&
      this.volumeChannels === channelKey &&
      this.volumeSource !== scene.volume &&
      sameVoxels(this.volumeSource!, scene.volume)
    ) {
      // Only the value range (or name) changed: the kernels map it, so nothing is uploaded;
      // the gradient volume and the majorant grid follow through their keys.
      this.volumeSource = scene.volume;
      this.dropGradient();
    }
    const t = this.volumeTexture;
    if (
      !this.bricked &&
      t &&
      // Scalar volumes only: a channel texture is written from its drawn channels at upload.
      channelKey === '' &&
      this.volumeChannels === '' &&
      this.volumeSource !== scene.volume &&
      this.volumeUpload?.format === upload.format &&
      this.volumeUpload.filter === upload.filter &&
      t.width === scene.volume.dims[0] &&
      t.height === scene.volume.dims[1] &&
      t.depth === scene.volume.dims[2]
    ) {
      // Another volume of the same grid and format (the next step of a time series): its
      // texels are written into the texture there is, with no new allocation.
      this.writeVolume(t, scene.volume, upload);
      this.dropGradient();
      this.volumeSource = scene.volume;
      this.volumeUpload = upload;
      this.volumeKey++;
      this.volumeRewrites++;
      same = true;
    }
    if (
      !this.bricked &&
      (this.volumeSource !== scene.volume || !this.volumeTexture || !same || this.volumeChannels !== channelKey)
    ) {
      this.dropVolume();
      this.volumeTexture = this.uploadVolume(scene.volume, upload, channels);
      this.volumeChannels = channelKey;
      this.volumeSource = scene.volume;
      this.volumeUpload = upload;
      this.volumeKey++;
    }
    const tfKey = JSON.stringify(scene.channels ?? scene.transferFunction);
    if (this.tfSource !== tfKey || !this.tfTexture) {
      // A channel scene: one row per drawn channel (scene/channels.ts).
      const data = scene.channels
        ? rasterizeChannelTransferFunctions(scene.channels, TF_RESOLUTION)
        : rasterizeTransferFunction(scene.transferFunction, TF_RESOLUTION);
      const [width, height] = scene.channels
        ? [TF_RESOLUTION, channels!.length]
        : transferFunctionSize(scene.transferFunction, TF_RESOLUTION);
      if (this.tfTexture && (this.tfTexture.width !== width || this.tfTexture.height !== height)) {
        this.backend.destroyTexture(this.tfTexture);
        this.tfTexture = null;
      }
      if (this.tfTexture) this.backend.writeTexture(this.tfTexture, data);
      else
        this.tfTexture = this.backend.createTexture({
          dimension: '2d',
          width,
          height,
          format: 'rgba32float',
          data,
          label: 'transfer function',
        });
      this.tfSource = tfKey;
    }
    this.syncGradient();
  }

  /** A 2D transfer function reads the gradient magnitude, and so does a renderer that asks for it. */
  wantsGradient(scene: Scene): boolean {
    // A channel scene's TFs are 1D (scene.transferFunction is not drawn).
    if (scene.channels) return this._renderer.needsGradient === true;
    return scene.transferFunction.dimensions === '2d' || this._renderer.needsGradient === true;
  }

  /** Build the gradient-magnitude volume when the scene first needs it (GPU passes, no read-back). */
  syncGradient(): void {
    const scene = this.scene!;
    if (!this.wantsGradient(scene) || !this.volumeTexture || this.backend.isLost) return;
    if (this.gradient && this.gradientSource === scene.volume && this.gradientKey === this.volumeBinding(scene).key)
      return;
    this.dropGradient();
    this.gradient = buildGradientVolume(this.backend, this.volumeTexture, scene.volume, this.gradientOptions(scene));
    this.gradientSource = scene.volume;
    this.gradientKey = this.volumeBinding(scene).key;
  }

  /** The gradient build reads texels through the scene's mapping; 16 bits on the fast path. */
  private gradientOptions(scene: Scene) {
    return {
      ...this.volumeMapping(scene),
      format: this.samplingOf(scene) === 'exact' ? ('r32float' as const) : ('r16float' as const),
    };
  }

  dropGradient(): void {
    if (this.gradient) destroyGradientVolume(this.backend, this.gradient);
    this.gradient = null;
    this.gradientSource = null;
    this.gradientKey = '';
  }

  /** The gradient volume of the current scene, built now if the scene had not needed it yet. */
  ensureGradient(): GradientVolume {
    const scene = this.scene!;
    if (!this.gradient || this.gradientSource !== scene.volume || this.gradientKey !== this.volumeBinding(scene).key) {
      this.dropGradient();
      this.gradient = buildGradientVolume(this.backend, this.volumeTexture!, scene.volume, this.gradientOptions(scene));
      this.gradientSource = scene.volume;
      this.gradientKey = this.volumeBinding(scene).key;
    }
    return this.gradient;
  }

  /** The renderer's auxiliary textures for the current scene, as declared (nothing is built). */
  auxiliarySpecs(binding: VolumeBinding = this.volumeBinding(this.scene!)): readonly AuxiliaryTexture[] {
    const scene = this.scene!;
    const r = this._renderer;
    return [
      ...(r.auxiliaryTextures?.(scene, binding) ?? []),
      // A slice plane's colour map, for the renderers that draw one (Renderer.drawsSlicePlane).
      ...(scene.slicePlane && r.drawsSlicePlane ? slicePlaneTextures(scene.slicePlane) : []),
      // A label volume and its table, for the renderers that draw labels (Renderer.drawsLabels).
      ...(scene.labels && r.drawsLabels ? labelSupport().labelTextures(scene.labels, this.backend.capabilities) : []),
    ];
  }

  /** The passes syncAuxiliaryTextures would run for these specs (those not built with the same key). */
  auxiliaryPassDescriptors(specs: readonly AuxiliaryTexture[]): PassDescriptor[] {
    return specs
      .filter((spec) => spec.render && spec.dimension === '2d' && this.auxTextures.get(spec.name)?.key !== spec.key)
      .map((spec) => auxPassDescriptor(spec.render!));
  }

  /** Build, reuse or free the renderer's auxiliary textures (only when scene or renderer changed). */
  syncAuxiliaryTextures(): void {
    const r = this._renderer;
    // A bricked volume's residency changes its binding (key, cell ranges) without a new scene.
    const binding = this.volumeBinding(this.scene!);
    if (
      this.auxFor.scene === this.scene &&
      this.auxFor.renderer === r &&
      this.auxFor.version === r.version &&
      this.auxFor.volumeKey === binding.key
    )
      return;
    const specs = this.auxiliarySpecs(binding);
    const wanted = new Set(specs.map((a) => a.name));
    for (const [name, aux] of this.auxTextures) {
      if (!wanted.has(name)) {
        this.releaseAux(aux);
        this.auxTextures.delete(name);
      }
    }
    for (const spec of specs) {
      const have = this.auxTextures.get(spec.name);
      if (have && have.key === spec.key) {
        // Same content; whether it is bound is the current renderer's choice (EAM builds
        // majorantRanges as an input only, MIP binds the same texture).
        have.bind = spec.bind !== false;
        continue;
      }
      if (have) {
        this.releaseAux(have);
        this.auxTextures.delete(spec.name);
      }
      this.auxTextures.set(
        spec.name,
        spec.render
          ? this.renderAux(spec, spec.render)
          : {
              key: spec.key,
              texture: this.backend.createTexture(this.auxDescriptor(spec)),
              dimension: spec.dimension,
              bind: spec.bind !== false,
            },
      );
    }
    this.auxFor = { scene: this.scene, renderer: r, version: r.version, volumeKey: binding.key };
  }

  private auxDescriptor(spec: AuxiliaryTexture) {
    if (!spec.create) throw new RangeError(`auxiliary texture "${spec.name}" has neither create() nor render`);
    return spec.create();
  }

  /** Run an AuxiliaryPass into a new 2D target, reading the scene's textures and earlier auxiliary ones. */
  private renderAux(spec: AuxiliaryTexture, p: AuxiliaryPass): AuxEntry {
    if (spec.dimension !== '2d') throw new RangeError(`auxiliary texture "${spec.name}": a GPU-made texture is 2D`);
    const textures: Record<string, GpuTexture> = {};
    for (const b of p.inputs) {
      const t =
        b.name === 'volume'
          ? this.volumeTexture
          : b.name === 'transferFunction'
            ? this.tfTexture
            : this.auxTextures.get(b.name)?.texture;
      if (!t)
        throw new RangeError(
          `auxiliary pass "${p.label}" reads "${b.name}", which is not the volume, the transfer function or an earlier auxiliary texture`,
        );
      textures[b.name] = t;
    }
    const pass = this.backend.createPass(auxPassDescriptor(p));
    const target = this.backend.createRenderTarget(p.width, p.height, [p.format], p.label);
    this.backend.draw(pass, { uniforms: p.uniforms.pack(p.values), textures, target });
    return { key: spec.key, texture: target.textures[0], dimension: '2d', target, bind: spec.bind !== false };
  }

  releaseAux(aux: AuxEntry): void {
    if (aux.target) this.backend.destroyRenderTarget(aux.target);
    else this.backend.destroyTexture(aux.texture);
  }

  /** Destroy every texture (dispose, or before rebuilding all). */
  release(): void {
    this.dropVolume();
    if (this.tfTexture) this.backend.destroyTexture(this.tfTexture);
    this.volumeTexture = null;
    this.tfTexture = null;
    this.dropGradient();
    this.auxTextures.forEach((a) => this.releaseAux(a));
    this.auxTextures.clear();
    this.auxFor = { scene: null, renderer: null, version: -1, volumeKey: '' };
  }

  /** After a context/device loss: the old handles belong to the lost context; forget them without calling destroy. */
  forget(): void {
    this.bricked?.release(false);
    this.bricked = null;
    this.brickKey = '';
    this.volumeTexture = null;
    this.volumeSource = null;
    this.tfTexture = null;
    this.tfSource = null;
    this.gradient = null;
    this.gradientSource = null;
    this.gradientKey = '';
    this.volumeUpload = null;
    this.volumeChannels = '';
    this.planMemo = null;
    this.auxTextures.clear();
    this.auxFor = { scene: null, renderer: null, version: -1, volumeKey: '' };
  }
}

function auxPassDescriptor(p: AuxiliaryPass): PassDescriptor {
  return { label: p.label, glsl: p.glsl, wgsl: p.wgsl, uniforms: p.uniforms, textures: p.inputs, outputs: [p.format] };
}

export interface AuxEntry {
  key: string;
  texture: GpuTexture;
  dimension: '2d' | '3d';
  /** Bound to the generate pass (AuxiliaryTexture.bind). */
  bind: boolean;
  /** The render target a GPU-made texture lives in (destroyed with it). */
  target?: RenderTarget;
}

const EXACT_DECODE = { decodeScale: 1, decodeOffset: 0 };

/** Per drawn channel, its texel → normalized value map: its own range, else the volume's rule for its data. */
export function channelMappings(
  volume: Scene['volume'],
  channels: readonly ChannelSettings[],
  upload: Pick<VolumeUpload, 'decodeScale' | 'decodeOffset'>,
): { valueScale: number; valueOffset: number }[] {
  return enabledChannels(channels).map((c) => volumeValueMapping(channelVolume(volume, c, channels[c].range), upload));
}
/** Voxels per converted upload slab (32 MiB of r16float, 64 MiB of r32float). */
const SLAB_VOXELS = 1 << 24;

/** Two volumes with the same voxels (the same array, dims and type): they differ at most in value range or name. */
export function sameVoxels(a: Scene['volume'], b: Scene['volume']): boolean {
  return a.data === b.data && a.type === b.type && a.dims.every((d, i) => d === b.dims[i]);
}

const sourceIds = new WeakMap<MultiscaleSource, number>();
let nextSourceId = 1;
function sourceId(source: MultiscaleSource): number {
  let id = sourceIds.get(source);
  if (id === undefined) sourceIds.set(source, (id = nextSourceId++));
  return id;
}
