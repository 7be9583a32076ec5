/**
 * `<vpt-viewer>`: a progressive volume renderer as one HTML element.
 *
 * Attributes (all reflected, all also properties): src, renderer, backend,
 * transfer-function, camera, clip, lights, environment, exposure, tone-mapper, denoise, temporal,
 * max-samples, target-error, density-scale, seed, renderer-params, resolution-scale, panels,
 * collapsed, hide-progress, hide-stats, layout, labels (with the `labelTable` property).
 * Events (typed through HTMLElementEventMap, prefixed so none collides with a native
 * event): vpt-load, vpt-progress (loading and refinement), vpt-converged, vpt-error,
 * vpt-change (the user edited something through the element: camera drag, panels),
 * vpt-hover (the label under the pointer changed: labels-layer.ts).
 *
 * Async work (loading a renderer package, a volume, an environment image, opening a GPU
 * context) runs in the background and applies the *current* attribute values when it
 * completes, so attributes can be set in any order at any time. Everything else applies
 * synchronously after Lit's update, and only a change of the image resets accumulation.
 */
import { LitElement, adoptStyles, html, nothing, type PropertyValues } from 'lit';
import {
  DEFAULT_RENDERER_NAME,
  hasClip,
  isVptError,
  VptError,
  type Camera,
  type Clip,
  type Environment,
  type LabelEntry,
  type Light,
  MAX_CLIP_PLANES,
  type Renderer,
  type RequestPolicy,
  type Scene,
  type SceneSlicePlane,
  type TransferFunction,
  type Volume,
  volumeBox,
} from '@vpt/core';
import { DenoiseStep, defaultPostChain, type ToneMapOperator } from '@vpt/post';
import { AdaptiveResolution } from './adaptive-resolution.js';
import {
  AttributeValidator,
  hasChanged,
  isFittedPreset,
  jsonConverter,
  parseCamera,
  parseClip,
  parseEnvironment,
  parseLights,
  parseRendererParams,
  parseSlicePlane,
  parseTransferFunction,
  type Crosshair3D,
  sameValue,
  type BackendName,
  type CheckedProperty,
  type DenoiseMode,
  type TemporalMode,
  type EnvironmentValue,
} from './attributes.js';
import { fitCamera } from './camera-fit.js';
import { CLIP_AXES, clipControls, clipFromControls, type ClipAxis } from './clip-model.js';
import { webglSlots, type SlotHolder } from './context-slots.js';
import { autoTransferFunction, defaultRendererParams, rendererLook } from './defaults.js';
import { download, encodeExr, encodePfm, encodePngBlob } from './export.js';
import { gradientSamples, valueHistogram, type GradientSamples, type Histogram1D } from './histogram.js';
import type { ViewerLoadDetail, ViewerProgressDetail } from './loading/load-events.js';
import type { LoadedVolumeLike, ViewerChannel, VolumeSource } from './loading/types.js';
import { VolumeLoading, type DataLevel } from './loading/volume-loading.js';
import { LazyOrbitCamera } from './orbit-lazy.js';
import type { TimePlayer } from './time-player.js';
import type { HoveredLabel, LabelLayer } from './labels-layer.js';
import { PANEL_NAMES, type InternalProperty, type PanelHost, type PanelName, type PanelState } from './panel-host.js';
import { DEFAULT_TRANSFER_FUNCTION, transferFunctionPreset } from './presets.js';
import { createRenderer, rendererEntry } from './renderer-registry.js';
import { RenderSession, type RefinementStats } from './session.js';
import {
  canvasPlacement,
  dataExtent,
  defaultWindow,
  paneGeometries,
  probeValue,
  screenPoint,
  sliceAspect,
  SlicePane,
  VIEWER_LAYOUTS,
  voxelAt,
  type PaneGeometry,
  type PaneName,
  type ViewerLayout,
  type Voxel,
} from './slice-panes.js';
import { viewerStyles } from './styles.js';

export type { ViewerLoadDetail, ViewerProgressDetail } from './loading/load-events.js';
export type { HoveredLabel, ViewerHoverDetail } from './labels-layer.js';

export interface ViewerErrorDetail {
  /** The typed error (a VptError: `code`, and `reason` for load failures). */
  error: VptError;
  code: VptError['code'];
  message: string;
  /** What failed: the volume, the renderer, the environment image, the GPU context, or an attribute value. */
  source: 'src' | 'labels' | 'renderer' | 'environment' | 'context' | 'attribute' | 'export';
}
export type ViewerConvergedDetail = RefinementStats & { reason: 'max-samples' | 'target-error' };
/**
 * `vpt-change`: the user changed `property` through the element (a panel, a camera drag);
 * `value` is its new value. A clip change (the Clip panel) carries the Clip object, or null
 * when nothing is cut any more.
 */
export type ViewerChangeDetail =
  | { property: 'clip'; value: Clip | null }
  /** The linked crosshair of the slice panes moved (a click, a tap or the wheel): its voxel index [i, j, k]. */
  | { property: 'crosshair'; value: Voxel }
  /** The slice panes' window [center, width] in data units changed (right-drag). */
  | { property: 'window'; value: [number, number] }
  /** The time step shown changed (the `time` property, or playback): its index. */
  | { property: 'time'; value: number }
  /** The Labels panel changed the label table (a colour, a visibility): the new table. */
  | { property: 'labelTable'; value: LabelEntry[] }
  | { property: Exclude<InternalProperty, 'clip' | 'labelTable'>; value: unknown };

/** What the value probe reads under the pointer in a slice pane: the voxel and its raw value in data units. */
export interface ProbeReading {
  pane: PaneName;
  index: Voxel;
  value: number;
}

/**
 * The panels' templates (panels.ts), loaded when an element first shows panels: a lazy chunk
 * of the one-file bundle, so a page with `panels="none"` never loads them.
 */
let panelsModule: typeof import('./panels.js') | null = null;
let panelsLoading: Promise<unknown> | null = null;
function loadPanels(): Promise<unknown> {
  panelsLoading ??= import('./panels.js').then((m) => {
    panelsModule = m;
  });
  return panelsLoading;
}

/** attributeErrorKey when the scene the attributes made was refused (no one attribute's parse failed). */
const SCENE_ERROR = '(scene)';

/** Below a sidebar's width plus this much image, the panels become an overlay. */
const NARROW_MIN_IMAGE_PX = 320;

/** Fields whose change goes straight to the GPU scene/post/stopping (no async work). */
const SYNC_FIELDS = [
  'transferFunction',
  'camera',
  'clip',
  'slicePlane',
  'crosshair3d',
  'crosshairPane',
  'lights',
  'densityScale',
  'seed',
  'exposure',
  'toneMapper',
  'denoise',
  'temporal',
  'maxSamples',
  'targetError',
  'resolutionScale',
] as const;

export class VptViewer extends LitElement implements PanelHost, SlotHolder {
  static override styles = viewerStyles;

  static override properties = {
    src: { type: String, reflect: true },
    renderer: { type: String, reflect: true },
    backend: { type: String, reflect: true },
    transferFunction: {
      attribute: 'transfer-function',
      reflect: true,
      converter: jsonConverter(parseTransferFunction, isFittedPreset),
      hasChanged,
    },
    camera: { reflect: true, converter: jsonConverter(parseCamera), hasChanged },
    clip: { reflect: true, converter: jsonConverter(parseClip), hasChanged },
    slicePlane: { attribute: 'slice-plane', reflect: true, converter: jsonConverter(parseSlicePlane), hasChanged },
    crosshair3d: { attribute: 'crosshair-3d', type: String, reflect: true },
    crosshairPane: { attribute: 'crosshair-pane', type: String, reflect: true },
    lights: { reflect: true, converter: jsonConverter(parseLights), hasChanged },
    environment: { reflect: true, converter: jsonConverter(parseEnvironment), hasChanged },
    exposure: { type: Number, reflect: true },
    toneMapper: { attribute: 'tone-mapper', type: String, reflect: true },
    denoise: { type: String, reflect: true },
    temporal: { type: String, reflect: true },
    maxSamples: { attribute: 'max-samples', type: Number, reflect: true },
    targetError: { attribute: 'target-error', type: Number, reflect: true },
    densityScale: { attribute: 'density-scale', type: Number, reflect: true },
    seed: { type: Number, reflect: true },
    rendererParams: {
      attribute: 'renderer-params',
      reflect: true,
      converter: jsonConverter(parseRendererParams),
      hasChanged,
    },
    resolutionScale: { attribute: 'resolution-scale', type: Number, reflect: true },
    panels: { type: String, reflect: true },
    collapsed: { type: Boolean, reflect: true },
    hideProgress: { attribute: 'hide-progress', type: Boolean, reflect: true },
    hideStats: { attribute: 'hide-stats', type: Boolean, reflect: true },
    layout: { type: String, reflect: true },
    time: { type: Number, reflect: true },
    fps: { type: Number, reflect: true },
    playing: { type: Boolean, reflect: true },
    labels: { type: String, reflect: true },
    _labelTable: { state: true },
    _crosshair: { state: true },
    _window: { state: true },
    _probe: { state: true },
    _paneSizes: { state: true },
    _loading: { state: true },
    _narrow: { state: true },
    _overlayOpen: { state: true },
    _error: { state: true },
    _status: { state: true },
    _lost: { state: true },
    _lostGaveUp: { state: true },
    _stats: { state: true },
    _histogram: { state: true },
    _dataLevel: { state: true },
    _dragOver: { state: true },
    _parked: { state: true },
  };

