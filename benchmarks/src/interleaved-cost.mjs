// The timing loop that clip-cost.mjs and slice-plane-cost.mjs share: per renderer (EAM, MIP, ISO,
// MCRT), ms per iteration of the procedural blob with each of two scene additions (a clip, a slice
// plane…) against the same scene without, interleaved (B X B Y, then Y B X B) in one page, printed
// as median ratios to the neighbouring batch without, with the load average. Plain JavaScript,
// like bench-cli.mjs, so that the launchers answer --help before a build.
import os from 'node:os';

/** The command-line options both benchmarks take (parseCliOrExit's table). */
export const COST_OPTIONS = {
  size: { type: 'integer', min: 1, default: 128, description: 'image side in pixels' },
  rounds: { type: 'integer', min: 1, default: 6, description: 'interleaved rounds (one batch of each per round)' },
  batch: { type: 'integer', min: 1, default: 8, description: 'iterations per timed batch' },
  backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2', description: 'the GPU backend' },
};

export const COST_SYNOPSIS = '[--size N] [--rounds N] [--batch N] [--backend webgl2|webgpu]';

/** The renderers timed, with their parameters. */
const RENDERERS = {
  eam: {},
  mip: {},
  iso: { surfaces: [{ value: 0.4, color: [0.9, 0.8, 0.7] }] },
  mcrt: {},
};

const load = () =>
  os
    .loadavg()
    .map((x) => x.toFixed(2))
    .join(' / ');

const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];

/**
 * Time the scene with and without two additions and print a line per renderer.
 * @param {object} o
 * @param {string} o.name the benchmark's name, first on the heading line
 * @param {{ size: number, rounds: number, batch: number, backend: string }} o.options the parsed command line
 * @param {string} o.baseline the label of the scene without additions (e.g. 'unclipped')
 * @param {[[string, object], [string, object]]} o.variants two labels with the scene fields each adds (e.g. `{ clip }`)
 */
export async function runInterleavedCost({ name, options, baseline, variants }) {
  const { size, rounds, batch, backend } = options;
  // After the arguments, so that --help works before a build.
  const { openVptPage } = await import('../../packages/headless/dist/index.js');
  const [[first], [second]] = variants;
  const session = await openVptPage();
  try {
    console.log(`${name}: ${backend}, ${size}² px, ${rounds} rounds of ${batch} iterations; load ${load()}`);
    for (const [renderer, params] of Object.entries(RENDERERS)) {
      const ms = await session.page.evaluate(
        async (o) => {
          const { core } = window.vpt;
          const base = {
            volume: core.createProceduralVolume('blob', 64),
            transferFunction: {
              dimensions: '1d',
              points: [
                { value: 0, color: [0.9, 0.8, 0.7], opacity: 0 },
                { value: 0.2, color: [0.9, 0.8, 0.7], opacity: 0 },
                { value: 1, color: [0.95, 0.95, 0.95], opacity: 1 },
              ],
            },
            camera: { position: [0.9, 0.6, 1.3], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 },
            lights: [{ type: 'directional', direction: [-0.5, 1, 0.4], irradiance: [2, 2, 2] }],
            environment: { type: 'constant', radiance: [0.4, 0.5, 0.7] },
            densityScale: 30,
            seed: 1,
          };
          // One context per configuration, so each keeps its compiled variant and neither recompiles.
          const make = async (extra) => {
            const ctx = await core.RenderContext.create({
              backend: o.backend,
              width: o.size,
              height: o.size,
              renderer: window.vpt.createRenderer(o.renderer, o.params),
            });
            ctx.setScene({ ...base, ...extra });
            await ctx.renderIterations(2); // compile and warm up, untimed
            return ctx;
          };
          const ctxs = { [o.baseline]: await make({}) };
          for (const [k, extra] of o.variants) ctxs[k] = await make(extra);
          const out = Object.fromEntries(Object.keys(ctxs).map((k) => [k, []]));
          const order = [o.baseline, o.variants[0][0], o.baseline, o.variants[1][0]];
          for (let r = 0; r < o.rounds; r++) {
            for (const k of r % 2 ? [...order].reverse() : order) {
              const t0 = performance.now();
              await ctxs[k].renderIterations(o.batch); // ends with backend.finish()
              out[k].push((performance.now() - t0) / o.batch);
            }
          }
          Object.values(ctxs).forEach((c) => c.dispose());
          return out;
        },
        { backend, size, rounds, batch, renderer, params, baseline, variants },
      );
      // Each batch with an addition against the batch without next to it (two per round).
      const ratio = (k) => ms[k].map((c, i) => c / ms[baseline][2 * i + (k === first ? 0 : 1)]);
      const text = (k) => {
        const r = ratio(k);
        return `${k} ${median(ms[k]).toFixed(2)} ms/it, ratio ${median(r).toFixed(3)} (${Math.min(...r).toFixed(3)}–${Math.max(...r).toFixed(3)})`;
      };
      console.log(
        `${renderer.padEnd(5)} ${baseline} ${median(ms[baseline]).toFixed(2)} ms/it; ${text(first)}; ${text(second)}; load ${load()}`,
      );
    }
  } finally {
    await session.close();
  }
}
