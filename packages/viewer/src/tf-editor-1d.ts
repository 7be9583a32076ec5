/**
 * `<vpt-tf-editor>`: a 1D transfer-function editor. Control points (value → colour,
 * opacity) sit over a log-scaled histogram of the data; drag them with a pointer, or
 * focus one (Tab) and use the arrow keys (Shift: 10× larger steps), Delete to remove it;
 * click empty space to add one. The selected point's numbers and colour are editable in
 * a form below. Fires `input` while dragging and `change` when an edit is done; both
 * carry `detail.transferFunction`.
 */
import { LitElement, css, html, svg, nothing, type PropertyValues } from 'lit';
import { tfEditorStyles } from './tf-editor-styles.js';
import type { TransferFunction, TransferPoint } from '@vpt/core';
import { cssColor, hexToLinear, intensityOf, linearToHex, round4 } from './color.js';
import type { Histogram1D } from './histogram.js';

type Tf1D = Extract<TransferFunction, { dimensions: '1d' }>;

export class VptTfEditor extends LitElement {
  static override properties = {
    value: { attribute: false },
    histogram: { attribute: false },
    selected: { state: true },
  };

  declare value: Tf1D | null;
  declare histogram: Histogram1D | null;
  declare selected: number;
  /** Top of the opacity axis, fixed while a drag runs so the point stays under the pointer. */
  private yMax = 1;
  private dragging: number | null = null;

  constructor() {
    super();
    this.value = null;
    this.histogram = null;
    this.selected = -1;
  }

  static override styles = [
    tfEditorStyles,
    css`
      .plot {
        height: 120px;
        cursor: crosshair;
      }
      .pt {
        position: absolute;
        width: 12px;
        height: 12px;
        margin: -7px 0 0 -7px;
        border: 2px solid #ddd;
        border-radius: 50%;
        transform: translateY(0);
        cursor: grab;
        box-sizing: content-box;
        padding: 0;
      }
      .pt[aria-selected='true'] {
        border-color: #6af;
        box-shadow: 0 0 0 2px #6af8;
      }
      .pt:focus-visible {
        outline: 2px solid #fff;
        outline-offset: 2px;
      }
      .strip {
        height: 12px;
        margin: 2px 7px 8px;
        border-radius: 3px;
        border: 1px solid #444;
      }
      form {
        grid-template-columns: auto 1fr auto 1fr;
      }
      label {
        white-space: nowrap;
      }
      .buttons {
        grid-column: 1 / -1;
      }
    `,
  ];

  private get points(): TransferPoint[] {
    return this.value?.points ?? [];
  }

  protected override willUpdate(changed: PropertyValues<this>): void {
    if (changed.has('value') && this.dragging === null) {
      this.yMax = Math.max(1, ...this.points.map((p) => p.opacity));
      if (this.selected >= this.points.length) this.selected = this.points.length - 1;
    }
  }

  protected override render() {
    const pts = this.points;
    const sel = pts[this.selected];
    return html`
      <p class="hint" id="hint">
        Click to add a point; drag points, or focus one and use the arrow keys; Delete removes it.
      </p>
      <div
        class="plot"
        part="plot"
        @pointerdown=${this.onPlotDown}
        @pointermove=${this.onMove}
        @pointerup=${this.onUp}
        @pointercancel=${this.onUp}
      >
        ${this.renderCurves(pts)}
        ${pts.map(
          (p, i) =>
            html`<div
              class="pt"
              role="slider"
              tabindex="0"
              aria-label="Control point ${i + 1} of ${pts.length}"
              aria-describedby="hint"
              aria-valuemin="0"
              aria-valuemax="1"
              aria-valuenow=${p.value}
              aria-valuetext="value ${p.value.toFixed(3)}, opacity ${p.opacity.toFixed(3)}"
              aria-selected=${i === this.selected ? 'true' : 'false'}
              style="left:${p.value * 100}%;top:${(1 - p.opacity / this.yMax) * 100}%;background:${cssColor(p.color)}"
              @pointerdown=${(e: PointerEvent) => this.onPointDown(e, i)}
              @keydown=${(e: KeyboardEvent) => this.onKey(e, i)}
              @focus=${() => {
                this.selected = i;
              }}
            ></div>`,
        )}
      </div>
      <div class="strip" style="background:${this.gradientCss(pts)}" aria-hidden="true"></div>
      ${
        sel
          ? html`<form @submit=${(e: Event) => e.preventDefault()} aria-label="Selected control point">
              <label for="v">Value</label
              ><input
                id="v"
                type="number"
                min="0"
                max="1"
                step="0.01"
                .value=${String(sel.value)}
                @change=${(e: Event) => this.setField('value', e)}
              />
              <label for="o">Opacity</label
              ><input
                id="o"
                type="number"
                min="0"
                step="0.01"
                .value=${String(sel.opacity)}
                @change=${(e: Event) => this.setField('opacity', e)}
              />
              <label for="c">Colour</label
              ><input
                id="c"
                type="color"
                .value=${linearToHex(sel.color)}
                @input=${(e: Event) => this.setColor(e, 'input')}
                @change=${(e: Event) => this.setColor(e, 'change')}
              />
              <label for="i">Intensity</label
              ><input
                id="i"
                type="number"
                min="1"
                step="0.1"
                .value=${String(round4(intensityOf(sel.color)))}
                @change=${(e: Event) => this.setIntensity(e)}
              />
              <div class="buttons">
                <button type="button" @click=${() => this.removePoint(this.selected)} ?disabled=${pts.length <= 1}>
                  Remove point
                </button>
              </div>
            </form>`
          : nothing
      }
    `;
  }

