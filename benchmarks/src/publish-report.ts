/**
 * `node benchmarks/dist/publish-report.js benchmarks/results/<stamp>/results.json docs/benchmarks/<name>.html`
 * Writes a run's report for the docs: the same page as the run's report.html, but loading
 * uPlot, the style and the chart code from the shared `report-assets/` beside it (written
 * too), so the published reports do not each carry a copy.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { reportContent, reportPage, writeReportAssets, type Results } from './report.js';

const [resultsFile, outFile] = process.argv.slice(2);
if (!resultsFile || !outFile) {
  console.error('usage: publish-report <results.json> <out.html>');
  process.exit(2);
}
const results = JSON.parse(readFileSync(resultsFile, 'utf8')) as Results;
writeFileSync(outFile, reportPage(reportContent(results), 'linked'));
await writeReportAssets(path.dirname(outFile));
console.log(`wrote ${outFile} and ${path.join(path.dirname(outFile), 'report-assets')}/`);
