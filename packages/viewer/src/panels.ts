/**
 * The viewer's side panels, as template functions over the element: transfer function,
 * lights and environment, clip planes and crop box (clip-panel.ts), labels (labels-layer.ts, with a label volume), renderer and quality, a live readout, and export. Each control
 * writes through `setInternal`, so the matching attribute is reflected and a `vpt-change`
 * event announces it. Native <details>, labelled controls and buttons keep it all
 * reachable and operable from the keyboard.
 */
import { errorReadout } from './readouts.js';
import { html, nothing } from 'lit';
import { TRANSFER_FUNCTION_PRESETS as CORE_TF_PRESETS, type Light, type TransferFunction } from '@vpt/core';
import { TONE_MAP_OPERATORS } from '@vpt/post';
import { BACKEND_NAMES } from './attributes.js';
import { hexToLinear, intensityOf, linearToHex, round4 } from './color.js';
import { TRANSFER_FUNCTION_PRESETS, transferFunctionPreset } from './presets.js';
import { rendererEntries, rendererEntry, type RendererParamSpec } from './renderer-registry.js';
import { clipPanel } from './clip-panel.js';
export { panelStyles } from './panel-styles.js';
import type { PanelHost } from './panel-host.js';

import { PANEL_NAMES, type PanelName } from './panel-host.js';
export { PANEL_NAMES, type PanelName };
// The clip handles on the image show only with the Clip panel, so their geometry rides in this chunk.
export { axisPoint, draggedPosition, projectPoint } from './clip-handles.js';

let uid = 0;
const id = (name: string) => `vpt-${name}-${++uid}`;

const num = (e: Event) => Number((e.target as HTMLInputElement).value);
const str = (e: Event) => (e.target as HTMLInputElement | HTMLSelectElement).value;

export function renderPanels(v: PanelHost, panels: Set<PanelName>) {
  // The Channels panel's template comes with the multichannel volume (channels.ts, its own lazy chunk).
  const mc = v.panelState.volume?.multichannel;
  return html` ${panels.has('tf') ? tfPanel(v) : nothing} ${panels.has('channels') && mc ? mc.panel(v) : nothing}
  ${panels.has('lights') ? lightsPanel(v) : nothing} ${panels.has('clip') ? clipPanel(v) : nothing}
  ${panels.has('labels') ? v.labelsPanel() : nothing} ${panels.has('quality') ? qualityPanel(v) : nothing}
  ${panels.has('stats') ? statsPanel(v) : nothing} ${panels.has('export') ? exportPanel(v) : nothing}`;
}

function presetOf(tf: TransferFunction): string {
  const json = JSON.stringify(tf);
  return (
    Object.keys(TRANSFER_FUNCTION_PRESETS).find((k) => JSON.stringify(TRANSFER_FUNCTION_PRESETS[k]) === json) ?? ''
  );
}

function tfPanel(v: PanelHost) {
  const st = v.panelState;
  const tf = st.transferFunction;
  const presetId = id('preset'),
    densityId = id('density'),
    kindId = id('kind');
  const preset = v.fittedPresetName ?? presetOf(tf);
  const onTf = (e: CustomEvent<{ transferFunction: TransferFunction }>) =>
    v.setInternal('transferFunction', e.detail.transferFunction);
  // A multichannel volume draws each channel's own function (the Channels panel): only the density stays here.
  if (v.channels)
    return html`<details open>
      <summary>Density</summary>
      <div class="panel">${densityRow(v, densityId)}</div>
    </details>`;
  return html`<details open>
    <summary>Transfer function</summary>
    <div class="panel">
      <div class="row">
        <label for=${presetId}>Preset</label>
        <select
          id=${presetId}
          @change=${(e: Event) => {
            const name = str(e);
            if (name) v.setInternal('transferFunction', transferFunctionPreset(name) ?? name);
          }}
        >
          <option value="" ?selected=${preset === ''}>(custom)</option>
          ${Object.keys(TRANSFER_FUNCTION_PRESETS).map((k) => html`<option value=${k} ?selected=${k === preset}>${k} (${TRANSFER_FUNCTION_PRESETS[k].dimensions})</option>`)}
          ${CORE_TF_PRESETS.map((k) => html`<option value=${k} ?selected=${k === preset}>${k} (2d, fitted to the volume)</option>`)}
        </select>
      </div>
      <div class="row">
        <label for=${kindId}>Kind</label>
        <select
          id=${kindId}
          .value=${tf.dimensions}
          @change=${(e: Event) => v.setInternal('transferFunction', transferFunctionPreset(str(e) === '2d' ? 'boundaries' : 'ramp'))}
        >
          <option value="1d" ?selected=${tf.dimensions === '1d'}>1D: value</option>
          <option value="2d" ?selected=${tf.dimensions === '2d'}>2D: value × gradient</option>
        </select>
      </div>
      ${
        tf.dimensions === '1d'
          ? html`<vpt-tf-editor .value=${tf} .histogram=${st.histogram} @input=${onTf} @change=${onTf}></vpt-tf-editor>`
          : html`<vpt-tf2d-editor
              .value=${tf}
              .samples=${v.gradientSamples()}
              @input=${onTf}
              @change=${onTf}
            ></vpt-tf2d-editor>`
      }
      ${densityRow(v, densityId)}
    </div>
  </details>`;
}

