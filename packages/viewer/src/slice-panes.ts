/**
 * The slice panes of `layout="slices" | "quad"`: axial, coronal and sagittal planes of the
 * loaded volume, each drawn by the slice renderer (`fit: true`) in a RenderContext of its
 * own (see docs/architecture.md, "Viewer layouts"), plus the geometry the element needs to
 * link them: which index axis each pane cuts, how its image is flipped on screen so that
 * anatomy reads as a radiologist expects, the orientation labels at its edges, and the
 * mapping from a pointer position to a voxel.
 */
import {
  RenderContext,
  type BackendPreference,
  type MultiscaleSource,
  type Renderer,
  type Scene,
  type Volume,
} from '@vpt/core';
import { defaultPostChain } from '@vpt/post';
import { anatomicalFrame, type OrientedVolume } from './camera-fit.js';
import { webglSlots, type SlotHolder } from './context-slots.js';
import { createRenderer } from './renderer-registry.js';
import { sameScene } from './session.js';

export type ViewerLayout = '3d' | 'slices' | 'quad';
export const VIEWER_LAYOUTS: readonly ViewerLayout[] = ['3d', 'slices', 'quad'];
export type PaneName = 'axial' | 'coronal' | 'sagittal';
export const PANE_NAMES: readonly PaneName[] = ['axial', 'coronal', 'sagittal'];
export type Voxel = [number, number, number];
type Axis = 0 | 1 | 2;
const AXIS_NAMES = ['x', 'y', 'z'] as const;

/** The slice renderer's image axes (columns, rows) per normal axis: z → (x, y), y → (x, z), x → (y, z). */
const IMAGE_AXES: Record<Axis, [Axis, Axis]> = { 0: [1, 2], 1: [0, 2], 2: [0, 1] };

/** The labels at the pane's four edges (null: the data says nothing about its orientation). */
export interface EdgeLabels {
  left: string;
  right: string;
  top: string;
  bottom: string;
}

/** How one pane shows the volume: the index axis it cuts and how its image sits on screen. */
export interface PaneGeometry {
  name: PaneName;
  /** The index axis perpendicular to the plane. */
  axis: Axis;
  /** Index axes along the slice image's columns and rows (row 0, the lowest index, is the image's top row). */
  col: Axis;
  row: Axis;
  /** The image is transposed on screen (its columns run down), then mirrored: left-right, top-bottom. */
  transpose: boolean;
  flipX: boolean;
  flipY: boolean;
  labels: EdgeLabels | null;
}

const OPPOSITE: Record<string, string> = { R: 'L', L: 'R', A: 'P', P: 'A', S: 'I', I: 'S' };
const samePair = (a: string, b: string) => a === b || a === OPPOSITE[b];

/** On screen, per pane: the anatomical direction toward the right and toward the bottom (radiological convention). */
const SCREEN: Record<PaneName, { right: string; bottom: string }> = {
  axial: { right: 'L', bottom: 'P' },
  coronal: { right: 'L', bottom: 'I' },
  sagittal: { right: 'P', bottom: 'I' },
};

/**
 * The three panes of a volume. With an orientation (anatomicalFrame: NIfTI, NRRD, DICOM or a
 * sidecar's axis codes) axial cuts the index axis nearest superior, coronal anterior and
 * sagittal right, and each image is transposed and mirrored on screen so that it shows
 * SCREEN's directions (the patient's right on the viewer's left, superior or anterior up);
 * without one, axial cuts z, coronal y, sagittal x, each with its rows running up and no labels.
 */
