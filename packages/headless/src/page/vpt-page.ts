/**
 * The in-browser side of @vpt/headless, loaded by page/index.html (whose import map
 * points the @vpt/* names at each package's dist/). It loads core, post and every renderer
 * package of core's renderer catalog, then exposes `window.vpt = { core, post, createRenderer,
 * renderers, <renderer name>: <its module>…, renderDescription, buildScene, loadVolume }` and
 * sets `window.__vptReady`, or `window.__vptError` when a package cannot be loaded.
 */
import type { Environment, MultiscaleSource, RenderContext, Renderer, RequestPolicy, Scene, Volume } from '@vpt/core';
import {
  DISPLAY_REFERRED_POST,
  SCENE_DEFAULTS,
  checkSceneDescription,
  selectTimeStep,
  isChannelFiles,
  type FileVolumeDescription,
  type SceneDescription,
  type VolumeDescription,
  type ZarrVolumeDescription,
} from '../scene-description.js';
import type { PageRenderCallOptions, PageRenderResult, PostModule, VptPageApi } from './types.js';

type CoreModule = VptPageApi['core'];
/** The part of @vpt/loaders this page uses (imported on first use; not a dependency of this package's types). */
interface LoadersModule {
  loadVolume(
    source: string | File[],
    options: {
      format?: string;
      zarr?: Record<string, unknown>;
      request?: Partial<RequestPolicy>;
      time?: number;
      labels?: boolean;
    },
  ): Promise<Volume & { meta?: Record<string, unknown> }>;
  openOmeZarr(url: string, options: Record<string, unknown>): Promise<MultiscaleSource>;
}

let core!: CoreModule;
/** @vpt/core/labels: label volumes (enabled at load). */
type LabelsModule = typeof import('@vpt/core/labels');
let labelsModule: LabelsModule | null = null;
let post!: PostModule;
/** The renderer classes of the catalog, by renderer name. */
const rendererClasses = new Map<string, new (params?: Record<string, unknown>) => Renderer>();
/** The renderer packages' modules (class and descriptor), by renderer name. */
const rendererModules = new Map<string, Record<string, unknown>>();

/** Largest sidecar fetched (as @vpt/loaders bounds its text files). */
const MAX_SIDECAR_BYTES = 16 * 1024 * 1024;
/** Largest file of a `volume.file` list (a DICOM slice, one of files loaded together). */
const MAX_LISTED_FILE_BYTES = 2 ** 31;

/** A URL's bytes under core's request policy: a stalled or hostile server ends in a typed error. */
async function fetchBounded(url: string, maxBytes: number, request: Partial<RequestPolicy>): Promise<Uint8Array> {
  return (await core.fetchWithPolicy(url, { policy: request, maxBytes })).bytes;
}

/** Turn a volume description into a core Volume; relative URLs resolve against baseUrl. */
async function loadVolume(
  desc: VolumeDescription,
  baseUrl: string = document.baseURI,
  request: Partial<RequestPolicy> = {},
  labels = false,
): Promise<Volume> {
  if ('procedural' in desc) return core.createProceduralVolume(desc.procedural, desc.size ?? 32);
  if (isChannelFiles(desc)) return loadChannels(desc.channels, baseUrl, request);
  if ('zarr' in desc) return loadZarr(desc, baseUrl, request, labels);
  if ('file' in desc) return loadFile(desc, baseUrl, request, labels);
  if ('timeSeries' in desc) return loadFile({ ...desc, file: desc.timeSeries[0] }, baseUrl, request, labels);
  if ('sidecar' in desc) {
    // core's raw reader parses the sidecar (as @vpt/loaders and the viewer's fallback do).
    const sidecarUrl = new URL(desc.sidecar, baseUrl).href;
    const text = new TextDecoder().decode(await fetchBounded(sidecarUrl, MAX_SIDECAR_BYTES, request));
    const sidecar = core.parseRawSidecar(text, sidecarUrl);
    // Without the sidecar's `file` (its raw file's name, now in `raw`): `file` is the loaders' volume kind.
    const { file: _rawName, ...header } = sidecar;
    return loadVolume({ raw: core.rawFileBeside(sidecarUrl, sidecar), ...header }, sidecarUrl, request, labels);
  }
  const url = new URL(desc.raw, baseUrl).href;
  // A raw file holds exactly dims × type bytes (rawVoxels checks it): nothing longer is read.
  const expected = desc.dims.reduce((a, b) => a * b, 1) * BYTES_PER_VOXEL[desc.type];
  const data = core.rawVoxels(await fetchBounded(url, expected, request), desc, url);
  const volume = core.createVolume(desc.dims, desc.type, data, desc.spacing ?? [1, 1, 1]);
  if (desc.valueRange) volume.valueRange = desc.valueRange;
  volume.name = url.split('/').pop();
  return volume;
}

