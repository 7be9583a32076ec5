/**
 * The report's charts, drawn in the browser with uPlot (a global of its IIFE build). This
 * function's compiled source is what a report page runs: inlined in a self-contained
 * report, or written once as `report-assets/report-charts.js` for the published ones.
 */
export interface ChartSpec {
  /** The id of the element the chart goes into. */
  id: string;
  title: string;
  xLabel: string;
  yLabel: string;
  logX: boolean;
  series: { label: string; x: number[]; y: number[] }[];
}

export function drawCharts(charts: ChartSpec[]): void {
  const uPlot = (window as unknown as { uPlot: new (...args: unknown[]) => unknown }).uPlot;
  const palette = [
    '#1f77b4',
    '#ff7f0e',
    '#2ca02c',
    '#d62728',
    '#9467bd',
    '#8c564b',
    '#e377c2',
    '#7f7f7f',
    '#bcbd22',
    '#17becf',
  ];
  for (const c of charts) {
    // uPlot wants one shared x array; a series without a point at some x gets null there.
    const xs = [...new Set(c.series.flatMap((s) => s.x))].sort((a, b) => a - b);
    const data = [
      xs,
      ...c.series.map((s) =>
        xs.map((x) => {
          const i = s.x.indexOf(x);
          return i < 0 ? null : s.y[i];
        }),
      ),
    ];
    const el = document.createElement('div');
    document.getElementById(c.id)!.appendChild(el);
    new uPlot(
      {
        title: c.title,
        width: 1000,
        height: 360,
        scales: { x: { time: false, distr: c.logX ? 3 : 1 } },
        axes: [{ label: c.xLabel }, { label: c.yLabel }],
        series: [
          { label: c.xLabel },
          ...c.series.map((s, i) => ({
            label: s.label,
            stroke: palette[i % palette.length],
            spanGaps: true,
            points: { show: true },
          })),
        ],
      },
      data,
      el,
    );
  }
}