  /**
   * URL of the volume (any format @vpt/loaders reads; a JSON sidecar; or `procedural:blob?size=64`).
   * Several URLs separated by whitespace (files of one grid): a time series, step i file i.
   */
  declare src: string | null;
  /** mip | iso | eam | mcrt, or any name added with registerRenderer(). */
  declare renderer: string;
  declare backend: BackendName;
  /** A preset name or JSON as attribute; the TransferFunction object as property (a string is parsed). */
  declare transferFunction: TransferFunction | string | null;
  /** null: framed automatically when a volume loads. */
  declare camera: Camera | string | null;
  /**
   * Clip planes and a crop box, the scene file's `clip` JSON (world units of the volume box:
   * centred at 0, longest side 1); null: nothing is cut. The Clip panel edits it.
   */
  declare clip: Clip | string | null;
  /**
   * A slice shown in the 3D view as an opaque, unlit plane (the scene file's `slicePlane` JSON:
   * axis + index/position or normal + point, window in data units, colormap); null: none.
   */
  declare slicePlane: SceneSlicePlane | string | null;
  /**
   * What a crosshair move in the slice panes does to the 3D view: 'none' (default), 'slice' (its
   * slice plane follows the `crosshair-pane` pane's plane, windowed as the panes) or 'clip' (a clip
   * plane there removes the side of higher index along that pane's axis).
   */
  declare crosshair3d: Crosshair3D;
  /** The pane whose plane the 3D view follows under `crosshair-3d` (default 'axial'). */
  declare crosshairPane: PaneName;
  declare lights: Light[] | string | null;
  declare environment: EnvironmentValue | string | null;
  /** Exposure in stops (applied before tone mapping). */
  declare exposure: number;
  declare toneMapper: ToneMapOperator;
  /** 'auto' (default): denoise while refining, show the plain estimate once converged; 'on'; 'off'. */
  declare denoise: DenoiseMode;
  /**
   * 'on' (default): on a camera move the image is reprojected into the new view and blended with
   * the new samples as a fading history (RenderContext temporal reuse); 'off': every move restarts.
   */
  declare temporal: TemporalMode;
  /** Refinement stops at this many samples per pixel. */
  declare maxSamples: number;
  /** Refinement stops when the estimated relative RMSE falls below this (0: off; needs a renderer with half accumulations). */
  declare targetError: number;
  /** Extinction per world unit at opacity 1; null: the renderer's default for the automatic transfer function. */
  declare densityScale: number | null;
  declare seed: number;
  declare rendererParams: Record<string, unknown> | string | null;
  /** Render resolution relative to the element's device pixels (1 = full). */
  declare resolutionScale: number;
  /** "all", "none", or a space-separated list of tf channels lights clip labels quality stats export. */
  declare panels: string;
  /** Panels sidebar closed (the toolbar button opens it). */
  declare collapsed: boolean;
  /** No progress bar on the image. */
  declare hideProgress: boolean;
  /** No stats line on the image. */
  declare hideStats: boolean;
  /** '3d' (default): the rendering alone; 'slices': axial, coronal and sagittal panes; 'quad': those and the 3D view. */
  declare layout: ViewerLayout;
  /** The time step shown of a time series (a 4D NIfTI, an OME-Zarr `t` axis); ignored for one volume. */
  declare time: number;
  /** Time steps per second while `playing`. */
  declare fps: number;
  /** Play the time series, looping (`play()`, `pause()`). */
  declare playing: boolean;
  /** The page's (or the Channels panel's) channel settings, over the defaults (channels.ts); a new source drops them. */
  private userChannels: Partial<ViewerChannel>[] | null = null;
  /**
   * Per channel of a multichannel volume: colour, enabled, transfer function, range (null for
   * one channel). Reading gives every channel's current settings, defaults filled in; setting
   * entries (missing fields and channels keep their defaults, null: all defaults) re-renders.
   */
  get channels(): ViewerChannel[] | null {
    return this.volume?.multichannel?.resolve(this.userChannels) ?? null;
  }
  set channels(value: Partial<ViewerChannel>[] | null) {
    try {
      this.volume?.multichannel?.check(value, this.effectiveDensityScale());
    } catch (e) {
      this.fail(e, 'attribute');
      return;
    }
    this.userChannels = value;
    this.applySync();
    this.requestUpdate();
  }
  /**
   * URL of a label volume (a segmentation: integer ids, 0 = background) on the grid of `src`, in
   * any format `src` takes, drawn with `labelTable`; null: none. Its code is a lazy chunk.
   */
  declare labels: string | null;
  /** The table set (by the page or the Labels panel) and the `labels` URL it was set for. */
  declare private _labelTable: [LabelEntry[] | null, string | null];
  private lab: LabelLayer | null = null;
  /** The time series player, loaded with the first series (time-player.ts, a lazy chunk). */
  private player: TimePlayer | null = null;
  declare private _crosshair: Voxel | null;
  declare private _window: [number, number] | null;
  declare private _probe: ProbeReading | null;
  declare private _paneSizes: Partial<Record<PaneName, { width: number; height: number }>>;
  /** Loading progress in [0, 1] (null: not loading; NaN: size unknown). */
  declare private _loading: number | null;
  /** The element is too narrow for panels beside the image: they become an overlay. */
  declare private _narrow: boolean;
  declare private _overlayOpen: boolean;

  declare private _error: ViewerErrorDetail | null;
  declare private _status: string;
  declare private _lost: boolean;
  /** The lost context did not come back within contextRestoreTimeoutMs: `error` fired, Retry offered. */
  declare private _lostGaveUp: boolean;
  /** How long a lost GPU context may take to be restored before `error` (code `context-lost`) fires. */
  contextRestoreTimeoutMs = 10_000;
  /**
   * The GPU memory budget in bytes (RenderContextOptions.maxGpuBytes), read when the context
   * opens; undefined: the context's default. It decides which levels of a multiscale store fit.
   */
  maxGpuBytes: number | undefined = undefined;
  /**
   * Bounds on every URL the element fetches (volumes, sidecars, environments, OME-Zarr):
   * core's RequestPolicy overrides, read when a load starts; {}: DEFAULT_REQUEST_POLICY.
   */
  requestPolicy: Partial<RequestPolicy> = {};
  private lostTimer: ReturnType<typeof setTimeout> | undefined;
  declare private _stats: RefinementStats | null;
  declare private _histogram: Histogram1D | null;
  declare private _dragOver: boolean;
  /** The WebGL 2 context was released for another viewer's (context-slots.ts): a still of the image shows until a slot is free. */
  declare private _parked: boolean;
  /** On screen, as an IntersectionObserver last said (true until it says otherwise). */
  private onScreen = true;
  private visibilityObserver: IntersectionObserver | null = null;
  /** Whether this element holds (or reserved) one of the page's WebGL 2 slots. */
  private holdsSlot = false;
  /** A multiscale volume's levels: shown, how many, the one that fits the budget, the one loading (null: none). */
  declare private _dataLevel: DataLevel | null;
  /** Loading src: one volume, or a multiscale store level by level (loading/volume-loading.ts). */
  private readonly volumeLoading: VolumeLoading;

  private session: RenderSession | null = null;
  private canvas: HTMLCanvasElement | null = null;
  private rendererInstance: Renderer | null = null;
  private rendererKey = '';
  private volume: LoadedVolumeLike | null = null;
  private loadedSource: VolumeSource | null = null;
  /** The environment attribute's value once loaded (a URL becomes a lat-long image); null: the renderer's default. */
  private resolvedEnvironment: Environment | null = null;
  /** The transfer function fitted to the loaded volume's histogram (used while transfer-function is unset). */
  private autoTransferFunction: TransferFunction | null = null;
  /** The camera the default lights are placed for (the framing camera when the volume loaded). */
  private lightCamera: Camera | null = null;
  private readonly orbit: LazyOrbitCamera;
  private cameraIsAuto = true;
  private homeCamera: Camera | null = null;
  private internalChange = new Set<string>();
  private readonly resolution = new AdaptiveResolution(this, () => this.applySize());
  private readonly validator: AttributeValidator;
  private pending = new Set<Promise<unknown>>();
  private tokens = { session: 0, renderer: 0, environment: 0 };
  private postKey = '';
  // The chain's denoise step, when the denoise mode and the renderer want one (makePost).
  private denoiseStep: DenoiseStep | null = null;
  private connected = false;

  constructor() {
    super();
    this.src = null;
    this.renderer = DEFAULT_RENDERER_NAME;
    this.backend = 'auto';
    this.transferFunction = null;
    this.camera = null;
    this.clip = null;
    this.slicePlane = null;
    this.crosshair3d = 'none';
    this.crosshairPane = 'axial';
    this.lights = null;
    this.environment = null;
    this.exposure = 0;
    this.toneMapper = 'aces';
    this.denoise = 'auto';
    this.temporal = 'on';
    this.maxSamples = 1024;
    this.targetError = 0;
    this.densityScale = null;
    this.seed = 1;
    this.rendererParams = null;
    this.resolutionScale = 1;
    this.panels = 'all';
    this.collapsed = false;
    this.hideProgress = false;
    this.hideStats = false;
    this.layout = '3d';
    this.time = 0;
    this.fps = 10;
    this.playing = false;
    this.labels = null;
    this._labelTable = [null, null];
    this._crosshair = null;
    this._window = null;
    this._probe = null;
    this._paneSizes = {};
    this._loading = null;
    this._narrow = false;
    this._overlayOpen = false;
    this._error = null;
    this._status = '';
    this._dataLevel = null;
    this._lost = false;
    this._lostGaveUp = false;
    this._stats = null;
    this._histogram = null;
    this._dragOver = false;
    this._parked = false;
    this.validator = new AttributeValidator(this as unknown as Record<CheckedProperty, unknown>);
    this.orbit = new LazyOrbitCamera({
      start: () => {
        /* a click without movement must not drop resolution: see change */
      },
      change: (camera) => this.onUserCamera(camera),
      end: () => this.resolution.interactionEnded(),
    });
    this.volumeLoading = new VolumeLoading({
      session: () => this.session,
      opening: () => this.opening,
      volume: () => this.volume,
      setStatus: (status) => {
        this._status = status;
      },
      setLoading: (loading) => {
        this._loading = loading;
      },
      dataLevel: () => this._dataLevel,
      setDataLevel: (level) => {
        this._dataLevel = level;
      },
      applyVolume: (volume, source, level) => this.applyVolume(volume, source, level),
      fail: (e) => this.fail(e, 'src'),
      dispatchEvent: (event) => this.dispatchEvent(event),
      requestUpdate: () => this.requestUpdate(),
      requestPolicy: () => this.requestPolicy,
    });
  }

  // ——— public API ———