export function paneGeometries(volume: OrientedVolume): PaneGeometry[] {
  const frame = anatomicalFrame(volume);
  const nonZero = (v: readonly number[]) => v.findIndex((x) => x !== 0) as Axis;
  const letterOf = (a: Axis): string => {
    if (frame!.right[a]) return frame!.right[a] > 0 ? 'R' : 'L';
    if (frame!.anterior[a]) return frame!.anterior[a] > 0 ? 'A' : 'P';
    return frame!.superior[a] > 0 ? 'S' : 'I';
  };
  const axes: Record<PaneName, Axis> = frame
    ? { axial: nonZero(frame.superior), coronal: nonZero(frame.anterior), sagittal: nonZero(frame.right) }
    : { axial: 2, coronal: 1, sagittal: 0 };
  return PANE_NAMES.map((name) => {
    const axis = axes[name];
    const [col, row] = IMAGE_AXES[axis];
    if (!frame) return { name, axis, col, row, transpose: false, flipX: false, flipY: true, labels: null };
    const want = SCREEN[name];
    const transpose = !samePair(letterOf(col), want.right);
    // Unflipped, the horizontal axis's + direction points right and the vertical one's down.
    const h = letterOf(transpose ? row : col);
    const v = letterOf(transpose ? col : row);
    const flipX = h !== want.right;
    const flipY = v !== want.bottom;
    const right = flipX ? OPPOSITE[h] : h;
    const bottom = flipY ? OPPOSITE[v] : v;
    return {
      name,
      axis,
      col,
      row,
      transpose,
      flipX,
      flipY,
      labels: { right, left: OPPOSITE[right], bottom, top: OPPOSITE[bottom] },
    };
  });
}

/** The voxel under a point of the pane's image ((fx, fy) in [0, 1] from its top-left corner on screen); the cut axis keeps `at`. */
export function voxelAt(g: PaneGeometry, dims: readonly number[], fx: number, fy: number, at: Voxel): Voxel {
  const a = g.flipX ? 1 - fx : fx;
  const b = g.flipY ? 1 - fy : fy;
  const [u, v] = g.transpose ? [b, a] : [a, b];
  const out: Voxel = [...at];
  out[g.col] = Math.min(dims[g.col] - 1, Math.max(0, Math.floor(u * dims[g.col])));
  out[g.row] = Math.min(dims[g.row] - 1, Math.max(0, Math.floor(v * dims[g.row])));
  return out;
}

/** Where a voxel's centre lies on the pane's image, (fx, fy) from its top-left corner on screen. */
export function screenPoint(g: PaneGeometry, dims: readonly number[], voxel: Voxel): { fx: number; fy: number } {
  const u = (voxel[g.col] + 0.5) / dims[g.col];
  const v = (voxel[g.row] + 0.5) / dims[g.row];
  const [a, b] = g.transpose ? [v, u] : [u, v];
  return { fx: g.flipX ? 1 - a : a, fy: g.flipY ? 1 - b : b };
}

/** The physical aspect (width / height) of the pane's slice on screen, from the voxel counts and the spacing. */
export function sliceAspect(g: PaneGeometry, volume: Pick<Volume, 'dims' | 'spacing'>): number {
  const aspect = (volume.dims[g.col] * volume.spacing[g.col]) / (volume.dims[g.row] * volume.spacing[g.row]);
  return g.transpose ? 1 / aspect : aspect;
}

/**
 * The CSS that puts the canvas (the slice image, columns across) on a stage of this size as the
 * geometry says: its box (the stage's, transposed when the image is) and a transform from its
 * top-left corner.
 */
export function canvasPlacement(g: PaneGeometry, stage: { width: number; height: number }): string {
  const sx = g.flipX ? -1 : 1,
    sy = g.flipY ? -1 : 1;
  const e = g.flipX ? stage.width : 0,
    f = g.flipY ? stage.height : 0;
  const [w, h] = g.transpose ? [stage.height, stage.width] : [stage.width, stage.height];
  const m = g.transpose ? [0, sy, sx, 0, e, f] : [sx, 0, 0, sy, e, f];
  return `width:${w}px;height:${h}px;transform:matrix(${m.join(',')})`;
}

/**
 * The raw data value of a voxel in data units: the loaded volume's CPU-side voxels, which
 * @vpt/loaders already holds scaled (NIfTI scl_slope/scl_inter, DICOM rescale slope and
 * intercept: HU for a CT). The value range only maps values to the renderers' [0, 1] and
 * does not enter here.
 */
