/**
 * `<vpt-tf2d-editor>`: a 2D transfer-function editor (Kniss et al. 2002): Gaussian and
 * box widgets over a log-scaled histogram of value (x) × normalized gradient magnitude
 * (y, up). Drag a widget's centre handle to move it and its corner handle to resize it;
 * from the keyboard, focus a handle (Tab) and use the arrows (Shift: 10× steps; on the
 * corner handle they resize), Delete removes the widget. The selected widget's numbers,
 * colour and opacity are editable below. Fires `input` while dragging and `change` when
 * an edit is done, with `detail.transferFunction`.
 */
import { LitElement, css, html, svg, nothing, type PropertyValues } from 'lit';
import { tfEditorStyles } from './tf-editor-styles.js';
import type { BoxWidget, GaussianWidget, TransferFunction, TransferWidget } from '@vpt/core';
import { cssColor, hexToLinear, intensityOf, linearToHex, round4 } from './color.js';
import { valueGradientHistogram, type GradientSamples, type Histogram2D } from './histogram.js';

type Tf2D = Extract<TransferFunction, { dimensions: '2d' }>;
type Handle = 'move' | 'size';

const clamp01 = (x: number) => Math.min(1, Math.max(0, x));

/** The widget's bounding box [v0, g0, v1, g1] (Gaussian: ±1 standard deviation). */
function extent(w: TransferWidget): [number, number, number, number] {
  if (w.type === 'gaussian')
    return [w.center[0] - w.width[0], w.center[1] - w.width[1], w.center[0] + w.width[0], w.center[1] + w.width[1]];
  return [w.min[0], w.min[1], w.max[0], w.max[1]];
}

function centre(w: TransferWidget): [number, number] {
  if (w.type === 'gaussian') return w.center;
  return [(w.min[0] + w.max[0]) / 2, (w.min[1] + w.max[1]) / 2];
}

/** Move by (dv, dg), or grow the upper corner by (dv, dg) (a Gaussian's width, a box's max). */
function edit(w: TransferWidget, handle: Handle, dv: number, dg: number): TransferWidget {
  if (w.type === 'gaussian') {
    if (handle === 'move') return { ...w, center: [round4(w.center[0] + dv), round4(w.center[1] + dg)] };
    return { ...w, width: [round4(Math.max(0.005, w.width[0] + dv)), round4(Math.max(0.005, w.width[1] + dg))] };
  }
  if (handle === 'move')
    return {
      ...w,
      min: [round4(w.min[0] + dv), round4(w.min[1] + dg)],
      max: [round4(w.max[0] + dv), round4(w.max[1] + dg)],
    };
  return { ...w, max: [round4(Math.max(w.min[0], w.max[0] + dv)), round4(Math.max(w.min[1], w.max[1] + dg))] };
}

export class VptTf2dEditor extends LitElement {
  static override properties = {
    value: { attribute: false },
    samples: { attribute: false },
    selected: { state: true },
  };

  declare value: Tf2D | null;
  /** The volume's (value, gradient) pairs; the histogram is binned from them for the current gradientMax. */
  declare samples: GradientSamples | null;
  declare selected: number;
  private histogram: Histogram2D | null = null;
  private histogramKey: unknown[] = [];
  private drag: { index: number; handle: Handle; start: [number, number]; widget: TransferWidget } | null = null;

  constructor() {
    super();
    this.value = null;
    this.samples = null;
    this.selected = 0;
  }

  static override styles = [
    tfEditorStyles,
    css`
      .plot {
        aspect-ratio: 2 / 1;
      }
      canvas {
        image-rendering: pixelated;
      }
      .h {
        position: absolute;
        width: 10px;
        height: 10px;
        margin: -6px 0 0 -6px;
        border: 2px solid #ddd;
        background: #222;
        cursor: move;
        padding: 0;
        box-sizing: content-box;
      }
      .h.size {
        border-radius: 50%;
        cursor: nwse-resize;
        width: 8px;
        height: 8px;
        margin: -5px 0 0 -5px;
      }
      .h[aria-selected='true'] {
        border-color: #6af;
      }
      .h:focus-visible {
        outline: 2px solid #fff;
        outline-offset: 2px;
      }
      .axes {
        display: flex;
        justify-content: space-between;
        font-size: 0.75em;
        opacity: 0.7;
        margin: 0 7px 6px;
      }
      form {
        grid-template-columns: auto 1fr 1fr;
      }
      .buttons {
        flex-wrap: wrap;
        margin: 6px 0;
      }
    `,
  ];

