import { copyFileSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { minify } from 'terser';
import { drawCharts, type ChartSpec } from './report-charts.js';
import type { ErrorCurveResult } from './suites/error-vs-time.js';
import type { FrameTimeRow } from './suites/frame-time.js';
import type { ConvergenceResult } from './suites/convergence.js';
import type { ScalingRow } from './suites/scaling.js';
import type { SpecializationRow } from './suites/specialization.js';
import type { CompactResults } from './suites/compact.js';
import type { SkippingResults } from './suites/skipping.js';
import type { DenoiseRow } from './suites/denoise.js';

export interface Results {
  machine: Record<string, unknown>;
  backends: Record<string, unknown>;
  preset: string;
  errorVsTime?: ErrorCurveResult[];
  frameTime?: FrameTimeRow[];
  convergence?: ConvergenceResult[];
  scaling?: ScalingRow[];
  specialization?: SpecializationRow[];
  compact?: CompactResults;
  skipping?: SkippingResults;
  denoise?: DenoiseRow[];
  skipped: string[];
}

const esc = (s: unknown) =>
  String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]!);
const fmt = (ms: number | null) =>
  ms === null ? '—' : ms < 1000 ? `${ms.toFixed(0)} ms` : `${(ms / 1000).toFixed(2)} s`;

/** The report's own style, beside uPlot's. */
const REPORT_CSS = `body{font-family:system-ui,sans-serif;max-width:1100px;margin:2rem auto;padding:0 1rem;color:#222}
table{border-collapse:collapse;margin:0.5rem 0 1.5rem}td,th{border:1px solid #ccc;padding:0.25rem 0.5rem;text-align:right}td:first-child,th:first-child{text-align:left}
table.setup td{text-align:left}`;

function uplotFile(name: 'uPlot.iife.min.js' | 'uPlot.min.css'): string {
  const require = createRequire(import.meta.url);
  return path.join(path.dirname(require.resolve('uplot/dist/uPlot.iife.min.js')), name);
}

/** What a report page shows, before it is wrapped in HTML. */
export interface ReportContent {
  date: string;
  preset: string;
  /** Machine, browser, flags, commit and adapters, one row per leaf. */
  setup: Record<string, unknown>;
  skipped: string[];
  /** The sections' HTML (tables, chart placeholders), one line each. */
  sections: string[];
  charts: ChartSpec[];
}

/**
 * `inline`: one self-contained file (what a run writes into benchmarks/results/). `linked`:
 * the page loads uPlot, the style and the chart code from `report-assets/` beside it, so
 * the published reports in docs/benchmarks/ share one copy (writeReportAssets).
 */
export type ReportAssets = 'inline' | 'linked';

