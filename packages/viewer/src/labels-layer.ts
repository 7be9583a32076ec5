/**
 * The element's label volume (the `labels` attribute), loaded on first use: a lazy chunk of
 * the one-file bundle, with core's opt-in `@vpt/core/labels` (enableLabels), so a page without
 * labels never loads either. It reads the label file (any format the viewer reads, ids kept:
 * loaders' `labels: true`), checks it lies on the image's grid, makes the default table (the
 * file's names and colours where it has them: OME-Zarr `image-label`, 3D Slicer's NRRD
 * `SegmentN_*` keys; else core's tab20 palette), draws the Labels panel and answers the hover
 * pick (label-pick.ts).
 */
import { html, nothing } from 'lit';
import {
  VptError,
  isClippedPoint,
  slicePlane,
  volumeBox,
  type LabelEntry,
  type RequestPolicy,
  type Scene,
  type Volume,
} from '@vpt/core';
import { defaultLabelColor, defaultLabelTable, enableLabels, toLabelVolume, withLabelColors } from '@vpt/core/labels';
import { hexToLinear, linearToHex } from './color.js';
import type { LoadedVolumeLike } from './loading/types.js';
import { sourceAtLevel } from './loading/multiscale.js';
import { volumeLoader, ELEMENT_RAW_HINT } from './loading/volume-source.js';
import { pickLabel, slicePointAt, sliceSpecOf, visibleIds, voxelOf } from './label-pick.js';

/**
 * The voxel of the visible label under pixel (fx, fy) of the 3D view (a label scene): for the
 * slice renderer the voxel of its plane there, for the others the first visible label on the
 * pixel's ray; null: none.
 */
export function labelHit(
  scene: Scene,
  renderer: string,
  params: Record<string, unknown>,
  aspect: number,
  fx: number,
  fy: number,
): [number, number, number] | null {
  const labels = scene.labels!;
  const visible = visibleIds(labels.table, labels.volume.type);
  if (renderer !== 'slice')
    return pickLabel(labels.volume, visible, scene.camera, aspect, fx, fy, scene.clip)?.voxel ?? null;
  let p;
  try {
    p = slicePointAt(slicePlane(sliceSpecOf(params), scene.volume), params.fit === true, scene.camera, aspect, fx, fy);
  } catch {
    return null; // a plane that misses this volume: the renderer draws nothing either
  }
  const voxel = p && !(scene.clip && isClippedPoint(scene.clip, p)) ? voxelOf(labels.volume, p) : null;
  const v = labels.volume;
  return voxel && visible[v.data[voxel[0] + v.dims[0] * (voxel[1] + v.dims[1] * voxel[2])]] ? voxel : null;
}

/** A label file's per-id colours and names, as core's withLabelColors takes them (rgba: sRGB bytes). */
type FileLabel = { id: number; rgba?: number[]; name?: string };

/**
 * 3D Slicer's segmentation NRRD keys (`Segment0_Name:=liver`, `Segment0_LabelValue:=1`,
 * `Segment0_Color:=0.8 0.2 0.1`, display colour in [0, 1]); a segment without LabelValue is
 * id index + 1 (Slicer's older files).
 */
export function nrrdSegments(keyValues: Record<string, string> | undefined): FileLabel[] {
  const out: FileLabel[] = [];
  if (!keyValues) return out;
  for (const k of Object.keys(keyValues)) {
    const m = /^Segment(\d+)_Name$/.exec(k);
    if (!m) continue;
    const i = Number(m[1]);
    const value = Number(keyValues[`Segment${i}_LabelValue`] ?? i + 1);
    if (!Number.isInteger(value) || value < 1 || value > 65535) continue;
    const rgb = (keyValues[`Segment${i}_Color`] ?? '').trim().split(/\s+/).map(Number);
    out.push({
      id: value,
      name: keyValues[k],
      ...(rgb.length === 3 && rgb.every((c) => c >= 0 && c <= 1)
        ? { rgba: [...rgb.map((c) => Math.round(c * 255)), 255] }
        : {}),
    });
  }
  return out;
}

