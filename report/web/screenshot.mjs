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
// Chromium now and then refuses one capture ("Unable to capture screenshot") and takes the
// same picture when asked again a moment later: a transient of the browser, retried twice.
async function screenshotWithRetry(page, out) {
  for (let attempt = 1; ; attempt++) {
    try {
      await page.screenshot({ path: out, fullPage: true });
      return;
    } catch (e) {
      if (attempt >= 3 || !String(e.message).includes('Unable to capture screenshot')) throw e;
      console.error(`screenshot.mjs: ${out}: ${e.message.split('\n')[0]}; retrying`);
      await new Promise((resolve) => setTimeout(resolve, 500 * attempt));
    }
  }
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
    await screenshotWithRetry(page, pairs[i + 1]);
    console.log(`wrote ${pairs[i + 1]}`);
    await page.close();
  }
} finally {
  await close();
}