function densityRow(v: PanelHost, densityId: string) {
  return html`<div class="row">
    <label for=${densityId}>Density scale</label>
    <input
      id=${densityId}
      type="number"
      min="0"
      step="1"
      .value=${String(v.panelState.densityScale)}
      @change=${(e: Event) => v.setInternal('densityScale', num(e))}
    />
  </div>`;
}

/** Direction from azimuth/elevation in degrees (y up): the direction TOWARD the light. */
function direction(azimuthDeg: number, elevationDeg: number): [number, number, number] {
  const a = (azimuthDeg * Math.PI) / 180,
    e = (elevationDeg * Math.PI) / 180;
  return [round4(Math.cos(e) * Math.sin(a)), round4(Math.sin(e)), round4(Math.cos(e) * Math.cos(a))];
}

function angles(d: readonly number[]): { azimuth: number; elevation: number } {
  const len = Math.hypot(d[0], d[1], d[2]) || 1;
  return {
    azimuth: Math.round((Math.atan2(d[0], d[2]) * 180) / Math.PI),
    elevation: Math.round((Math.asin(d[1] / len) * 180) / Math.PI),
  };
}

function lightsPanel(v: PanelHost) {
  const st = v.panelState;
  const env = st.environment;
  const constant = !env || env.type === 'constant' ? (env?.radiance ?? [1, 1, 1]) : null;
  const light: Light | undefined = st.lights[0];
  const { azimuth, elevation } = light ? angles(light.direction) : { azimuth: 45, elevation: 45 };
  const ids = {
    envc: id('envc'),
    envi: id('envi'),
    on: id('light'),
    az: id('az'),
    el: id('el'),
    lc: id('lc'),
    li: id('li'),
  };
  const setLight = (patch: Partial<{ azimuth: number; elevation: number; color: string; intensity: number }>) => {
    const cur = light ?? {
      type: 'directional' as const,
      direction: direction(45, 45),
      irradiance: [3, 3, 3] as [number, number, number],
    };
    const a = patch.azimuth ?? angles(cur.direction).azimuth;
    const el = patch.elevation ?? angles(cur.direction).elevation;
    const k = patch.intensity ?? intensityOf(cur.irradiance);
    const irradiance = hexToLinear(patch.color ?? linearToHex(cur.irradiance), k);
    v.setInternal('lights', [{ type: 'directional', direction: direction(a, el), irradiance }, ...st.lights.slice(1)]);
  };
  return html`<details>
    <summary>Lights and environment</summary>
    <div class="panel">
      ${
        constant
          ? html` <div class="row">
                <label for=${ids.envc}>Environment colour</label>
                <input
                  id=${ids.envc}
                  type="color"
                  .value=${linearToHex(constant)}
                  @change=${(e: Event) => v.setInternal('environment', { type: 'constant', radiance: hexToLinear(str(e), intensityOf(constant)) })}
                />
              </div>
              <div class="row">
                <label for=${ids.envi}>Environment radiance</label>
                <input
                  id=${ids.envi}
                  type="number"
                  min="0"
                  step="0.1"
                  .value=${String(round4(Math.max(...constant)))}
                  @change=${(e: Event) => {
                    const k = Math.max(0, num(e));
                    const m = Math.max(...constant) || 1;
                    v.setInternal('environment', {
                      type: 'constant',
                      radiance: constant.map((c) => round4((m ? c / m : 1) * k)),
                    });
                  }}
                />
              </div>`
          : html`<p>
              Environment: ${env?.type === 'url' ? env.url : 'lat-long image'}
              <button
                type="button"
                @click=${() => v.setInternal('environment', { type: 'constant', radiance: [1, 1, 1] })}
              >
                Use a constant
              </button>
            </p>`
      }
      <div class="row">
        <label for=${ids.on}>Directional light</label>
        <input
          id=${ids.on}
          type="checkbox"
          .checked=${!!light}
          @change=${(e: Event) => ((e.target as HTMLInputElement).checked ? setLight({}) : v.setInternal('lights', []))}
        />
      </div>
      ${
        light
          ? html` <div class="row">
                <label for=${ids.az}>Azimuth ${azimuth}°</label>
                <input
                  id=${ids.az}
                  type="range"
                  min="-180"
                  max="180"
                  step="1"
                  .value=${String(azimuth)}
                  @change=${(e: Event) => setLight({ azimuth: num(e) })}
                />
              </div>
              <div class="row">
                <label for=${ids.el}>Elevation ${elevation}°</label>
                <input
                  id=${ids.el}
                  type="range"
                  min="-90"
                  max="90"
                  step="1"
                  .value=${String(elevation)}
                  @change=${(e: Event) => setLight({ elevation: num(e) })}
                />
              </div>
              <div class="row">
                <label for=${ids.lc}>Light colour</label>
                <input
                  id=${ids.lc}
                  type="color"
                  .value=${linearToHex(light.irradiance)}
                  @change=${(e: Event) => setLight({ color: str(e) })}
                />
              </div>
              <div class="row">
                <label for=${ids.li}>Irradiance</label>
                <input
                  id=${ids.li}
                  type="number"
                  min="0"
                  step="0.1"
                  .value=${String(round4(intensityOf(light.irradiance)))}
                  @change=${(e: Event) => setLight({ intensity: Math.max(0, num(e)) })}
                />
              </div>`
          : nothing
      }
    </div>
  </details>`;
}

