// `snapfit serve`'s page in headless chromium, driven as a person would: the page follows
// the loop's frames, a mouse drag moves the device, Reset brings it back, the peg is
// pushed into the hole along the scene's insertion and the session ends assembled, and a
// recording writes report.html and loop.csv.
//   node check_live_page.mjs SNAPFIT SOURCE_DIR OUT_DIR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import { chromiumAvailable, launchChromium } from '../browser.mjs';
import { Checks, SKIP, pixelStats } from './page_checks.mjs';

const [snapfit, source, out] = process.argv.slice(2);
if (!chromiumAvailable()) {
  console.log('SKIP: no chromium (apt-get install chromium; .ci/setup installs it)');
  process.exit(SKIP);
}
fs.rmSync(out, { recursive: true, force: true });
fs.mkdirSync(out, { recursive: true });
process.env.SNAPFIT_CACHE_DIR = path.join(out, 'cache');
const scenePath = path.join(source, 'scenes/default.json');
const started = execFileSync('bash', [path.join(source, 'tests/serve_session.sh'), snapfit, scenePath,
  path.join(out, 'serve'), '--modes', '2048', '--strategy', 'tricubic', '--loop-wait', 'sleep', '--out', path.join(out, 'recording')],
  { encoding: 'utf8' }).trim().split(/\s+/);
const [port, , pid] = started.map(Number);
const url = `http://127.0.0.1:${port}/`;
const checks = new Checks('live page');
const sleep = (ms) => new Promise((done) => setTimeout(done, ms));

// The scene's insertion as (time, position, quaternion w x y z) keyframes.
function insertion() {
  const scene = JSON.parse(fs.readFileSync(scenePath, 'utf8'));
  return scene.trajectory.keyframes.map((k) => {
    const r = k.rotation || {};
    const axis = r.axis || [0, 0, 1], angle = ((r.angle_deg || 0) * Math.PI) / 180;
    const n = Math.hypot(...axis) || 1, s = Math.sin(angle / 2);
    return { t: k.time_s, p: k.position, q: r.quaternion || [Math.cos(angle / 2), ...axis.map((a) => (s * a) / n)] };
  });
}

function poseAt(keys, t) {
  if (t <= keys[0].t) return keys[0];
  for (let i = 1; i < keys.length; i++) {
    if (t > keys[i].t) continue;
    const f = (t - keys[i - 1].t) / (keys[i].t - keys[i - 1].t);
    const mix = (a, b) => a.map((v, k) => v + f * (b[k] - v));
    const q = mix(keys[i - 1].q, keys[i].q), n = Math.hypot(...q);
    return { p: mix(keys[i - 1].p, keys[i].p), q: q.map((v) => v / n) };
  }
  return keys[keys.length - 1];
}

const browser = await launchChromium();
try {
  const page = await browser.context.newPage();
  await page.setViewportSize({ width: 960, height: 720 });  // less to paint in the software renderer
  const problems = [];
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console error: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`uncaught: ${e.message}`));
  await page.goto(url);
  await page.waitForFunction(() => window.snapfitLive && window.snapfitLive.ready === true, null, { timeout: 60000 });
  const live = (what) => page.evaluate((w) => {
    const s = window.snapfitLive;
    return { updates: s.updates, draws: s.draws, state: s.state, recording: s.lastRecording }[w];
  }, what);

  // The page follows the loop: new frames keep arriving (how many a second is measured,
  // not checked: a timed check would fail on a busy machine with a software renderer).
  const before = await live('updates'), drawsBefore = await live('draws');
  const frameBefore = (await live('state')).frame.frame;
  await sleep(2000);
  const rate = ((await live('updates')) - before) / 2, drawRate = ((await live('draws')) - drawsBefore) / 2;
  const frameAfter = (await live('state')).frame.frame;
  console.log(`measured: the page took ${rate} of the loop's frames a second and drew ${drawRate}`);
  checks.check(rate > 0 && frameAfter > frameBefore + 1000,
    `the page follows the loop (frame ${frameBefore} -> ${frameAfter} in 2 s)`);

  // A drag moves the device in the view plane; Reset brings it back.
  const start = (await live('state')).frame.device.position;
  const box = await page.locator('#view canvas').boundingBox();
  const cx = box.x + box.width / 2, cy = box.y + box.height / 2;
  await page.mouse.move(cx, cy);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(cx + 12 * i, cy);
  await page.mouse.up();
  await sleep(400);
  const dragged = (await live('state')).frame.device.position;
  const moved = Math.hypot(...dragged.map((v, i) => v - start[i]));
  checks.check(moved > 1, `a 120-pixel drag moved the device ${moved.toFixed(2)} mm`);
  await page.click('#reset');
  await sleep(400);
  const back = (await live('state')).frame.device.position;
  checks.check(Math.hypot(...back.map((v, i) => v - start[i])) < 1e-9, 'Reset put the device back at the start');

  // The insertion, a pose a display frame through the page's device, while recording.
  await page.click('#record');
  const keys = insertion();
  const t0 = Date.now();
  for (let t = 0; t <= keys[keys.length - 1].t; t = (Date.now() - t0) / 1000) {
    const { p, q } = poseAt(keys, t);
    await page.evaluate(([p, q]) => window.snapfitLive.setDevicePose(p, q), [p, q]);
    await sleep(16);
  }
  const last = keys[keys.length - 1];
  await page.evaluate(([p, q]) => window.snapfitLive.setDevicePose(p, q), [last.p, last.q]);
  await sleep(1500);
  const end = await live('state');
  checks.check(end.status.assembled === true,
    `the session is assembled after the insertion (${end.status.position_error.toFixed(3)} mm, ` +
    `${end.status.angle_error_deg.toFixed(3)} deg)`);
  checks.check(end.frame.late === false && end.frame.fade === 1, "the mouse's pose holds: not late, no fade");
  await page.screenshot({ path: path.join(out, 'live_session.png') });
  const shot = await pixelStats(page, fs.readFileSync(path.join(out, 'live_session.png')), { background: [255, 255, 255] });
  checks.check(shot.bluish > 500, `part 2 is drawn (${shot.bluish} bluish pixels)`);

  await page.click('#record');
  await page.waitForFunction(() => window.snapfitLive.lastRecording && window.snapfitLive.lastRecording.folder, null,
                             { timeout: 60000 });
  const recording = await live('recording');
  for (const file of ['summary.json', 'loop.csv', 'report.html'])
    checks.check(recording.files.includes(file) && fs.existsSync(path.join(recording.folder, file)),
      `the recording wrote ${file} in ${recording.folder}`);
  const summary = JSON.parse(fs.readFileSync(path.join(recording.folder, 'summary.json'), 'utf8'));
  checks.check(summary.haptic_loop && summary.haptic_loop.frames > 3000,
    `the recording holds the insertion's frames (${summary.haptic_loop && summary.haptic_loop.frames})`);
  checks.check(problems.length === 0, `no console errors or exceptions${problems.length ? ': ' + problems.join('; ') : ''}`);

  await fetch(`${url}quit`, { method: 'POST', body: '{}' });
  for (let i = 0; i < 100; i++) {
    try { process.kill(pid, 0); } catch { break; }
    await sleep(100);
  }
  const log = fs.readFileSync(path.join(out, 'serve.log'), 'utf8');
  checks.check(/: ASSEMBLED/.test(log), 'snapfit serve ended saying ASSEMBLED');
} finally {
  await browser.close();
  try { process.kill(pid); } catch { /* already ended */ }
}
checks.finish();