/** A label image's own colours and names (OME-Zarr `image-label`), by the loaded volume: the scene's default table. */
const fileLabelColors = new WeakMap<Volume, { id: number; rgba?: number[]; name?: string }[]>();

/** Each channel's own value range (a sidecar's, an omero window) of a volume loaded from channels: the scene's default per-channel range. */
const channelRanges = new WeakMap<Volume, ([number, number] | undefined)[]>();

/** One multichannel volume from one description per channel (files of one grid, OME-Zarr channels along c). */
async function loadChannels(
  descs: VolumeDescription[],
  baseUrl: string,
  request: Partial<RequestPolicy>,
): Promise<Volume> {
  const parts = await Promise.all(descs.map((d) => loadVolume(d, baseUrl, request)));
  const volume = core.interleaveChannels(parts.map((p) => ({ ...p, valueRange: undefined })));
  channelRanges.set(
    volume,
    parts.map((p) => p.valueRange),
  );
  volume.name = parts.map((p) => p.name ?? '').join(' + ');
  return volume;
}

/**
 * An OME-Zarr level through @vpt/loaders (its worker holds zarrita and the codecs, so this
 * page's import map needs nothing more). The omero window is the normalization range
 * unless the description gives one, as a sidecar's value_range is for raw data.
 */
async function loadZarr(
  desc: ZarrVolumeDescription,
  baseUrl: string,
  request: Partial<RequestPolicy>,
  labels = false,
): Promise<Volume> {
  const url = new URL(desc.zarr, baseUrl).href;
  const loaders = await load<LoadersModule>('@vpt/loaders');
  let loaded: Awaited<ReturnType<LoadersModule['loadVolume']>>;
  try {
    loaded = await loaders.loadVolume(url, {
      format: 'ome-zarr',
      zarr: {
        level: desc.level ?? 0,
        ...(desc.channel !== undefined ? { channel: desc.channel } : {}),
        // Several channels along c: one read of the store, interleaved by the loaders.
        ...(desc.channels ? { channels: desc.channels } : {}),
        ...(desc.time !== undefined ? { time: desc.time } : {}),
        ...(desc.missingChunks ? { missingChunks: desc.missingChunks } : {}),
      },
      request,
      ...(labels ? { labels } : {}),
    });
  } catch (e) {
    // A store beyond a bound (too many chunk requests, a bomb) stays limit-exceeded.
    const code = (e as { code?: unknown }).code === 'limit-exceeded' ? 'limit-exceeded' : 'load-failed';
    throw new core.VptError(code, `Could not load OME-Zarr ${url}: ${(e as Error).message}`, { cause: e });
  }
  const base = loaded.name ?? url.split('/').filter(Boolean).pop();
  if (desc.channels) {
    // Each channel's range: the description's (for every channel), else its omero window.
    const windows = (loaded.meta?.channelRanges ?? []) as ([number, number] | null)[];
    const volume = core.createVolume(loaded.dims, loaded.type, loaded.data, loaded.spacing, desc.channels.length);
    channelRanges.set(
      volume,
      desc.channels.map((_, k) => desc.valueRange ?? windows[k] ?? undefined),
    );
    volume.name = desc.channels.map((c) => `${base} c${c}`).join(' + ');
    return volume;
  }
  const volume = core.createVolume(loaded.dims, loaded.type, loaded.data, loaded.spacing);
  const imageLabel = (
    loaded.meta?.zarr as { imageLabel?: { id: number; rgba?: number[]; name?: string }[] } | undefined
  )?.imageLabel;
  if (labels && imageLabel) fileLabelColors.set(volume, imageLabel);
  const window = loaded.meta?.value_range as [number, number] | undefined;
  const range = desc.valueRange ?? window;
  if (range) volume.valueRange = [range[0], range[1]];
  volume.name = base;
  return volume;
}