/** The report's tables and chart specifications from a run's results. */
export function reportContent(r: Results): ReportContent {
  const sections: string[] = [];
  const charts: ChartSpec[] = [];

  if (r.errorVsTime?.length) {
    const rows = r.errorVsTime
      .map(
        (c) =>
          `<tr><td>${esc(c.scene)}</td><td>${esc(c.label)}</td><td>${esc(c.backend)}</td><td>${c.size}²</td>${[25, 30, 35, 40].map((d) => `<td>${fmt(c.timeToDb[d])}</td>`).join('')}<td>${c.points.at(-1)?.psnr.toFixed(1)} dB @ ${c.points.at(-1)?.iterations} it</td></tr>`,
      )
      .join('');
    sections.push(`<h2>Error against wall-clock time</h2><p>Time to reach a PSNR (HDR, peak = reference maximum) against a converged reference rendered by the same configuration with another seed (one reference serves both backends, which give bit-identical images). Where the renderer estimates its error (MCRT), the reference's own noise variance, estimated from its even/odd half-accumulations, is subtracted from the measured mean squared error, so the curve shows the error against the converged image rather than flattening at the reference's noise. Interpolated in log time between checkpoints; read-backs excluded from the clock.</p>
<table><tr><th>scene</th><th>configuration</th><th>backend</th><th>size</th><th>25 dB</th><th>30 dB</th><th>35 dB</th><th>40 dB</th><th>last point</th></tr>${rows}</table><div id="evt"></div>`);
    for (const scene of new Set(r.errorVsTime.map((c) => c.scene))) {
      const curves = r.errorVsTime.filter((c) => c.scene === scene);
      charts.push({
        id: 'evt',
        title: `PSNR vs time — ${scene}`,
        xLabel: 'seconds',
        yLabel: 'PSNR (dB)',
        logX: true,
        series: curves.map((c) => ({
          label: `${c.label} (${c.backend})`,
          x: c.points.map((p) => p.ms / 1000),
          y: c.points.map((p) => p.psnr),
        })),
      });
    }
    const withEstimate = r.errorVsTime.filter((c) => c.points.some((p) => p.estimatedRmse !== null));
    if (withEstimate.length) {
      sections.push(
        `<h2>Live error estimate</h2><p>The context's estimate (two half-accumulations) divided by the true RMSE against the reference, along each curve. 1 is perfect.</p><div id="est"></div>`,
      );
      charts.push({
        id: 'est',
        title: 'estimated / true RMSE',
        xLabel: 'iterations',
        yLabel: 'ratio',
        logX: true,
        series: withEstimate.map((c) => ({
          label: `${c.scene} ${c.label} (${c.backend})`,
          x: c.points.filter((p) => p.estimatedRmse !== null).map((p) => p.iterations),
          y: c.points.filter((p) => p.estimatedRmse !== null).map((p) => p.estimatedRmse! / p.rmse),
        })),
      });
    }
  }

  if (r.frameTime?.length) {
    const table = (t: FrameTimeRow['table'], col: (x: FrameTimeRow) => string) => {
      const rows = r.frameTime!.filter((x) => x.table === t);
      const gpu = (x: FrameTimeRow) =>
        x.gpuMedianMs === null || x.gpuMedianMs === undefined
          ? '<td>—</td><td>—</td>'
          : `<td>${x.gpuMedianMs.toFixed(1)}</td><td>${x.gpuMinMs!.toFixed(1)}–${x.gpuMaxMs!.toFixed(1)}</td>`;
      return `<table><tr><th>configuration</th><th>backend</th><th>${t === 'by-volume' ? 'volume' : 'framebuffer'}</th><th>median ms/iteration (wall)</th><th>min–max</th><th>median ms/iteration (GPU timer)</th><th>min–max</th></tr>${rows.map((x) => `<tr><td>${esc(x.label)}</td><td>${x.backend}</td><td>${col(x)}</td><td>${x.medianMs.toFixed(1)}</td><td>${x.minMs.toFixed(1)}–${x.maxMs.toFixed(1)}</td>${gpu(x)}</tr>`).join('')}</table>`;
    };
    sections.push(
      `<h2>Frame time (Lesar et al. 2018, Table 1)</h2><p>Wall clock: a batch of iterations between two blocking GPU syncs. GPU timer: the same batch timed by EXT_disjoint_timer_query_webgl2 (WebGL 2) or timestamp queries (WebGPU) where offered. On SwiftShader the "GPU" is the CPU, so the two agree closely.</p><h3>By volume size</h3>${table('by-volume', (x) => `${x.volumeSize}³ at ${x.size}²`)}<h3>By framebuffer size (128³)</h3>${table('by-framebuffer', (x) => `${x.size}²`)}`,
    );
  }

  if (r.convergence?.length) {
    sections.push(`<h2>Convergence per iteration (Lesar et al. 2018, Figure 5)</h2><div id="conv"></div>`);
    charts.push({
      id: 'conv',
      title: 'PSNR vs iterations',
      xLabel: 'iterations',
      yLabel: 'PSNR (dB)',
      logX: true,
      series: r.convergence.map((c) => ({
        label: `${c.label} ${c.size}²`,
        x: c.points.map((p) => p.iterations),
        y: c.points.map((p) => p.psnr),
      })),
    });
  }

  if (r.scaling?.length) {
    for (const axis of ['volume-size', 'empty-fraction'] as const) {
      const rows = r.scaling.filter((x) => x.axis === axis);
      if (!rows.length) continue;
      sections.push(
        `<h2>Scaling: cost per path against ${axis === 'volume-size' ? 'volume size' : 'fraction of empty space'}</h2><div id="sc-${axis}"></div>`,
      );
      charts.push({
        id: `sc-${axis}`,
        title: `ns per path vs ${axis}`,
        xLabel: axis === 'volume-size' ? 'volume side (voxels)' : 'empty fraction',
        yLabel: 'ns per path',
        logX: axis === 'volume-size',
        series: [...new Set(rows.map((x) => x.label))].map((label) => ({
          label,
          x: rows.filter((x) => x.label === label).map((x) => x.x),
          y: rows.filter((x) => x.label === label).map((x) => x.nsPerPath),
        })),
      });
    }
  }

  if (r.specialization?.length) {
    const rows = r.specialization
      .map(
        (x) =>
          `<tr><td>${esc(x.scene)}</td><td>${x.scattering}</td><td>${x.backend}</td><td>${x.size}²</td><td>${x.specializedMs.toFixed(1)}</td><td>${x.genericMs.toFixed(1)}</td><td>${x.ratio.toFixed(2)}×</td><td>${fmt(x.specializedFirstMs)} / ${fmt(x.genericFirstMs)}</td></tr>`,
      )
      .join('');
    sections.push(`<h2>MCRT kernel specialization</h2><p>Median ms per iteration of the kernel compiled for the scene against the generic kernel (<code>specialize: false</code>: environment map, light loop, scattering order and majorant grid as runtime data), measured alternately in the same run. Ratio &gt; 1: specialization saves that factor. Last column: first iteration after a scene change (kernel compilation + one iteration), specialised / generic.</p>
<table><tr><th>scene</th><th>scattering</th><th>backend</th><th>size</th><th>specialised ms/it</th><th>generic ms/it</th><th>generic / specialised</th><th>first iteration</th></tr>${rows}</table>`);
  }

  if (r.denoise?.length) {
    const t = (x: Record<string, number | null>) => [25, 30, 35].map((d) => `<td>${fmt(x[d])}</td>`).join('');
    const rows = r.denoise
      .map(
        (x) =>
          `<tr><td>${esc(x.scene)}</td><td>${x.backend}</td><td>${x.size}²</td>${t(x.timeToDb.plain)}${t(x.timeToDb.denoised)}<td>${x.bias.psnr.toFixed(1)} dB (${(100 * x.bias.relativeRmse).toFixed(2)} %; noise ${x.bias.noiseRmse === null ? '—' : (100 * x.bias.noiseRmse).toFixed(2) + ' %'}) at ${x.bias.iterations} it</td><td>${x.loadAverage.before.map((v) => v.toFixed(2)).join(' ')}</td></tr>`,
      )
      .join('');
    sections.push(`<h2>Denoiser</h2><p>MCRT (multiple scattering) with and without the denoise step, measured A/B/B/A; the clock counts the iterations and rendering the image at each checkpoint. Bias: the reference's own samples denoised against the plain reference (an upper bound: it includes the noise removed, given beside it as the plain image's own relative noise).</p>
<table><tr><th>scene</th><th>backend</th><th>size</th><th>plain 25 dB</th><th>30 dB</th><th>35 dB</th><th>denoised 25 dB</th><th>30 dB</th><th>35 dB</th><th>bias at convergence (PSNR, rel. RMSE)</th><th>load avg</th></tr>${rows}</table>`);
  }

  if (r.compact) {
    const c = r.compact;
    const bpv = c.bytesPerVoxel
      .map(
        (x) =>
          `<tr><td>${x.type}</td><td>${x.backend}</td><td>${x.sampling}</td><td>${x.bytesPerVoxel.toFixed(2)}</td></tr>`,
      )
      .join('');
    const fe = c.fastVsExact
      .map(
        (x) =>
          `<tr><td>${esc(x.renderer)}</td><td>${x.backend}</td><td>${x.size}²</td><td>${x.fastMs.toFixed(1)}</td><td>${x.exactMs.toFixed(1)}</td><td>${x.ratio.toFixed(2)}×</td></tr>`,
      )
      .join('');
    const ct = c.ctLoad
      .map(
        (x) =>
          `<tr><td>512×512×${x.depth}</td><td>${x.backend}</td><td>${fmt(x.generateMs)}</td><td>${fmt(x.setSceneMs)}</td><td>${fmt(x.firstImageMs)}</td><td>${fmt(x.loadMs)}</td><td>${x.baseHeapMiB.toFixed(0)} → ${x.peakHeapMiB.toFixed(0)}</td><td>${(x.gpuBytes.volume / 2 ** 20).toFixed(0)}</td><td>${x.uploadedDims.join('×')}</td></tr>`,
      )
      .join('');
    sections.push(`<h2>Compact volumes: GPU bytes, fast vs exact sampling, CT load</h2><p>Load average at the start: ${c.loadAverage.map((x) => x.toFixed(2)).join(', ')}.</p>
<table><tr><th>voxel type</th><th>backend</th><th>sampling</th><th>GPU bytes / voxel (volume)</th></tr>${bpv}</table>
<p>Median ms per iteration on the bundled head, fast path (compact texture, one hardware-filtered fetch) and exact path (r32float, manual trilinear), measured alternately (A/B then B/A) in one run. Ratio = exact / fast.</p>
<table><tr><th>renderer</th><th>backend</th><th>size</th><th>fast ms/it</th><th>exact ms/it</th><th>exact / fast</th></tr>${fe}</table>
<p>Synthetic int16 CT: generated in the page, then setScene (upload) and the first image (EAM, 64²). JS heap: V8 heap + array-buffer backing stores, before → peak.</p>
<table><tr><th>volume</th><th>backend</th><th>generate ms</th><th>setScene ms</th><th>first image ms</th><th>load ms</th><th>JS heap MiB</th><th>GPU volume MiB</th><th>uploaded</th></tr>${ct}</table>
${c.ctSkipped.length ? `<p>Not measured: ${c.ctSkipped.map(esc).join('; ')}</p>` : ''}`);
  }

  if (r.skipping) {
    const k = r.skipping;
    const load = (l: number[]) => l.map((x) => x.toFixed(2)).join(', ');
    const fr = k.frame
      .map(
        (x) =>
          `<tr><td>${esc(x.scene)}</td><td>${esc(x.renderer)}</td><td>${x.backend}</td><td>${x.stepVoxels}</td><td>${x.skipMs.toFixed(1)}</td><td>${x.plainMs.toFixed(1)}</td><td>${x.ratio.toFixed(2)}×</td></tr>`,
      )
      .join('');
    const st = k.steps
      .map(
        (x) =>
          `<tr><td>${esc(x.scene)}</td><td>${esc(x.renderer)}</td><td>${x.backend}</td><td>${x.stepVoxels}</td><td>${x.msPerIteration.toFixed(1)}</td>${[30, 35, 40].map((d) => `<td>${fmt(x.ownTimeToDb[d])}</td>`).join('')}<td>${x.ownIterationsToDb[35]?.toFixed(1) ?? '—'}</td>${[30, 35].map((d) => `<td>${fmt(x.fineTimeToDb[d])}</td>`).join('')}<td>${x.ceilingDb === null ? '—' : x.ceilingDb.toFixed(1)}</td></tr>`,
      )
      .join('');
    sections.push(`<h2>Empty-space skipping and the ray-march step</h2><p>Load average at the start ${load(k.loadAverageStart)}, at the end ${load(k.loadAverageEnd)}. Median ms per iteration at ${k.frameSize}² with skipping on and off (<code>emptySpaceSkipping: false</code>), alternately (A/B, B/A) in one run; ratio = off / on.</p>
<table><tr><th>scene</th><th>renderer</th><th>backend</th><th>step (voxels)</th><th>on ms/it</th><th>off ms/it</th><th>off / on</th></tr>${fr}</table>
<p>Step sweep at ${k.size}², skipping on: time to a PSNR (HDR) against the step's own converged image (${k.refIterations} iterations, another seed), the iterations to 35 dB, the time against the finest step's converged image, and the PSNR of the step's converged image against the finest's (the ceiling its bias sets).</p>
<table><tr><th>scene</th><th>renderer</th><th>backend</th><th>step (voxels)</th><th>ms/it</th><th>own 30 dB</th><th>own 35 dB</th><th>own 40 dB</th><th>it to own 35 dB</th><th>finest 30 dB</th><th>finest 35 dB</th><th>ceiling</th></tr>${st}</table>`);
  }

  return {
    date: String(r.machine.date),
    preset: r.preset,
    setup: { machine: r.machine, backends: r.backends },
    skipped: r.skipped,
    sections,
    charts,
  };
}

