// Browser test of report.html (CTest label `browser`): node check_run_report.mjs RUN_DIR
// opens RUN_DIR/report.html from disk in headless chromium and checks that it loads with no
// console errors and no network request, that the summary in the DOM says what
// RUN_DIR/summary.json says, that the 3D view and every chart draw something, and, for a
// run with a trajectory, that the playback moves part 2: two screenshots at the run's
// first and last moments differ, mostly where the part is. Exits 77 (skipped) without chromium.
import fs from 'node:fs';
import path from 'node:path';

import { Checks, openPage, pixelDifference, pixelStats } from './page_checks.mjs';

const dir = process.argv[2];
if (!dir) {
  console.error('usage: node check_run_report.mjs RUN_DIR');
  process.exit(2);
}
const summary = JSON.parse(fs.readFileSync(path.join(dir, 'summary.json'), 'utf8'));
const loop = summary.haptic_loop;
const t = new Checks(`report.html in ${dir}`);
t.check(summary.report_html === 'report.html', 'summary.json names report.html');

const { page, problems, requests, close } = await openPage(path.join(dir, 'report.html'), 'snapfitReport');
try {
  // --- the summary at the top
  const dom = await page.evaluate(() => Object.fromEntries([...document.querySelectorAll('#summary dd')].map(
    (dd) => [dd.dataset.key, { value: JSON.parse(dd.dataset.value), text: dd.textContent }])));
  t.check(dom.scene && dom.scene.value === summary.scene && dom.scene.text.includes(summary.scene), `scene is "${summary.scene}"`);
  t.check(dom.device && dom.device.value === summary.device, `device is "${summary.device}"`);
  t.check(dom.loop_device && dom.loop_device.value === summary.loop_device, 'loop device as in summary.json');
  if (summary.method.startsWith('vps')) {
    t.check(dom.modes && dom.modes.text.startsWith('none'), "Voxmap PointShell: no m'");
  } else {
    t.check(dom.modes && dom.modes.value === summary.tuning.chosen_modes &&
            dom.modes.text.startsWith(String(summary.tuning.chosen_modes)), `m' is ${summary.tuning.chosen_modes}`);
  }
  const strategy = summary.query_strategy;
  if (strategy) {
    t.check(dom.query_strategy && dom.query_strategy.value.name === strategy.name &&
            dom.query_strategy.text.startsWith(dom.query_strategy.value.label) &&
            dom.query_strategy.text.includes(strategy.chosen_by),
            `query strategy "${strategy.name}" (${strategy.chosen_by})`);
    t.check(!strategy.why || dom.query_strategy.text.includes(strategy.why), 'the strategy card gives the reason in its one line');
    const rows = await page.evaluate(() => [...document.querySelectorAll('#strategy-table tr[data-strategy]')].map(
      (tr) => ({ name: tr.dataset.strategy, modes: Number(tr.children[1].textContent), chosen: tr.className === 'chosen' })));
    const candidates = strategy.candidates || [];
    if (candidates.length > 1) {
      t.check(rows.length === candidates.length && rows.every((r, i) => r.name === candidates[i].strategy && r.modes === candidates[i].modes),
              `the strategies' table beside the chart: ${rows.length} rows as in summary.json`);
      t.check(rows.filter((r) => r.chosen).length === 1, 'one row marked: the lowest error that fits');
    } else {
      t.check(rows.length === 0, 'one strategy or none measured: no table');
    }
  } else {
    t.check(!dom.query_strategy, 'no query strategy in summary.json: none on the page');
  }
  if (loop) {
    t.check(dom.misses && dom.misses.value === loop.misses && dom.misses.text.startsWith(`${loop.misses} of ${loop.frames}`),
            `misses: ${loop.misses} of ${loop.frames}`);
    t.check(dom.assembled && dom.assembled.value === loop.assembled &&
            dom.assembled.text === (loop.assembled === null ? 'not evaluated (no assembled pose)'
                                                            : loop.assembled ? 'ASSEMBLED' : 'NOT assembled'),
            `success: ${loop.assembled} (${loop.verdict})`);
    const fe = loop.final_error;
    t.check(dom.final_error && dom.final_error.text.includes('axial') && dom.final_error.text.includes('lateral') &&
            dom.final_error.text.includes(' N sent') &&
            Math.abs(dom.final_error.value.axial - fe.axial) < 1e-9 && Math.abs(dom.final_error.value.lateral - fe.lateral) < 1e-9,
            `final error: axial ${fe.axial}, lateral ${fe.lateral} (signed, as in summary.json)`);
    if (!summary.method.startsWith('vps')) {
      const changes = loop.modes.changes.length;
      t.check(dom.modes.text.includes('the loop rendered') && dom.modes.text.includes(`${changes} changes`),
              `m': tuned and rendered (${changes} changes)`);
    }
    const stiff = loop.stiffness_at_fit;
    if (stiff) {
      const lowest = Math.min(...Object.values(stiff.force_n_per_mm));
      t.check(dom.stiffness_at_fit && JSON.stringify(dom.stiffness_at_fit.value) === JSON.stringify(stiff) &&
              dom.stiffness_at_fit.text.includes('N/mm') && dom.stiffness_at_fit.text.includes('coupling'),
              `stiffness at the fit as in summary.json (lowest ${lowest} N/mm)`);
    } else {
      t.check(!dom.stiffness_at_fit, 'no stiffness at the fit in summary.json: none on the page');
    }
  } else {
    t.check(dom.misses && dom.misses.value === null && dom.misses.text.includes('no loop'), 'no loop: misses say so');
    t.check(await page.locator('#play').isDisabled(), 'no loop: the play button is disabled');
  }

  // --- the 3D view draws both parts
  const view = page.locator('#view');
  const still = await view.screenshot();
  const drawn = await pixelStats(page, still, { background: [244, 245, 247] });
  t.check(drawn.differs > 0.02 * drawn.total, `3D view: ${drawn.differs} of ${drawn.total} pixels drawn`);
  t.check(drawn.bluish > 300, `3D view: ${drawn.bluish} pixels of part 2's blue`);

  // --- every chart draws its series (in the palette's first two colours; a series may
  // hide another where they coincide)
  const charts = page.locator('.chart');
  const chartCount = await charts.count();
  const tuned = summary.tuning !== null && summary.tuning.key !== '';
  const data = await page.evaluate(() => JSON.parse(document.getElementById('snapfit-data').textContent));
  const timeCharts = data.timeline ? data.timeline.charts.length : 0;
  t.check(!loop || timeCharts >= 5, `${timeCharts} time charts`);
  const strategies = data.strategy_chart ? 1 : 0;  // the strategies' errors against frame time, when measured
  t.check(chartCount === timeCharts + (loop ? 1 : 0) + (tuned ? 1 : 0) + strategies, `${chartCount} charts on the page`);
  if (!tuned) {
    const note = await page.locator('#no-tuning').textContent();
    t.check(summary.method.startsWith('vps') ? note.includes('Voxmap PointShell') : note.includes('--modes'),
            `no sweep ran, and the page says why: "${note}"`);
  }
  for (let i = 0; i < chartCount; i++) {
    const shot = await charts.nth(i).locator('canvas').first().screenshot();
    const first = await pixelStats(page, shot, { color: [31, 119, 180], tolerance: 40 });
    const second = await pixelStats(page, shot, { color: [214, 39, 40], tolerance: 40 });
    const id = await charts.nth(i).getAttribute('id');
    t.check(first.differs > 0.005 * first.total && first.near + second.near > 15,
            `chart ${id}: ${first.differs} pixels drawn, ${first.near + second.near} in the series' colours`);
  }

  // --- the field figures
  const images = await page.evaluate(() => [...document.querySelectorAll('.slices img')].map((i) => i.naturalWidth));
  if (summary.method.startsWith('vps')) t.check(images.length === 0, 'Voxmap PointShell: no field figures');
  else t.check(images.length === 2 && images.every((w) => w > 200), `field figures: ${images.join(', ')} pixels wide`);
  if (summary.method.startsWith('vps'))
    t.check(await page.locator('#value-modes').count() === 0, "Voxmap PointShell: no m' beside the view");

  if (loop) {
    // --- the playback moves the part
    const [t0, t1] = await page.evaluate(() => window.snapfitReport.range);
    t.check(t1 > t0, `playback spans ${t0} .. ${t1} s`);
    await page.evaluate((x) => window.snapfitReport.setTime(x), t0);
    const box0 = await page.evaluate(() => window.snapfitReport.partScreenBox());
    const canvas = await view.boundingBox();
    for (const [name, b] of [['start', box0]])
      t.check(b.left >= 0 && b.top >= 0 && b.right <= canvas.width && b.bottom <= canvas.height,
              `part 2 is wholly in view at the ${name} (${b.left.toFixed(0)}..${b.right.toFixed(0)} x ` +
              `${b.top.toFixed(0)}..${b.bottom.toFixed(0)} in ${canvas.width.toFixed(0)} x ${canvas.height.toFixed(0)})`);
    const first = await view.screenshot();
    await page.evaluate((x) => window.snapfitReport.setTime(x), t1);
    const box1 = await page.evaluate(() => window.snapfitReport.partScreenBox());
    t.check(box1.left >= 0 && box1.top >= 0 && box1.right <= canvas.width && box1.bottom <= canvas.height,
            'part 2 is wholly in view at the end');
    const last = await view.screenshot();
    const moved = Math.hypot((box1.left + box1.right - box0.left - box0.right) / 2, (box1.top + box1.bottom - box0.top - box0.bottom) / 2);
    t.check(moved > 20, `part 2's screen box moved ${moved.toFixed(0)} pixels`);
    const union = { left: Math.min(box0.left, box1.left), top: Math.min(box0.top, box1.top),
                    right: Math.max(box0.right, box1.right), bottom: Math.max(box0.bottom, box1.bottom) };
    const diff = await pixelDifference(page, first, last, union);
    t.check(diff.inside > 500 && diff.inside >= 0.5 * diff.all,
            `screenshots at ${t0} s and ${t1} s differ in ${diff.all} pixels, ${diff.inside} where the part is`);
    const slider = await page.locator('#timeline').inputValue();
    t.check(Math.abs(Number(slider) - t1) < 1e-6, 'the timeline slider follows');
    const heads = await page.evaluate(() => [...document.querySelectorAll('.playhead')].filter((p) => p.style.display !== 'none').length);
    t.check(heads === timeCharts, `${heads} time charts show the playback cursor`);

    // --- play runs the clock
    await page.evaluate((x) => window.snapfitReport.setTime(x), t0);
    await page.locator('#play').click();
    await page.waitForTimeout(800);
    const now = await page.evaluate(() => window.snapfitReport.time());
    await page.locator('#play').click();
    t.check(now > t0, `play advanced the playback to ${now.toFixed(3)} s`);
  }
  t.check(problems.length === 0, `no console errors or exceptions${problems.length ? ': ' + problems.join('; ') : ''}`);
  t.check(requests.length === 0, `no network requests${requests.length ? ': ' + requests.join(', ') : ''}`);
} finally {
  await close();
}
t.finish();