/**
 * `volume.file` through @vpt/loaders, as the viewer reads a file: one URL (the loader fetches
 * a sidecar's raw file, an .nhdr's data or an .hdr's .img beside it), or a list of URLs
 * fetched here and handed over as Files (a DICOM series, files loaded together).
 */
async function loadFile(
  desc: FileVolumeDescription,
  baseUrl: string,
  request: Partial<RequestPolicy>,
  labels = false,
): Promise<Volume> {
  const loaders = await load<LoadersModule>('@vpt/loaders');
  const format = desc.format && desc.format !== 'auto' ? { format: desc.format } : {};
  const list = Array.isArray(desc.file) ? desc.file.map((f) => new URL(f, baseUrl).href) : null;
  const where = list ? `${list.length} files` : new URL(desc.file as string, baseUrl).href;
  let loaded: Awaited<ReturnType<LoadersModule['loadVolume']>>;
  try {
    const source = list
      ? await Promise.all(
          list.map(
            async (url) =>
              new File(
                [(await fetchBounded(url, MAX_LISTED_FILE_BYTES, request)) as Uint8Array<ArrayBuffer>],
                decodeURIComponent(url.split('/').pop() ?? ''),
              ),
          ),
        )
      : where;
    loaded = await loaders.loadVolume(source, {
      ...format,
      request,
      ...(desc.time ? { time: desc.time } : {}),
      ...(labels ? { labels } : {}),
    });
  } catch (e) {
    throw new core.VptError('load-failed', `Could not load ${where}: ${(e as Error).message}`, { cause: e });
  }
  // A file with a channel axis (NRRD list/vector/colour, NIfTI dim[5] or RGB) stays multichannel: the scene needs `channels`.
  const volume = core.createVolume(loaded.dims, loaded.type, loaded.data, loaded.spacing, loaded.channels ?? 1);
  // As for a sidecar's or an OME-Zarr omero window: the description's range wins.
  const window = loaded.valueRange ?? (loaded.meta?.value_range as [number, number] | undefined);
  const range = desc.valueRange ?? window;
  if (range) volume.valueRange = [range[0], range[1]];
  volume.name = loaded.name ?? where.split('/').filter(Boolean).pop();
  return volume;
}

const BYTES_PER_VOXEL = { uint8: 1, uint16: 2, int16: 2, float32: 4 } as const;

/**
 * An OME-Zarr volume without a `level` whose level 0 does not fit the context's budget
 * (volumeBudgetBytes) or 3D texture limit as it is: the source, opened in this thread for
 * the brick cache, and the finest level that fits, which stands in for it (the coarsest
 * when none does). Null when level 0 fits: it loads whole, as before. A multichannel volume
 * (`channels` along c) opens one source per channel and streams them as one interleaved
 * source (MultiscaleSource.channels); the budget counts the drawn channels' bytes (the
 * atlas is rg / rgba of the source type, planChannelUpload).
 */