  /** The RenderContext (null until the GPU context is open): stats, readHDR/readLDR, estimateError… */
  get context() {
    return this.session?.ctx ?? null;
  }
  /** Samples per pixel accumulated for the current image. */
  get samples(): number {
    return this.session?.samples ?? 0;
  }
  /** The latest refinement numbers (samples, ms per iteration, estimated error, render size). */
  get stats(): RefinementStats | null {
    return this._stats;
  }
  /** The volume on display. */
  get loadedVolume(): LoadedVolumeLike | null {
    return this.volume;
  }
  /** Whether the current image has reached max-samples or target-error. */
  get converged(): boolean {
    return this.session?.isConverged ?? false;
  }

  /**
   * The label table (core's LabelEntry per id: name, linear RGB color, opacity, visible): set it
   * after `labels`; until then (and for a new `labels` file) the file's own (names and colours
   * where it has them, else the tab20 palette). The Labels panel edits it (`vpt-change`).
   */
  get labelTable(): LabelEntry[] | null {
    const [table, url] = this._labelTable;
    return (url === this.labels && table) || (this.lab?.table ?? null);
  }
  set labelTable(table: LabelEntry[] | null) {
    this._labelTable = [table, this.labels];
  }
  /** The label under the pointer (the first visible one on the pixel's ray; the slice's voxel), null: none. */
  get hoveredLabel(): HoveredLabel | null {
    return this.lab?.hovered ?? null;
  }

  /** The slice panes' linked crosshair, a voxel index [i, j, k] (null before a volume is loaded). */
  get crosshair(): Voxel | null {
    return this._crosshair ? [...this._crosshair] : null;
  }
  set crosshair(voxel: Voxel | null) {
    this._crosshair = voxel && this.volume ? this.clampVoxel(voxel) : null;
  }
  /** The slice panes' window [center, width] in data units (null before a volume is loaded). */
  get sliceWindow(): [number, number] | null {
    return this._window ? [...this._window] : null;
  }
  set sliceWindow(window: [number, number] | null) {
    this._window = window && window[1] > 0 && window.every(Number.isFinite) ? [window[0], window[1]] : null;
  }
  /** The value probe's reading under the pointer (null: the pointer is over no slice pane). */
  get probeReading(): ProbeReading | null {
    return this._probe;
  }
  /** A slice pane's RenderContext (null in layout "3d" or before it opens): readHDR/readLDR of the pane. */
  paneContext(name: PaneName) {
    return this.slicePanes.get(name)?.context ?? null;
  }
  /** The raw data value of a voxel of the loaded volume, in data units (what the probe shows). */
  probe(voxel: Voxel): number | null {
    return this.volume ? probeValue(this.volume, this.clampVoxel(voxel)) : null;
  }

  /** Resolves once every pending load (renderer, volume, environment, GPU context) has been applied. */
  async whenSettled(): Promise<void> {
    await this.updateComplete;
    while (this.pending.size) {
      await Promise.allSettled([...this.pending]);
      await this.updateComplete;
    }
  }

  /** Load a volume from anything @vpt/loaders accepts (Files from a picker or a drop, bytes, a URL). */
  async load(source: VolumeSource): Promise<void> {
    if (typeof source === 'string') {
      this.src = source;
      await this.whenSettled();
      return;
    }
    await this.track(this.volumeLoading.loadSource(source));
  }

  /** Time steps of the volume (1: not a time series). */
  get timeSteps(): number {
    return this.player?.steps ?? 1;
  }

  play(): void {
    this.playing = true;
  }

  pause(): void {
    this.playing = false;
  }

  /** The time player's step is read (or failed): it becomes the scene's volume, and `time` and `vpt-change` follow. */
  showStep(volume: LoadedVolumeLike | null, index: number, error?: unknown): void {
    if (!volume) return this.fail(error, 'src');
    // The channels' settings stay from step to step, as the transfer function does (not refitted).
    if (volume.multichannel) this.userChannels = this.channels;
    this.volume = volume;
    this.time = index;
    this.applySync();
    this.dispatchEvent(
      new CustomEvent<ViewerChangeDetail>('vpt-change', { detail: { property: 'time', value: index } }),
    );
  }

  /** Frame the volume again (the camera attribute's value when one was given, else an automatic fit). */
  resetCamera(): void {
    const cam = this.homeCamera ?? (this.volume ? fitCamera(this.volume) : null);
    if (cam) this.setInternal('camera', cam);
  }

  /** The displayed image as a PNG. */
  async screenshot(): Promise<Blob> {
    const ctx = this.requireContext();
    const ldr = await ctx.readLDR();
    const { width, height } = ctx.size;
    return encodePngBlob(ldr, width, height);
  }

  /** Whether the image on display (and so exportHDR's) is denoised: the denoise step is in the chain and enabled now. */
  get denoised(): boolean {
    return this.denoiseStep?.enabled === true && this.session !== null;
  }

  /**
   * The linear HDR render (before exposure and tone mapping) as PFM or 32-bit float OpenEXR
   * bytes: denoised exactly when the displayed image is (`denoised`; downloadHDR names the file so).
   */
  async exportHDR(format: 'pfm' | 'exr' = 'exr'): Promise<Uint8Array> {
    const ctx = this.requireContext();
    const hdr = await ctx.readHDR({ afterPost: this.denoised });
    const { width, height } = ctx.size;
    return format === 'pfm' ? encodePfm(hdr, width, height) : encodeExr(hdr, width, height);
  }

  // ——— lifecycle ———

  override connectedCallback(): void {
    super.connectedCallback();
    this.connected = true;
    this.observeVisibility();
    if (this.panelSet.size) void loadPanels(); // fetched alongside the renderer and the volume
    // Re-attached after a removal: the GPU context was released, open a new one.
    if (this.hasUpdated) this.observeHostWidth();
    if (this.hasUpdated && !this.session) this.track(this.openSession());
  }

  override disconnectedCallback(): void {
    super.disconnectedCallback();
    this.connected = false;
    this.hostObserver?.disconnect();
    this.visibilityObserver?.disconnect();
    this.volumeLoading.abort();
    this.tokens.session++;
    // While the canvas is still in the shadow tree (OrbitControls listens on its root node).
    this.orbit.detach();
    this.session?.dispose();
    this.session = null;
    this.releaseSlot();
    this._parked = false;
    this.closePanes();
    this.stopLostTimer();
  }

  // ——— the page's WebGL 2 context slots (context-slots.ts) ———

  /** @internal SlotHolder: on screen. */
  get visible(): boolean {
    return this.onScreen;
  }

  /** @internal SlotHolder: give the WebGL 2 context up for another viewer's, keeping a still of the image. */
  async release(): Promise<void> {
    const session = this.session;
    this.holdsSlot = false;
    if (!session) {
      // Still opening: that open is dropped; a slot is handed back through resume().
      if (this.opening) {
        this.tokens.session++;
        this._parked = true;
      }
      return;
    }
    this.tokens.session++;
    ++this.tokens.renderer;
    let still: HTMLCanvasElement | null = null;
    try {
      if (session.ctx.getScene() && !session.ctx.backend.isLost) {
        const { width, height } = session.ctx.size;
        const ldr = await session.ctx.readLDR();
        still = document.createElement('canvas');
        still.width = width;
        still.height = height;
        still.className = 'still';
        still.setAttribute('part', 'still');
        still.setAttribute('aria-hidden', 'true');
        still.getContext('2d')?.putImageData(new ImageData(new Uint8ClampedArray(ldr), width, height), 0, 0);
      }
    } catch {
      still = null; // no still: the released canvas shows until a slot is free
    }
    if (this.session !== session) return;
    this.orbit.detach();
    session.dispose();
    this.session = null;
    this._parked = true;
    this._lost = false;
    this.stopLostTimer();
    this.stillCanvas?.remove();
    this.stillCanvas = still;
    // Right after the released canvas, so it paints over it and under the overlays.
    if (still) (this.canvas ?? this.renderRoot.querySelector('.view'))?.after(still);
  }

  /** @internal SlotHolder: a slot is free again. */
  resume(): void {
    if (!this.connected) {
      webglSlots.drop(this);
      return;
    }
    this.holdsSlot = true;
    this._parked = false;
    if (!this.session) this.track(this.openSession());
  }

  private stillCanvas: HTMLCanvasElement | null = null;

  private releaseSlot(): void {
    this.holdsSlot = false;
    webglSlots.drop(this);
  }

  private observeVisibility(): void {
    if (typeof IntersectionObserver !== 'function') return;
    this.visibilityObserver ??= new IntersectionObserver((entries) => {
      const entry = entries[entries.length - 1];
      if (!entry || entry.isIntersecting === this.onScreen) return;
      this.onScreen = entry.isIntersecting;
      webglSlots.visibilityChanged(this);
      for (const pane of this.slicePanes.values()) webglSlots.visibilityChanged(pane);
    });
    this.visibilityObserver.observe(this);
  }

  protected override firstUpdated(): void {
    this.resolution.observe(this.renderRoot.querySelector('.view') as HTMLElement);
    this.observeHostWidth();
  }

  protected override willUpdate(changed: PropertyValues<this>): void {
    if (changed.has('transferFunction') && !this.keepFittedPreset) {
      // A fitted preset's name is kept until a volume is loaded, then refitted to each new one.
      this.fittedPreset = isFittedPreset(this.transferFunction) ? (this.transferFunction as string).trim() : null;
    }
    this.keepFittedPreset = false;
    if (changed.has('layout') && this.layout !== null && !(VIEWER_LAYOUTS as readonly string[]).includes(this.layout)) {
      this.fail(
        new VptError('invalid-scene', `layout: "${this.layout}" is not one of ${VIEWER_LAYOUTS.join(', ')}`),
        'attribute',
      );
      this.layout = '3d';
    }
    // A new volume: the panes' geometry and a crosshair and window for it, before rendering them.
    if (this.layoutNow !== '3d') this.paneGeometry();
    // Normalize and validate what changed; an invalid value is reported and the last valid one restored.
    const failed = new Set<string>();
    this.validator.validate(
      this as unknown as Record<CheckedProperty, unknown>,
      changed as Map<PropertyKey, unknown>,
      this.volume ?? undefined,
      (e, key) => {
        failed.add(key);
        this.fail(e, 'attribute');
        this.attributeErrorKey = key;
      },
    );
    // The attribute whose value the banner reports got a valid value: it renders now, the banner goes.
    const key = this.attributeErrorKey;
    if (key && key !== SCENE_ERROR && changed.has(key as keyof VptViewer) && !failed.has(key)) {
      this.clearError('attribute');
    }
    if (changed.has('camera') && !this.internalChange.has('camera')) {
      // A camera given from outside becomes "home" for resetCamera().
      this.cameraIsAuto = this.camera === null;
      this.homeCamera = this.camera as Camera | null;
    }
  }

