/**
 * `node benchmarks/dist/publish-report.js benchmarks/results/<stamp>/results.json docs/benchmarks/<name>.html`
 * Writes a run's report for the docs: the same page as the run's report.html, but loading
 * uPlot, the style and the chart code from the shared `report-assets/` beside it (written
 * too), so the published reports do not each carry a copy.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { parseCliOrExit } from '@vpt/cli-options';
import { reportContent, reportPage, writeReportAssets, type Results } from './report.js';

const { resultsFile, outFile } = parseCliOrExit({
  name: 'node benchmarks/dist/publish-report.js',
  synopsis: 'RESULTS.json OUT.html',
  summary: "Write a run's report for the docs, with uPlot, the style and the charts in report-assets/ beside it.",
  positionals: [
    { key: 'resultsFile', name: 'RESULTS.json', type: 'string', required: true, description: "a run's results.json" },
    { key: 'outFile', name: 'OUT.html', type: 'string', required: true, description: 'the page to write' },
  ],
});
const results = JSON.parse(readFileSync(resultsFile, 'utf8')) as Results;
writeFileSync(outFile, reportPage(reportContent(results), 'linked'));
await writeReportAssets(path.dirname(outFile));
console.log(`wrote ${outFile} and ${path.join(path.dirname(outFile), 'report-assets')}/`);