async function zarrToStream(
  d: SceneDescription,
  ctx: RenderContext,
  baseUrl: string,
  request: Partial<RequestPolicy>,
): Promise<{ source: MultiscaleSource; level: number } | null> {
  const v = d.volume;
  if (!v || !('zarr' in v) || v.level !== undefined) return null;
  const url = new URL(v.zarr, baseUrl).href;
  const loaders = await load<LoadersModule>('@vpt/loaders');
  const open = (channel: number | undefined) =>
    loaders.openOmeZarr(url, {
      ...(channel !== undefined ? { channel } : {}),
      ...(v.time !== undefined ? { time: v.time } : {}),
      ...(v.missingChunks ? { missingChunks: v.missingChunks } : {}),
      request,
    });
  let parts: MultiscaleSource[];
  try {
    parts = await Promise.all((v.channels ?? [v.channel]).map(open));
  } catch (e) {
    throw new core.VptError('load-failed', `Could not load OME-Zarr ${url}: ${(e as Error).message}`, { cause: e });
  }
  const source = parts[0];
  // Texel components of the texture: the drawn channels (2 → rg, 3 or 4 → rgba), 1 for a scalar volume.
  const drawn = v.channels ? (d.channels ?? []).filter((c) => c.enabled !== false).length : 1;
  const components = drawn <= 1 ? 1 : drawn === 2 ? 2 : 4;
  const perVoxel = components * ((d.sampling ?? 'fast') === 'exact' ? 4 : BYTES_PER_VOXEL[source.type]);
  const budget = ctx.volumeBudgetBytes;
  const max3D = ctx.backend.limits.maxTextureDimension3D;
  const fits = (k: number) => core.fitFactors(source.levels[k].dims, perVoxel, budget, max3D)?.every((f) => f === 1);
  if (fits(0)) return null;
  const level = source.levels.findIndex((_, k) => fits(k));
  const pick = { level: level < 0 ? source.levels.length - 1 : level };
  if (v.channels) return { source: interleavedSource(parts), ...pick };
  // The description's valueRange wins over the omero window, as for a loaded level.
  const range = v.valueRange ?? source.valueRange;
  const streamed: MultiscaleSource = {
    type: source.type,
    levels: source.levels,
    ...(range ? { valueRange: [range[0], range[1]] as [number, number] } : {}),
    readRegion: (l, min, max, signal) => source.readRegion(l, min, max, signal),
    readLevel: (l, signal) => source.readLevel(l, signal),
  };
  return { source: streamed, ...pick };
}

/**
 * One multiscale source of several channel sources of one store (the same levels and type):
 * each region read from every channel, interleaved (the channel fastest, Volume.channels).
 * The channels' value ranges are the scene's (channel settings, the omero windows).
 */
function interleavedSource(parts: MultiscaleSource[]): MultiscaleSource {
  const first = parts[0];
  parts.forEach((p, k) => {
    const same = p.type === first.type && p.levels.length === first.levels.length;
    if (!same || p.levels.some((l, i) => l.dims.some((n, a) => n !== first.levels[i].dims[a])))
      throw new core.VptError(
        'invalid-scene',
        `volume.channels: channel ${k} of the store has other levels or type than channel 0`,
      );
  });
  const C = parts.length;
  return {
    type: first.type,
    levels: first.levels,
    channels: C,
    async readRegion(l, min, max, signal) {
      const regions = await Promise.all(parts.map((p) => p.readRegion(l, min, max, signal)));
      const n = regions[0].length;
      const out = new (regions[0].constructor as new (n: number) => (typeof regions)[0])(n * C);
      for (let k = 0; k < C; k++) {
        const r = regions[k];
        for (let i = 0; i < n; i++) out[k + C * i] = r[i];
      }
      return out;
    },
    async readLevel(l, signal) {
      const levels = await Promise.all(parts.map((p) => p.readLevel(l, signal)));
      return core.interleaveChannels(levels.map((p) => ({ ...p, valueRange: undefined })));
    },
  };
}

function environmentOf(d: SceneDescription): Environment {
  const env = d.environment ?? SCENE_DEFAULTS.environment;
  if (env.type === 'latlong') return { ...env, data: Float32Array.from(env.data) };
  return env;
}