function qualityPanel(v: PanelHost) {
  const ids = {
    r: id('renderer'),
    b: id('backend'),
    t: id('tone'),
    x: id('exposure'),
    m: id('max'),
    e: id('err'),
    s: id('scale'),
    seed: id('seed'),
  };
  const entry = rendererEntry(v.renderer);
  const params = (v.rendererParams && typeof v.rendererParams === 'object' ? v.rendererParams : {}) as Record<
    string,
    unknown
  >;
  return html`<details>
    <summary>Renderer and quality</summary>
    <div class="panel">
      <div class="row">
        <label for=${ids.r}>Renderer</label>
        <select
          id=${ids.r}
          .value=${v.renderer}
          @change=${(e: Event) => {
            v.setInternal('rendererParams', null);
            v.setInternal('renderer', str(e));
          }}
        >
          ${rendererEntries().map((r) => html`<option value=${r.name} ?selected=${r.name === v.renderer}>${r.label}</option>`)}
        </select>
      </div>
      ${(entry?.params ?? []).map((spec) => paramControl(v, spec, params))}
      <div class="row">
        <label for=${ids.b}>Backend</label>
        <select id=${ids.b} .value=${v.backend} @change=${(e: Event) => v.setInternal('backend', str(e))}>
          ${BACKEND_NAMES.map((b) => html`<option value=${b} ?selected=${b === v.backend}>${b === 'auto' ? 'auto' : b === 'webgpu' ? 'WebGPU' : 'WebGL 2'}</option>`)}
        </select>
      </div>
      <div class="row">
        <label for=${ids.x}>Exposure ${v.exposure.toFixed(1)} EV</label>
        <input
          id=${ids.x}
          type="range"
          min="-6"
          max="6"
          step="0.1"
          .value=${String(v.exposure)}
          @input=${(e: Event) => v.setInternal('exposure', num(e))}
        />
      </div>
      <div class="row">
        <label for=${ids.t}>Tone mapper</label>
        <select id=${ids.t} .value=${v.toneMapper} @change=${(e: Event) => v.setInternal('toneMapper', str(e))}>
          ${TONE_MAP_OPERATORS.map((o) => html`<option value=${o} ?selected=${o === v.toneMapper}>${o}</option>`)}
        </select>
      </div>
      <div class="row">
        <label for=${ids.m}>Max samples</label>
        <input
          id=${ids.m}
          type="number"
          min="1"
          step="1"
          .value=${String(v.maxSamples)}
          @change=${(e: Event) => v.setInternal('maxSamples', Math.max(1, Math.round(num(e))))}
        />
      </div>
      <div class="row">
        <label for=${ids.e}>Target error</label>
        <input
          id=${ids.e}
          type="number"
          min="0"
          step="0.001"
          placeholder="off"
          .value=${v.targetError ? String(v.targetError) : ''}
          @change=${(e: Event) => v.setInternal('targetError', Math.max(0, num(e) || 0))}
        />
      </div>
      <div class="row">
        <label for=${ids.s}>Resolution ×${v.resolutionScale}</label>
        <input
          id=${ids.s}
          type="range"
          min="0.25"
          max="2"
          step="0.25"
          .value=${String(v.resolutionScale)}
          @change=${(e: Event) => v.setInternal('resolutionScale', num(e))}
        />
      </div>
      <div class="row">
        <label for=${ids.seed}>Seed</label>
        <input
          id=${ids.seed}
          type="number"
          min="0"
          step="1"
          .value=${String(v.seed)}
          @change=${(e: Event) => v.setInternal('seed', Math.max(0, Math.round(num(e))))}
        />
      </div>
    </div>
  </details>`;
}

