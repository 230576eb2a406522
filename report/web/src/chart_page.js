// A page of charts (benchmarks, `snapfit tune --html`): the data block is
//   {kind: "charts", title, notes: [lines], charts: [chart spec, ...]}
// Sets window.snapfitPage = {ready: true, charts: n} when every chart is drawn.
import './style.css';

import { createChart, fitChartsToWidth } from './charts.js';
import { element, readPageData } from './page_data.js';

function main() {
  const data = readPageData();
  document.title = data.title || 'snapfit charts';
  const root = document.getElementById('app');
  root.append(element('h1', { text: data.title || 'snapfit charts' }));
  for (const line of data.notes || []) root.append(element('p', { class: 'note', text: line }));
  const entries = [];
  (data.charts || []).forEach((spec, i) => {
    const container = element('div', { class: 'chart', id: `chart-${i}` });
    root.append(container);
    entries.push({ chart: createChart(container, spec, { height: 360 }), container });
  });
  fitChartsToWidth(entries);
  window.snapfitPage = { ready: true, charts: entries.length };
}

main();