/** Build the core Scene for a description (defaults filled in): the page API's entry, which checks it. */
async function buildScene(d: SceneDescription, baseUrl?: string, request?: Partial<RequestPolicy>): Promise<Scene> {
  checkSceneDescription(d, [...rendererClasses.keys()]);
  return sceneOf(selectTimeStep(d), baseUrl, request);
}

/** The Scene of a description that was checked where it entered the page (buildScene, renderDescription). */
async function sceneOf(d: SceneDescription, baseUrl?: string, request?: Partial<RequestPolicy>): Promise<Scene> {
  const tf = d.transferFunction;
  // Label ids are kept as loaded (integers, no value range): core's toLabelVolume refuses anything else.
  const lm = labelsModule;
  if (d.labels && !lm)
    throw new core.VptError('invalid-scene', 'labels: this page could not load @vpt/core/labels (label volumes)');
  const loadedLabels = d.labels ? await loadVolume(d.labels.volume, baseUrl, request, true) : null;
  const labelVolume = loadedLabels && lm ? lm.toLabelVolume(loadedLabels, 'labels.volume') : null;
  // The default table: every id present, in the file's own colours where it has them (OME-Zarr image-label).
  const fileColors = loadedLabels ? fileLabelColors.get(loadedLabels) : undefined;
  // Labels alone: an empty image on their grid.
  const volume =
    labelVolume && !d.volume
      ? core.createVolume(labelVolume.dims, 'uint8', new Uint8Array(labelVolume.data.length), labelVolume.spacing)
      : await loadVolume(d.volume ?? SCENE_DEFAULTS.volume, baseUrl, request);
  const ranges = channelRanges.get(volume);
  return {
    volume,
    ...(labelVolume
      ? {
          labels: {
            volume: labelVolume,
            table: d.labels!.table
              ? d.labels!.table.map((e) => ({ ...e }))
              : fileColors
                ? lm!.withLabelColors(lm!.defaultLabelTable(labelVolume), fileColors)
                : lm!.defaultLabelTable(labelVolume),
          },
        }
      : {}),
    ...(d.channels
      ? {
          channels: d.channels.map((c, k) => {
            const range = c.range ?? ranges?.[k];
            return {
              transferFunction: { dimensions: '1d' as const, points: c.transferFunction.points },
              ...(c.enabled !== undefined ? { enabled: c.enabled } : {}),
              ...(c.color ? { color: c.color } : {}),
              ...(range ? { range: [range[0], range[1]] as [number, number] } : {}),
            };
          }),
        }
      : {}),
    transferFunction: !tf
      ? core.rampTransferFunction()
      : tf.dimensions === '2d'
        ? core.transferFunctionFromJSON(tf)
        : { dimensions: '1d', points: tf.points },
    camera: { ...core.defaultCamera(), ...d.camera },
    lights: d.lights ?? [],
    environment: environmentOf(d),
    densityScale: d.densityScale ?? SCENE_DEFAULTS.densityScale,
    seed: d.seed ?? SCENE_DEFAULTS.seed,
    ...(d.sampling ? { sampling: d.sampling } : {}),
    ...(d.clip ? { clip: d.clip } : {}),
    ...(d.slicePlane ? { slicePlane: d.slicePlane } : {}),
  };
}

/** A renderer of the catalog by name, constructed with its parameter object. */
function createRenderer(name: string, params: Record<string, unknown> = {}): Renderer {
  const Ctor = rendererClasses.get(name);
  if (!Ctor)
    throw new core.VptError('invalid-scene', `Unknown renderer "${name}" (${[...rendererClasses.keys()].join(', ')})`);
  return new Ctor(params);
}

function makeRenderer(d: SceneDescription): Renderer {
  return createRenderer(d.renderer ?? core.DEFAULT_RENDERER_NAME, d.rendererParams ?? {});
}