  private get widgets(): TransferWidget[] {
    return this.value?.widgets ?? [];
  }

  protected override willUpdate(changed: PropertyValues<this>): void {
    const gmax = this.value?.gradientMax;
    const key = [this.samples, gmax];
    if (this.samples && (key[0] !== this.histogramKey[0] || key[1] !== this.histogramKey[1])) {
      this.histogram = valueGradientHistogram(this.samples, gmax ?? this.samples.maxGradient);
      this.histogramKey = key;
    }
    if (changed.has('value') && this.selected >= this.widgets.length) this.selected = this.widgets.length - 1;
  }

  protected override updated(): void {
    this.drawHistogram();
  }

  private drawHistogram(): void {
    const canvas = this.renderRoot.querySelector('canvas');
    const h = this.histogram;
    if (!canvas || !h) return;
    canvas.width = h.width;
    canvas.height = h.height;
    const ctx = canvas.getContext('2d')!;
    const img = ctx.createImageData(h.width, h.height);
    const logMax = Math.log1p(h.max);
    for (let y = 0; y < h.height; y++) {
      for (let x = 0; x < h.width; x++) {
        const c = Math.round(Math.sqrt(Math.min(1, Math.log1p(h.bins[x + h.width * y]) / logMax)) * 200);
        const o = 4 * (x + h.width * (h.height - 1 - y)); // gradient grows upward
        img.data[o] = c;
        img.data[o + 1] = c;
        img.data[o + 2] = c + 10;
        img.data[o + 3] = 255;
      }
    }
    ctx.putImageData(img, 0, 0);
  }

  protected override render() {
    const ws = this.widgets;
    const sel = ws[this.selected];
    const gmax = this.value?.gradientMax;
    return html` <p class="hint" id="hint2d">
        Drag a square to move a widget, a circle to resize it; or focus one and use the arrow keys; Delete removes.
      </p>
      <div class="plot" part="plot" @pointermove=${this.onMove} @pointerup=${this.onUp} @pointercancel=${this.onUp}>
        <canvas aria-hidden="true"></canvas>
        <svg viewBox="0 0 1 1" preserveAspectRatio="none" aria-hidden="true">
          ${ws.map((w, i) => this.renderWidget(w, i))}
        </svg>
        ${ws.map((w, i) => {
          const [cv, cg] = centre(w);
          const [, , v1, g1] = extent(w);
          const label = `Widget ${i + 1} of ${ws.length} (${w.type})`;
          return html`${this.renderHandle(i, 'move', `${label}: move`, cv, cg, `value ${cv.toFixed(2)}, gradient ${cg.toFixed(2)}`)}
          ${this.renderHandle(i, 'size', `${label}: size`, v1, g1, `up to value ${v1.toFixed(2)}, gradient ${g1.toFixed(2)}`)}`;
        })}
      </div>
      <div class="axes" aria-hidden="true">
        <span>value →</span
        ><span>↑ gradient magnitude${this.histogram ? ` (0 … ${this.histogram.maxGradient.toPrecision(3)})` : ''}</span>
      </div>
      <div class="buttons">
        <button type="button" @click=${() => this.add('gaussian')}>Add Gaussian</button>
        <button type="button" @click=${() => this.add('box')}>Add box</button>
        <button type="button" ?disabled=${ws.length <= 1} @click=${() => this.removeWidget(this.selected)}>
          Remove widget
        </button>
      </div>
      ${sel ? this.renderForm(sel) : nothing}
      <form @submit=${(e: Event) => e.preventDefault()}>
        <label for="gm">Gradient max</label>
        <input
          id="gm"
          type="number"
          min="0"
          step="any"
          placeholder=${this.samples ? `volume max ${this.samples.maxGradient.toPrecision(4)}` : 'volume max'}
          .value=${gmax === undefined ? '' : String(gmax)}
          @change=${(e: Event) => {
            const t = (e.target as HTMLInputElement).value.trim();
            this.setGradientMax(t === '' ? undefined : Number(t));
          }}
        />
        <span></span>
      </form>`;
  }

