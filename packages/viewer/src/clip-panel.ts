/**
 * The Clip panel: one plane per axis (on/off, a position slider, a flip) and the crop box
 * (on/off, six sliders), over the element's `clip` (clip-model.ts reads and writes it).
 * Sliders write on `input`, so dragging one updates the image as it moves; every write goes
 * through `setInternal('clip', …)`, which reflects the attribute and fires `vpt-change`.
 */
import { html, nothing } from 'lit';
import { volumeBox, type Clip } from '@vpt/core';
import {
  CLIP_AXES,
  canAddPlane,
  clipControls,
  clipFromControls,
  moveBoxBound,
  type ClipAxis,
  type ClipControls,
  type Vec3,
} from './clip-model.js';
import type { PanelHost } from './panel-host.js';

let uid = 0;
const id = (name: string) => `vpt-clip-${name}-${++uid}`;
const num = (e: Event) => Number((e.target as HTMLInputElement).value);
const checked = (e: Event) => (e.target as HTMLInputElement).checked;
const fmt = (x: number) => (Math.abs(x) < 5e-5 ? 0 : x).toFixed(2);

/** Slider resolution: a thousandth of the volume box's longest side (1). */
const STEP = 0.001;

/** The volume box in world units (a unit cube before a volume is loaded). */
function worldBox(v: PanelHost): { min: Vec3; max: Vec3 } {
  const vol = v.panelState.volume;
  if (!vol) return { min: [-0.5, -0.5, -0.5], max: [0.5, 0.5, 0.5] };
  const b = volumeBox(vol);
  return { min: b.min, max: b.max };
}

export function clipPanel(v: PanelHost) {
  const clip = v.clip && typeof v.clip === 'object' ? (v.clip as Clip) : null;
  const c = clipControls(clip);
  const box = worldBox(v);
  const write = (next: ClipControls) => v.setInternal('clip', clipFromControls(next));
  const setAxis = (axis: ClipAxis, plane: ClipControls['axes'][ClipAxis]) =>
    write({ ...c, axes: { ...c.axes, [axis]: plane } });
  const free = canAddPlane(c);

  const axisRows = CLIP_AXES.map((axis, i) => {
    const plane = c.axes[axis];
    const ids = { on: id(`on-${axis}`), pos: id(`plane-${axis}`), flip: id(`flip-${axis}`) };
    return html`<div class="row">
        <label for=${ids.on}>Plane ${axis}</label>
        <input
          id=${ids.on}
          type="checkbox"
          data-clip=${`on-${axis}`}
          .checked=${!!plane}
          ?disabled=${!plane && !free}
          @change=${(e: Event) => setAxis(axis, checked(e) ? { position: 0, flip: false } : null)}
        />
      </div>
      ${
        plane
          ? html`<div class="row">
                <label for=${ids.pos}>Keep ${axis} ${plane.flip ? '≥' : '≤'} ${fmt(plane.position)}</label>
                <input
                  id=${ids.pos}
                  type="range"
                  data-clip=${`plane-${axis}`}
                  min=${box.min[i]}
                  max=${box.max[i]}
                  step=${STEP}
                  .value=${String(plane.position)}
                  @input=${(e: Event) => setAxis(axis, { ...plane, position: num(e) })}
                />
              </div>
              <div class="row">
                <label for=${ids.flip}>Flip ${axis}</label>
                <input
                  id=${ids.flip}
                  type="checkbox"
                  data-clip=${`flip-${axis}`}
                  .checked=${plane.flip}
                  @change=${(e: Event) => setAxis(axis, { ...plane, flip: checked(e) })}
                />
              </div>`
          : nothing
      }`;
  });

  const boxId = id('box');
  const boxRows = c.box
    ? (['min', 'max'] as const).flatMap((side) =>
        CLIP_AXES.map((axis, i) => {
          const sid = id(`box-${side}-${axis}`);
          const value = c.box![side][i];
          return html`<div class="row">
            <label for=${sid}>${side} ${axis} ${fmt(value)}</label>
            <input
              id=${sid}
              type="range"
              data-clip=${`box-${side}-${axis}`}
              min=${box.min[i]}
              max=${box.max[i]}
              step=${STEP}
              .value=${String(value)}
              @input=${(e: Event) => write({ ...c, box: moveBoxBound(c.box!, box, side, i, num(e)) })}
            />
          </div>`;
        }),
      )
    : [];

  return html`<details>
    <summary>Clip</summary>
    <div class="panel" part="clip-panel">
      ${axisRows}
      ${c.others.length ? html`<p>${c.others.length} more plane${c.others.length > 1 ? 's' : ''} from the clip attribute (kept)</p>` : nothing}
      <div class="row">
        <label for=${boxId}>Crop box</label>
        <input
          id=${boxId}
          type="checkbox"
          data-clip="box"
          .checked=${!!c.box}
          @change=${(e: Event) => write({ ...c, box: checked(e) ? { min: [...box.min], max: [...box.max] } : null })}
        />
      </div>
      ${boxRows}
    </div>
  </details>`;
}