  protected override updated(changed: PropertyValues<this>): void {
    const internal = this.internalChange;
    this.internalChange = new Set();
    if (!this.connected) return;
    if (changed.has('camera') && this.camera && !internal.has('camera')) this.orbit.set(this.camera as Camera);
    // A viewer waiting for a WebGL 2 slot opens when one is free (resume), not on every change.
    if (changed.has('backend') || (!this.session && !this.opening && !this._parked)) this.track(this.openSession());
    else if (this.session && (changed.has('renderer') || changed.has('rendererParams')))
      this.track(this.switchRenderer());
    // The first update reports the constructor's null src as a change; loading null would cancel
    // a load() called before it, so only a src that was set (or cleared after being set) loads.
    if (changed.has('src') && (this.src || changed.get('src') !== undefined))
      this.track(this.volumeLoading.loadSource(this.src?.trim().split(/\s/)[0] ?? null));
    if (changed.has('time') || changed.has('playing') || changed.has('fps')) this.player?.update();
    if (changed.has('labels') && (this.labels || changed.get('labels') !== undefined)) this.track(this.loadLabels());
    if (changed.has('environment')) this.track(this.resolveEnvironment());
    // The crosshair and the panes' window reach the 3D scene only under crosshair-3d.
    const followed =
      this.crosshair3d !== 'none' &&
      (changed.has('_crosshair' as keyof VptViewer) ||
        changed.has('_window' as keyof VptViewer) ||
        changed.has('layout'));
    if (followed || changed.has('_labelTable' as keyof VptViewer) || SYNC_FIELDS.some((f) => changed.has(f)))
      this.applySync();
    this.syncPanes(changed.has('backend') || changed.has('layout'));
  }

  // ——— rendering (DOM) ———

  private get panelSet(): Set<PanelName> {
    const p = (this.panels ?? 'all').trim();
    if (p === 'none') return new Set();
    if (p === 'all' || p === '') return new Set(PANEL_NAMES);
    return new Set(p.split(/[\s,]+/).filter((n): n is PanelName => (PANEL_NAMES as readonly string[]).includes(n)));
  }

  protected override render() {
    const panels = this.panelSet;
    // The panels' and clip handles' rules come with the panels' chunk, adopted beside the element's once.
    if (panelsModule && !this.panelStyled) {
      adoptStyles(this.renderRoot as ShadowRoot, [viewerStyles, panelsModule.panelStyles]);
      this.panelStyled = true;
    }
    // Wide: a sidebar beside the image (the collapsed attribute closes it). Narrow: an
    // overlay over the image, closed at rest and opened by the toolbar button.
    const showAside = panels.size > 0 && (this._narrow ? this._overlayOpen : !this.collapsed);
    const toggle = () => {
      if (this._narrow) this._overlayOpen = !this._overlayOpen;
      else this.collapsed = !this.collapsed;
    };
    const layout = this.layoutNow;
    return html` <div class="layout ${this._narrow ? 'narrow' : ''}" @keydown=${this.onLayoutKey}>
      <div class="panes" part="panes" data-layout=${layout}>
        <div
          class="view"
          part="view"
          @dragover=${this.onDragOver}
          @dragleave=${() => {
            this._dragOver = false;
          }}
          @drop=${this.onDrop}
        >
          ${this._status ? html`<p class="overlay status" part="status" role="status">${this._status}</p>` : nothing}
          ${panels.has('clip') ? this.renderClipHandles() : nothing} ${this.renderHud()}
          ${this.player?.bar(panels.size)}
          ${
            panels.size
              ? html`<div class="toolbar">
                  ${panels.has('export') && this.volume && !showAside ? html`<button type="button" part="screenshot" title="Download the image as PNG" @click=${() => this.downloadScreenshot()}>PNG</button>` : nothing}
                  <button
                    type="button"
                    part="panels-toggle"
                    aria-expanded=${showAside ? 'true' : 'false'}
                    aria-controls="panels"
                    @click=${toggle}
                  >
                    ${showAside ? (this._narrow ? 'Close' : 'Hide panels') : this._narrow ? 'Settings' : 'Panels'}
                  </button>
                </div>`
              : nothing
          }
          ${
            this._lost
              ? html`<div class="overlay lost" role="alert">
                  <p>
                    ${this._lostGaveUp ? 'The GPU context was lost and was not restored.' : 'The GPU context was lost. Restoring…'}
                  </p>
                  <div>
                    <button type="button" @click=${() => this.track(this.openSession())}>
                      ${this._lostGaveUp ? 'Retry' : 'Restart renderer'}
                    </button>
                  </div>
                </div>`
              : nothing
          }
          ${
            this._error
              ? html`<div class="overlay error" part="error" role="alert">
                  <p>${this._error.message}</p>
                  <button
                    type="button"
                    aria-label="Dismiss error"
                    @click=${() => {
                      this._error = null;
                    }}
                  >
                    ×
                  </button>
                </div>`
              : nothing
          }
          ${this._dragOver ? html`<div class="drop" aria-hidden="true">Drop a volume file</div>` : nothing}
        </div>
        ${layout === '3d' ? nothing : this.renderSlicePanes()}
      </div>
      ${showAside ? html`<aside id="panels" part="panels" aria-label="Viewer settings">${this.panelsNow(panels)}</aside>` : nothing}
    </div>`;
  }

  /** The layout attribute, '3d' unless it names another layout. */
  private get layoutNow(): ViewerLayout {
    return (VIEWER_LAYOUTS as readonly string[]).includes(this.layout) ? this.layout : '3d';
  }

  // ——— slice panes (layout="slices" | "quad", slice-panes.ts) ———

  private readonly slicePanes = new Map<PaneName, SlicePane>();
  private geometries: PaneGeometry[] = [];
  private geometryVolume: LoadedVolumeLike | null = null;
  private extent: [number, number] = [0, 1];
  private paneObserver: ResizeObserver | null = null;
  private paneDrawn = new Map<PaneName, string>();
  private paneToken = 0;
  /** A right-drag adjusting the window: where it started and the window then. */
  private windowDrag: { x: number; y: number; window: [number, number]; width: number; height: number } | null = null;

  private clampVoxel(v: Voxel): Voxel {
    const d = this.volume!.dims;
    return v.map((x, i) => Math.min(d[i] - 1, Math.max(0, Math.round(Number.isFinite(x) ? x : 0)))) as Voxel;
  }

  /** The panes' geometry, extent and starting crosshair and window, refreshed for a new volume. */
  private paneGeometry(): PaneGeometry[] {
    const v = this.volume;
    if (!v) return [];
    if (this.geometryVolume !== v) {
      const first = this.geometryVolume === null || this.geometryVolume.dims.join() !== v.dims.join();
      this.geometryVolume = v;
      this.geometries = paneGeometries(v);
      this.extent = dataExtent(v);
      if (first || !this._crosshair) this._crosshair = v.dims.map((n) => Math.floor(n / 2)) as Voxel;
      if (first || !this._window) this._window = defaultWindow(this.extent);
    }
    return this.geometries;
  }

  private renderSlicePanes() {
    const geometries = this.paneGeometry();
    const v = this.volume;
    return (geometries.length ? geometries : ([] as PaneGeometry[])).map((g) => {
      const size = this._paneSizes[g.name];
      const stage = v && size ? this.stageSize(g, size) : null;
      const cross = v && this._crosshair ? screenPoint(g, v.dims, this._crosshair) : null;
      const probe = this._probe?.pane === g.name ? this._probe : null;
      return html`<div class="pane" part="pane ${g.name}-pane" data-pane=${g.name}>
        <div
          class="stage"
          data-stage=${g.name}
          style=${stage ? `width:${stage.width}px;height:${stage.height}px` : 'display:none'}
          @pointerdown=${(e: PointerEvent) => this.onPaneDown(e, g)}
          @pointermove=${(e: PointerEvent) => this.onPaneMove(e, g)}
          @pointerup=${this.onPaneUp}
          @pointercancel=${this.onPaneUp}
          @pointerleave=${() => {
            if (this._probe?.pane === g.name) this._probe = null;
          }}
          @wheel=${(e: WheelEvent) => this.onPaneWheel(e, g)}
          @contextmenu=${(e: Event) => e.preventDefault()}
        >
          ${
            cross
              ? html`<div class="cross-v" style="left:${(100 * cross.fx).toFixed(3)}%"></div>
                  <div class="cross-h" style="top:${(100 * cross.fy).toFixed(3)}%"></div>`
              : nothing
          }
          ${
            g.labels
              ? html`<span class="orient top" data-edge="top">${g.labels.top}</span
                  ><span class="orient bottom" data-edge="bottom">${g.labels.bottom}</span
                  ><span class="orient left" data-edge="left">${g.labels.left}</span
                  ><span class="orient right" data-edge="right">${g.labels.right}</span>`
              : nothing
          }
        </div>
        <p class="pane-title">${g.name} ${this._crosshair ? this._crosshair[g.axis] : ''}</p>
        ${probe ? html`<p class="probe" part="probe" data-probe=${g.name}>${this.probeText(probe)}</p>` : nothing}
      </div>`;
    });
  }

  private probeText(p: ProbeReading): string {
    const units = typeof this.volume?.meta?.units === 'string' ? ` ${this.volume.meta.units}` : '';
    const value = Number.isInteger(p.value) ? String(p.value) : p.value.toPrecision(6);
    return `${value}${units} · [${p.index.join(', ')}]`;
  }

  /** The slice's rectangle in a pane of this CSS size: its physical aspect, as large as fits. */
  private stageSize(g: PaneGeometry, size: { width: number; height: number }) {
    const aspect = sliceAspect(g, this.volume!);
    const w = Math.max(1, size.width),
      h = Math.max(1, size.height - 18);
    return w / h > aspect
      ? { width: Math.round(h * aspect), height: Math.round(h) }
      : { width: Math.round(w), height: Math.round(w / aspect) };
  }