  private renderCurves(pts: TransferPoint[]) {
    const h = this.histogram;
    let bars = '';
    if (h) {
      const n = h.bins.length;
      const logMax = Math.log1p(h.max);
      for (let i = 0; i < n; i++) {
        const y = Math.min(1, Math.log1p(h.bins[i]) / logMax);
        if (y > 0) bars += `M${i / n},1V${1 - y}H${(i + 1) / n}V1Z`;
      }
    }
    const line = pts.length
      ? [
          `M0,${1 - pts[0].opacity / this.yMax}`,
          ...pts.map((p) => `L${p.value},${1 - p.opacity / this.yMax}`),
          `L1,${1 - pts[pts.length - 1].opacity / this.yMax}`,
        ].join('')
      : '';
    return html`<svg viewBox="0 0 1 1" preserveAspectRatio="none" aria-hidden="true">
      ${svg`<path d=${bars} fill="#5a5a66" opacity="0.8"></path>
      <path d=${line} fill="none" stroke="#eee" stroke-width="1.5" vector-effect="non-scaling-stroke"></path>`}
    </svg>`;
  }

  private gradientCss(pts: TransferPoint[]): string {
    if (!pts.length) return '#000';
    const stops = pts.map(
      (p) => `${cssColor(p.color, Math.min(1, p.opacity / this.yMax + 0.15))} ${(p.value * 100).toFixed(1)}%`,
    );
    return `linear-gradient(to right, ${stops.join(', ')})`;
  }

  // ——— editing ———

  private emit(type: 'input' | 'change'): void {
    this.dispatchEvent(new CustomEvent(type, { detail: { transferFunction: this.value }, bubbles: true }));
  }

  private update1(points: TransferPoint[], type: 'input' | 'change'): void {
    this.value = { dimensions: '1d', points };
    this.emit(type);
  }

  /** Move point i, kept between its neighbours so the list stays sorted. */
  private movePoint(i: number, value: number, opacity: number, type: 'input' | 'change'): void {
    const pts = this.points.map((p) => ({ ...p, color: [...p.color] as TransferPoint['color'] }));
    const lo = i > 0 ? pts[i - 1].value : 0;
    const hi = i < pts.length - 1 ? pts[i + 1].value : 1;
    pts[i].value = round4(Math.min(hi, Math.max(lo, value)));
    pts[i].opacity = round4(Math.max(0, opacity));
    this.update1(pts, type);
  }

  private removePoint(i: number): void {
    if (this.points.length <= 1 || i < 0) return;
    const pts = this.points.filter((_, k) => k !== i);
    this.selected = Math.min(i, pts.length - 1);
    this.update1(pts, 'change');
  }

