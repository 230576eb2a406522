// Browser test of a chart page (CTest label `browser`): node check_chart_page.mjs PAGE.html
// opens the page from disk in headless chromium and checks that it loads with no console
// errors and no network request, shows its title, and draws every chart its data block
// holds, each with pixels of every series' colour. Exits 77 (skipped) without chromium.
import { Checks, openPage, pixelStats } from './page_checks.mjs';

const PALETTE = [[31, 119, 180], [214, 39, 40], [44, 160, 44], [255, 127, 14], [148, 103, 189]];

const file = process.argv[2];
if (!file) {
  console.error('usage: node check_chart_page.mjs PAGE.html');
  process.exit(2);
}
const t = new Checks(`chart page ${file}`);
const { page, problems, requests, close } = await openPage(file, 'snapfitPage');
try {
  const data = await page.evaluate(() => JSON.parse(document.getElementById('snapfit-data').textContent));
  t.check((await page.locator('h1').textContent()) === data.title, `title "${data.title}"`);
  const charts = page.locator('.chart');
  t.check((await charts.count()) === data.charts.length && data.charts.length > 0, `${data.charts.length} charts drawn`);
  for (let i = 0; i < data.charts.length; i++) {
    const shot = await charts.nth(i).locator('canvas').first().screenshot();
    const spec = data.charts[i];
    for (let s = 0; s < Math.min(spec.series.length, PALETTE.length); s++) {
      if (spec.series[s].color) continue;
      const stats = await pixelStats(page, shot, { color: PALETTE[s], tolerance: 40 });
      t.check(stats.near > 10, `chart ${i} "${spec.title}": series "${spec.series[s].label}" has ${stats.near} pixels`);
    }
    const legend = await charts.nth(i).locator('.u-legend').textContent();
    t.check(spec.series.every((s) => legend.includes(s.label)), `chart ${i}: every series in the legend`);
  }
  t.check(problems.length === 0, `no console errors or exceptions${problems.length ? ': ' + problems.join('; ') : ''}`);
  t.check(requests.length === 0, `no network requests${requests.length ? ': ' + requests.join(', ') : ''}`);
} finally {
  await close();
}
t.finish();