/** One renderer parameter as a labelled control; clearing a number field restores the renderer's default. */
function paramControl(v: PanelHost, spec: RendererParamSpec, params: Record<string, unknown>) {
  const pid = id(spec.name);
  const value = spec.read ? spec.read(params) : params[spec.name];
  const write = (next: unknown) => {
    let out: Record<string, unknown>;
    if (spec.write) out = spec.write(params, next ?? spec.read?.({}));
    else {
      out = { ...params };
      if (next === undefined) delete out[spec.name];
      else out[spec.name] = next;
    }
    v.setInternal('rendererParams', Object.keys(out).length ? out : null);
  };
  let control;
  switch (spec.kind ?? 'number') {
    case 'boolean':
      control = html`<input
        id=${pid}
        type="checkbox"
        .checked=${(value ?? spec.defaultValue) === true}
        @change=${(e: Event) => write((e.target as HTMLInputElement).checked)}
      />`;
      break;
    case 'select':
      control = html`<select
        id=${pid}
        .value=${String(value ?? spec.defaultValue ?? '')}
        @change=${(e: Event) => write(str(e))}
      >
        ${(spec.options ?? []).map((o) => html`<option value=${o} ?selected=${o === (value ?? spec.defaultValue)}>${o}</option>`)}
      </select>`;
      break;
    case 'color':
      control = html`<input
        id=${pid}
        type="color"
        .value=${linearToHex((value as number[] | undefined) ?? [1, 1, 1])}
        @change=${(e: Event) => write(hexToLinear(str(e)))}
      />`;
      break;
    default:
      control = html`<input
        id=${pid}
        type="number"
        min=${spec.min ?? ''}
        max=${spec.max ?? ''}
        step=${spec.step ?? 'any'}
        placeholder=${spec.placeholder ?? 'default'}
        .value=${typeof value === 'number' ? String(value) : ''}
        @change=${(e: Event) => {
          const t = str(e).trim();
          write(t === '' ? undefined : Number(t));
        }}
      />`;
  }
  return html`<div class="row"><label for=${pid}>${spec.label}</label>${control}</div>`;
}

/** MCRT's reasons for its estimator choices, one per line (the readout's tooltip). */
function rendererChoiceReasons(r: Record<string, string>): string {
  return Object.entries(r)
    .filter(([k]) => k.endsWith('Reason'))
    .map(([k, reason]) => `${k.slice(0, -'Reason'.length)}: ${reason}`)
    .join('\n');
}

function statsPanel(v: PanelHost) {
  const st = v.panelState;
  const s = st.stats;
  const vol = st.volume;
  return html`<details open>
    <summary>Progress</summary>
    <div class="panel">
      <dl class="readout" part="readout">
        <dt>Samples</dt>
        <dd data-stat="samples">${s ? `${s.samples} / ${v.maxSamples}` : '—'}${v.converged ? ' (converged)' : ''}</dd>
        <dt>ms / iteration</dt>
        <dd data-stat="ms">${s && s.msPerIteration > 0 ? s.msPerIteration.toFixed(2) : '—'}</dd>
        <dt>Est. error</dt>
        <dd data-stat="error">${errorReadout(s, st.rendererInstance)}</dd>
        <dt>Resolution</dt>
        <dd>${s ? `${s.width} × ${s.height}` : '—'}</dd>
        <dt>Backend</dt>
        <dd>${st.backendKind ?? '—'}</dd>
        ${
          s?.renderer.tracking
            ? html`<dt>Estimator</dt>
                <dd data-stat="estimator" title=${rendererChoiceReasons(s.renderer)}>
                  ${s.renderer.estimator}: ${s.renderer.tracking} tracking, ${s.renderer.environmentSampling}
                  environment, ${s.renderer.majorantGrid} majorant
                </dd>`
            : ''
        }
        <dt>Volume</dt>
        <dd>${vol ? `${vol.dims.join('×')} ${vol.type}` : '—'}</dd>
      </dl>
    </div>
  </details>`;
}

function exportPanel(v: PanelHost) {
  const fileId = id('file');
  return html`<details>
    <summary>View and export</summary>
    <div class="panel">
      <div class="buttons">
        <button type="button" @click=${() => v.resetCamera()}>Reset camera</button>
        <button type="button" @click=${() => v.downloadScreenshot()}>Screenshot (PNG)</button>
        <button type="button" @click=${() => v.downloadHDR('exr')}>HDR (EXR)</button>
        <button type="button" @click=${() => v.downloadHDR('pfm')}>HDR (PFM)</button>
      </div>
      <div class="row">
        <label for=${fileId}>Open volume file</label>
        <input
          id=${fileId}
          type="file"
          multiple
          @change=${(e: Event) => {
            const files = [...((e.target as HTMLInputElement).files ?? [])];
            if (files.length) void v.load(files.length === 1 ? files[0] : files);
          }}
        />
      </div>
    </div>
  </details>`;
}
