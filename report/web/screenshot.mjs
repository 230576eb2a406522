// Screenshots of snapfit pages for docs: node screenshot.mjs [--width W] [--time T] PAGE.html OUT.png ...
// Each page is loaded from disk in headless chromium (browser.mjs) and shot whole once it
// says it is ready; --time moves a report's playback there first. Exits 77 without chromium.
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { chromiumAvailable, launchChromium } from './browser.mjs';

const args = process.argv.slice(2);
let width = 1280, time = null;
const pairs = [];
for (let i = 0; i < args.length; i++) {
  if (args[i] === '--width') width = Number(args[++i]);
  else if (args[i] === '--time') time = Number(args[++i]);
  else pairs.push(args[i]);
}
if (pairs.length === 0 || pairs.length % 2 !== 0 || !(width > 0)) {
  console.error('usage: node screenshot.mjs [--width W] [--time T] PAGE.html OUT.png [PAGE.html OUT.png ...]');
  process.exit(2);
}
if (!chromiumAvailable()) {
  console.error('screenshot.mjs: no chromium (apt-get install chromium)');
  process.exit(77);
}
const { context, close } = await launchChromium();
try {
  for (let i = 0; i < pairs.length; i += 2) {
    const page = await context.newPage();
    await page.setViewportSize({ width, height: 900 });
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(pathToFileURL(path.resolve(pairs[i])).href);
    await page.waitForFunction(() => (window.snapfitReport || window.snapfitPage || {}).ready === true, null,
                               { timeout: 60000 });
    if (time !== null) await page.evaluate((t) => window.snapfitReport && window.snapfitReport.setTime(t), time);
    if (errors.length) throw new Error(`${pairs[i]}: ${errors.join('; ')}`);
    await page.screenshot({ path: pairs[i + 1], fullPage: true });
    console.log(`wrote ${pairs[i + 1]}`);
    await page.close();
  }
} finally {
  await close();
}