  /** A widget's handle at (value, gradient) in the plot: a slider for the pointer and the keys. */
  private renderHandle(i: number, handle: Handle, label: string, v: number, g: number, valueText: string) {
    return html`<div
      class=${handle === 'size' ? 'h size' : 'h'}
      role="slider"
      tabindex="0"
      aria-label=${label}
      aria-describedby="hint2d"
      aria-valuetext=${valueText}
      aria-selected=${i === this.selected ? 'true' : 'false'}
      style="left:${clamp01(v) * 100}%;top:${(1 - clamp01(g)) * 100}%"
      @pointerdown=${(e: PointerEvent) => this.startDrag(e, i, handle)}
      @keydown=${(e: KeyboardEvent) => this.onKey(e, i, handle)}
      @focus=${() => {
        this.selected = i;
      }}
    ></div>`;
  }

  private renderWidget(w: TransferWidget, i: number) {
    const fill = cssColor(w.color, Math.min(0.6, 0.15 + 0.45 * Math.min(1, w.opacity)));
    const stroke = i === this.selected ? '#6af' : '#ddd';
    if (w.type === 'gaussian') {
      const [cx, cy] = [w.center[0], 1 - w.center[1]];
      return svg`<ellipse cx=${cx} cy=${cy} rx=${w.width[0] * 2} ry=${w.width[1] * 2} fill="none" stroke=${stroke} stroke-dasharray="3 3" vector-effect="non-scaling-stroke"></ellipse>
        <ellipse cx=${cx} cy=${cy} rx=${w.width[0]} ry=${w.width[1]} fill=${fill} stroke=${stroke} vector-effect="non-scaling-stroke"></ellipse>`;
    }
    const ramp = w.ramp ?? [0, 0];
    return svg`<rect x=${w.min[0] - ramp[0]} y=${1 - w.max[1] - ramp[1]} width=${w.max[0] - w.min[0] + 2 * ramp[0]} height=${w.max[1] - w.min[1] + 2 * ramp[1]} fill="none" stroke=${stroke} stroke-dasharray="3 3" vector-effect="non-scaling-stroke"></rect>
      <rect x=${w.min[0]} y=${1 - w.max[1]} width=${w.max[0] - w.min[0]} height=${w.max[1] - w.min[1]} fill=${fill} stroke=${stroke} vector-effect="non-scaling-stroke"></rect>`;
  }

  private renderForm(w: TransferWidget) {
    const pair = (label: string, key: string, values: [number, number], min: number) =>
      html` <label>${label}</label>
        ${(['value', 'gradient'] as const).map(
          (axis, i) =>
            html`<input
              type="number"
              step="0.01"
              min=${min}
              aria-label="${label}, ${axis} axis"
              .value=${String(round4(values[i]))}
              @change=${(e: Event) => this.setPair(key, i as 0 | 1, Number((e.target as HTMLInputElement).value))}
            />`,
        )}`;
    return html`<form @submit=${(e: Event) => e.preventDefault()} aria-label="Selected widget">
      <span></span><span>value</span><span>gradient</span>
      ${
        w.type === 'gaussian'
          ? html`${pair('Centre', 'center', w.center, -1)}${pair('Std. dev.', 'width', w.width, 0.001)}`
          : html`${pair('Min', 'min', w.min, -1)}${pair('Max', 'max', w.max, -1)}${pair('Soft edge', 'ramp', w.ramp ?? [0, 0], 0)}`
      }
      <label for="wc">Colour</label>
      <input
        id="wc"
        type="color"
        .value=${linearToHex(w.color)}
        @change=${(e: Event) => this.patch({ color: hexToLinear((e.target as HTMLInputElement).value, intensityOf(w.color)) })}
      />
      <input
        type="number"
        min="1"
        step="0.1"
        aria-label="Colour intensity"
        title="Intensity"
        .value=${String(round4(intensityOf(w.color)))}
        @change=${(e: Event) => {
          const k = Math.max(1, Number((e.target as HTMLInputElement).value) || 1);
          const old = intensityOf(w.color);
          this.patch({ color: w.color.map((c) => round4((c / old) * k)) as TransferWidget['color'] });
        }}
      />
      <label for="wo">Opacity</label>
      <input
        id="wo"
        type="number"
        min="0"
        step="0.05"
        .value=${String(w.opacity)}
        @change=${(e: Event) => this.patch({ opacity: Math.max(0, Number((e.target as HTMLInputElement).value) || 0) })}
      />
      <span></span>
    </form>`;
  }

  // ——— editing ———

