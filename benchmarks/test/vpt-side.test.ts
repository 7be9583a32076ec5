import { describe, expect, it } from 'vitest';
import { anchorDensity, anchorVolume, skyRadiance } from '../src/vpt-side/anchor-scene.js';
import { formatRatio, psnrAgainstTruth, ratioSummary, sideTimeTo } from '../src/vpt-side/side-metrics.js';
import { vptBuildDir } from '../src/vpt-side/run-side.js';

describe('side-by-side arithmetic', () => {
  it('removes the reference noise: MSE v/n + v/R measured gives the PSNR of v/n', () => {
    const v = 0.01;
    for (const [n, R] of [
      [1, 64],
      [16, 64],
      [100, 400],
    ]) {
      const measured = v / n + v / R;
      expect(psnrAgainstTruth(measured, n, R)).toBeCloseTo(10 * Math.log10(n / v), 9);
    }
    expect(psnrAgainstTruth(0.001, 5, Infinity)).toBeCloseTo(30, 9);
  });

  it('finds the time to a target on a corrected Monte Carlo curve', () => {
    // ms = 10 per iteration, v = 0.01, reference of 1000 iterations: PSNR(n) = 20 + 10 log10 n, so 30 dB at n = 10.
    const R = 1000;
    const points = [1, 2, 4, 8, 12, 18, 27].map((n) => ({ iterations: n, ms: 10 * n, mse: 0.01 / n + 0.01 / R }));
    expect(sideTimeTo(points, R, 30)!).toBeCloseTo(100, 6);
    expect(sideTimeTo(points, R, 40)).toBeNull();
  });

  it('summarises per-round ratios, leaving out rounds without a value', () => {
    const s = ratioSummary([1, 2, null, 6], [2, 2, 5, 3])!;
    expect(s.rounds).toBe(3);
    expect([s.median, s.min, s.max]).toEqual([1, 0.5, 2]);
    expect(ratioSummary([null], [1])).toBeNull();
    expect(formatRatio(s)).toBe('1.00 (0.50–2.00)');
  });
});

describe('the anchor scene', () => {
  it('has the documented mean (11.5/255) and stays in [0, 1]', () => {
    const data = anchorVolume(32);
    let sum = 0;
    for (const v of data) sum += v;
    expect(sum / data.length).toBeGreaterThan(11.4);
    expect(sum / data.length).toBeLessThan(11.65);
    expect(anchorDensity(0.5 + 0.05, 0.5 - 0.04, 0.5 + 0.02)).toBeGreaterThan(0.9); // the Gaussian core
    expect(anchorDensity(0.01, 0.99, 0.01)).toBeLessThan(1e-6); // a corner outside the bounding sphere: only the Gaussian's tail
  });
  it('sky: 0.05 at the nadir, 1 at the zenith', () => {
    expect(skyRadiance(-1)).toBeCloseTo(0.05, 12);
    expect(skyRadiance(1)).toBeCloseTo(1, 12);
  });
  it('finds no VPT build where there is none', () => {
    expect(vptBuildDir('/nonexistent-vpt-dir')).toBeNull();
  });
});

describe('pnpm bench --vpt without a VPT build', () => {
  it('says why and returns without opening a browser', async () => {
    const { runSide } = await import('../src/vpt-side/run-side.js');
    const lines: string[] = [];
    const log = console.log;
    console.log = (line: string) => lines.push(line);
    try {
      await runSide(['--vpt', '/nonexistent-vpt-dir']);
    } finally {
      console.log = log;
    }
    expect(lines.join('\n')).toMatch(/skipped: no VPT build at "\/nonexistent-vpt-dir"/);
  });
});
