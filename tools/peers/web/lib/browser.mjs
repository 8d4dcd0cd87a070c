// Debian's Chromium, headless, driven by playwright-core. WebGL2 runs on SwiftShader (ANGLE's CPU
// Vulkan device): there is no GPU here, and SwiftShader gives the same pixels on every machine.
import fs from 'node:fs';
import { chromium } from 'playwright-core';

export const CHROMIUM = process.env.VRI_CHROMIUM || '/usr/bin/chromium';

const ARGS = [
  '--headless=new',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader', // WebGL on SwiftShader is otherwise refused in recent Chromium
  '--ignore-gpu-blocklist',
  '--disable-gpu-watchdog', // a slow software frame is not a hung GPU
  '--no-first-run',
];

// A page of exactly width x height CSS pixels at device pixel ratio 1, so that the canvas has one pixel
// per image pixel. pageErrors collects what the page throws or logs as an error, for the error message;
// VRI_WEB_DEBUG=1 also echoes the page's console on standard error.
export async function openPage(origin, width, height) {
  if (!fs.existsSync(CHROMIUM)) throw new Error(`${CHROMIUM} not found (apt-get install chromium)`);
  // Chromium's sandbox refuses to start as root; the page loads only our own local files.
  const args = process.getuid?.() === 0 ? [...ARGS, '--no-sandbox'] : ARGS;
  const browser = await chromium.launch({ executablePath: CHROMIUM, args, headless: true });
  try {
    const context = await browser.newContext({ viewport: { width, height }, deviceScaleFactor: 1 });
    const page = await context.newPage();
    const pageErrors = [];
    page.on('pageerror', (e) => pageErrors.push(e.message));
    page.on('console', (m) => {
      if (m.type() === 'error') pageErrors.push(m.text());
      if (process.env.VRI_WEB_DEBUG) process.stderr.write(`page ${m.type()}: ${m.text()}\n`);
    });
    await page.goto(origin + '/');
    return { browser, page, pageErrors };
  } catch (e) {
    await browser.close();
    throw e;
  }
}
