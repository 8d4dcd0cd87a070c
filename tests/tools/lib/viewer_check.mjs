// viewer_check.mjs: drives a vri experiment page (results/<experiment>/index.html, built by vri-viewer.js)
// in Debian's Chromium, headless, through playwright-core, the way a user would, and reports what it saw.
//
//   node tests/tools/lib/viewer_check.mjs <path/to/experiment/index.html> <idA> <idB> <x> <y> <outdir>
//
// It opens the page from the file system (a file:// URL, no server, and without
// --allow-file-access-from-files, because the page must work without it), waits for body[data-ready="1"], picks A
// and B with the #pick-a and #pick-b selects, zooms so that image pixel (x, y) covers a 16x16 block of the
// canvas centred on canvasPointOf(x, y), hovers it, and reads the probe's data-values. Then it screenshots
// #view in each mode into <outdir>/<mode>.png. When the page's "index" link target exists, it opens it, checks
// that it lists at least one experiment and links to this page, and screenshots it into <outdir>/index.png.
//
// Output: one JSON object on stdout:
//   {"a": [...], "b": [...], "error": [...], "errorMax": v, "channels": {"a": [...], "b": [...], "error": [...]},
//    "points": {"<mode>": {"x": cx, "y": cy}}, "screenshots": {"<mode>": "<outdir>/<mode>.png"},
//    "index": "<outdir>/index.png" or null, "consoleErrors": []}
// The values are the float32 values as the page decoded them (JSON numbers; NaN and infinities as the
// strings "NaN", "Infinity", "-Infinity"); [] when an image has no float data. points are where pixel
// (x, y)'s centre lies in each mode's screenshot (the left panel in side-by-side). Exit 0. On any failure
// (a console error or uncaught exception on a page included), exit 1 with one line on stderr naming what failed.
//
// Environment: VRI_CHROMIUM (default /usr/bin/chromium), VRI_VIEWER_TIMEOUT_MS (default 60000 per step),
// VRI_WEB_DEBUG=1 echoes the pages' console on stderr.
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL, fileURLToPath } from 'node:url';
// playwright-core lives with the web peers' packages; a relative import needs no NODE_PATH or install step.
import { chromium } from '../../../tools/peers/web/node_modules/playwright-core/index.mjs';

const CHROMIUM = process.env.VRI_CHROMIUM || '/usr/bin/chromium';
const TIMEOUT = Number(process.env.VRI_VIEWER_TIMEOUT_MS) || 60000;
const MODES = ['a', 'b', 'side-by-side', 'swipe', 'flip', 'error'];
const ZOOM = 16;
const ARGS = ['--headless=new', '--no-first-run', '--disable-gpu', '--hide-scrollbars', '--font-render-hinting=none'];

class Failure extends Error {}

function fail(what) {
  throw new Failure(what);
}

function usage() {
  process.stderr.write('viewer_check.mjs: usage: node viewer_check.mjs <experiment/index.html> <idA> <idB> <x> <y> <outdir>\n');
  process.exit(1);
}

// Waits for `promise`, failing as soon as the page reports an error (no need to sit out a timeout then).
function guarded(promise, errors, what) {
  return Promise.race([
    promise.catch((e) => fail(`${what}: ${oneLine(e.message)}`)),
    errors.signal.then((message) => fail(`${what}: page error: ${message}`)),
  ]);
}

function oneLine(text) {
  return String(text).split('\n').filter((l) => l.trim() && !/^\s*(=+|Call log:|- )/.test(l))[0] || String(text);
}

// Console errors and uncaught exceptions of a page, with a promise that settles on the first one.
function watchErrors(page) {
  const errors = { list: [] };
  let signal;
  errors.signal = new Promise((resolve) => (signal = resolve));
  const add = (text) => {
    errors.list.push(text);
    signal(text);
  };
  page.on('pageerror', (e) => add(`uncaught ${e.message}`));
  page.on('console', (m) => {
    if (m.type() === 'error') add(`console error: ${m.text()}${m.location()?.url ? ` (${m.location().url})` : ''}`);
    if (process.env.VRI_WEB_DEBUG) process.stderr.write(`page ${m.type()}: ${m.text()}\n`);
  });
  page.on('dialog', (d) => {
    add(`unexpected ${d.type()} dialog: ${d.message()}`);
    d.dismiss().catch(() => {});
  });
  return errors;
}