export function probeValue(volume: Pick<Volume, 'dims' | 'data'>, voxel: Voxel): number {
  const [nx, ny] = volume.dims;
  return volume.data[voxel[0] + nx * (voxel[1] + ny * voxel[2])];
}

/** The data's value extent (min, max) over all voxels: the starting window, and the scale of a window drag. */
export function dataExtent(volume: Pick<Volume, 'data'>): [number, number] {
  let lo = Infinity,
    hi = -Infinity;
  const d = volume.data;
  for (let i = 0; i < d.length; i++) {
    const x = d[i];
    if (x < lo) lo = x;
    if (x > hi) hi = x;
  }
  return Number.isFinite(lo) ? [lo, hi] : [0, 1];
}

/** A window [center, width] covering the whole extent (width at least a data unit's millionth, so never 0). */
export function defaultWindow(extent: [number, number]): [number, number] {
  const width = Math.max(extent[1] - extent[0], Math.abs(extent[1]) * 1e-6, 1e-6);
  return [(extent[0] + extent[1]) / 2, width];
}

/** What a pane needs of its element: whether it is on screen, and a call when its context came back on a new canvas. */
export interface PaneHost {
  isVisible(): boolean;
  reopened(pane: SlicePane): void;
}

/**
 * One slice pane's GPU side: a canvas and a RenderContext with its own slice renderer. A
 * pane's image is one sample (the slice renderer draws no random numbers), so drawing is a
 * reset, one iteration and a present, done synchronously whenever the plane, the window, the
 * size or the scene changes. A WebGL 2 pane holds one of the page's context slots
 * (context-slots.ts) like a viewer: when another needs it the pane keeps a still of its image,
 * gives its context up, and opens a new one (on a new canvas) when a slot is free.
 */
export class SlicePane implements SlotHolder {
  canvas: HTMLCanvasElement;
  private ctx: RenderContext | null = null;
  private renderer: (Renderer & { setParams(p: Record<string, unknown>): void }) | null = null;
  private disposed = false;
  private paramsKey = '';
  private scene: Scene | null = null;
  private backendWanted: BackendPreference = 'auto';
  private holdsSlot = false;
  private still: HTMLCanvasElement | null = null;
  private streamed: { standIn: Volume; source: MultiscaleSource } | null = null;

  constructor(
    readonly name: PaneName,
    private readonly host: PaneHost = { isVisible: () => true, reopened: () => {} },
  ) {
    this.canvas = SlicePane.newCanvas(name);
  }

  private static newCanvas(name: PaneName): HTMLCanvasElement {
    const canvas = document.createElement('canvas');
    canvas.setAttribute('part', `slice-canvas ${name}-canvas`);
    canvas.setAttribute('role', 'img');
    canvas.setAttribute('aria-label', `${name} slice`);
    return canvas;
  }

  get visible(): boolean {
    return this.host.isVisible();
  }

  /** Whether the pane gave its context up for another and waits for a slot. */
  get parked(): boolean {
    return this.ctx === null && webglSlots.isWaiting(this);
  }

  get context(): RenderContext | null {
    return this.ctx;
  }

  /** The volume of the scene last drawn (the element's, before the context's own fit to the device). */
  get volume(): Volume | null {
    return this.scene?.volume ?? null;
  }