  /** Open or close the panes for the layout, then draw what changed. */
  private syncPanes(reopen: boolean): void {
    const want = this.connected && this.layoutNow !== '3d';
    if (!want || reopen) this.closePanes();
    if (want && !this.slicePanes.size) this.track(this.openPanes());
    for (const [name, pane] of this.slicePanes) {
      const stage = this.renderRoot.querySelector(`[data-stage="${name}"]`);
      if (stage && pane.canvas.parentElement !== stage) stage.prepend(pane.canvas);
    }
    const panesEl = this.renderRoot.querySelectorAll('.pane');
    if (panesEl.length) {
      this.paneObserver ??= new ResizeObserver((entries) => {
        const sizes = { ...this._paneSizes };
        for (const e of entries) {
          const name = (e.target as HTMLElement).dataset.pane as PaneName;
          sizes[name] = { width: e.contentRect.width, height: e.contentRect.height };
        }
        this._paneSizes = sizes;
      });
      panesEl.forEach((p) => this.paneObserver!.observe(p));
    }
    this.drawPanes();
  }

  private async openPanes(): Promise<void> {
    const token = ++this.paneToken;
    // The panes take the page's WebGL 2 slots as viewers do (context-slots.ts), on screen when the element is.
    const host = {
      isVisible: () => this.visible,
      reopened: (pane: SlicePane) => {
        this.paneDrawn.delete(pane.name);
        this.requestUpdate();
      },
    };
    const panes = ['axial', 'coronal', 'sagittal'].map((n) => new SlicePane(n as PaneName, host));
    panes.forEach((p) => this.slicePanes.set(p.name, p));
    try {
      await Promise.all(panes.map((p) => p.open(this.backend)));
    } catch (e) {
      if (token === this.paneToken) this.fail(e, 'context');
      return;
    }
    if (token !== this.paneToken) return;
    this.paneDrawn.clear();
    this.requestUpdate();
  }

  private closePanes(): void {
    this.paneToken++;
    for (const p of this.slicePanes.values()) {
      p.dispose();
      p.canvas.remove();
    }
    this.slicePanes.clear();
    this.paneDrawn.clear();
    this.paneObserver?.disconnect();
    this.paneObserver = null;
    this._probe = null;
  }

  private drawPanes(): void {
    // The attributes' scene, clip included (the slice renderer cuts the plane as the clip cuts the volume).
    const scene = this.sceneFromAttributes();
    const cross = this._crosshair;
    const window = this._window;
    if (!scene || !cross || !window) return;
    const dpr = globalThis.devicePixelRatio || 1;
    // A store's channels: the panes stream channel 0 under the element's scalar view (volume-loading.ts).
    const streamed = this.volumeLoading.streamed?.pane ?? this.volumeLoading.streamed;
    for (const g of this.paneGeometry()) {
      const pane = this.slicePanes.get(g.name);
      const size = this._paneSizes[g.name];
      if (!pane?.context || !size) continue;
      const stage = this.stageSize(g, size);
      pane.canvas.setAttribute('style', canvasPlacement(g, stage));
      const max = pane.context.backend.limits.maxTextureDimension2D;
      const [cw, ch] = g.transpose ? [stage.height, stage.width] : [stage.width, stage.height];
      const w = Math.min(max, Math.max(1, Math.round(cw * dpr)));
      const h = Math.min(max, Math.max(1, Math.round(ch * dpr)));
      const key = `${cross[g.axis]}|${window.join()}|${w}x${h}|${JSON.stringify(scene.clip ?? null)}`;
      if (this.paneDrawn.get(g.name) === key && pane.volume === this.volume) continue;
      try {
        if (streamed && streamed.standIn === scene.volume) pane.useSource(streamed.standIn, streamed.source);
        pane.draw(scene, g.axis, cross[g.axis], window, w, h);
        this.paneDrawn.set(g.name, key);
        if (pane.refining) this.redrawPaneSoon(g.name);
      } catch (e) {
        this.paneDrawn.set(g.name, key);
        this.fail(e, 'attribute');
      }
    }
  }

  private paneRedraws = new Set<PaneName>();

  /** A streamed pane whose bricks are still arriving draws again shortly (each draw uploads what arrived). */
  private redrawPaneSoon(name: PaneName): void {
    if (this.paneRedraws.has(name)) return;
    this.paneRedraws.add(name);
    setTimeout(() => {
      this.paneRedraws.delete(name);
      if (!this.slicePanes.has(name)) return;
      this.paneDrawn.delete(name);
      this.drawPanes();
    }, 100);
  }

  private paneFraction(e: PointerEvent | WheelEvent): { fx: number; fy: number } {
    const r = (e.currentTarget as HTMLElement).getBoundingClientRect();
    return { fx: (e.clientX - r.left) / r.width, fy: (e.clientY - r.top) / r.height };
  }

  private moveCrosshair(voxel: Voxel): void {
    const v = this.clampVoxel(voxel);
    if (this._crosshair && v.every((x, i) => x === this._crosshair![i])) return;
    this._crosshair = v;
    this.dispatchEvent(
      new CustomEvent<ViewerChangeDetail>('vpt-change', { detail: { property: 'crosshair', value: [...v] } }),
    );
  }

  private updateProbe(e: PointerEvent, g: PaneGeometry): void {
    if (!this.volume || !this._crosshair) return;
    const { fx, fy } = this.paneFraction(e);
    if (fx < 0 || fx > 1 || fy < 0 || fy > 1) return;
    const index = voxelAt(g, this.volume.dims, fx, fy, this._crosshair);
    this._probe = { pane: g.name, index, value: probeValue(this.volume, index) };
    this.lab?.hoverVoxel(index, fx, fy, e.currentTarget as HTMLElement);
  }

  private onPaneDown(e: PointerEvent, g: PaneGeometry): void {
    if (!this.volume || !this._crosshair || !this._window) return;
    const target = e.currentTarget as HTMLElement;
    target.setPointerCapture?.(e.pointerId);
    e.preventDefault();
    if (e.button === 2) {
      const r = target.getBoundingClientRect();
      this.windowDrag = { x: e.clientX, y: e.clientY, window: [...this._window], width: r.width, height: r.height };
      return;
    }
    if (e.button !== 0) return;
    const { fx, fy } = this.paneFraction(e);
    this.moveCrosshair(voxelAt(g, this.volume.dims, fx, fy, this._crosshair));
    this.updateProbe(e, g);
    this.crossDrag = true;
  }

  private crossDrag = false;

  private onPaneMove(e: PointerEvent, g: PaneGeometry): void {
    const drag = this.windowDrag;
    if (drag) {
      // Radiologists' right-drag: horizontal widens (right) or narrows the window, vertical moves its
      // centre (down raises it); a drag across the pane spans the data's whole extent.
      const range = this.extent[1] - this.extent[0] || 1;
      const width = Math.max(range * 1e-4, drag.window[1] + ((e.clientX - drag.x) / drag.width) * range);
      const center = drag.window[0] + ((e.clientY - drag.y) / drag.height) * range;
      this._window = [center, width];
      this.dispatchEvent(
        new CustomEvent<ViewerChangeDetail>('vpt-change', { detail: { property: 'window', value: [center, width] } }),
      );
      return;
    }
    if (this.crossDrag && this.volume && this._crosshair) {
      const { fx, fy } = this.paneFraction(e);
      this.moveCrosshair(voxelAt(g, this.volume.dims, fx, fy, this._crosshair));
    }
    this.updateProbe(e, g);
  }

  private onPaneUp = (): void => {
    this.windowDrag = null;
    this.crossDrag = false;
  };

  /** The wheel moves the pane's plane one voxel per notch (down: toward higher indices). */
  private onPaneWheel(e: WheelEvent, g: PaneGeometry): void {
    if (!this.volume || !this._crosshair || e.deltaY === 0) return;
    e.preventDefault();
    const next: Voxel = [...this._crosshair];
    next[g.axis] += Math.sign(e.deltaY);
    this.moveCrosshair(next);
  }

  /** The clip value as an object (null: nothing cut, or a string not parsed yet). */
  private clipNow(): Clip | null {
    return this.clip && typeof this.clip === 'object' ? this.clip : null;
  }

  /** A drag of a clip plane's handle: its axis, the position and pointer where it started. */
  private clipDrag: { axis: ClipAxis; start: number; x: number; y: number } | null = null;

  /**
   * The axis planes' handles over the image (clip-handles.ts), shown with the Clip panel: each
   * at the centre of its cut face; dragging one moves its plane along the axis. Their geometry
   * comes with the panels' module, which the Clip panel loads.
   */
  private renderClipHandles() {
    const ctx = this.session?.ctx;
    const m = panelsModule;
    if (!this.volume || !ctx || !m) return nothing;
    const c = clipControls(this.clipNow());
    const camera = this.sceneNow()!.camera;
    const aspect = ctx.size.width / ctx.size.height;
    const handles = CLIP_AXES.flatMap((axis) => {
      const plane = c.axes[axis];
      const p = plane ? m.projectPoint(camera, aspect, m.axisPoint(axis, plane.position)) : null;
      return p && p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1 ? [{ axis, p }] : [];
    });
    return handles.map(
      ({ axis, p }) =>
        html`<div
          class="clip-handle"
          part="clip-handle"
          data-clip-handle=${axis}
          title="Drag to move the ${axis} clip plane"
          aria-hidden="true"
          style="left: ${(100 * p.x).toFixed(3)}%; top: ${(100 * p.y).toFixed(3)}%"
          @pointerdown=${(e: PointerEvent) => this.onClipHandleDown(e, axis)}
          @pointermove=${this.onClipHandleMove}
          @pointerup=${this.onClipHandleUp}
          @pointercancel=${this.onClipHandleUp}
        >
          ${axis}
        </div>`,
    );
  }

