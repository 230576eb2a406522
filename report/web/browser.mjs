// Debian's chromium, headless, driven by playwright-core (which downloads no browser):
// the flags a root user on a machine without network needs. SNAPFIT_CHROMIUM overrides
// the executable (default /usr/bin/chromium).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

export const CHROMIUM = process.env.SNAPFIT_CHROMIUM || '/usr/bin/chromium';

export function chromiumAvailable() { return fs.existsSync(CHROMIUM); }

// Resolves to {browser, close()}; close() also removes the fresh profile folder.
export async function launchChromium() {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'snapfit-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: { width: 1280, height: 900 },
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', '--enable-unsafe-swiftshader'],
  });
  return {
    context,
    async close() {
      await context.close();
      fs.rmSync(profile, { recursive: true, force: true });
    },
  };
}