  async open(backend: BackendPreference): Promise<void> {
    this.backendWanted = backend;
    const renderer = (await createRenderer('slice', { fit: true })) as SlicePane['renderer'];
    if (this.disposed) return;
    // WebGPU has no cap on contexts; anything that may become WebGL 2 takes a slot first.
    if (backend !== 'webgpu') {
      this.holdsSlot = true;
      await webglSlots.acquire(this);
      if (this.disposed) return;
    }
    const ctx = await RenderContext.create({
      canvas: this.canvas,
      backend,
      renderer: renderer!,
      post: defaultPostChain({ exposure: 0, toneMapper: 'aces', displayReferred: true }),
      width: 1,
      height: 1,
    });
    if (this.disposed) {
      ctx.dispose();
      return;
    }
    if (ctx.backend.kind !== 'webgl2' && this.holdsSlot) {
      this.holdsSlot = false;
      webglSlots.drop(this);
    }
    this.ctx = ctx;
    this.renderer = renderer;
    this.scene = null;
    this.paramsKey = '';
    if (this.streamed) ctx.setVolumeSource(this.streamed.standIn, this.streamed.source);
  }

  /**
   * The scene's volume is the stand-in of a multiscale source streamed as bricks (the 3D view's
   * RenderContext.setVolumeSource): the pane's context streams the same source, so the pane reads
   * the finest level resident in each region rather than the stand-in alone.
   */
  useSource(standIn: Volume, source: MultiscaleSource): void {
    if (this.streamed?.standIn === standIn && this.streamed.source === source) return;
    this.streamed = { standIn, source };
    this.ctx?.setVolumeSource(standIn, source);
  }

  /** Bricks of a streamed source are still arriving: the pane's image will change when they land. */
  get refining(): boolean {
    const b = this.ctx?.stats.bricking;
    return !!b && !b.complete;
  }

  /** Another viewer or pane needs the slot: keep a still of the image, give the context up. */
  async release(): Promise<void> {
    const ctx = this.ctx;
    this.holdsSlot = false;
    if (!ctx) return;
    let still: HTMLCanvasElement | null = null;
    try {
      if (ctx.getScene() && !ctx.backend.isLost) {
        const { width, height } = ctx.size;
        const ldr = await ctx.readLDR();
        still = document.createElement('canvas');
        still.width = width;
        still.height = height;
        still.setAttribute('part', 'still');
        still.setAttribute('aria-hidden', 'true');
        still.setAttribute('style', `position:absolute;left:0;top:0;${this.canvas.getAttribute('style') ?? ''}`);
        still.getContext('2d')?.putImageData(new ImageData(new Uint8ClampedArray(ldr), width, height), 0, 0);
      }
    } catch {
      still = null;
    }
    if (this.ctx !== ctx) return;
    ctx.dispose();
    this.ctx = null;
    this.still?.remove();
    this.still = still;
    if (still) this.canvas.after(still);
  }

  /** A slot is free again: a new context on a new canvas (a canvas keeps its first context), then the host redraws. */
  resume(): void {
    if (this.disposed) return;
    const old = this.canvas;
    this.canvas = SlicePane.newCanvas(this.name);
    this.canvas.setAttribute('style', old.getAttribute('style') ?? '');
    old.replaceWith(this.canvas);
    void this.open(this.backendWanted).then(() => {
      this.still?.remove();
      this.still = null;
      if (!this.disposed) this.host.reopened(this);
    });
  }

  /** Draw the plane through `index` along `axis` under `window`, at width × height pixels. */
  draw(scene: Scene, axis: Axis, index: number, window: [number, number], width: number, height: number): void {
    const ctx = this.ctx;
    if (!ctx || !this.renderer || ctx.backend.isLost) return;
    const params = { axis: AXIS_NAMES[axis], index, window, fit: true, sampling: 'nearest' };
    const key = JSON.stringify(params);
    if (!this.scene || !sameScene(this.scene, scene)) {
      ctx.setScene(scene);
      this.scene = scene;
    }
    if (key !== this.paramsKey) {
      this.renderer.setParams(params);
      this.paramsKey = key;
    }
    ctx.setSize(width, height);
    ctx.reset();
    ctx.iterate(1);
    ctx.present();
    if (this.holdsSlot) webglSlots.touch(this);
  }

  dispose(): void {
    this.disposed = true;
    this.ctx?.dispose();
    this.ctx = null;
    this.still?.remove();
    this.still = null;
    webglSlots.drop(this);
  }
}