  private onClipHandleDown(e: PointerEvent, axis: ClipAxis): void {
    const plane = clipControls(this.clipNow()).axes[axis];
    if (!plane || e.button !== 0) return;
    e.preventDefault();
    e.stopPropagation();
    (e.currentTarget as Element).setPointerCapture?.(e.pointerId);
    this.clipDrag = { axis, start: plane.position, x: e.clientX, y: e.clientY };
  }

  private onClipHandleMove = (e: PointerEvent): void => {
    const drag = this.clipDrag;
    const ctx = this.session?.ctx;
    const view = this.renderRoot.querySelector('.view') as HTMLElement | null;
    const m = panelsModule;
    if (!drag || !ctx || !view || !this.volume || !m) return;
    const c = clipControls(this.clipNow());
    const plane = c.axes[drag.axis];
    if (!plane) return;
    const rect = view.getBoundingClientRect();
    const i = CLIP_AXES.indexOf(drag.axis);
    const box = volumeBox(this.volume);
    const position = m.draggedPosition(
      this.sceneNow()!.camera,
      ctx.size.width / ctx.size.height,
      drag.axis,
      drag.start,
      { dx: (e.clientX - drag.x) / rect.width, dy: (e.clientY - drag.y) / rect.height },
      { min: box.min[i], max: box.max[i] },
    );
    this.resolution.interactionStarted();
    this.setInternal('clip', clipFromControls({ ...c, axes: { ...c.axes, [drag.axis]: { ...plane, position } } }));
  };

  private onClipHandleUp = (): void => {
    if (!this.clipDrag) return;
    this.clipDrag = null;
    this.resolution.interactionEnded();
  };

  private panelStyled = false;

  /** The panels' templates, or nothing while their module loads (tracked: whenSettled waits for it). */
  private panelsNow(panels: Set<PanelName>) {
    if (panelsModule) return panelsModule.renderPanels(this, panels);
    this.track(loadPanels().then(() => this.requestUpdate()));
    return nothing;
  }

  /** The thin progress bar (loading bytes; refining toward max-samples or target-error) and the stats line. */
  private renderHud() {
    const bar = this.hideProgress ? null : this.progressFraction();
    const stats = this.hideStats ? null : this.statsLine();
    return html` ${stats ? html`<p class="stats-line" part="stats" aria-live="off">${stats}</p>` : nothing}
    ${
      bar === null
        ? nothing
        : html`<div
            class="progress ${Number.isNaN(bar) ? 'indeterminate' : ''}"
            part="progress"
            role="progressbar"
            aria-label=${this._loading !== null ? 'Loading' : 'Refining'}
            aria-valuemin="0"
            aria-valuemax="100"
            aria-valuenow=${Number.isNaN(bar) ? nothing : Math.round(100 * bar)}
          >
            <div style="width: ${Number.isNaN(bar) ? 100 : (100 * bar).toFixed(2)}%"></div>
          </div>`
    }`;
  }

  /**
   * Progress in [0, 1], NaN when unknown, null when there is nothing to show. Refining:
   * samples / max-samples, or with a target error (target / error)² when larger — the
   * error of a mean falls as 1/√n, so that is the fraction of the samples needed.
   */
  private progressFraction(): number | null {
    if (this._loading !== null) return this._loading;
    const s = this._stats;
    if (!s || !this.volume || this.converged) return null;
    let p = s.samples / Math.max(1, this.maxSamples);
    if (this.targetError > 0 && s.error !== null && s.error > 0) p = Math.max(p, (this.targetError / s.error) ** 2);
    return Math.min(1, p);
  }

  private statsLine(): string | null {
    const s = this._stats;
    if (!s || !this.volume) return null;
    const parts = [
      `${s.samples} / ${this.maxSamples} spp`,
      `${s.msPerIteration < 10 ? s.msPerIteration.toFixed(1) : Math.round(s.msPerIteration)} ms/it`,
    ];
    const level = this._dataLevel;
    const streamed = this.volumeLoading.streamed;
    const bricking = level?.bricked && streamed ? (this.session?.ctx.stats.bricking ?? null) : null;
    if (bricking) {
      // Level-0 bricks served by their own data, of all of them.
      const total = streamed!.source.levels[0].dims.reduce((n, d) => n * Math.ceil(d / bricking.brickSize), 1);
      const failed = bricking.failed ? `, ${bricking.failed} failed` : '';
      parts.push(`level bricked 0 (${bricking.finest}/${total} bricks${failed}) of ${level!.count}`);
    } else if (level)
      parts.push(`level ${level.shown}${level.loading !== null ? ` → ${level.loading}…` : ''} of ${level.count}`);
    if (s.error !== null)
      parts.push(
        `err ${(100 * s.error).toFixed(1)}%${this.targetError > 0 ? ` → ${(100 * this.targetError).toFixed(1)}%` : ''}`,
      );
    parts.push(`${s.width}×${s.height}`);
    if (this.converged) parts.push('done');
    return parts.join(' · ');
  }

  /** Escape closes the panel overlay (narrow layout) and returns focus to the image. */
  private onLayoutKey = (e: KeyboardEvent): void => {
    if (e.key !== 'Escape' || !this._narrow || !this._overlayOpen) return;
    this._overlayOpen = false;
    this.canvas?.focus();
  };

  /** Narrow: panels and the image cannot share the element (a sidebar plus at least 320 px of image). */
  private hostObserver: ResizeObserver | null = null;
  private observeHostWidth(): void {
    this.hostObserver ??= new ResizeObserver(() => this.updateNarrow());
    this.hostObserver.observe(this);
    this.updateNarrow();
  }

  private updateNarrow(): void {
    const width = this.getBoundingClientRect().width;
    const w = getComputedStyle(this).getPropertyValue('--vpt-panel-width').trim();
    const rootFont = parseFloat(getComputedStyle(document.documentElement).fontSize) || 16;
    const panelPx = (w.endsWith('px') ? parseFloat(w) : parseFloat(w) * rootFont) || 304;
    const narrow = width > 0 && width < panelPx + NARROW_MIN_IMAGE_PX;
    if (narrow !== this._narrow) {
      this._narrow = narrow;
      this._overlayOpen = false;
    }
  }

  // ——— state the panels read and write ———

  /** @internal for the panels */
  get panelState(): PanelState {
    return {
      transferFunction: this.currentTransferFunction(),
      histogram: this._histogram,
      lights: this.effectiveLights(),
      environment: (this.environment as EnvironmentValue | null) ?? rendererLook(this.renderer).environment,
      densityScale: this.effectiveDensityScale(),
      stats: this._stats,
      backendKind: this.session?.ctx.backend.kind ?? null,
      volume: this.volume,
      rendererInstance: this.rendererInstance,
    };
  }

  /** @internal Set a property as the user did through the element: reflected, and announced with `change`. */
  setInternal(property: InternalProperty, value: unknown): void {
    if (sameValue(this[property], value)) return;
    (this as Record<string, unknown>)[property] = value;
    if (property === 'camera') this.internalChange.add('camera');
    const detail = { property, value } as ViewerChangeDetail;
    this.dispatchEvent(new CustomEvent<ViewerChangeDetail>('vpt-change', { detail }));
  }

  private gradientCache: { volume: Volume; samples: GradientSamples } | null = null;
  /** Name of core's volume-fitted 2D preset the transfer function came from, if it did. */
  private fittedPreset: string | null = null;
  private keepFittedPreset = false;

  /** @internal The volume's (value, gradient) pairs for the 2D editor's histogram; computed once per volume, on first use. */
  gradientSamples(): GradientSamples | null {
    if (!this.volume) return null;
    if (this.gradientCache?.volume !== this.volume)
      this.gradientCache = { volume: this.volume, samples: gradientSamples(this.volume) };
    return this.gradientCache.samples;
  }

  /** @internal The core 2D preset the transfer function was fitted from, if any. */
  get fittedPresetName(): string | null {
    return this.fittedPreset;
  }

  /** @internal */
  async downloadScreenshot(): Promise<void> {
    try {
      download(await this.screenshot(), 'vpt.png');
    } catch (e) {
      this.fail(e, 'export');
    }
  }

  /** @internal */
  async downloadHDR(format: 'pfm' | 'exr'): Promise<void> {
    try {
      // The name says whether the radiance was denoised (the formats carry no such field here).
      const name = this.denoised ? `vpt-denoised.${format}` : `vpt.${format}`;
      download(await this.exportHDR(format), name, format === 'exr' ? 'image/x-exr' : 'image/x-portable-floatmap');
    } catch (e) {
      this.fail(e, 'export');
    }
  }

  // ——— async work ———

  private track<T>(p: Promise<T>): Promise<T> {
    this.pending.add(p);
    p.finally(() => this.pending.delete(p)).catch(() => {});
    return p;
  }

  private requireContext() {
    const ctx = this.session?.ctx;
    if (!ctx || !ctx.getScene())
      throw new VptError('invalid-scene', '<vpt-viewer>: nothing rendered yet (no volume loaded)');
    return ctx;
  }

  /**
   * The renderer the attributes ask for now. A load that lands after the attributes moved
   * on (a renderer package is a dynamic import: slow under load) is returned but not
   * remembered, so a stale renderer never replaces the current one's key.
   */
  private async loadRendererInstance(): Promise<Renderer> {
    const key = this.desiredRendererKey();
    if (this.rendererInstance && key === this.rendererKey) return this.rendererInstance;
    try {
      const r = await createRenderer(this.renderer, this.effectiveRendererParams());
      if (key !== this.desiredRendererKey()) return r;
      this.rendererInstance = r;
      this.rendererKey = key;
      this.failedRendererKey = '';
      return r;
    } catch (e) {
      this.failedRendererKey = key;
      throw e;
    }
  }

  private async switchRenderer(): Promise<void> {
    const token = ++this.tokens.renderer;
    try {
      const r = await this.loadRendererInstance();
      if (token !== this.tokens.renderer || !this.session) return;
      if (this.session.ctx.renderer !== r) this.session.setRenderer(r);
      this.clearError('renderer');
      this.applySync(); // the defaults of unset attributes depend on the renderer
      this.requestUpdate();
    } catch (e) {
      if (token === this.tokens.renderer) this.fail(e, 'renderer');
    }
  }

