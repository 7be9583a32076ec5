import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { describe, expect, it } from 'vitest';
import { reportContent, reportPage, writeReportAssets, type Results } from '../src/report.js';

const results: Results = {
  machine: { date: '2026-01-02T03:04:05Z', cpus: '2 x <cpu>', flags: ['--a', '--b'] },
  backends: { webgl2: { limits: { maxTextureDimension3D: 2048 } } },
  preset: 'smoke',
  convergence: [{ label: 'eam', size: 16, points: [{ iterations: 1, psnr: 20 }] }] as Results['convergence'],
  skipped: ['ct-chest (not fetched)'],
};

describe('benchmark report pages', () => {
  it('the inline page carries uPlot and the chart code; the linked page names the shared assets instead', () => {
    const content = reportContent(results);
    const inline = reportPage(content, 'inline');
    const linked = reportPage(content, 'linked');
    expect(inline).not.toMatch(/<script[^>]+src=/);
    expect(inline).toContain('uPlot');
    expect(inline).toContain('function drawCharts(');
    expect(linked).toContain('<script src="report-assets/uPlot.iife.min.js">');
    expect(linked).toContain('<script src="report-assets/report-charts.js">');
    expect(linked).not.toContain('function drawCharts(');
    // The same data in both: the chart specification and the setup rows, escaped.
    for (const page of [inline, linked]) {
      expect(page).toContain(JSON.stringify(content.charts));
      expect(page).toContain('<tr><th>machine.cpus</th><td>2 x &lt;cpu&gt;</td></tr>');
      expect(page).toContain('<tr><th>machine.flags</th><td>--a --b</td></tr>');
      expect(page).toContain('<tr><th>backends.webgl2.limits.maxTextureDimension3D</th><td>2048</td></tr>');
      expect(page).toContain('<p>Skipped: ct-chest (not fetched)</p>');
    }
  });
  it('writes the shared assets a linked page loads', async () => {
    const dir = mkdtempSync(path.join(tmpdir(), 'vpt-report-'));
    try {
      await writeReportAssets(dir);
      const linked = reportPage(reportContent(results), 'linked');
      for (const [, href] of linked.matchAll(/(?:src|href)="(report-assets\/[^"]+)"/g))
        expect(readFileSync(path.join(dir, href), 'utf8').length).toBeGreaterThan(100);
      expect(readFileSync(path.join(dir, 'report-assets/report-charts.js'), 'utf8')).toMatch(/function drawCharts\(/);
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }
  });
});