/** Base64 of a typed array's bytes, in chunks (String.fromCharCode takes limited arguments). */
function toBase64(a: ArrayBufferView): string {
  const bytes = new Uint8Array(a.buffer, a.byteOffset, a.byteLength);
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

/**
 * Render a scene description: exactly `iterations` progressive iterations, then read
 * the HDR and LDR images back. `totalMs` times those iterations plus the render and
 * post passes, after one warm-up iteration has compiled the kernels (compilation is
 * reported in `setupMs`, with volume loading and upload).
 */
async function renderDescription(
  input: SceneDescription,
  options: PageRenderCallOptions = {},
): Promise<PageRenderResult> {
  const t0 = performance.now();
  checkSceneDescription(input, [...rendererClasses.keys()]);
  const desc = selectTimeStep(input);
  const width = desc.width ?? SCENE_DEFAULTS.width;
  const height = desc.height ?? SCENE_DEFAULTS.height;
  const iterations = desc.iterations ?? SCENE_DEFAULTS.iterations;
  const steps = post.postChainFromJSON(desc.post ?? defaultPost(desc));
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  const ctx = await core.RenderContext.create({
    canvas,
    backend: desc.backend ?? SCENE_DEFAULTS.backend,
    width,
    height,
    renderer: makeRenderer(desc),
    post: steps,
    ...(desc.maxGpuBytes ? { maxGpuBytes: desc.maxGpuBytes } : {}),
    ...(options.temporal ? { temporal: true } : {}),
  });
  const warnings: string[] = [];
  ctx.onWarning((w) => warnings.push(w.message));
  try {
    // An OME-Zarr level 0 beyond the budget streams through the brick cache, from the finest level that fits.
    const request = options.request ?? {};
    const streamed = await zarrToStream(desc, ctx, options.baseUrl ?? document.baseURI, request);
    const volume = streamed && { ...(desc.volume as ZarrVolumeDescription), level: streamed.level };
    // Checked on entry above; the level added to a streamed volume is the page's own.
    const scene = await sceneOf(volume ? { ...desc, volume } : desc, options.baseUrl, request);
    let bricked = false;
    if (streamed) {
      ctx.setVolumeSource(scene.volume, streamed.source);
      try {
        ctx.setScene(scene);
        bricked = true;
      } catch (e) {
        if (!(e instanceof core.VptError && e.code === 'limit-exceeded')) throw e;
        // Level 0 cannot be bricked (its page table alone is beyond the budget, a 100000³ shape
        // say): render the finest level that fits, whole, as if it had been asked for. A copy,
        // so the context uploads it instead of bricking it from the source.
        warnings.push(
          `OME-Zarr level 0 [${streamed.source.levels[0].dims.join(', ')}] cannot be streamed (${e.message}); level ${streamed.level} is rendered whole`,
        );
        ctx.setScene({ ...scene, volume: { ...scene.volume } });
      }
    } else ctx.setScene(scene);
    // Every brick the view needs (or as many as the atlas holds) before the timed iterations.
    const bricking = bricked ? await ctx.whenBricksSettled() : null;
    if (options.warmup !== false) await ctx.renderIterations(1);
    const t1 = performance.now();
    const run =
      options.progress || options.timeLimitMs !== undefined
        ? await iterateInBatches(ctx, iterations, options.timeLimitMs ?? Infinity)
        : { done: await ctx.renderIterations(iterations).then(() => iterations), timeLimited: false };
    const totalMs = performance.now() - t1;
    // The HDR image after the post steps that keep radiance (a denoiser), before exposure and tone mapping.
    const hdr = await ctx.readHDR({ afterPost: true });
    const hdrPostSteps = ctx.post.slice(0, ctx.radianceStepCount()).map((s) => s.name);
    // Without post steps there is no LDR image (core refuses to invent one).
    const ldr = steps.length > 0 ? await ctx.readLDR() : null;
    const stats = ctx.stats;
    return {
      width,
      height,
      hdr: toBase64(hdr),
      hdrPostSteps,
      ldr: ldr ? toBase64(ldr) : null,
      timings: {
        totalMs,
        iterations: stats.iterations,
        msPerIteration: run.timeLimited || options.progress ? totalMs / run.done : stats.msPerIteration,
        setupMs: t1 - t0,
        ...(run.timeLimited ? { timeLimited: true } : {}),
      },
      backend: { kind: ctx.backend.kind, renderer: ctx.backend.info.renderer },
      gpuBytes: stats.gpuBytes,
      volumeDims: [...ctx.getScene()!.volume.dims] as [number, number, number],
      warnings,
      bricking,
      rendererStats: { ...stats.renderer },
    };
  } finally {
    ctx.dispose();
  }
}

/** The post chain of a description without one: the renderer's descriptor says whether its HDR image holds display values. */
function defaultPost(desc: SceneDescription): Record<string, unknown>[] {
  const name = desc.renderer ?? core.DEFAULT_RENDERER_NAME;
  const descriptor = rendererModules.get(name)?.descriptor as { displayReferred?: boolean } | undefined;
  return descriptor?.displayReferred ? DISPLAY_REFERRED_POST : SCENE_DEFAULTS.post;
}

/**
 * The same iterations as renderIterations(n) (one reset, then iterate, then the image), in
 * batches of about BATCH_MS each, so that progress is reported and a time limit can stop
 * between batches. The batch grows from 1 while batches are quick.
 */
const BATCH_MS = 250;
async function iterateInBatches(
  ctx: RenderContext,
  total: number,
  timeLimitMs: number,
): Promise<{ done: number; timeLimited: boolean }> {
  ctx.reset();
  const t0 = performance.now();
  let done = 0;
  let batch = 1;
  let timeLimited = false;
  while (done < total) {
    const n = Math.min(batch, total - done);
    const tb = performance.now();
    ctx.iterate(n);
    await ctx.backend.finish();
    done += n;
    const elapsed = performance.now() - t0;
    window.__vptRenderProgress?.(done, total, elapsed);
    if (done < total && elapsed >= timeLimitMs) {
      timeLimited = true;
      break;
    }
    const ms = performance.now() - tb;
    if (ms < BATCH_MS / 2) batch = Math.min(batch * 2, 1 << 16);
  }
  ctx.renderImage();
  await ctx.backend.finish();
  return { done, timeLimited };
}

async function load<T>(name: string): Promise<T> {
  try {
    return (await import(/* @vite-ignore */ name)) as T;
  } catch (e) {
    throw new Error(`could not load ${name} (${(e as Error).message}); build the packages first: pnpm run build`);
  }
}

try {
  [core, post] = await Promise.all([load<CoreModule>('@vpt/core'), load<PostModule>('@vpt/post')]);
  // Scene files may carry label volumes (core's scene/labels.ts): opt-in, so bundles without them stay small.
  try {
    labelsModule = await load<LabelsModule>('@vpt/core/labels');
    labelsModule.enableLabels();
  } catch {
    // A core without the subpath (the page test's stub packages): a scene with labels is then refused, typed.
  }
  // Every renderer of the catalog, imported by its package name (the import map resolves it).
  const modules = await Promise.all(core.RENDERER_CATALOG.map((e) => load<Record<string, unknown>>(e.packageName)));
  const renderers: Record<string, Record<string, unknown>> = {};
  core.RENDERER_CATALOG.forEach((e, i) => {
    const Ctor = modules[i][e.exportName];
    if (typeof Ctor !== 'function') throw new Error(`${e.packageName} does not export ${e.exportName}`);
    rendererClasses.set(e.name, Ctor as new (params?: Record<string, unknown>) => Renderer);
    rendererModules.set(e.name, modules[i]);
    renderers[e.name] = modules[i];
  });
  window.vpt = {
    ...renderers,
    core,
    post,
    renderers,
    createRenderer,
    renderDescription,
    buildScene,
    loadVolume,
  } as unknown as VptPageApi;
  window.__vptReady = true;
} catch (e) {
  window.__vptError = (e as Error).message;
  console.error(window.__vptError);
}