  /** (Re)open the GPU context on a fresh canvas (a canvas keeps the first context type it was given). */
  private async openSession(): Promise<void> {
    const token = ++this.tokens.session;
    const opening = this.openSessionNow(token).finally(() => {
      if (this.opening === opening) this.opening = null;
    });
    this.opening = opening;
    return opening;
  }

  private opening: Promise<void> | null = null;
  /** The renderer key that failed to load last, so it is reported once rather than on every retry. */
  private failedRendererKey = '';

  private desiredRendererKey(): string {
    return `${this.renderer}|${JSON.stringify(this.effectiveRendererParams())}`;
  }

  private async openSessionNow(token: number): Promise<void> {
    ++this.tokens.renderer;
    this.session?.dispose();
    this.session = null;
    this._lost = false;
    this.stopLostTimer();
    await this.updateComplete;
    const view = this.renderRoot.querySelector('.view') as HTMLElement | null;
    if (!view || token !== this.tokens.session) return;
    let renderer: Renderer;
    try {
      // Until the renderer that landed is the one the attributes still ask for: the context
      // must not start (and report samples) with a renderer the page already replaced.
      for (;;) {
        const key = this.desiredRendererKey();
        renderer = await this.loadRendererInstance();
        if (token !== this.tokens.session || key === this.desiredRendererKey()) break;
      }
    } catch (e) {
      if (token !== this.tokens.session) return;
      this.fail(e, 'renderer');
      // Keep going with the previous renderer, or else the default one, so the element stays usable.
      try {
        renderer = this.rendererInstance ?? (await createRenderer(DEFAULT_RENDERER_NAME));
      } catch {
        return;
      }
    }
    if (token !== this.tokens.session) return;
    // A WebGL 2 context takes one of the page's slots first (another viewer may release its context).
    const mayBeWebgl2 = this.backend === 'webgl2' || (this.backend !== 'webgpu' && !('gpu' in navigator));
    if (mayBeWebgl2) {
      this.holdsSlot = true;
      await webglSlots.acquire(this);
      if (token !== this.tokens.session) return;
    }
    const canvas = document.createElement('canvas');
    canvas.tabIndex = 0;
    canvas.setAttribute('part', 'canvas');
    canvas.setAttribute('role', 'img');
    canvas.setAttribute(
      'aria-label',
      'Volume rendering. Drag or use the arrow keys to orbit; right-drag or Shift+arrows to pan; wheel, +/- to zoom.',
    );
    // The first size before the device's limits are known; applySize() fits it right after.
    const { width, height } = this.resolution.renderSize(2048, 2048 * 2048);
    let session: RenderSession;
    try {
      session = await RenderSession.create(
        {
          canvas,
          backend: this.backend,
          renderer,
          post: this.makePost(),
          width,
          height,
          ...(this.maxGpuBytes !== undefined ? { maxGpuBytes: this.maxGpuBytes } : {}),
        },
        {
          progress: (s) => this.onProgress(s),
          converged: (s) => {
            this.updateDenoiser();
            this.dispatchEvent(new CustomEvent<ViewerConvergedDetail>('vpt-converged', { detail: s }));
          },
          // The panel and the stats line read the estimate from the same stats, as soon as it lands.
          estimated: (s) => {
            this._stats = s;
          },
          lost: () => {
            this._lost = true;
            this.startLostTimer();
          },
          restored: () => {
            this._lost = false;
            this.stopLostTimer();
            this.clearError('context');
          },
        },
      );
    } catch (e) {
      if (token === this.tokens.session) {
        this.releaseSlot();
        this.fail(e, 'context');
      }
      return;
    }
    if (token !== this.tokens.session || !this.connected) {
      session.dispose();
      return;
    }
    if (session.ctx.backend.kind !== 'webgl2') this.releaseSlot();
    else if (!this.holdsSlot) {
      // 'auto' fell back to WebGL 2: take a slot now.
      this.holdsSlot = true;
      await webglSlots.acquire(this);
      if (token !== this.tokens.session || !this.connected) {
        session.dispose();
        return;
      }
    }
    // Detach while the old canvas is still in the tree (see OrbitCamera.detach).
    this.orbit.detach();
    this.canvas?.remove();
    this.stillCanvas?.remove();
    this.stillCanvas = null;
    this._parked = false;
    this.canvas = canvas;
    view.prepend(canvas);
    this.session = session;
    const streamed = this.volumeLoading.streamed;
    if (streamed) session.ctx.setVolumeSource(streamed.standIn, streamed.source);
    session.ctx.onWarning((w) => this.volumeLoading.onContextWarning(w));
    this.postKey = this.postKeyNow();
    this.orbit.attach(canvas);
    this.track(this.orbit.ready);
    if (this.camera) this.orbit.set(this.camera as Camera);
    this.clearError('context');
    this.applySize();
    this.applySync();
    this.requestUpdate();
    // The renderer attribute may have changed while the context was opening.
    if (this.desiredRendererKey() !== this.rendererKey && this.desiredRendererKey() !== this.failedRendererKey)
      this.track(this.switchRenderer());
  }

  /**
   * Show a loaded volume: histogram, fitted transfer function and preset, the framing
   * camera while it is automatic (not for a finer level of the volume already shown),
   * `vpt-load`. `level` is set for the levels of a multiscale store.
   */
  private applyVolume(volume: LoadedVolumeLike, source: VolumeSource, level: ViewerLoadDetail['level'] | null): void {
    const refinement = level !== null && this.loadedSource === source && this.volume !== null;
    this.player?.dispose();
    this.player = null;
    // A time series; or src is a list of URLs when it is not the source loaded (or a File came): the player decides.
    if (((volume.meta?.timeSteps as number) > 1 || this.src !== source) && !level?.bricked && (!level || level.final))
      this.track(
        import('./time-player.js').then(async (m) => {
          const p = await m.attachPlayer(
            this,
            volume,
            source,
            this.session?.ctx.volumeBudgetBytes,
            level?.index,
            this.src,
          );
          // Another volume came meanwhile: this series is not shown any more. (Null: src is no series.)
          if (this.volume !== volume) p?.dispose();
          else (this.player = p)?.update();
        }),
      );
    if (source !== this.loadedSource) this.userChannels = null;
    this.volume = volume;
    this.loadedSource = source;
    this._status = '';
    this._loading = null;
    this._histogram = valueHistogram(volume);
    this.autoTransferFunction = autoTransferFunction(volume);
    if (this.fittedPreset) {
      const name = this.fittedPreset;
      this.transferFunction = parseTransferFunction(name, volume);
      this.fittedPreset = name; // the willUpdate for this set would clear it
      this.keepFittedPreset = true;
    }
    if (!refinement && (this.cameraIsAuto || !this.camera)) {
      const fit = fitCamera(volume, (this.camera as Camera | null)?.fovy);
      this.internalChange.add('camera');
      this.camera = fit;
      this.cameraIsAuto = true;
      this.orbit.set(fit);
    }
    if (!refinement) this.lightCamera = (this.camera as Camera | null) ?? null;
    this.clearError('src');
    if (this.lab) this.track(this.lab.check());
    this.applySync();
    // Renderer parameters that follow the data (iso's default surface) may have changed.
    if (this.session && this.desiredRendererKey() !== this.rendererKey) this.track(this.switchRenderer());
    this.dispatchEvent(
      new CustomEvent<ViewerLoadDetail>('vpt-load', {
        detail: {
          volume,
          format: volume.format,
          dims: [...volume.dims],
          type: volume.type,
          ...(level ? { level } : {}),
        },
      }),
    );
  }

  private async resolveEnvironment(): Promise<void> {
    const token = ++this.tokens.environment;
    const env = this.environment as EnvironmentValue | null;
    if (!env) this.resolvedEnvironment = null;
    else if (env.type !== 'url') this.resolvedEnvironment = env;
    else {
      try {
        // Loaded on first use (Three.js' EXR and HDR parsers: a lazy chunk of the one-file bundle).
        const { loadEnvironment } = await import('./loading/environment-loader.js');
        const loaded = await loadEnvironment(env.url, env.scale ?? 1, { request: this.requestPolicy });
        if (token !== this.tokens.environment) return;
        this.resolvedEnvironment = loaded;
        this.clearError('environment');
      } catch (e) {
        if (token === this.tokens.environment) this.fail(e, 'environment');
        return;
      }
    }
    this.applySync();
  }

  // ——— applying state to the GPU ———

  private currentTransferFunction(): TransferFunction {
    const tf = this.transferFunction;
    if (tf && typeof tf === 'object') return tf;
    if (this.autoTransferFunction) return rendererLook(this.renderer).transferFunction(this.autoTransferFunction);
    return transferFunctionPreset(DEFAULT_TRANSFER_FUNCTION)!;
  }

  // ——— defaults for unset attributes (defaults.ts) ———

  private effectiveDensityScale(): number {
    return this.densityScale ?? rendererLook(this.renderer).densityScale;
  }

  private effectiveLights(): Light[] {
    if (Array.isArray(this.lights)) return this.lights;
    const camera = this.lightCamera ?? (this.camera && typeof this.camera === 'object' ? this.camera : null);
    return camera ? rendererLook(this.renderer).lights(camera) : [];
  }

  private effectiveRendererParams(): Record<string, unknown> {
    const p = this.rendererParams;
    if (p && typeof p === 'object') return p;
    // A multichannel volume's drawn channels (their functions and colours) shape the defaults too.
    const drawn = this.volume?.multichannel
      ? this.channels?.filter(
          (c): c is ViewerChannel & { transferFunction: TransferFunction } =>
            c.enabled !== false && c.transferFunction !== undefined,
        )
      : undefined;
    return defaultRendererParams(this.renderer, this.autoTransferFunction, drawn);
  }

  private makePost() {
    const descriptor = rendererEntry(this.renderer)?.descriptor;
    // A renderer whose HDR image holds display values is shown as it is (tone-mapper does not apply).
    const chain = defaultPostChain({
      exposure: this.exposure,
      toneMapper: this.toneMapper,
      displayReferred: descriptor?.displayReferred ?? false,
    });
    // Auto denoises a renderer that writes the guides (MIP's running maximum does not: its variance does not describe its error).
    const wanted = this.denoise === 'on' || (this.denoise === 'auto' && (descriptor?.writesGuides ?? true));
    this.denoiseStep = wanted ? new DenoiseStep() : null;
    this.updateDenoiser();
    return this.denoiseStep ? [this.denoiseStep, ...chain] : chain;
  }

