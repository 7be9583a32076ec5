import { describe, expect, it } from 'vitest';
import { rendererNames } from '../packages/core/src/index.js';
import { useViewerPage } from './helpers/viewer-page.js';
import { mutateScene, seededRandom, EXTREME_NUMBERS, type Json } from './helpers/scene-fuzz.js';

/**
 * Issue 15 for <vpt-viewer>: removing an attribute returns to its default, a context that is
 * never restored is reported (code context-lost) with a Retry, and a fuzz of attribute values
 * leaves the element usable: typed `error` events only, no exception, a finite image after.
 * VPT_FUZZ_ATTRIBUTE_CASES (default 300) and VPT_FUZZ_SEED (default 15).
 */
const CASES = Number(process.env.VPT_FUZZ_ATTRIBUTE_CASES ?? 300);
const SEED = Number(process.env.VPT_FUZZ_SEED ?? 15);
const viewer = useViewerPage();

describe('<vpt-viewer> attribute removal', () => {
  it(
    'removing exposure, density-scale, seed, renderer, tone-mapper, max-samples returns each to its default, with no error and no exception',
    async () => {
      const r = await viewer().run(async (vt) => {
        const el = vt.create({
          src: 'procedural:blob?size=16',
          renderer: 'mip',
          backend: 'webgl2',
          panels: 'all',
          exposure: '1',
          'density-scale': '3',
          seed: '7',
          'tone-mapper': 'reinhard',
          'max-samples': '2',
        });
        await vt.converged(el);
        const errorsBefore = el.__events.filter((e: any) => e.type === 'error').length;
        for (const name of ['exposure', 'density-scale', 'seed', 'renderer', 'tone-mapper', 'max-samples'])
          el.removeAttribute(name);
        await el.whenSettled();
        await vt.frames(4);
        el.maxSamples = 2; // the default (1024) would take long to converge on SwiftShader
        await vt.converged(el);
        const out = {
          values: {
            exposure: el.exposure,
            densityScale: el.densityScale,
            seed: el.seed,
            renderer: el.renderer,
            toneMapper: el.toneMapper,
          },
          newErrors: el.__events.filter((e: any) => e.type === 'error').slice(errorsBefore),
          samples: el.samples,
        };
        el.remove();
        return out;
      });
      expect(r.values).toEqual({ exposure: 0, densityScale: null, seed: 1, renderer: 'eam', toneMapper: 'aces' }); // density-scale's default: the renderer's own
      expect(r.newErrors).toEqual([]);
      expect(r.samples).toBeGreaterThanOrEqual(2); // it rendered on after the removals
      expect(viewer().errors).toEqual([]);
    },
    Math.max(240_000, CASES * 150),
  );
});

describe('<vpt-viewer> renderer-params', () => {
  it('an EAM stepSize of 1e-9, 0 or -1 fires a typed error naming the parameter and the element keeps rendering', async () => {
    const r = await viewer().run(async (vt) => {
      const el = vt.blob('eam', 2);
      await vt.converged(el);
      const out: any[] = [];
      for (const step of ['1e-9', '0', '-1']) {
        const error = vt.next(el, 'error', 20000);
        el.setAttribute('renderer-params', `{"stepSize":${step}}`);
        const d = await error;
        out.push({ code: d.code, message: d.message });
      }
      el.setAttribute('renderer-params', '{"stepSize":0.02}');
      el.setAttribute('seed', '5'); // a new accumulation
      await el.whenSettled();
      await vt.converged(el);
      const hdr = await el.context.readHDR();
      let alpha = 0;
      for (let i = 3; i < hdr.length; i += 4) alpha = Math.max(alpha, hdr[i]);
      el.remove();
      return { out, alpha, finite: hdr.every(Number.isFinite) };
    });
    for (const e of r.out) {
      expect(e.code).toBe('invalid-scene');
      expect(e.message).toMatch(/EAM\.stepSize/);
    }
    expect(r.finite).toBe(true);
    expect(r.alpha).toBeGreaterThan(0);
  });
});