  /** Add a point at (value, opacity) with the colour the function has there now. */
  private addPoint(value: number, opacity: number): number {
    const pts = this.points.map((p) => ({ ...p }));
    let j = 0;
    while (j < pts.length && pts[j].value < value) j++;
    const a = pts[Math.max(0, j - 1)],
      b = pts[Math.min(pts.length - 1, j)];
    let color: TransferPoint['color'] = [1, 1, 1];
    if (a && b) {
      const t = b.value > a.value ? (value - a.value) / (b.value - a.value) : 0;
      color = [0, 1, 2].map((c) => round4(a.color[c] + t * (b.color[c] - a.color[c]))) as TransferPoint['color'];
    }
    pts.splice(j, 0, { value: round4(value), color, opacity: round4(opacity) });
    this.selected = j;
    this.update1(pts, 'input');
    return j;
  }

  private toModel(e: PointerEvent): { value: number; opacity: number } {
    const r = (this.renderRoot.querySelector('.plot') as HTMLElement).getBoundingClientRect();
    const x = Math.min(1, Math.max(0, (e.clientX - r.left) / r.width));
    const y = Math.min(1, Math.max(0, 1 - (e.clientY - r.top) / r.height));
    return { value: x, opacity: y * this.yMax };
  }

  private onPlotDown = (e: PointerEvent): void => {
    if (e.button !== 0 || (e.target !== e.currentTarget && !(e.target instanceof SVGElement))) return;
    const m = this.toModel(e);
    const i = this.addPoint(m.value, m.opacity);
    this.startDrag(e, i);
  };

  private onPointDown(e: PointerEvent, i: number): void {
    if (e.button !== 0) return;
    e.stopPropagation();
    this.selected = i;
    this.startDrag(e, i);
  }

  private startDrag(e: PointerEvent, i: number): void {
    this.dragging = i;
    (this.renderRoot.querySelector('.plot') as HTMLElement).setPointerCapture(e.pointerId);
    e.preventDefault();
  }

  private onMove = (e: PointerEvent): void => {
    if (this.dragging === null) return;
    const m = this.toModel(e);
    this.movePoint(this.dragging, m.value, m.opacity, 'input');
  };

  private onUp = (): void => {
    if (this.dragging === null) return;
    this.dragging = null;
    this.yMax = Math.max(1, ...this.points.map((p) => p.opacity));
    this.emit('change');
  };

  private onKey(e: KeyboardEvent, i: number): void {
    const p = this.points[i];
    const k = e.shiftKey ? 10 : 1;
    let handled = true;
    switch (e.key) {
      case 'ArrowLeft':
        this.movePoint(i, p.value - 0.01 * k, p.opacity, 'change');
        break;
      case 'ArrowRight':
        this.movePoint(i, p.value + 0.01 * k, p.opacity, 'change');
        break;
      case 'ArrowUp':
        this.movePoint(i, p.value, p.opacity + 0.01 * k * this.yMax, 'change');
        break;
      case 'ArrowDown':
        this.movePoint(i, p.value, p.opacity - 0.01 * k * this.yMax, 'change');
        break;
      case 'Delete':
      case 'Backspace':
        this.removePoint(i);
        this.focusPoint(this.selected);
        break;
      default:
        handled = false;
    }
    if (handled) e.preventDefault();
  }

  private async focusPoint(i: number): Promise<void> {
    await this.updateComplete;
    (this.renderRoot.querySelectorAll('.pt')[i] as HTMLElement | undefined)?.focus();
  }

  private setField(field: 'value' | 'opacity', e: Event): void {
    const n = Number((e.target as HTMLInputElement).value);
    const p = this.points[this.selected];
    if (!p || !Number.isFinite(n)) return;
    this.movePoint(this.selected, field === 'value' ? n : p.value, field === 'opacity' ? n : p.opacity, 'change');
  }

  private setColor(e: Event, type: 'input' | 'change'): void {
    const p = this.points[this.selected];
    if (!p) return;
    const pts = this.points.map((q) => ({ ...q }));
    pts[this.selected] = { ...p, color: hexToLinear((e.target as HTMLInputElement).value, intensityOf(p.color)) };
    this.update1(pts, type);
  }

  private setIntensity(e: Event): void {
    const p = this.points[this.selected];
    const k = Number((e.target as HTMLInputElement).value);
    if (!p || !Number.isFinite(k)) return;
    const k1 = Math.max(1, k); // below 1 the hue itself is darker: pick it in the colour field
    const old = intensityOf(p.color);
    const pts = this.points.map((q) => ({ ...q }));
    pts[this.selected] = { ...p, color: p.color.map((c) => round4((c / old) * k1)) as TransferPoint['color'] };
    this.update1(pts, 'change');
  }
}
