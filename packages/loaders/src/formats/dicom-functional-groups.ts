/**
 * Enhanced (multi-frame) DICOM: each frame's geometry and rescale from the functional
 * groups (PS3.3 C.7.6.16): a macro in the frame's item of the Per-Frame Functional Groups
 * Sequence (5200,9230) wins over the Shared Functional Groups Sequence (5200,9229), which
 * wins over the top-level attribute. And which frames make one volume: the largest stack
 * (Stack ID), and within it the first volume along every dimension other than the stack
 * and the position in it (time, echo, b-value…), by Dimension Index Values (C.7.6.17).
 */
import type { LoadContext } from '../context.js';
import type { Scaling } from '../convert/voxels.js';
import { finite, firstItem, numbersOf, reader, type DataSet } from './dicom-elements.js';

/** One frame's own values; absent fields fall back to the file's top level. */
export interface FrameGeometry {
  /** Index of the frame in the pixel data. */
  frame: number;
  ipp?: number[];
  iop?: number[];
  pixelSpacing?: [number, number];
  thickness?: number;
  between?: number;
  scaling?: Scaling;
}

const PER_FRAME = 'x52009230';
const SHARED = 'x52009229';
const STACK_ID = 0x00209056;
const IN_STACK_POSITION = 0x00209057;

/** Whether the file carries per-frame functional groups (an enhanced multi-frame image). */
export function hasFunctionalGroups(ds: DataSet): boolean {
  return (ds.elements[PER_FRAME]?.items?.length ?? 0) > 0;
}

/** The first item of macro `tag` for a frame: the frame's own, else the shared one. */
function macro(frame: DataSet | undefined, shared: DataSet | undefined, tag: string): DataSet | undefined {
  return firstItem(frame, tag) ?? firstItem(shared, tag);
}

/** The values of an AT/UL multi-valued element (Dimension Index Pointer, Dimension Index Values). */
function uint32s(ds: DataSet, tag: string, at: boolean): number[] {
  const el = ds.elements[tag];
  if (!el) return [];
  const out: number[] = [];
  for (let i = 0; i < Math.floor(el.length / 4); i++) {
    // AT is two 16-bit words (group, element) in the file's byte order, not one 32-bit value.
    const v = at ? (ds.uint16(tag, 2 * i)! << 16) + ds.uint16(tag, 2 * i + 1)! : ds.uint32(tag, i);
    if (finite(v)) out.push(v >>> 0);
  }
  return out;
}

/**
 * The frames of the first volume of an enhanced file, each with its own geometry and
 * rescale; what was left out is said in ctx.warnings.
 */
export function enhancedFrames(ds: DataSet, frames: number, where: string, ctx: LoadContext): FrameGeometry[] {
  const items = ds.elements[PER_FRAME].items!;
  if (items.length !== frames)
    ctx.warnings.push(
      `${where}: the Per-Frame Functional Groups Sequence describes ${items.length} frames, NumberOfFrames says ${frames}; the ${Math.min(items.length, frames)} described are read`,
    );
  const shared = firstItem(ds, SHARED);
  const dimItems = ds.elements.x00209222?.items ?? [];
  const pointers: (number | undefined)[] = dimItems.map((d) =>
    d.dataSet ? uint32s(d.dataSet, 'x00209165', true)[0] : undefined,
  );
  const others = pointers.map((p, i) => (p === STACK_ID || p === IN_STACK_POSITION ? -1 : i)).filter((i) => i >= 0);

  const all = items.slice(0, frames).map((item, frame) => {
    const f = item.dataSet;
    const content = macro(f, undefined, 'x00209111');
    const pos = macro(f, shared, 'x00209113');
    const ori = macro(f, shared, 'x00209116');
    const measures = macro(f, shared, 'x00289110');
    const pvt = macro(f, shared, 'x00289145');
    const c = content ? reader(content) : undefined;
    const m = measures ? reader(measures) : undefined;
    const ps = measures ? numbersOf(measures, 'x00280030', 2) : undefined;
    const slope = pvt ? reader(pvt).num('x00281053') : undefined;
    const inter = pvt ? reader(pvt).num('x00281052') : undefined;
    const thickness = m?.num('x00180050');
    const between = m?.num('x00180088');
    const indexValues = content ? uint32s(content, 'x00209157', false) : [];
    const temporal = content ? uint32s(content, 'x00209128', false)[0] : undefined;
    const geometry: FrameGeometry = {
      frame,
      ipp: pos ? numbersOf(pos, 'x00200032', 3) : undefined,
      iop: ori ? numbersOf(ori, 'x00200037', 6) : undefined,
      pixelSpacing: ps && ps[0] > 0 && ps[1] > 0 ? [ps[0], ps[1]] : undefined,
      thickness: finite(thickness) && thickness > 0 ? thickness : undefined,
      between: finite(between) && between > 0 ? between : undefined,
      scaling: finite(slope) && slope !== 0 ? { slope, inter: finite(inter) ? inter : 0 } : undefined,
    };
    const volume =
      others.length && indexValues.length ? others.map((i) => indexValues[i] ?? 0) : finite(temporal) ? [temporal] : [];
    return { geometry, stack: (c?.str('x00209056') ?? '').trim(), volume };
  });

  const stacks = new Map<string, typeof all>();
  for (const f of all) {
    const list = stacks.get(f.stack);
    if (list) list.push(f);
    else stacks.set(f.stack, [f]);
  }
  let chosen = [...stacks.values()].sort((a, b) => b.length - a.length)[0];
  if (stacks.size > 1)
    ctx.warnings.push(
      `${where} holds ${stacks.size} stacks (Stack ID ${[...stacks.keys()].join(', ')}); stack ${chosen[0].stack} (${chosen.length} frames) is loaded`,
    );
  const key = (v: number[]) => v.join(',');
  const lowest = chosen
    .map((f) => f.volume)
    .sort((a, b) => {
      for (let i = 0; i < Math.max(a.length, b.length); i++)
        if ((a[i] ?? 0) !== (b[i] ?? 0)) return (a[i] ?? 0) - (b[i] ?? 0);
      return 0;
    })[0];
  const volumes = new Set(chosen.map((f) => key(f.volume)));
  if (volumes.size > 1) {
    chosen = chosen.filter((f) => key(f.volume) === key(lowest));
    ctx.warnings.push(
      `${where} holds ${volumes.size} volumes in its stack (time points, echoes…: dimension indices ${others.map((i) => pointerName(pointers[i])).join(', ') || 'TemporalPositionIndex'}); the first (${chosen.length} frames) is loaded`,
    );
  }
  return chosen.map((f) => f.geometry);
}

function pointerName(p: number | undefined): string {
  if (p === undefined) return '(unnamed)';
  return `(${(p >>> 16).toString(16).padStart(4, '0')},${(p & 0xffff).toString(16).padStart(4, '0')})`;
}