  /**
   * 'auto' filters while refining and shows the plain estimate once converged (the step stays, a
   * pass-through); nor while the camera moves for a renderer whose descriptor says
   * `denoiseWhileMoving: false`.
   */
  private updateDenoiser(): void {
    if (!this.denoiseStep) return;
    const still = this.resolution.interacting && this.denoiserStopsWhileMoving();
    this.denoiseStep.enabled = this.denoise === 'on' || (!this.converged && !still);
  }

  /** 'auto' with a renderer whose descriptor says `denoiseWhileMoving: false`. */
  private denoiserStopsWhileMoving(): boolean {
    return this.denoise === 'auto' && rendererEntry(this.renderer)?.descriptor?.denoiseWhileMoving === false;
  }

  private postKeyNow(): string {
    return `${this.exposure}|${this.toneMapper}|${this.denoise}|${this.renderer}`;
  }

  /**
   * The 3D view's scene: the panes' (sceneFromAttributes) plus the slice plane, and what the
   * crosshair puts there under `crosshair-3d`: the followed pane's plane as the slice plane, or a
   * clip plane at it.
   */
  private sceneNow(): Scene | null {
    const scene = this.sceneFromAttributes();
    if (!scene) return null;
    const mc = this.volume!.multichannel;
    if (mc) {
      const channels = this.channels!;
      Object.assign(scene, { volume: mc.volume, channels });
      // A streamed store reads the channels drawn, from before the context's bricks need them.
      const streamed = this.volumeLoading.streamed;
      if (streamed?.standIn === mc.volume) streamed.draw?.(channels.flatMap((c, k) => (c.enabled ? [k] : [])));
    }
    const attr = this.slicePlane && typeof this.slicePlane === 'object' ? this.slicePlane : null;
    const follow = this.followedPlane();
    if (follow && this.crosshair3d === 'slice') {
      const { colormap, sampling } = attr ?? {};
      const window = attr?.window ?? this._window ?? undefined;
      scene.slicePlane = {
        axis: follow.axis,
        index: follow.index,
        ...(window ? { window } : {}),
        ...(colormap ? { colormap } : {}),
        ...(sampling ? { sampling } : {}),
      };
    } else if (attr) scene.slicePlane = attr;
    if (follow && this.crosshair3d === 'clip') {
      const planes = scene.clip?.planes ?? [];
      const normal: [number, number, number] = [0, 0, 0];
      normal[follow.a] = 1;
      if (planes.length < MAX_CLIP_PLANES)
        scene.clip = { ...scene.clip, planes: [...planes, { normal, offset: follow.position }] };
    }
    return scene;
  }

  /** The plane of the `crosshair-pane` pane through the crosshair, while `crosshair-3d` asks for it in quad or slices layout. */
  private followedPlane(): { a: 0 | 1 | 2; axis: 'x' | 'y' | 'z'; index: number; position: number } | null {
    const v = this.volume;
    if (this.crosshair3d === 'none' || this.layoutNow === '3d' || !v || !this._crosshair) return null;
    const g = this.paneGeometry().find((p) => p.name === this.crosshairPane);
    if (!g) return null;
    const a = g.axis;
    const index = this._crosshair[a];
    const box = volumeBox(v);
    // Through the centres of voxel layer `index` (cell-centred), as the slice renderer's index.
    const position = box.min[a] + ((index + 0.5) * box.size[a]) / v.dims[a];
    return { a, axis: (['x', 'y', 'z'] as const)[a], index, position };
  }

  /** The scene from the current attributes (the slice panes' scene), or null before a volume is loaded. */
  private sceneFromAttributes(): Scene | null {
    if (!this.volume) return null;
    const camera = this.camera && typeof this.camera === 'object' ? this.camera : fitCamera(this.volume);
    const clip = this.clip && typeof this.clip === 'object' && hasClip(this.clip) ? this.clip : null;
    return {
      volume: this.volume,
      transferFunction: this.currentTransferFunction(),
      camera,
      lights: this.effectiveLights(),
      environment: this.resolvedEnvironment ?? rendererLook(this.renderer).environment,
      densityScale: this.effectiveDensityScale(),
      seed: this.seed,
      ...(clip ? { clip } : {}),
      ...this.lab?.scene(this.volume),
    };
  }

  private applySync(): void {
    const s = this.session;
    if (!s) return;
    const key = this.postKeyNow();
    if (key !== this.postKey) {
      try {
        s.setPost(this.makePost());
        this.postKey = key;
      } catch (e) {
        this.fail(e, 'attribute');
      }
    }
    // Turned on after the context opens (its pass is a lazy chunk), so the first image does not wait for it.
    if (s.ctx.temporalReuse !== (this.temporal !== 'off'))
      s.ctx.setTemporal(this.temporal !== 'off').catch((e: unknown) => this.fail(e, 'context'));
    this.applySize();
    s.setStopping(this.maxSamples, this.targetError);
    // Defaults of the renderer's parameters that follow the scene (ISO: a surface per drawn
    // channel) changed: the new renderer first (switchRenderer applies the scene after it), so
    // the scene never meets parameters made for another one.
    const desired = this.desiredRendererKey();
    if (
      this.rendererInstance &&
      s.ctx.renderer === this.rendererInstance &&
      desired !== this.rendererKey &&
      desired !== this.failedRendererKey
    ) {
      this.track(this.switchRenderer());
      return;
    }
    const scene = this.sceneNow();
    if (!scene) return;
    try {
      s.applyScene(scene);
      // A scene the attributes made failed before; this one renders: the banner goes.
      if (this.attributeErrorKey === SCENE_ERROR) this.clearError('attribute');
    } catch (e) {
      if (isVptError(e, 'limit-exceeded')) {
        // The volume does not fit this device: drop it rather than fail again on every change.
        this.volume = null;
        this.fail(e, 'src');
      } else {
        this.fail(e, 'attribute');
        this.attributeErrorKey = SCENE_ERROR;
      }
    }
  }

  private applySize(): void {
    const s = this.session;
    if (!s) return;
    const max = s.ctx.backend.limits.maxTextureDimension2D;
    // Clamped to the GPU memory budget (a 3000 px element at resolution-scale 4 would not fit).
    const { width, height } = this.resolution.renderSize(max, s.ctx.maxRenderPixels);
    // The denoiser may follow the interaction (updateDenoiser); the size changes when it starts and ends.
    this.updateDenoiser();
    try {
      s.setSize(width, height);
    } catch (e) {
      this.fail(e, 'context');
    }
  }

  private onProgress(s: RefinementStats): void {
    if (this.holdsSlot) webglSlots.touch(this);
    // What a frame costs while the camera moves: the iterations, and the render + post chain
    // unless the denoiser stops then (denoiseWhileMoving false), when its cost must not shrink the image.
    const post = this.denoiserStopsWhileMoving() ? 0 : (this.session?.ctx.stats.msPostPerFrame ?? 0);
    this.resolution.recordIteration(s.msPerIteration + post);
    this._stats = s;
    this.updateDenoiser();
    this.dispatchEvent(new CustomEvent<ViewerProgressDetail>('vpt-progress', { detail: { phase: 'refining', ...s } }));
  }

  private onUserCamera(camera: Camera): void {
    if (this.holdsSlot) webglSlots.touch(this);
    this.resolution.interactionStarted();
    this.cameraIsAuto = false;
    this.setInternal('camera', camera);
  }

  /** Load `labels` (labels-layer.ts: a lazy chunk with @vpt/core/labels, imported only here). */
  private async loadLabels(): Promise<void> {
    const { LabelLayer } = await import('./labels-layer.js');
    this.lab ??= new LabelLayer(this, {
      fail: (e) => this.fail(e, 'labels'),
      clear: () => this.clearError('labels'),
      apply: () => this.applySync(),
    });
    await this.lab.load(this.labels);
  }

  /** @internal for the panels: the Labels panel while a label volume is loaded. */
  labelsPanel() {
    return this.lab?.panel();
  }

  // ——— errors ———

  private fail(e: unknown, source: ViewerErrorDetail['source']): void {
    const error = isVptError(e)
      ? e
      : new VptError(source === 'src' ? 'load-failed' : 'invalid-scene', (e as Error)?.message ?? String(e), {
          cause: e,
        });
    const detail: ViewerErrorDetail = { error, code: error.code, message: error.message, source };
    this._error = detail;
    this.dispatchEvent(new CustomEvent<ViewerErrorDetail>('vpt-error', { detail }));
  }

  /** A loss that is never restored must not leave "Restoring…" up forever: report it and offer Retry. */
  private startLostTimer(): void {
    this.stopLostTimer();
    this.lostTimer = setTimeout(() => {
      this.lostTimer = undefined;
      if (!this._lost) return;
      this._lostGaveUp = true;
      this.fail(
        new VptError(
          'context-lost',
          `The GPU context was lost and not restored within ${this.contextRestoreTimeoutMs} ms; press Retry to start a new one`,
        ),
        'context',
      );
    }, this.contextRestoreTimeoutMs);
  }

  private stopLostTimer(): void {
    if (this.lostTimer !== undefined) clearTimeout(this.lostTimer);
    this.lostTimer = undefined;
    this._lostGaveUp = false;
  }

  private clearError(source: ViewerErrorDetail['source']): void {
    if (this._error?.source !== source) return;
    this._error = null;
    if (source === 'attribute') this.attributeErrorKey = null;
  }

  /** The property whose invalid value the 'attribute' banner reports (SCENE_ERROR: the scene they made). */
  private attributeErrorKey: string | null = null;

  // ——— drag and drop ———

  private onDragOver = (e: DragEvent): void => {
    if (!e.dataTransfer?.types.includes('Files')) return;
    e.preventDefault();
    this._dragOver = true;
  };

  private onDrop = (e: DragEvent): void => {
    this._dragOver = false;
    const files = [...(e.dataTransfer?.files ?? [])];
    if (!files.length) return;
    e.preventDefault();
    void this.load(files.length === 1 ? files[0] : files);
  };
}

export type { PanelName };