describe('<vpt-viewer> context loss that is never restored', () => {
  it('fires error with code context-lost after the timeout, shows Retry, and Retry renders again', async () => {
    const r = await viewer().run(async (vt) => {
      const el = vt.blob('eam', 2);
      el.contextRestoreTimeoutMs = 300;
      await vt.converged(el);
      const error = vt.next(el, 'error', 20000);
      el.context.backend.simulateLoss(600000).catch(() => {}); // restored only after 10 minutes: never, here
      const detail = await error;
      await el.updateComplete;
      const text = vt.shadowText(el, '.lost p');
      const button = el.shadowRoot.querySelector('.lost button');
      const label = button?.textContent.trim();
      button.click();
      await el.whenSettled();
      await vt.converged(el);
      const out = {
        code: detail.code,
        source: detail.source,
        message: detail.message,
        text,
        label,
        after: vt.shadowText(el, '.lost p'),
        samples: el.samples,
        lost: el.context.backend.isLost,
      };
      el.remove();
      return out;
    });
    expect(r.code).toBe('context-lost');
    expect(r.source).toBe('context');
    expect(r.message).toMatch(/not restored within 300 ms/);
    expect(r.text).toMatch(/was not restored/);
    expect(r.label).toBe('Retry');
    expect(r.after).toBeNull();
    expect(r.samples).toBe(2);
    expect(r.lost).toBe(false);
  });
});

// ——— attribute fuzz ———