/** The default table of a loaded label volume: every id present, the file's names and colours where it has them. */
export function fileLabelTable(loaded: LoadedVolumeLike, volume: Volume): LabelEntry[] {
  const zarr = (loaded.meta?.zarr as { imageLabel?: FileLabel[] } | undefined)?.imageLabel;
  const named = zarr ?? nrrdSegments(loaded.meta?.keyValues as Record<string, string> | undefined);
  const table = defaultLabelTable(volume);
  return named.length ? withLabelColors(table, named) : table;
}

/** A label volume read: the ids, the file's default table, and an OME-Zarr group's level and its levels' dims. */
interface LabelData {
  volume: Volume;
  table: LabelEntry[];
  level: number;
  levels: number[][];
}

/** Read `url` as a label volume (integer ids, never normalized) and its default table. */
export async function loadLabels(
  url: string,
  request: Partial<RequestPolicy>,
  signal: AbortSignal,
): Promise<LabelData> {
  enableLabels();
  const { loadVolume } = await volumeLoader();
  // An OME-Zarr label image is a group inside the image's store (….ome.zarr/labels/<name>): its URL does not end in .zarr.
  const zarr = /\.zarr\/labels\/[^/?#]+\/?([?#].*)?$/i.test(url);
  const loaded = await loadVolume(url, {
    labels: true,
    request,
    rawHint: ELEMENT_RAW_HINT,
    signal,
    ...(zarr ? { format: 'ome-zarr' as const } : {}),
  });
  const volume = toLabelVolume(loaded, 'labels');
  const z = loaded.meta?.zarr as { level?: number; levels?: { dims: number[] }[] } | undefined;
  return {
    volume,
    table: fileLabelTable(loaded, volume),
    level: z?.level ?? 0,
    levels: z?.levels?.map((l) => l.dims) ?? [],
  };
}

/** The typed error of a label volume that does not lie on the image's grid (same dims, same box), else null. */
export function gridError(labels: Volume, image: Volume): VptError | null {
  const lb = volumeBox(labels).size,
    ib = volumeBox(image).size;
  const sameDims = labels.dims.every((d, i) => d === image.dims[i]);
  if (sameDims && lb.every((s, i) => Math.abs(s - ib[i]) <= 1e-6)) return null;
  return new VptError(
    'invalid-scene',
    `labels: the label volume's grid ${labels.dims.join('×')} (spacing ${labels.spacing.join(', ')}) is not the image's ${image.dims.join('×')} (spacing ${image.spacing.join(', ')}); a label volume must lie on the image's grid`,
  );
}

/** The label under the pointer (`hoveredLabel`, `vpt-hover`): its id, its name in the label table, the voxel [i, j, k]. */
export interface HoveredLabel {
  id: number;
  name?: string;
  voxel: [number, number, number];
}
/** `vpt-hover`: the label under the pointer changed (null: none now). */
export interface ViewerHoverDetail {
  label: HoveredLabel | null;
}

/** What the layer reads of the element (its public side). */
export interface LabelHost extends EventTarget {
  readonly labels: string | null;
  readonly labelTable: LabelEntry[] | null;
  readonly loadedVolume: Volume | null;
  /** The RenderContext: its size, the scene it draws and its renderer (the slice renderer's plane). */
  readonly context: {
    size: { width: number; height: number };
    getScene(): Scene | null;
    renderer: { name: string; getParams?(): unknown };
  } | null;
  readonly requestPolicy: Partial<RequestPolicy>;
  readonly renderRoot: HTMLElement | DocumentFragment;
  requestUpdate(): void;
  setInternal(property: 'labelTable', value: unknown): void;
}

/** The element's private side the layer needs, as closures. */
export interface LabelHostHooks {
  /** Report an error with source 'labels' (the banner, `vpt-error`), and clear it. */
  fail(e: unknown): void;
  clear(): void;
  /** Apply the scene to the GPU. */
  apply(): void;
}

let uid = 0;

/** The element's label volume: loading, the scene's `labels`, the hover readout and the Labels panel. */
export class LabelLayer {
  private data: LabelData | null = null;
  private url: string | null = null;
  private abort: AbortController | null = null;
  private over: (HoveredLabel & { fx: number; fy: number }) | null = null;

  /** The tooltip over the image (the hovered label's name, or its id), a node of the view beside the canvas. */
  private readonly tip: HTMLElement;
  /** The elements whose pointerleave hides the tooltip. */
  private readonly left = new WeakSet<HTMLElement>();

  constructor(
    private readonly host: LabelHost,
    private readonly hooks: LabelHostHooks,
  ) {
    // The view listens here, not in the element's template: the entry bundle stays as it was.
    const view = host.renderRoot.querySelector('.view') as HTMLElement;
    view.addEventListener('pointermove', (e) => this.hover(e));
    view.addEventListener('pointerleave', () => this.hover(null));
    this.left.add(view);
    this.tip = document.createElement('p');
    this.tip.setAttribute('part', 'label-tip');
    this.tip.setAttribute('role', 'status');
    this.tip.hidden = true;
    this.tip.style.cssText =
      'position:absolute;z-index:2;margin:0;padding:1px 4px;transform:translate(8px,8px);font-size:11px;white-space:nowrap;pointer-events:none;color:#fff;background:rgba(0,0,0,0.7)';
    view.append(this.tip);
  }

  /** The label file's default table (null: no label volume loaded). */
  get table(): LabelEntry[] | null {
    return this.data?.table ?? null;
  }

  get hovered(): HoveredLabel | null {
    const h = this.over;
    return h ? { id: h.id, ...(h.name ? { name: h.name } : {}), voxel: [...h.voxel] } : null;
  }

  /** Load the label volume at `url` (null: none); a failure or another grid is reported and drawn as no labels. */
  async load(url: string | null): Promise<void> {
    this.abort?.abort();
    const abort = (this.abort = new AbortController());
    this.data = null;
    this.url = url;
    this.setHover(null);
    try {
      if (url) {
        const data = await loadLabels(url, this.host.requestPolicy, abort.signal);
        if (abort.signal.aborted) return;
        this.data = data;
      }
      this.hooks.clear();
      await this.check();
    } catch (e) {
      if (abort.signal.aborted) return;
      this.hooks.fail(e);
    }
    this.hooks.apply();
    this.host.requestUpdate();
  }

  /**
   * A new image (or new labels): a label volume off the image's grid is reported, unless it is
   * an OME-Zarr group with a level on that grid (the image shown at a coarser level of its
   * store, as the element does while it refines), which is read instead, the table kept.
   */
  async check(): Promise<void> {
    const image = this.host.loadedVolume,
      d = this.data,
      abort = this.abort;
    if (!d || !image || !abort) return;
    const err = gridError(d.volume, image);
    if (!err) return this.hooks.clear();
    const k = d.levels.findIndex((dims) => dims.every((n, i) => n === image.dims[i]));
    if (k < 0 || k === d.level) return this.hooks.fail(err);
    try {
      const next = await loadLabels(sourceAtLevel(this.url!, k), this.host.requestPolicy, abort.signal);
      // Another image (a finer level) or other labels came meanwhile: their own check decides.
      if (abort.signal.aborted || this.data !== d || this.host.loadedVolume !== image) return;
      this.data = { ...next, table: d.table, levels: d.levels };
    } catch (e) {
      if (!abort.signal.aborted) this.hooks.fail(e);
      return;
    }
    this.hooks.clear();
    this.hooks.apply();
  }

  /** The scene's `labels` for this image: none without a label volume on its grid. */
  scene(image: Volume | null): Pick<Scene, 'labels'> {
    const d = this.data,
      table = this.host.labelTable;
    if (!d || !table || !image || gridError(d.volume, image)) return {};
    return { labels: { volume: d.volume, table } };
  }

  /** The pointer over the 3D view (null: it left): the label its pixel sees (labelHit). */
  hover(e: PointerEvent | null): void {
    // The scene on display (its camera, clip and labels), as its renderer draws it.
    const ctx = this.host.context;
    const drawn = e && ctx ? ctx.getScene() : null;
    if (!e || !drawn?.labels) return this.setHover(null);
    // The file's label volume, not the context's copy (downsampled when over the memory budget):
    // the voxel reported is the file's.
    const own = this.scene(this.host.loadedVolume).labels;
    const scene = own ? { ...drawn, labels: { ...drawn.labels, volume: own.volume } } : drawn;
    const r = (e.currentTarget as HTMLElement).getBoundingClientRect();
    const fx = (e.clientX - r.left) / r.width,
      fy = (e.clientY - r.top) / r.height;
    const { width, height } = ctx!.size;
    const params = (ctx!.renderer.getParams?.() ?? {}) as Record<string, unknown>;
    const hit =
      fx >= 0 && fx <= 1 && fy >= 0 && fy <= 1
        ? labelHit(scene, ctx!.renderer.name, params, width / height, fx, fy)
        : null;
    this.hoverVoxel(hit, fx, fy, e.currentTarget as HTMLElement);
  }

  /**
   * The label of a voxel (the pick's, or a slice pane's probe), its tooltip at (fx, fy) of `where`
   * (the 3D view, or the pane's stage).
   */
  hoverVoxel(voxel: [number, number, number] | null, fx: number, fy: number, where: HTMLElement): void {
    if (this.tip.parentElement !== where) {
      // A pane's stage: the tooltip goes when the pointer leaves it, as the probe line does.
      if (!this.left.has(where)) where.addEventListener('pointerleave', () => this.hover(null));
      this.left.add(where);
      where.append(this.tip);
    }
    const scene = this.scene(this.host.loadedVolume);
    const labels = scene.labels;
    if (!voxel || !labels) return this.setHover(null);
    const v = labels.volume;
    const id = v.data[voxel[0] + v.dims[0] * (voxel[1] + v.dims[1] * voxel[2])];
    if (!visibleIds(labels.table, v.type)[id]) return this.setHover(null);
    const name = labels.table.find((e) => e.id === id)?.name;
    this.setHover({ id, ...(name ? { name } : {}), voxel: [...voxel], fx, fy });
  }

  private setHover(h: (HoveredLabel & { fx: number; fy: number }) | null): void {
    const before = this.over;
    this.over = h;
    this.tip.hidden = !h;
    if (h) {
      this.tip.textContent = h.name ?? `label ${h.id}`;
      this.tip.style.left = `${(100 * h.fx).toFixed(2)}%`;
      this.tip.style.top = `${(100 * h.fy).toFixed(2)}%`;
    }
    if ((before?.id ?? 0) !== (h?.id ?? 0))
      this.host.dispatchEvent(new CustomEvent<ViewerHoverDetail>('vpt-hover', { detail: { label: this.hovered } }));
  }

  /**
   * The Labels panel: per label of the table its id and name, a colour picker, an opacity slider
   * (the entry's `opacity`, the extinction per unit densityScale its voxels add; 0 draws it as hidden)
   * and a visible toggle.
   */
  panel() {
    const table = this.host.labelTable;
    if (!this.data || !table) return nothing;
    const write = (i: number, patch: Partial<LabelEntry>) =>
      this.host.setInternal(
        'labelTable',
        table.map((e, k) => (k === i ? { ...e, ...patch } : e)),
      );
    const n = ++uid;
    return html`<details open>
      <summary>Labels</summary>
      <div class="panel">
        ${
          table.length
            ? table.map((e, i) => {
                const cid = `vpt-label-${n}-${e.id}`;
                return html`<div class="row" data-label-id=${e.id}>
                  <label for=${cid}>${e.id}${e.name ? ` ${e.name}` : ''}</label>
                  <span>
                    <input
                      type="color"
                      aria-label="Colour of label ${e.id}"
                      .value=${linearToHex(e.color ?? defaultLabelColor(e.id))}
                      @change=${(ev: Event) => write(i, { color: hexToLinear((ev.target as HTMLInputElement).value) })}
                    />
                    <input
                      type="range"
                      min="0"
                      max="1"
                      step="0.05"
                      aria-label="Opacity of label ${e.id}"
                      title="Opacity"
                      .value=${String(e.opacity ?? 1)}
                      @input=${(ev: Event) => write(i, { opacity: Number((ev.target as HTMLInputElement).value) })}
                    />
                    <input
                      id=${cid}
                      type="checkbox"
                      title="Visible"
                      .checked=${e.visible !== false}
                      @change=${(ev: Event) => write(i, { visible: (ev.target as HTMLInputElement).checked })}
                    />
                  </span>
                </div>`;
              })
            : html`<p>No labels in the volume.</p>`
        }
      </div>
    </details>`;
  }
}