async function settled(page, errors, what) {
  await guarded(page.waitForSelector('#view[data-busy="0"]', { state: 'attached', timeout: TIMEOUT }), errors, what);
}

async function checkExperiment(page, errors, pagePath, idA, idB, x, y, outdir) {
  const url = pathToFileURL(pagePath).href;
  await guarded(page.goto(url, { waitUntil: 'load', timeout: TIMEOUT }), errors, `opening ${pagePath}`);
  await guarded(page.waitForSelector('body[data-ready]', { state: 'attached', timeout: TIMEOUT }), errors, 'waiting for the page to be ready');
  const ready = await page.evaluate(() => document.body.dataset.ready);
  if (ready !== '1') fail(`the page did not get ready (data-ready="${ready}")`);
  // The sentence a page shows when its script never runs is gone once it has.
  if (await page.$('#vri-fallback')) fail('the page still shows its no-script sentence (#vri-fallback)');
  if (!(await page.$('#view'))) fail('the page has no #view (no images?)');

  // Pick as a user would, through the selects.
  for (const [select, id] of [['#pick-a', idA], ['#pick-b', idB]]) {
    const known = await page.$eval(select, (s, v) => [...s.options].some((o) => o.value === v), id);
    if (!known) fail(`${select} has no image ${JSON.stringify(id)}`);
    await guarded(page.selectOption(select, { value: id }, { timeout: TIMEOUT }), errors, `choosing ${id} in ${select}`);
    await settled(page, errors, `loading ${id}`);
  }
  const picked = await page.evaluate(() => window.vriViewer.state());
  if (picked.a !== idA || picked.b !== idB) fail(`picked ${JSON.stringify([picked.a, picked.b])}, wanted ${JSON.stringify([idA, idB])}`);

  // Zoom to the pixel, bring the canvas into view, hover the pixel's centre.
  await page.locator('#view').scrollIntoViewIfNeeded();
  await guarded(page.evaluate(([px, py, z]) => window.vriViewer.zoomTo(px, py, z), [x, y, ZOOM]), errors, 'zooming');
  const point = await page.evaluate(([px, py]) => window.vriViewer.canvasPointOf(px, py), [x, y]);
  const box = await page.locator('#view').boundingBox();
  if (point.x < box.x || point.y < box.y || point.x >= box.x + box.width || point.y >= box.y + box.height) {
    fail(`pixel (${x}, ${y}) is not on the canvas after zooming (${JSON.stringify(point)})`);
  }
  await page.mouse.move(point.x, point.y);
  await guarded(page.waitForFunction(([px, py]) => {
    const p = document.getElementById('probe-a');
    return p && p.dataset.x === String(px) && p.dataset.y === String(py);
  }, [x, y], { timeout: TIMEOUT }), errors, `probing pixel (${x}, ${y})`);
  const probe = await page.evaluate(() => {
    const read = (id) => {
      const n = document.getElementById(id);
      return { values: JSON.parse(n.dataset.values || '[]'), channels: JSON.parse(n.dataset.channels || '[]'), text: n.textContent, max: n.dataset.max };
    };
    return { a: read('probe-a'), b: read('probe-b'), err: read('probe-err') };
  });

  // Each mode, through the #mode select; screenshot the canvas.
  fs.mkdirSync(outdir, { recursive: true });
  const screenshots = {};
  const points = {};
  for (const mode of MODES) {
    await guarded(page.selectOption('#mode', mode, { timeout: TIMEOUT }), errors, `choosing mode ${mode}`);
    await settled(page, errors, `drawing mode ${mode}`);
    const shown = await page.$eval('#view', (c) => c.dataset.mode);
    if (shown !== mode) fail(`#view shows mode ${shown} after choosing ${mode}`);
    const p = await page.evaluate(([px, py]) => window.vriViewer.canvasPointOf(px, py), [x, y]);
    points[mode] = { x: p.canvasX, y: p.canvasY };
    const file = path.join(outdir, `${mode}.png`);
    await guarded(page.locator('#view').screenshot({ path: file, timeout: TIMEOUT }), errors, `screenshot of mode ${mode}`);
    screenshots[mode] = file;
  }
  const indexRef = await page.evaluate(() => {
    try {
      return JSON.parse(document.getElementById('vri-experiment').textContent).index || null;
    } catch {
      return null;
    }
  });
  return { probe, screenshots, points, indexRef, url };
}