const VALID: Record<string, Json[]> = {
  renderer: rendererNames(),
  'transfer-function': [
    'ramp',
    'tissue',
    {
      dimensions: '1d',
      points: [
        { value: 0, color: [1, 1, 1], opacity: 0 },
        { value: 1, color: [1, 0.5, 0.2], opacity: 2 },
      ],
    },
  ],
  camera: [{ position: [0, 0.5, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 }],
  lights: ['none', [{ type: 'directional', direction: [1, 1, 1], irradiance: [3, 3, 3] }]],
  environment: [{ type: 'constant', radiance: [1, 1, 1] }],
  exposure: [0, 1.5, -2],
  'tone-mapper': ['aces', 'reinhard'],
  'max-samples': [1, 2, 3],
  'target-error': [0, 0.1],
  'density-scale': [1, 10, 40],
  seed: [1, 42],
  'renderer-params': [{}, { stepSize: 0.05 }],
  'resolution-scale': [0.5, 1],
  clip: [
    { planes: [{ normal: [1, 0, 0], offset: 0 }] },
    { planes: [{ normal: [0, 1, 1], offset: 0.1 }], box: { min: [-0.3, -0.4, -0.5], max: [0.3, 0.4, 0.5] } },
  ],
  src: ['procedural:blob?size=16', 'procedural:sphere?size=12'],
};
const NAMES = Object.keys(VALID);
const BAD_WORDS = [
  '',
  'x',
  'null',
  '{',
  '[]',
  '{}',
  'NaN',
  'Infinity',
  '-1',
  '1e39',
  'procedural:blob?size=100000',
  'nope.json',
  '{"a":1}',
  '[1,2,3]',
  'middle',
];

function attributeValue(name: string, rnd: () => number): string | null {
  const r = rnd();
  const pick = <T>(xs: readonly T[]) => xs[Math.floor(rnd() * xs.length)];
  if (r < 0.1) return null; // removeAttribute
  const valid = pick(VALID[name]);
  if (r < 0.35) return typeof valid === 'string' ? valid : JSON.stringify(valid);
  if (r < 0.6) return pick(BAD_WORDS);
  if (typeof valid === 'number') return String(pick(EXTREME_NUMBERS));
  if (valid && typeof valid === 'object') {
    const wrapped = { v: valid } as Record<string, Json>;
    return JSON.stringify(mutateScene(wrapped, rnd).scene.v ?? null);
  }
  return String(pick(EXTREME_NUMBERS));
}

describe('<vpt-viewer> attribute fuzz', () => {
  it(
    `${CASES} random attribute values (seed ${SEED}): only typed errors, no exception, no hang, and a finite image afterwards`,
    async () => {
      const rnd = seededRandom(SEED);
      const steps: { name: string; value: string | null }[] = [];
      for (let i = 0; i < CASES; i++) {
        const name = NAMES[Math.floor(rnd() * NAMES.length)];
        steps.push({ name, value: attributeValue(name, rnd) });
      }
      // In chunks: one page.evaluate must stay well below the protocol timeout.
      await viewer().page.evaluate(async () => {
        const w = window as any;
        const vt = w.vt;
        w.__fuzz = {
          el: vt.create(
            { src: 'procedural:blob?size=16', renderer: 'eam', backend: 'webgl2', panels: 'all', 'max-samples': '2' },
            'width:24px;height:24px',
          ),
          problems: [],
        };
        await vt.converged(w.__fuzz.el);
        w.__fuzz.withTimeout = (p: Promise<unknown>, ms: number, what: string) =>
          Promise.race([
            p,
            new Promise((_, reject) =>
              setTimeout(() => reject(new Error(`HANG: ${what} not settled within ${ms} ms`)), ms),
            ),
          ]);
        w.__fuzz.usable = async (label: string) => {
          const { el, problems, withTimeout } = w.__fuzz;
          // Back to a valid state: the element must render a finite image again.
          for (const [k, v] of [
            ['src', 'procedural:blob?size=16'],
            ['renderer', 'eam'],
            ['renderer-params', '{}'],
            ['camera', '{"position":[0,0.5,2],"target":[0,0,0],"up":[0,1,0],"fovy":0.7}'],
            ['density-scale', '10'],
            ['max-samples', '2'],
            ['target-error', '0'],
            ['resolution-scale', '1'],
            ['environment', '{"type":"constant","radiance":[1,1,1]}'],
            ['lights', 'none'],
            ['transfer-function', 'ramp'],
          ])
            el.setAttribute(k, v);
          try {
            await withTimeout(vt.converged(el, 60000), 70000, `recovery after ${label}`);
            const hdr = await el.context.readHDR();
            if (!hdr.every(Number.isFinite)) problems.push(`${label}: non-finite image`);
          } catch (e: any) {
            problems.push(`${label}: ${e.message}`);
          }
        };
      });
      for (let at = 0; at < steps.length; at += 200) {
        await viewer().page.evaluate(
          async (chunk, offset) => {
            const w = window as any;
            const { el, problems, withTimeout, usable } = w.__fuzz;
            for (let j = 0; j < chunk.length; j++) {
              const i = offset + j;
              const { name, value } = chunk[j];
              const label = `step ${i}: ${name}=${value === null ? '(removed)' : JSON.stringify(value)}`;
              try {
                if (value === null) el.removeAttribute(name);
                else el.setAttribute(name, value);
                await withTimeout(el.whenSettled(), 60000, label);
                await w.vt.frames(1);
              } catch (e: any) {
                problems.push(`${label}: ${e.message}`);
              }
              if (i % 20 === 19) await usable(label);
            }
          },
          steps.slice(at, at + 200),
          at,
        );
      }
      const r = await viewer().page.evaluate(async () => {
        const { el, problems, usable } = (window as any).__fuzz;
        await usable('the end');
        const errors = el.__events.filter((e: any) => e.type === 'error');
        const untyped = errors.filter(
          (e: any) =>
            !['invalid-scene', 'limit-exceeded', 'load-failed', 'context-lost', 'missing-extension'].includes(e.code),
        );
        el.remove();
        return {
          problems,
          errorCount: errors.length,
          untyped: untyped.map((e: any) => `${e.code}: ${e.message}`),
          codes: [...new Set(errors.map((e: any) => e.code))],
        };
      });
      console.log(
        `attribute fuzz seed ${SEED}, ${CASES} steps: ${r.errorCount} typed error events (${r.codes.join(', ')})`,
      );
      expect(r.problems).toEqual([]);
      expect(r.untyped).toEqual([]);
      expect(r.errorCount).toBeGreaterThan(CASES / 10); // the fuzz does reach the error paths
      expect(viewer().errors).toEqual([]);
    },
    Math.max(240_000, CASES * 150),
  );
});
