// What every web adapter does around its library: read the arguments and the card, serve the page, drive
// Chromium, time the frames, read the pixels back and write the image and the stats. An adapter supplies
// only prepare() (the card mapped to its library, in Node) and a page module (the library, in the browser:
// setup(scene), timeFrames(n), readPixels()).
// Usage: NAME.mjs CARD.json OUTPUT.f32|OUTPUT.png STATS.json [--step H] [--frames N] [FLAGS]
import fs from 'node:fs';
import path from 'node:path';
import { openPage } from './browser.mjs';
import { CardError, loadCard, loadVoxels, requestedStep } from './card.mjs';
import { writeImage, writeJson } from './output.mjs';
import { startServer } from './server.mjs';

const WEB_DIR = path.resolve(path.dirname(new URL(import.meta.url).pathname), '..');

class UsageError extends Error {}

// flags: the adapter's own diagnostic switches (--NAME, no value), passed to its prepare().
function parseArgs(argv, flags) {
  const positional = [];
  const options = { frames: 3, flags: {} };
  for (let i = 0; i < argv.length; i++) {
    const word = argv[i];
    if (word === '--step' || word === '--frames') {
      const value = Number(argv[++i]);
      if (!(Number.isFinite(value) && value > 0)) throw new UsageError(`${word} needs a positive number, not '${argv[i] ?? ''}'`);
      if (word === '--frames' && !Number.isInteger(value)) throw new UsageError('--frames needs a whole number');
      options[word.slice(2)] = value;
    } else if (flags.includes(word)) {
      options.flags[word.slice(2)] = true;
    } else if (word.startsWith('--') && word.length > 2) {
      throw new UsageError(`unknown option '${word}'`);
    } else {
      positional.push(word);
    }
  }
  if (positional.length !== 3) throw new UsageError('usage: CARD.json OUTPUT.f32|OUTPUT.png STATS.json [--step H] [--frames N]');
  const [card, output, stats] = positional;
  if (!/\.(f32|png)$/.test(output)) throw new UsageError(`${output}: the output must end in .f32 or .png`);
  return { card, output, stats, ...options };
}

export function packageVersion(name) {
  return JSON.parse(fs.readFileSync(path.join(WEB_DIR, 'node_modules', name, 'package.json'), 'utf8')).version;
}

// Pixels from the page (base64 of float32 or uint8 RGBA, rows bottom to top as WebGL reads them) as
// float32 RGBA with row 0 at the top.
function decodePixels(pixels, width, height) {
  const bytes = Buffer.from(pixels.base64, 'base64');
  const src = pixels.format === 'float32'
    ? new Float32Array(bytes.buffer, bytes.byteOffset, bytes.length / 4)
    : Float32Array.from(bytes, (b) => b / 255);
  if (src.length !== width * height * 4) throw new Error(`the page read ${src.length / 4} pixels, not ${width} x ${height}`);
  const rgba = new Float32Array(src.length);
  const row = width * 4;
  for (let y = 0; y < height; y++) rgba.set(src.subarray((height - 1 - y) * row, (height - y) * row), y * row);
  return rgba;
}

// adapter: { name, renderer: { name, version }, pageModule: '/page/NAME.js', flags: ['--NAME', ...],
// prepare(card, voxels, step, flags) -> { scene (JSON for the page), data ({ '/data/NAME': Buffer }), settings,
// notes } }.
export async function runAdapter(adapter, argv = process.argv.slice(2)) {
  let session = null;
  let server = null;
  try {
    const args = parseArgs(argv, adapter.flags ?? []);
    const card = loadCard(args.card);
    const voxels = loadVoxels(card, args.card);
    const { width, height } = card.camera;
    const prepared = adapter.prepare(card, voxels, requestedStep(card, args.step), args.flags);
    server = await startServer(prepared.data);
    session = await openPage(server.origin, width, height);
    const { page, pageErrors } = session;
    const fromPage = async (what, fn, arg) => {
      try {
        return await page.evaluate(fn, arg);
      } catch (e) {
        const detail = pageErrors.length ? pageErrors.join('; ') : e.message.split('\n')[0];
        throw new Error(`${what}: ${detail}`);
      }
    };
    const pageInfo = await fromPage('setting up the scene', async ({ module, scene }) => {
      window.vriAdapter = await import(module);
      return window.vriAdapter.setup(scene);
    }, { module: adapter.pageModule, scene: prepared.scene });
    const times = await fromPage('rendering', (frames) => window.vriAdapter.timeFrames(frames), args.frames);
    const pixels = await fromPage('reading the pixels back', () => window.vriAdapter.readPixels());
    const image = { width, height, rgba: decodePixels(pixels, width, height), quantisation: pixels.format === 'float32' ? 'float32' : '8-bit' };
    const notes = [...prepared.notes, ...(pageInfo.notes ?? [])];
    const quantisation = writeImage(args.output, image);
    if (args.output.endsWith('.png')) notes.push('the PNG holds premultiplied alpha (the card\'s output), not PNG\'s usual straight alpha');
    const stats = {
      format: 'vri-outside-stats',
      version: 1,
      renderer: adapter.renderer,
      timing: {
        what: 'frame',
        meaning: 'wall-clock seconds of one frame in the page (render, then a one-pixel readPixels to wait for it), after one warm-up frame; WebGL on SwiftShader (CPU)',
        wall_seconds: times,
      },
      image: { quantisation, read_back: pixels.format === 'float32' ? 'float32 render target' : '8-bit RGBA framebuffer' },
      settings: { ...prepared.settings, ...(pageInfo.settings ?? {}), webgl_renderer: pageInfo.webglRenderer },
      notes,
    };
    try {
      writeJson(args.stats, stats);
    } catch (e) {
      fs.rmSync(args.output, { force: true }); // nothing written on failure: the image goes with its stats
      throw e;
    }
    return 0;
  } catch (e) {
    const known = e instanceof CardError || e instanceof UsageError;
    process.stderr.write(`${adapter.name}: error: ${known ? e.message : e.message.split('\n')[0]}\n`);
    return e instanceof UsageError ? 64 : 1;
  } finally {
    if (session) await session.browser.close();
    if (server) await server.close();
  }
}
