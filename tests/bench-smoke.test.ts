import { describe, expect, it } from 'vitest';
import { execFileSync } from 'node:child_process';
import { readdirSync, readFileSync, statSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

// The benchmark suites are not part of the test run; this only keeps their harness honest:
// all five suites at the smoke preset's tiny sizes, and the denoise suite. It checks what the runner records
// (shapes, finiteness, ordering), never how fast anything is: timings belong in benchmarks/.
describe('smoke: benchmark harness (smoke preset)', () => {
  it('records monotone error and convergence curves, frame times, scaling rows and the specialization comparison, and a self-contained report', () => {
    const root = fileURLToPath(new URL('..', import.meta.url));
    const resultsDir = path.join(root, 'benchmarks', 'results');
    const before = new Set(safeList(resultsDir));
    execFileSync(
      'node',
      [
        path.join(root, 'benchmarks/dist/run.js'),
        '--preset',
        'smoke',
        '--suites',
        'error,frame,convergence,scaling,specialization',
      ],
      { cwd: root, stdio: 'pipe', timeout: 420_000 },
    );
    const fresh = safeList(resultsDir).filter((d) => !before.has(d));
    expect(fresh.length).toBe(1);
    const dir = path.join(resultsDir, fresh[0]);
    const results = JSON.parse(readFileSync(path.join(dir, 'results.json'), 'utf8'));
    expect(results.machine.commit).toMatch(/^[0-9a-f]{40}$|unknown/);
    expect(Object.keys(results.backends).sort()).toEqual(['webgl2', 'webgpu']);
    for (const curve of results.errorVsTime) {
      const pts = curve.points;
      expect(pts.length).toBeGreaterThan(2);
      for (let i = 1; i < pts.length; i++) {
        expect(pts[i].ms).toBeGreaterThan(pts[i - 1].ms);
        expect(pts[i].iterations).toBeGreaterThan(pts[i - 1].iterations);
      }
      expect(pts.every((p: { nonFinite: number; psnr: number }) => p.nonFinite === 0 && Number.isFinite(p.psnr))).toBe(
        true,
      );
      if (curve.label === 'eam') expect(pts.at(-1).psnr).toBeGreaterThan(pts[0].psnr); // error falls with samples
    }
    const backendsTimed = new Set(results.frameTime.map((r: { backend: string }) => r.backend));
    expect([...backendsTimed].sort()).toEqual(['webgl2', 'webgpu']);
    expect(results.frameTime.every((r: { medianMs: number }) => r.medianMs > 0)).toBe(true);
    // Convergence (first backend): one curve per renderer, iterations rising, every point finite.
    const conv = results.convergence as {
      label: string;
      size: number;
      points: { iterations: number; psnr: number; nonFinite: number }[];
    }[];
    expect(conv.length).toBeGreaterThanOrEqual(4);
    expect(new Set(conv.map((c) => c.label)).size).toBe(conv.length);
    for (const c of conv) {
      expect(c.size).toBe(16);
      expect(c.points.length, c.label).toBeGreaterThan(2);
      for (let i = 1; i < c.points.length; i++)
        expect(c.points[i].iterations).toBeGreaterThan(c.points[i - 1].iterations);
      expect(
        c.points.every((p) => p.nonFinite === 0 && Number.isFinite(p.psnr)),
        c.label,
      ).toBe(true);
    }
    // Scaling: every renderer at each volume size and empty fraction of the preset, a finite positive cost.
    const scaling = results.scaling as { axis: string; label: string; x: number; nsPerPath: number }[];
    expect(scaling.filter((r) => r.axis === 'volume-size').map((r) => r.x)).toEqual(conv.map(() => 16));
    expect([...new Set(scaling.filter((r) => r.axis === 'empty-fraction').map((r) => r.x))]).toEqual([0, 0.9]);
    expect(scaling.length).toBe(3 * conv.length);
    expect(scaling.every((r) => Number.isFinite(r.nsPerPath) && r.nsPerPath > 0)).toBe(true);
    const spec = results.specialization as {
      scene: string;
      scattering: string;
      backend: string;
      ratio: number;
      specializedMs: number;
      genericMs: number;
    }[];
    expect(spec.length).toBe(2 * 3 * 2); // backends × scenes × scattering orders
    expect(new Set(spec.map((r) => r.backend)).size).toBe(2);
    for (const r of spec) {
      expect(r.specializedMs).toBeGreaterThan(0);
      expect(r.ratio).toBeCloseTo(r.genericMs / r.specializedMs, 10);
    }
    const html = readFileSync(path.join(dir, 'report.html'), 'utf8');
    expect(html).toContain('MCRT kernel specialization');
    expect(html).toContain('Convergence per iteration');
    expect(html).toContain('Scaling: cost per path');
    expect(html).toContain('uPlot');
    expect(html).not.toMatch(/<script[^>]+src=/); // self-contained
  }, 480_000);

  it('records the denoise suite: both curves on the same checkpoints, finite errors, the bias and the load average', () => {
    const root = fileURLToPath(new URL('..', import.meta.url));
    const resultsDir = path.join(root, 'benchmarks', 'results');
    const before = new Set(safeList(resultsDir));
    execFileSync(
      'node',
      [path.join(root, 'benchmarks/dist/run.js'), '--preset', 'smoke', '--suites', 'denoise', '--backends', 'webgl2'],
      { cwd: root, stdio: 'pipe', timeout: 420_000 },
    );
    const fresh = safeList(resultsDir).filter((d) => !before.has(d));
    expect(fresh.length).toBe(1);
    const dir = path.join(resultsDir, fresh[0]);
    const results = JSON.parse(readFileSync(path.join(dir, 'results.json'), 'utf8'));
    type Point = { iterations: number; ms: number; psnr: number; nonFinite: number };
    const rows = results.denoise as {
      scene: string;
      plain: Point[];
      denoised: Point[];
      bias: { psnr: number; relativeRmse: number };
      loadAverage: { before: number[] };
    }[];
    expect(rows.map((r) => r.scene)).toEqual(expect.arrayContaining(['cloud', 'head']));
    for (const r of rows) {
      expect(r.denoised.map((p) => p.iterations)).toEqual(r.plain.map((p) => p.iterations));
      for (const p of [...r.plain, ...r.denoised]) {
        expect(p.nonFinite).toBe(0);
        expect(Number.isFinite(p.psnr) && p.ms > 0).toBe(true);
      }
      expect(Number.isFinite(r.bias.psnr) && r.bias.relativeRmse >= 0).toBe(true);
      expect(r.loadAverage.before).toHaveLength(3);
    }
    expect(readFileSync(path.join(dir, 'report.html'), 'utf8')).toContain('<h2>Denoiser</h2>');
  }, 480_000);
});

function safeList(dir: string): string[] {
  try {
    return readdirSync(dir).filter((d) => statSync(path.join(dir, d)).isDirectory());
  } catch {
    return [];
  }
}
