// Shared by the browser tests: open a page from disk in headless chromium, record what
// would make it broken (console errors, uncaught exceptions, any network request), and
// look at screenshots pixel by pixel inside the page itself (no PNG decoder needed here).
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { chromiumAvailable, launchChromium } from '../browser.mjs';

export const SKIP = 77;  // CTest SKIP_RETURN_CODE

export class Checks {
  constructor(name) {
    this.name = name;
    this.failures = [];
    this.passed = 0;
  }
  check(ok, what) {
    if (ok) this.passed++;
    else this.failures.push(what);
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  }
  finish() {
    console.log(`${this.name}: ${this.passed} checks passed, ${this.failures.length} failed`);
    process.exit(this.failures.length ? 1 : 0);
  }
}

// Resolves to {page, problems, requests, close}, with the page loaded and `readyFlag`
// (a window property with ready === true) set.
export async function openPage(file, readyFlag) {
  if (!chromiumAvailable()) {
    console.log('SKIP: no chromium (apt-get install chromium; .ci/setup installs it)');
    process.exit(SKIP);
  }
  const browser = await launchChromium();
  const page = await browser.context.newPage();
  const problems = [], requests = [];
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console error: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`uncaught: ${e.message}`));
  const url = pathToFileURL(path.resolve(file)).href;
  page.on('request', (r) => {
    const u = r.url();
    if (u !== url && !u.startsWith('data:') && !u.startsWith('blob:')) requests.push(u);
  });
  await page.goto(url);
  await page.waitForFunction((flag) => window[flag] && window[flag].ready === true, readyFlag, { timeout: 60000 });
  return { page, problems, requests, close: () => browser.close() };
}

// Pixel statistics of a PNG screenshot (a Buffer), computed in the page:
//   differs: pixels farther than `tolerance` (max channel difference) from `background`
//   near: pixels within `tolerance` of `color`, when given
//   bluish: pixels clearly blue (part 2's colour family: b > r + 40 and b > g + 10)
export async function pixelStats(page, png, { background = [255, 255, 255], color = null, tolerance = 30 } = {}) {
  return page.evaluate(async ({ b64, background, color, tolerance }) => {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
    const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
    const ctx = canvas.getContext('2d');
    ctx.drawImage(bitmap, 0, 0);
    const d = ctx.getImageData(0, 0, bitmap.width, bitmap.height).data;
    let differs = 0, near = 0, bluish = 0;
    const far = (i, c) => Math.max(Math.abs(d[i] - c[0]), Math.abs(d[i + 1] - c[1]), Math.abs(d[i + 2] - c[2])) > tolerance;
    for (let i = 0; i < d.length; i += 4) {
      if (far(i, background)) differs++;
      if (color && !far(i, color)) near++;
      if (d[i + 2] > d[i] + 40 && d[i + 2] > d[i + 1] + 10) bluish++;
    }
    return { width: bitmap.width, height: bitmap.height, total: bitmap.width * bitmap.height, differs, near, bluish };
  }, { b64: png.toString('base64'), background, color, tolerance });
}

// Pixels that differ (max channel difference above `tolerance`) between two screenshots
// of the same size, in all and inside `box` ({left, top, right, bottom}, CSS pixels).
export async function pixelDifference(page, a, b, box, tolerance = 40) {
  return page.evaluate(async ({ a64, b64, box, tolerance }) => {
    const read = async (s) => {
      const bytes = Uint8Array.from(atob(s), (c) => c.charCodeAt(0));
      const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
      const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
      const ctx = canvas.getContext('2d');
      ctx.drawImage(bitmap, 0, 0);
      return { w: bitmap.width, h: bitmap.height, d: ctx.getImageData(0, 0, bitmap.width, bitmap.height).data };
    };
    const A = await read(a64), B = await read(b64);
    if (A.w !== B.w || A.h !== B.h) return { error: 'sizes differ' };
    let all = 0, inside = 0;
    for (let y = 0; y < A.h; y++)
      for (let x = 0; x < A.w; x++) {
        const i = 4 * (y * A.w + x);
        const diff = Math.max(Math.abs(A.d[i] - B.d[i]), Math.abs(A.d[i + 1] - B.d[i + 1]), Math.abs(A.d[i + 2] - B.d[i + 2]));
        if (diff <= tolerance) continue;
        all++;
        if (x >= box.left && x <= box.right && y >= box.top && y <= box.bottom) inside++;
      }
    return { all, inside };
  }, { a64: a.toString('base64'), b64: b.toString('base64'), box, tolerance });
}