  private emit(type: 'input' | 'change'): void {
    this.dispatchEvent(new CustomEvent(type, { detail: { transferFunction: this.value }, bubbles: true }));
  }

  private setWidgets(widgets: TransferWidget[], type: 'input' | 'change'): void {
    const tf: Tf2D = { dimensions: '2d', widgets };
    if (this.value?.gradientMax !== undefined) tf.gradientMax = this.value.gradientMax;
    this.value = tf;
    this.emit(type);
  }

  private replace(i: number, w: TransferWidget, type: 'input' | 'change'): void {
    const ws = [...this.widgets];
    ws[i] = w;
    this.setWidgets(ws, type);
  }

  private patch(p: Partial<GaussianWidget> | Partial<BoxWidget>): void {
    const w = this.widgets[this.selected];
    if (w) this.replace(this.selected, { ...w, ...p } as TransferWidget, 'change');
  }

  private setPair(key: string, axis: 0 | 1, x: number): void {
    const w = this.widgets[this.selected] as unknown as Record<string, [number, number] | undefined>;
    if (!w || !Number.isFinite(x)) return;
    const pair: [number, number] = [...(w[key] ?? [0, 0])] as [number, number];
    pair[axis] = round4(x);
    const next = { ...w, [key]: pair } as unknown as TransferWidget;
    // Keep a box valid (min ≤ max) by moving the other bound along.
    if (next.type === 'box') {
      if (key === 'min') next.max = [Math.max(next.max[0], next.min[0]), Math.max(next.max[1], next.min[1])];
      if (key === 'max') next.min = [Math.min(next.min[0], next.max[0]), Math.min(next.min[1], next.max[1])];
    }
    this.replace(this.selected, next, 'change');
  }

  private setGradientMax(g: number | undefined): void {
    if (g !== undefined && !(g > 0)) return;
    const tf: Tf2D = { dimensions: '2d', widgets: this.widgets };
    if (g !== undefined) tf.gradientMax = g;
    this.value = tf;
    this.emit('change');
  }

  private add(type: 'gaussian' | 'box'): void {
    const w: TransferWidget =
      type === 'gaussian'
        ? { type: 'gaussian', center: [0.5, 0.3], width: [0.08, 0.15], color: [1, 1, 1], opacity: 1 }
        : { type: 'box', min: [0.4, 0.2], max: [0.6, 1], ramp: [0.05, 0.05], color: [1, 1, 1], opacity: 1 };
    this.selected = this.widgets.length;
    this.setWidgets([...this.widgets, w], 'change');
  }

  private removeWidget(i: number): void {
    if (this.widgets.length <= 1 || i < 0) return;
    this.selected = Math.max(0, Math.min(i, this.widgets.length - 2));
    this.setWidgets(
      this.widgets.filter((_, k) => k !== i),
      'change',
    );
  }

  private toModel(e: PointerEvent): [number, number] {
    const r = (this.renderRoot.querySelector('.plot') as HTMLElement).getBoundingClientRect();
    return [(e.clientX - r.left) / r.width, 1 - (e.clientY - r.top) / r.height];
  }

  private startDrag(e: PointerEvent, index: number, handle: Handle): void {
    if (e.button !== 0) return;
    e.preventDefault();
    this.selected = index;
    this.drag = { index, handle, start: this.toModel(e), widget: this.widgets[index] };
    (this.renderRoot.querySelector('.plot') as HTMLElement).setPointerCapture(e.pointerId);
  }

  private onMove = (e: PointerEvent): void => {
    const d = this.drag;
    if (!d) return;
    const [v, g] = this.toModel(e);
    this.replace(d.index, edit(d.widget, d.handle, v - d.start[0], g - d.start[1]), 'input');
  };

  private onUp = (): void => {
    if (!this.drag) return;
    this.drag = null;
    this.emit('change');
  };

  private onKey(e: KeyboardEvent, i: number, handle: Handle): void {
    const step = e.shiftKey ? 0.1 : 0.01;
    const moves: Record<string, [number, number]> = {
      ArrowLeft: [-step, 0],
      ArrowRight: [step, 0],
      ArrowUp: [0, step],
      ArrowDown: [0, -step],
    };
    if (moves[e.key]) {
      e.preventDefault();
      this.replace(i, edit(this.widgets[i], handle, ...moves[e.key]), 'change');
    } else if (e.key === 'Delete' || e.key === 'Backspace') {
      e.preventDefault();
      this.removeWidget(i);
    }
  }
}