async function checkIndex(page, errors, indexPath, pagePath, outdir) {
  await guarded(page.goto(pathToFileURL(indexPath).href, { waitUntil: 'load', timeout: TIMEOUT }), errors, `opening ${indexPath}`);
  await guarded(page.waitForSelector('body[data-ready="1"]', { state: 'attached', timeout: TIMEOUT }), errors, 'waiting for the index page');
  const links = await page.$$eval('#experiments tbody tr', (rows) => rows.map((r) => [...r.querySelectorAll('a[href]')].map((a) => a.href)));
  if (!links.length) fail(`${indexPath} lists no experiment`);
  const target = path.resolve(pagePath);
  const hrefs = links.flat().filter((h) => h.startsWith('file:'));
  const found = hrefs.find((h) => {
    try {
      return path.resolve(fileURLToPath(h.split('#')[0])) === target;
    } catch {
      return false;
    }
  });
  if (!found) fail(`${indexPath} has no link to ${target}`);
  if (!fs.existsSync(fileURLToPath(found))) fail(`the index's link ${found} does not resolve to a file`);
  const file = path.join(outdir, 'index.png');
  await guarded(page.screenshot({ path: file, fullPage: true, timeout: TIMEOUT }), errors, 'screenshot of the index page');
  return file;
}

async function main() {
  const [pagePath, idA, idB, xs, ys, outdir] = process.argv.slice(2);
  if (process.argv.length !== 8) usage();
  const x = Number(xs);
  const y = Number(ys);
  if (!Number.isInteger(x) || !Number.isInteger(y) || x < 0 || y < 0) fail(`pixel (${xs}, ${ys}) is not two whole numbers >= 0`);
  if (!fs.existsSync(pagePath)) fail(`${pagePath}: no such file`);
  if (!fs.existsSync(CHROMIUM)) fail(`${CHROMIUM} not found (apt-get install chromium)`);

  // Chromium's sandbox refuses to start as root; the pages load only local files.
  const args = process.getuid?.() === 0 ? [...ARGS, '--no-sandbox'] : ARGS;
  let browser;
  try {
    browser = await chromium.launch({ executablePath: CHROMIUM, args, headless: true, timeout: TIMEOUT });
  } catch (e) {
    fail(`starting ${CHROMIUM}: ${oneLine(e.message)}`);
  }
  try {
    const context = await browser.newContext({ viewport: { width: 1280, height: 900 }, deviceScaleFactor: 1 });
    const page = await context.newPage();
    const errors = watchErrors(page);
    const result = await checkExperiment(page, errors, pagePath, idA, idB, x, y, outdir);
    let index = null;
    if (result.indexRef) {
      const indexURL = new URL(result.indexRef, result.url);
      const indexPath = indexURL.protocol === 'file:' ? fileURLToPath(indexURL) : null;
      if (indexPath && fs.existsSync(indexPath)) index = await checkIndex(page, errors, indexPath, pagePath, outdir);
    }
    if (errors.list.length) fail(`page errors: ${errors.list.join(' | ')}`);
    const { probe } = result;
    const output = {
      a: probe.a.values, b: probe.b.values, error: probe.err.values,
      errorMax: probe.err.max === undefined || probe.err.max === '' ? null : JSON.parse(probe.err.max),
      channels: { a: probe.a.channels, b: probe.b.channels, error: probe.err.channels },
      points: result.points, screenshots: result.screenshots, index, consoleErrors: errors.list,
    };
    process.stdout.write(JSON.stringify(output) + '\n');
  } finally {
    await browser.close().catch(() => {});
  }
}

main().then(() => process.exit(0), (e) => {
  const message = e instanceof Failure ? e.message : `unexpected: ${e && e.stack ? e.stack.split('\n')[0] : e}`;
  process.stderr.write(`viewer_check.mjs: ${oneLine(message)}\n`);
  process.exit(1);
});