/** Nested setup data as "a.b.c → value" rows, on one line (the same keys recur in every report). */
function setupTable(setup: Record<string, unknown>): string {
  const rows: string[] = [];
  const walk = (prefix: string, v: unknown) => {
    if (v && typeof v === 'object' && !Array.isArray(v))
      for (const [k, x] of Object.entries(v)) walk(prefix ? `${prefix}.${k}` : k, x);
    else rows.push(`<tr><th>${esc(prefix)}</th><td>${esc(Array.isArray(v) ? v.join(' ') : v)}</td></tr>`);
  };
  walk('', setup);
  return `<table class="setup">${rows.join('')}</table>`;
}

/** A report page: tables plus uPlot charts, with its assets inlined or linked (see ReportAssets). */
export function reportPage(c: ReportContent, assets: ReportAssets): string {
  const head =
    assets === 'inline'
      ? `<style>${readFileSync(uplotFile('uPlot.min.css'), 'utf8')}\n${REPORT_CSS}</style>`
      : '<link rel="stylesheet" href="report-assets/uPlot.min.css"><link rel="stylesheet" href="report-assets/report.css">';
  const scripts =
    assets === 'inline'
      ? `<script>${readFileSync(uplotFile('uPlot.iife.min.js'), 'utf8')}</script>\n<script>(${drawCharts.toString()})(${JSON.stringify(c.charts)});</script>`
      : `<script src="report-assets/uPlot.iife.min.js"></script><script src="report-assets/report-charts.js"></script>\n<script>drawCharts(${JSON.stringify(c.charts)});</script>`;
  return `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>vpt benchmarks — ${esc(c.date)}</title>${head}</head><body>
<h1>vpt benchmarks (${esc(c.preset)} preset)</h1>
${setupTable(c.setup)}
${c.skipped.length ? `<p>Skipped: ${c.skipped.map(esc).join('; ')}</p>` : ''}
${c.sections.join('\n')}
${scripts}</body></html>`;
}

/** A self-contained HTML report of a run: tables plus uPlot charts (the library is inlined). */
export function htmlReport(r: Results): string {
  return reportPage(reportContent(r), 'inline');
}

/**
 * Write `report-assets/` (uPlot, the style, the chart code) into a folder of linked reports.
 * The chart code is minified like uPlot beside it: a shipped build output of report-charts.ts.
 */
export async function writeReportAssets(dir: string): Promise<void> {
  const assets = path.join(dir, 'report-assets');
  mkdirSync(assets, { recursive: true });
  copyFileSync(uplotFile('uPlot.iife.min.js'), path.join(assets, 'uPlot.iife.min.js'));
  copyFileSync(uplotFile('uPlot.min.css'), path.join(assets, 'uPlot.min.css'));
  writeFileSync(path.join(assets, 'report.css'), REPORT_CSS + '\n');
  const { code } = await minify(drawCharts.toString(), { compress: true, mangle: { reserved: ['drawCharts'] } });
  writeFileSync(
    path.join(assets, 'report-charts.js'),
    `/* Generated by benchmarks/src/report.ts from report-charts.ts (drawCharts). */\n${code}\n`,
  );
}
