/*
 * vri-viewer.js: the browser side of vri's static result pages.
 *
 * vri-run --gallery (C++) writes results/index.html, holding <script id="vri-index" type="application/json">,
 * and results/<experiment>/index.html, holding <script id="vri-experiment" type="application/json">; both
 * load this classic script and vri-viewer.css from results/viewer/. The pages must work when opened by double
 * click (file:// URLs, no server, nothing from the network), and that decides most of what follows:
 *  - a classic script and no ES modules, because Chromium refuses module scripts on file://;
 *  - no fetch or XHR of local files (also refused on file://). A render's float pixels come in a "sidecar"
 *    script, viewer-data/<id>.js, that calls the global vriViewerFloats(record). We load one on demand by
 *    appending a <script src> (only for images whose "floats" is not null, because a failed load logs a
 *    console error);
 *  - a PNG drawn from file:// taints a canvas, so pixel values are never read back from PNGs. The probe and
 *    the error view use only the sidecars' float32 data;
 *  - every string from the data reaches the DOM through textContent, setAttribute or DOM construction, never
 *    innerHTML. Every relative file name is encoded one path segment at a time, because names may contain
 *    '#', '?', '%' or spaces.
 *
 * Hooks for tests (tests/tools/lib/viewer_check.mjs drives them in headless Chromium):
 *  - body[data-ready="1"] once the page is built and its first picture drawn;
 *  - #view[data-busy] is "1" while pictures or float data load, and "0" after the draw that follows;
 *    #view[data-drawn] counts draws; #view[data-mode] holds the mode;
 *  - #probe-a, #probe-b and #probe-err carry data-x, data-y and data-values (a JSON array of the float32
 *    values as decoded; a non-finite value is written as the string "NaN", "Infinity" or "-Infinity") and
 *    data-channels (their names); #probe-err has |A - B| per shared channel, counted as vri counts errors
 *    (a NaN against a number is infinite, equal NaNs 0), and data-max, their maximum. They always hold the
 *    last pixel probed inside the image; #probe[data-where] says whether the pointer is on it ("in"), on the
 *    canvas outside the image ("outside"), gone from the canvas ("left"), or no pixel was probed ("none");
 *  - #zoom-level shows the zoom (CSS pixels per image pixel: "zoom 16x", with a multiplication sign);
 *  - window.vriViewer = {ready, pick(aId, bId), setMode(mode), zoomTo(x, y, pixelsPerImagePixel),
 *    canvasPointOf(x, y), whenIdle(), fit(), state()}; the first four return promises that settle once the
 *    loads they start are done and drawn (pick and setMode reject, never throw, on an unknown id or mode).
 *    canvasPointOf gives viewport CSS pixels (x, y, as mouse events take them), page pixels (pageX, pageY)
 *    and pixels within #view (canvasX, canvasY).
 *
 * Display of float images: c = rgb + (1 - a) * background (linear, premultiplied, as vri's PNG previews),
 * then clamp01(c * 2^exposure) through the sRGB curve (the default) or 1/gamma, rounded to a byte; NaN
 * shows as 0. With the defaults (sRGB, exposure 0, a black background) this reproduces the PNG previews of
 * scenes without png: settings (inverted or exposed previews differ) byte for byte. The error view uses
 * heat_map.cpp's viridis, scale and error rule, so it reproduces vri-diff's heat maps.
 * Keys: 1 A, 2 B, s side by side, w swipe, f flip, e error, 0 fit.
 */
(function () {
  'use strict';

  // ---------------------------------------------------------------- constants

  const MODES = [
    ['a', 'A'],
    ['b', 'B'],
    ['side-by-side', 'side by side'],
    ['swipe', 'swipe'],
    ['flip', 'flip A/B'],
    ['error', 'error |A \u2212 B|'],
  ];
  const DEFAULT_GAMMA = 2.2;
  const MAX_SCALE = 64; // screen pixels per image pixel at the closest zoom
  const MIN_SCALE = 1 / 64;
  const PANEL_GAP = 4; // CSS pixels between the two side-by-side panels
  const FLOAT_CACHE_SIZE = 12; // decoded float images kept (about 8 MB each at 800x600 RGBA)
  const TONE_CACHE_SIZE = 8; // tone-mapped canvases kept
  const LONG_TEXT = 400; // characters: a longer description or agreement starts collapsed to its opening
  const OUTLINE_SCALE = 8; // CSS pixels per image pixel from which the probed pixel is outlined
  // The checker background, in linear units (composited before the transfer curve, like the PNG previews).
  const CHECKER = [0.2, 0.45];
  const CHECKER_CELL = 8; // image pixels
  const CLIPPED_RGB = [255, 0, 255]; // error view: above the top of the scale (as vri's PNG heat maps)
  // Viridis in sRGB at 9 evenly spaced stops plus the last colour, interpolated linearly: the same table as
  // libvri/core/heat_map.cpp, so that the error view matches the PNG heat maps that vri-diff writes.
  const VIRIDIS = [
    [0.267, 0.005, 0.329], [0.283, 0.141, 0.458], [0.254, 0.265, 0.530], [0.207, 0.372, 0.553],
    [0.164, 0.471, 0.558], [0.128, 0.567, 0.551], [0.135, 0.659, 0.518], [0.267, 0.749, 0.441],
    [0.478, 0.821, 0.318], [0.993, 0.906, 0.144],
  ];
  const LITTLE_ENDIAN = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

  // ---------------------------------------------------------------- small helpers

  // A string from the data, whatever JSON type arrived (null and undefined become '').
  function str(v) {
    return typeof v === 'string' ? v : v == null ? '' : String(v);
  }

  function posInt(v) {
    return Number.isInteger(v) && v > 0 ? v : 0;
  }

  function clamp(v, lo, hi) {
    return v < lo ? lo : v > hi ? hi : v;
  }

  // Builds an element. attrs: 'text' sets textContent, 'class' the class, anything else goes through
  // setAttribute; children are nodes or strings (append() makes Text nodes of strings, never markup).
  function el(tag, attrs, children) {
    const node = document.createElement(tag);
    if (attrs) {
      for (const key of Object.keys(attrs)) {
        const v = attrs[key];
        if (v === undefined || v === null || v === false) continue;
        if (key === 'text') node.textContent = str(v);
        else if (key === 'class') node.className = str(v);
        else node.setAttribute(key, v === true ? '' : str(v));
      }
    }
    if (children) for (const c of children) if (c !== null && c !== undefined) node.append(c);
    return node;
  }

  // A relative file name from the data as a URL: each segment percent-encoded, so that '#', '?', '%' and
  // ':' stay parts of the name (this also makes "javascript:..." a harmless relative name).
  function urlOf(path) {
    return str(path).split('/').map(encodeURIComponent).join('/');
  }

  // A paper or item name from the data; "none" (our own studies write paper: none) is no name.
  function named(v) {
    v = str(v).trim();
    return v.toLowerCase() === 'none' ? '' : v;
  }

  // "Paper B, Table IV"; a study without a paper is "own study", with its item if it has one.
  function paperItem(paper, item) {
    paper = named(paper);
    item = named(item);
    if (paper && item) return 'Paper ' + paper + ', ' + item;
    if (paper) return 'Paper ' + paper;
    return item ? 'own study: ' + item : 'own study';
  }

  // Where a text's opening sentences end: the first sentence end at 60 characters or more, else the last
  // one before 300 ("Differs." alone when the next sentence is long); -1 when no sentence ends by then. A
  // sentence ends at '.', '!' or '?' (and closing brackets or quotes) followed by space and a capital, not
  // after an abbreviation such as "Fig." or "vs.", nor inside `code`.
  function openingEnd(text) {
    const re = /[.!?][)\]"']*\s+(?=[A-Z(\[`*"])/g;
    let m;
    let last = -1;
    while ((m = re.exec(text)) !== null) {
      const end = m.index + m[0].trimEnd().length;
      if (end > 300) return last;
      const word = /(\S+)$/.exec(text.slice(0, m.index));
      if (word && /^(?:Fig|Figs|Sec|Secs|Eq|Eqs|Tab|No|Ref|Refs|vs|cf|al|etc|approx|e\.g|i\.e|[A-Z])$/i.test(word[1].replace(/^[(\[]+/, ''))) continue;
      if ((text.slice(0, end).match(/`/g) || []).length % 2) continue;
      if (end >= 60) return end;
      last = end;
    }
    return last;
  }

  // C's "%.<p>g", as vri's heat-map labels print numbers.
  function formatG(v, p) {
    if (v === 0) return '0';
    if (!Number.isFinite(v)) return String(v);
    const e = v.toExponential(p - 1);
    const exp = parseInt(e.slice(e.indexOf('e') + 1), 10);
    const strip = (s) => (s.indexOf('.') >= 0 ? s.replace(/0+$/, '').replace(/\.$/, '') : s);
    if (exp < -4 || exp >= p) {
      const m = strip(e.slice(0, e.indexOf('e')));
      return m + 'e' + (exp < 0 ? '-' : '+') + String(Math.abs(exp)).padStart(2, '0');
    }
    return strip(v.toFixed(Math.max(0, p - 1 - exp)));
  }

  // A probe value as text: 6 significant digits, non-finite values by name.
  function formatValue(v) {
    if (Number.isNaN(v)) return 'NaN';
    if (v === Infinity) return '+Inf';
    if (v === -Infinity) return '-Inf';
    return v.toPrecision(6);
  }

  // A JSON array of numbers as decoded; JSON has no NaN or Infinity, so those become strings.
  function valuesJson(values) {
    return '[' + values.map((v) => (Number.isFinite(v) ? JSON.stringify(v) : JSON.stringify(String(v)))).join(',') + ']';
  }

  function parseJsonScript(node) {
    try {
      return JSON.parse(node.textContent);
    } catch (e) {
      throw new Error('#' + node.id + ' does not hold valid JSON: ' + e.message);
    }
  }

  // Shown on the page and logged as an error: a broken page must fail its test, not look empty.
  function fatal(error) {
    const message = error && error.message ? error.message : str(error);
    document.body.prepend(el('div', { class: 'vri-fatal', role: 'alert', text: 'vri viewer: ' + message }));
    document.body.dataset.ready = 'error';
    console.error('vri viewer: ' + message);
  }

  // ---------------------------------------------------------------- float sidecars

  function base64Bytes(text) {
    if (typeof Uint8Array.fromBase64 === 'function') return Uint8Array.fromBase64(text);
    const binary = atob(text);
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
    return bytes;
  }

  // zlib (RFC 1950) inflation by the browser's own DecompressionStream: no library needed.
  async function inflate(bytes) {
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
    return new Response(stream).arrayBuffer();
  }

  // A sidecar's record -> {id, width, height, channels, data: Float32Array}; rejects with a message that
  // names what is wrong.
  async function decodeFloatRecord(record) {
    if (!record || typeof record !== 'object') throw new Error('the sidecar passed no record');
    const width = posInt(record.width);
    const height = posInt(record.height);
    const channels = Array.isArray(record.channels) ? record.channels.map(str) : [];
    if (!width || !height || !channels.length) throw new Error('the sidecar has no width, height or channels');
    if (record.encoding !== 'f32le-zlib-base64') throw new Error('unknown encoding "' + str(record.encoding) + '"');
    let raw;
    try {
      raw = await inflate(base64Bytes(str(record.data)));
    } catch (e) {
      throw new Error('cannot decode the data (' + (e && e.message ? e.message : e) + ')');
    }
    const count = width * height * channels.length;
    if (raw.byteLength !== count * 4) {
      throw new Error('the data holds ' + raw.byteLength + ' bytes, ' + width + 'x' + height + 'x' +
        channels.length + ' float32 values need ' + count * 4);
    }
    let data;
    if (LITTLE_ENDIAN) {
      data = new Float32Array(raw);
    } else {
      const view = new DataView(raw);
      data = new Float32Array(count);
      for (let i = 0; i < count; ++i) data[i] = view.getFloat32(i * 4, true);
    }
    return { id: str(record.id), width, height, channels, data };
  }

  // The sidecar script being executed -> the slot its vriViewerFloats call fills. A sidecar is matched to
  // its request by document.currentScript, not by the id inside it, so that two loads never mix.
  const sidecarSlots = new Map();

  window.vriViewerFloats = function (record) {
    const decoded = decodeFloatRecord(record);
    decoded.catch(() => {}); // the loader reports failures; this only keeps them from being "unhandled"
    const slot = sidecarSlots.get(document.currentScript);
    if (slot) slot.decoded = decoded;
  };

  function loadSidecar(path) {
    return new Promise((resolve, reject) => {
      const script = document.createElement('script');
      const slot = { decoded: null };
      sidecarSlots.set(script, slot);
      const done = () => {
        sidecarSlots.delete(script);
        script.remove(); // the record is decoded by now; megabytes of source text need not stay in the DOM
      };
      script.onload = () => {
        done();
        if (slot.decoded) slot.decoded.then(resolve, reject);
        else reject(new Error(path + ' did not call vriViewerFloats'));
      };
      script.onerror = () => {
        done();
        const error = new Error('cannot load ' + path);
        error.missing = true; // not written (no EXR here, or vri-run --gallery not run since), not broken
        reject(error);
      };
      script.src = urlOf(path);
      document.head.append(script);
    });
  }

  // ---------------------------------------------------------------- colour

  // The display colour of a float image: composite over the background in linear units (rgb + (1 - a) bg,
  // premultiplied, as vri's PNG previews do), scale by 2^exposure, clamp to [0, 1], apply the transfer
  // curve (1/gamma power, or sRGB's), round to a byte. NaN shows as 0, as in the previews. Returns a canvas
  // the size of the image.
  function toneMap(image, look) {
    const { width: w, height: h, channels, data } = image;
    const nc = channels.length;
    let r = channels.indexOf('R');
    let g = channels.indexOf('G');
    let b = channels.indexOf('B');
    const a = nc > 1 ? channels.indexOf('A') : -1;
    if (r < 0 || g < 0 || b < 0) r = g = b = a === 0 ? 1 : 0; // a lone channel shows as grey
    const gain = Math.pow(2, look.exposure);
    const invGamma = 1 / look.gamma;
    const encode = look.srgb
      ? (v) => (v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055)
      : (v) => Math.pow(v, invGamma);
    const byteOf = (v) => {
      v *= gain;
      if (!(v > 0)) return 0; // NaN too
      if (v >= 1) return 255;
      return Math.floor(encode(v) * 255 + 0.5);
    };
    const canvas = document.createElement('canvas');
    canvas.width = w;
    canvas.height = h;
    const ctx = canvas.getContext('2d');
    const out = ctx.createImageData(w, h);
    const px = out.data;
    for (let y = 0, i = 0, o = 0; y < h; ++y) {
      for (let x = 0; x < w; ++x, i += nc, o += 4) {
        // Without an alpha channel the image is opaque and the background never shows.
        let cover = 0;
        if (a >= 0 && look.background !== 'black') {
          const bg = look.background === 'white' ? 1
            : CHECKER[(Math.floor(x / CHECKER_CELL) + Math.floor(y / CHECKER_CELL)) & 1];
          cover = (1 - data[i + a]) * bg;
        }
        px[o] = byteOf(data[i + r] + cover);
        px[o + 1] = byteOf(data[i + g] + cover);
        px[o + 2] = byteOf(data[i + b] + cover);
        px[o + 3] = 255;
      }
    }
    ctx.putImageData(out, 0, 0);
    return canvas;
  }

  function viridisBytes(u) {
    u = clamp(u, 0, 1);
    const at = u * (VIRIDIS.length - 1);
    const i = Math.min(Math.floor(at), VIRIDIS.length - 2);
    const f = at - i;
    const lo = VIRIDIS[i];
    const hi = VIRIDIS[i + 1];
    return [0, 1, 2].map((c) => Math.floor((lo[c] + f * (hi[c] - lo[c])) * 255 + 0.5));
  }

  // Where an error sits on the scale: 0 at the bottom, 1 at the top, above 1 when clipped (heat_map.cpp).
  function positionOf(e, scale) {
    if (!scale.log) return e / scale.top;
    if (!(e > 0)) return 0;
    return Math.max(0, 1 + Math.log10(e / scale.top) / scale.decades);
  }

  // Tick positions and labels of the colour bar: quarters on a linear scale, decades on a log one.
  function ticksOf(scale) {
    const ticks = [];
    if (!scale.log) {
      for (let q = 0; q <= 4; ++q) ticks.push({ at: q / 4, label: q ? formatG((scale.top * q) / 4, 2) : '0' });
    } else {
      for (let d = 0; d <= scale.decades; ++d) {
        ticks.push({ at: d / scale.decades, label: formatG(scale.top * Math.pow(10, d - scale.decades), 2) });
      }
    }
    return ticks;
  }

  // One pixel-channel's error as vri counts it (image_compare.h's absoluteError): |a - b| in double, 0 for
  // equal values (infinities and NaNs too), infinite for a NaN against a number, so the view, the probe and
  // vri-diff's heat maps agree pixel for pixel.
  function absoluteError(a, b) {
    if (a === b || (Number.isNaN(a) && Number.isNaN(b))) return 0;
    const d = Math.abs(a - b);
    return Number.isNaN(d) ? Infinity : d;
  }

  // The per-pixel error max over the shared channels of |A - B|, with its statistics. Channels are matched
  // by name (A's order); A and B must have the same size (the caller checks).
  function errorField(A, B) {
    const shared = [];
    for (let c = 0; c < A.channels.length; ++c) {
      const k = B.channels.indexOf(A.channels[c]);
      if (k >= 0) shared.push([c, k, A.channels[c]]);
    }
    const n = A.width * A.height;
    const e = new Float32Array(n);
    let max = -Infinity;
    let maxAt = -1;
    let sum = 0;
    let finite = 0;
    let inf = 0;
    const na = A.channels.length;
    const nb = B.channels.length;
    for (let p = 0; p < n; ++p) {
      let m = 0;
      for (const [ca, cb] of shared) m = Math.max(m, absoluteError(A.data[p * na + ca], B.data[p * nb + cb]));
      e[p] = m;
      if (m === Infinity) ++inf;
      else {
        sum += m;
        ++finite;
        if (m > max) {
          max = m;
          maxAt = p;
        }
      }
    }
    return {
      width: A.width, height: A.height, e, channels: shared.map((s) => s[2]),
      max: finite ? max : NaN, maxX: maxAt >= 0 ? maxAt % A.width : -1, maxY: maxAt >= 0 ? Math.floor(maxAt / A.width) : -1,
      mean: finite ? sum / finite : NaN, inf,
    };
  }

  function colouriseError(field, scale) {
    const canvas = document.createElement('canvas');
    canvas.width = field.width;
    canvas.height = field.height;
    const ctx = canvas.getContext('2d');
    const out = ctx.createImageData(field.width, field.height);
    const px = out.data;
    for (let p = 0, o = 0; p < field.e.length; ++p, o += 4) {
      const u = positionOf(field.e[p], scale);
      const rgb = u > 1 ? CLIPPED_RGB : viridisBytes(u);
      px[o] = rgb[0];
      px[o + 1] = rgb[1];
      px[o + 2] = rgb[2];
      px[o + 3] = 255;
    }
    ctx.putImageData(out, 0, 0);
    return canvas;
  }

  // ---------------------------------------------------------------- Markdown (the subset vri writes)

  // Inline Markdown into DOM nodes: `code`, **bold**, *italic*, [text](link) and backslash escapes. Text is
  // only ever textContent; a link keeps its href only when it is relative or http(s).
  function appendInline(parent, text) {
    const re = /\\([\\`*_|[\]()#+\-.!<>])|`([^`]+)`|\*\*(?=\S)(.+?)\*\*|\*(?=[^\s*])([^*]*?[^\s*]|[^\s*])\*|\[([^\]]+)\]\(([^)\s]+)\)/g;
    let last = 0;
    let m;
    let plain = '';
    const flush = () => {
      if (plain) parent.append(plain);
      plain = '';
    };
    while ((m = re.exec(text)) !== null) {
      plain += text.slice(last, m.index);
      last = re.lastIndex;
      if (m[1] !== undefined) {
        plain += m[1];
        continue;
      }
      flush();
      if (m[2] !== undefined) parent.append(el('code', { text: m[2] }));
      else if (m[3] !== undefined) appendInline(parent.appendChild(el('strong')), m[3]);
      else if (m[4] !== undefined) appendInline(parent.appendChild(el('em')), m[4]);
      else {
        const href = m[6];
        const safe = !/^[a-z][a-z0-9+.-]*:/i.test(href) || /^https?:/i.test(href);
        const link = parent.appendChild(safe ? el('a', { href }) : el('span'));
        appendInline(link, m[5]);
      }
    }
    plain += text.slice(last);
    flush();
  }

  // A table row's cells: split at '|' not escaped by '\' (the escape is kept for appendInline to undo).
  function splitRow(line) {
    let s = line.trim();
    if (s.startsWith('|')) s = s.slice(1);
    if (s.endsWith('|') && !s.endsWith('\\|')) s = s.slice(0, -1);
    const cells = [];
    let cell = '';
    for (let i = 0; i < s.length; ++i) {
      if (s[i] === '\\' && i + 1 < s.length) {
        cell += s[i] + s[i + 1];
        ++i;
      } else if (s[i] === '|') {
        cells.push(cell.trim());
        cell = '';
      } else cell += s[i];
    }
    cells.push(cell.trim());
    return cells;
  }

  const SEPARATOR_ROW = /^\s*\|?\s*:?-+:?\s*(\|\s*:?-+:?\s*)*\|?\s*$/;

  // Markdown text -> a DocumentFragment: pipe tables (alignment from the separator row), headings, '-'
  // lists and paragraphs with inline formatting. Enough for vri-tabulate's tables and their notes.
  function renderMarkdown(text) {
    const frag = document.createDocumentFragment();
    const lines = str(text).replace(/\r\n?/g, '\n').split('\n');
    let i = 0;
    while (i < lines.length) {
      const line = lines[i];
      if (!line.trim()) {
        ++i;
        continue;
      }
      if (line.trim().startsWith('|') && i + 1 < lines.length && SEPARATOR_ROW.test(lines[i + 1])) {
        const head = splitRow(line);
        const align = splitRow(lines[i + 1]).map((c) =>
          c.startsWith(':') && c.endsWith(':') ? 'center' : c.endsWith(':') ? 'right' : c.startsWith(':') ? 'left' : '');
        const table = el('table', { class: 'vri-md-table' });
        const tr = table.appendChild(el('thead')).appendChild(el('tr'));
        head.forEach((c, k) => appendInline(tr.appendChild(el('th', { class: align[k] ? 'align-' + align[k] : null })), c));
        const body = table.appendChild(el('tbody'));
        i += 2;
        while (i < lines.length && lines[i].trim().startsWith('|')) {
          const row = body.appendChild(el('tr'));
          const cells = splitRow(lines[i]);
          for (let k = 0; k < Math.max(cells.length, head.length); ++k) {
            appendInline(row.appendChild(el('td', { class: align[k] ? 'align-' + align[k] : null })), cells[k] || '');
          }
          ++i;
        }
        frag.append(el('div', { class: 'vri-table-wrap' }, [table]));
        continue;
      }
      const heading = /^(#{1,6})\s+(.*)$/.exec(line);
      if (heading) {
        appendInline(frag.appendChild(el('h' + Math.min(6, heading[1].length + 2))), heading[2]);
        ++i;
        continue;
      }
      if (/^\s*[-*]\s+/.test(line)) {
        const list = frag.appendChild(el('ul'));
        while (i < lines.length && /^\s*[-*]\s+/.test(lines[i])) {
          appendInline(list.appendChild(el('li')), lines[i].replace(/^\s*[-*]\s+/, ''));
          ++i;
        }
        continue;
      }
      const para = [];
      while (i < lines.length && lines[i].trim() && !lines[i].trim().startsWith('|') && !/^#{1,6}\s/.test(lines[i])) {
        para.push(lines[i].trim());
        ++i;
      }
      appendInline(frag.appendChild(el('p')), para.join(' '));
    }
    return frag;
  }

  // ---------------------------------------------------------------- the index page

  function indexPage(data) {
    const title = str(data.title) || 'vri results';
    document.title = title;
    const experiments = Array.isArray(data.experiments) ? data.experiments : [];
    const main = el('main', { class: 'vri-index' }, [el('h1', { text: title })]);
    const table = el('table', { id: 'experiments', class: 'vri-md-table' });
    const head = table.appendChild(el('thead')).appendChild(el('tr'));
    for (const h of ['paper item', 'experiment', 'ours against the paper']) head.append(el('th', { text: h }));
    const body = table.appendChild(el('tbody'));
    for (const x of experiments) {
      if (!x || typeof x !== 'object') continue;
      const name = str(x.title) || str(x.dir);
      const page = str(x.page);
      const verdict = str(x.verdict).trim();
      body.append(el('tr', null, [
        el('td', { text: paperItem(x.paper, x.item) }),
        el('td', null, [page ? el('a', { href: urlOf(page), text: name }) : name]),
        el('td', { class: verdict ? null : 'vri-none', text: verdict || '\u2013', title: verdict ? null : 'no verdict: not a paper\'s item' }),
      ]));
    }
    main.append(experiments.length ? el('div', { class: 'vri-table-wrap' }, [table]) : el('p', { text: 'No experiments.' }));
    document.body.prepend(main);
    document.body.dataset.ready = '1';
    window.vriViewer = { ready: Promise.resolve() };
  }

  // ---------------------------------------------------------------- the experiment page

  function parseHeat(h) {
    if (!h || typeof h !== 'object') return null;
    const top = Number(h.top);
    if (!(top > 0 && Number.isFinite(top))) return null;
    const log = h.scale === 'log';
    const decades = Number.isInteger(h.decades) && h.decades >= 1 && h.decades <= 12 ? h.decades : 3;
    return { log, top, decades };
  }

  function makeEntry(raw, gridName) {
    const floatsPath = raw.floats ? str(raw.floats) : '';
    return {
      id: str(raw.id), grid: gridName, row: str(raw.row), column: str(raw.column),
      png: str(raw.png), floatsPath,
      width: posInt(raw.width), height: posInt(raw.height),
      channels: Array.isArray(raw.channels) ? raw.channels.map(str) : [],
      run: str(raw.run), reference: str(raw.reference), heat: parseHeat(raw.heat),
      picture: null, pictureState: 'none', pictureError: '',
      floats: null, floatState: floatsPath ? 'none' : 'absent', floatError: '', floatMissing: false,
      lastUse: 0, thumbs: [],
    };
  }

  function experimentPage(data) {
    const title = str(data.title) || 'vri experiment';
    document.title = title;
    const grids = (Array.isArray(data.grids) ? data.grids : []).filter((g) => g && typeof g === 'object');
    const entries = new Map(); // id -> entry; a repeated id keeps its first image
    const gridEntries = grids.map((g) => {
      const list = [];
      for (const raw of Array.isArray(g.images) ? g.images : []) {
        if (!raw || typeof raw !== 'object') continue;
        const entry = makeEntry(raw, str(g.name));
        if (!entries.has(entry.id)) entries.set(entry.id, entry);
        list.push(entries.get(entry.id));
      }
      return list;
    });

    const main = el('main', { class: 'vri-experiment' });
    document.body.prepend(main);
    main.append(headerOf(data, title));

    const layoutOfGrids = grids.map((g, k) => ({
      name: str(g.name), rows: Array.isArray(g.rows) ? g.rows.map(str) : [],
      columns: Array.isArray(g.columns) ? g.columns.map(str) : [], list: gridEntries[k],
    }));
    const viewer = entries.size ? makeViewer(entries, layoutOfGrids, resultsFolderOf(data)) : null;
    if (viewer) main.append(viewer.section);
    grids.forEach((g, k) => main.append(gridSection(g, gridEntries[k], viewer)));
    main.append(...extrasOf(data));

    if (!viewer) {
      document.body.dataset.ready = '1';
      window.vriViewer = { ready: Promise.resolve() };
      return;
    }
    window.vriViewer = viewer.api;
    viewer.start();
  }

  // The results folder as a shell word for the hint that writes missing float data: the folder of the
  // index page, when the page is a file; else a placeholder.
  function resultsFolderOf(data) {
    const placeholder = '<results folder>';
    if (!data.index) return placeholder;
    try {
      const url = new URL('.', new URL(urlOf(data.index), window.location.href));
      if (url.protocol !== 'file:') return placeholder;
      let folder = decodeURIComponent(url.pathname).replace(/\/+$/, '') || '/';
      if (/^\/[A-Za-z]:/.test(folder)) folder = folder.slice(1); // file:///C:/... on Windows
      return /^[\w@%+=:,./-]+$/.test(folder) ? folder : "'" + folder.replace(/'/g, "'\\''") + "'";
    } catch (e) {
      return placeholder;
    }
  }

  function headerOf(data, title) {
    const header = el('header', { class: 'vri-header' });
    const nav = header.appendChild(el('nav'));
    if (data.index) nav.append(el('a', { href: urlOf(data.index), id: 'index-link', text: '\u2190 all results' }));
    if (data.manifest) nav.append(el('a', { href: urlOf(data.manifest), id: 'manifest-link', text: 'manifest.json' }));
    header.append(el('h1', { text: title }), el('p', { class: 'vri-item', text: paperItem(data.paper, data.item) }));
    const dl = header.appendChild(el('dl'));
    // A long text starts collapsed to its opening sentences (the summary; the rest follows it when opened),
    // so that the compare view stays on the first screen.
    const add = (term, id, value) => {
      const text = str(value).trim();
      if (!text) return;
      dl.append(el('dt', { text: term }));
      const dd = dl.appendChild(el('dd', { id }));
      if (text.length <= LONG_TEXT) {
        appendInline(dd, text);
        return;
      }
      const details = dd.appendChild(el('details', { class: 'vri-long' }));
      const summary = details.appendChild(el('summary'));
      const end = openingEnd(text);
      if (end > 0) {
        appendInline(summary.appendChild(el('span', { class: 'vri-opening' })), text.slice(0, end));
        summary.append(el('span', { class: 'vri-more', text: ' \u2026 more' }));
        appendInline(details.appendChild(el('div', { class: 'vri-rest' })), text.slice(end).trim());
      } else {
        // No sentence ends early enough: the summary is the first words, the full text follows when opened.
        const cut = text.slice(0, 240).replace(/\s+\S*$/, '');
        appendInline(summary.appendChild(el('span', { class: 'vri-opening vri-cut' })), cut);
        summary.append(el('span', { class: 'vri-more', text: '\u2026 more' }), el('span', { class: 'vri-less', text: 'less' }));
        appendInline(details.appendChild(el('div', { class: 'vri-rest' })), text);
      }
    };
    // A study of our own has no paper: its "says" describes the study, its "agreement" is what it found.
    const own = !named(data.paper);
    add(own ? 'About this study' : 'The paper', 'says', data.says);
    add(own ? 'Findings' : 'Ours', 'agreement', data.agreement);
    if (data.commit) {
      dl.append(el('dt', { text: 'Commit' }));
      dl.append(el('dd', null, [el('code', { text: str(data.commit) }),
        data.modified ? el('span', { class: 'vri-modified', text: ' (tracked files modified)' }) : null]));
    }
    return header;
  }

  function extrasOf(data) {
    const out = [];
    const figures = Array.isArray(data.figures) ? data.figures.filter((f) => f && f.file) : [];
    if (figures.length) {
      const s = el('section', { class: 'vri-figures' }, [el('h2', { text: 'Figures' })]);
      for (const f of figures) {
        const src = urlOf(f.file);
        s.append(el('figure', { id: 'figure-' + str(f.id) }, [
          el('a', { href: src }, [el('img', { src, alt: str(f.id), loading: 'lazy' })]),
          el('figcaption', null, [el('a', { href: src, text: str(f.file) })]),
        ]));
      }
      out.push(s);
    }
    const tables = Array.isArray(data.tables) ? data.tables.filter((t) => t && typeof t === 'object') : [];
    if (tables.length) {
      const s = el('section', { class: 'vri-tables' }, [el('h2', { text: 'Tables' })]);
      for (const t of tables) {
        const box = s.appendChild(el('div', { class: 'vri-md', id: 'table-' + str(t.id) }));
        box.append(renderMarkdown(t.markdown));
        if (t.file) box.append(el('p', { class: 'vri-file' }, [el('a', { href: urlOf(t.file), text: str(t.file) })]));
      }
      out.push(s);
    }
    const notes = Array.isArray(data.notes) ? data.notes : [];
    if (notes.length) {
      const s = el('section', { class: 'vri-notes' }, [el('h2', { text: 'Notes' })]);
      for (const n of notes) appendInline(s.appendChild(el('p')), str(n));
      out.push(s);
    }
    return out;
  }

  // One grid as a table: row headers, column headers, a lazy thumbnail per image. Images whose row or
  // column is not listed get rows or columns of their own at the end.
  function gridSection(grid, list, viewer) {
    const name = str(grid.name);
    const section = el('section', { class: 'vri-grid' }, [el('h2', { text: name || 'Images' })]);
    if (!list.length) {
      section.append(el('p', { text: 'No images.' }));
      return section;
    }
    const rows = (Array.isArray(grid.rows) ? grid.rows.map(str) : []).slice();
    const cols = (Array.isArray(grid.columns) ? grid.columns.map(str) : []).slice();
    for (const e of list) {
      if (!rows.includes(e.row)) rows.push(e.row);
      if (!cols.includes(e.column)) cols.push(e.column);
    }
    section.append(el('p', { class: 'vri-help', text: 'Click a thumbnail to show it as A, shift-click to show it as B.' }));
    const table = el('table', { class: 'vri-thumbs' });
    const head = table.appendChild(el('thead')).appendChild(el('tr'));
    head.append(el('th'));
    for (const c of cols) head.append(el('th', { scope: 'col', text: c }));
    const body = table.appendChild(el('tbody'));
    for (const r of rows) {
      const tr = body.appendChild(el('tr'));
      tr.append(el('th', { scope: 'row', text: r }));
      for (const c of cols) {
        const td = tr.appendChild(el('td'));
        for (const e of list) {
          if (e.row !== r || e.column !== c) continue;
          const button = td.appendChild(el('button', { type: 'button', class: 'vri-thumb', title: e.id }));
          button.append(el('img', {
            src: urlOf(e.png), alt: e.id, loading: 'lazy', decoding: 'async',
            width: e.width || null, height: e.height || null,
          }));
          button.append(el('span', { class: 'vri-thumb-tag' }));
          e.thumbs.push(button);
          if (viewer) button.addEventListener('click', (ev) => viewer.pickOne(e.id, ev.shiftKey ? 'b' : 'a'));
        }
      }
    }
    section.append(el('div', { class: 'vri-table-wrap' }, [table]));
    return section;
  }

  // ---------------------------------------------------------------- the compare view

  function makeViewer(entries, grids, resultsFolder) {
    const ids = [...entries.keys()];
    const refreshHint = 'run vri-run --gallery ' + resultsFolder + ' after make experiments (EXRs are not kept in git)';
    const state = {
      a: null, b: null, mode: 'a', flipB: false, swipe: 0.5,
      cx: 0, cy: 0, s: 1, fitted: false, geometry: '',
      look: { exposure: 0, gamma: DEFAULT_GAMMA, srgb: true, background: 'black' },
      errorScale: null, // {log, top, decades}, reset on each new pair
      probe: null, // {x, y} of the last image pixel probed inside the image
      probeWhere: 'none', // the pointer: 'in' the image, 'outside' it on the canvas, 'left' the canvas; 'none' yet
      W: 0, H: 0, dpr: 1, drawn: 0, pending: 0, useClock: 0,
    };
    const toneCache = new Map(); // key -> canvas, in least recently used order
    let errorCache = null; // {key, field}
    let errorImageCache = null; // {key, canvas}
    let shownTop = null; // {text, top}: the error scale's top as #error-top shows it (rounded), and exactly
    let idleWaiters = [];
    let drag = null;

    // -------- DOM
    const optionsOf = (select) => {
      const groups = new Map();
      for (const e of entries.values()) {
        if (!groups.has(e.grid)) groups.set(e.grid, select.appendChild(el('optgroup', { label: e.grid || 'images' })));
        groups.get(e.grid).append(el('option', { value: e.id, text: e.id }));
      }
      return select;
    };
    const pickA = optionsOf(el('select', { id: 'pick-a', 'aria-label': 'image A' }));
    const pickB = optionsOf(el('select', { id: 'pick-b', 'aria-label': 'image B' }));
    const modeSelect = el('select', { id: 'mode', 'aria-label': 'mode' });
    for (const [v, label] of MODES) modeSelect.append(el('option', { value: v, text: label }));
    const swapButton = el('button', { type: 'button', id: 'swap', text: 'swap A/B' });
    const flipButton = el('button', { type: 'button', id: 'flip', text: 'flip (f)' });
    const fitButton = el('button', { type: 'button', id: 'fit', text: 'fit (0)' });
    const oneButton = el('button', { type: 'button', id: 'one', text: '1:1' });
    const swipeRange = el('input', { type: 'range', id: 'swipe', min: 0, max: 1000, step: 1, value: 500, 'aria-label': 'swipe divider' });
    const exposure = el('input', { type: 'range', id: 'exposure', min: -10, max: 10, step: 0.1, value: 0, 'aria-label': 'exposure in stops' });
    const exposureValue = el('output', { id: 'exposure-value', text: '0.0' });
    const gamma = el('input', { type: 'number', id: 'gamma', min: 0.1, max: 10, step: 0.1, value: DEFAULT_GAMMA, 'aria-label': 'gamma', disabled: true });
    const srgb = el('input', { type: 'checkbox', id: 'srgb', checked: true, title: 'the sRGB curve (as the PNG previews), or untick for a 1/gamma power' });
    const background = el('select', { id: 'background', 'aria-label': 'background' });
    for (const v of ['black', 'white', 'checker']) background.append(el('option', { value: v, text: v }));
    const errorScaleSelect = el('select', { id: 'error-scale', 'aria-label': 'error scale' });
    for (const v of ['linear', 'log']) errorScaleSelect.append(el('option', { value: v, text: v }));
    const errorTop = el('input', { type: 'text', id: 'error-top', inputmode: 'decimal', size: 10, 'aria-label': 'top of the error scale', placeholder: 'default',
      title: 'shown to 4 significant digits; the exact value is used until you edit it' });
    const errorDecades = el('input', { type: 'number', id: 'error-decades', min: 1, max: 12, step: 1, value: 3, 'aria-label': 'decades' });
    const pairButton = el('button', { type: 'button', id: 'open-pair', hidden: true });

    const canvas = el('canvas', { id: 'view', 'data-busy': '1', 'data-drawn': '0', 'data-mode': 'a', tabindex: 0 });
    const ctx = canvas.getContext('2d');
    const canvasWrap = el('div', { class: 'vri-canvas-wrap' }, [canvas]);
    const message = el('p', { id: 'view-message', class: 'vri-view-message', 'aria-live': 'polite' });
    const zoomLevel = el('output', { id: 'zoom-level', class: 'vri-zoom-level', title: 'zoom: CSS pixels per image pixel' });
    const viewStatus = el('div', { class: 'vri-view-status' }, [zoomLevel, message]);
    const pairInfo = el('p', { id: 'pair-info', class: 'vri-pair-info' });
    const bar = el('canvas', { id: 'colorbar', width: 256, height: 12 });
    const barTicks = el('div', { class: 'vri-colorbar-ticks' });
    const errorInfo = el('p', { id: 'error-info', class: 'vri-error-info' });
    const colorbar = el('div', { class: 'vri-colorbar', id: 'colorbar-box', hidden: true }, [
      el('div', { class: 'vri-colorbar-scale' }, [bar, barTicks]),
      el('span', { class: 'vri-swatch vri-swatch-clipped' }), ' above the top (a NaN against a number: infinite)',
      errorInfo,
    ]);
    const probeA = el('div', { id: 'probe-a', 'data-values': '[]' });
    const probeB = el('div', { id: 'probe-b', 'data-values': '[]' });
    const probeErr = el('div', { id: 'probe-err', 'data-values': '[]' });
    const probeXY = el('div', { id: 'probe-xy', text: 'Hover over the picture to read its pixels.' });
    const probe = el('div', { id: 'probe', class: 'vri-probe', 'data-where': 'none' }, [probeXY, probeA, probeB, probeErr]);

    const label = (text, control) => el('label', null, [text + ' ', control]);
    const section = el('section', { class: 'vri-compare', id: 'compare' }, [
      el('h2', { text: 'Compare' }),
      el('div', { class: 'vri-controls' }, [
        label('A', pickA), label('B', pickB), swapButton, pairButton,
      ]),
      el('div', { class: 'vri-controls' }, [
        label('mode', modeSelect), flipButton, label('swipe', swipeRange), fitButton, oneButton,
        label('exposure', exposure), exposureValue, label('gamma', gamma), label('sRGB', srgb),
        label('background', background),
      ]),
      el('div', { class: 'vri-controls vri-error-controls', id: 'error-controls' }, [
        label('error scale', errorScaleSelect), label('top', errorTop), label('decades (log)', errorDecades),
      ]),
      el('p', { class: 'vri-help', text: 'Wheel zooms about the cursor, drag pans (in swipe mode, drag the divider). ' +
        'Keys: 1 A, 2 B, s side by side, w swipe, f flip, e error, 0 fit. Click a thumbnail below for A, shift-click for B.' }),
      pairInfo, canvasWrap, viewStatus, colorbar, probe,
    ]);

    // -------- loading

    function touch(entry) {
      entry.lastUse = ++state.useClock;
    }

    // Starts whatever entry still needs: its PNG, and its floats when it has a sidecar.
    function ensureLoaded(entry) {
      touch(entry);
      if (entry.pictureState === 'none' && entry.png) {
        entry.pictureState = 'loading';
        const img = new Image();
        track(new Promise((resolve) => {
          img.onload = () => {
            entry.picture = img;
            entry.pictureState = 'ready';
            resolve();
          };
          img.onerror = () => {
            entry.pictureState = 'error';
            entry.pictureError = 'cannot load ' + entry.png;
            resolve();
          };
          img.src = urlOf(entry.png);
        }));
      }
      if (entry.floatState === 'none') {
        entry.floatState = 'loading';
        track(loadSidecar(entry.floatsPath).then((image) => {
          entry.floats = image;
          entry.floatState = 'ready';
          evictFloats();
        }, (error) => {
          entry.floatState = 'error';
          entry.floatMissing = !!(error && error.missing); // then refreshHint says how to write it
          entry.floatError = entry.floatMissing ? 'no float data (' + entry.floatsPath + ' is missing)'
            : 'float data unavailable: ' + (error && error.message ? error.message : error);
        }));
      }
    }

    // Keeps at most FLOAT_CACHE_SIZE decoded images, never A's or B's; an evicted one reloads when picked.
    function evictFloats() {
      const ready = [...entries.values()].filter((e) => e.floatState === 'ready' && e !== state.a && e !== state.b);
      ready.sort((x, y) => x.lastUse - y.lastUse);
      const keep = FLOAT_CACHE_SIZE - (state.a && state.a.floats ? 1 : 0) - (state.b && state.b.floats ? 1 : 0);
      for (let i = 0; i < ready.length - Math.max(0, keep); ++i) {
        ready[i].floats = null;
        ready[i].floatState = 'none';
        for (const key of [...toneCache.keys()]) if (key.startsWith(ready[i].id + '\u0000')) toneCache.delete(key);
      }
    }

    function track(promise) {
      ++state.pending;
      canvas.dataset.busy = '1';
      promise.then(done, done);
      function done() {
        --state.pending;
        draw();
      }
    }

    function whenIdle() {
      if (state.pending === 0) return Promise.resolve();
      return new Promise((resolve) => idleWaiters.push(resolve));
    }

    // -------- picking

    function setPair(aId, bId) {
      const a = entries.get(aId);
      const b = entries.get(bId);
      if (!a || !b) {
        const known = ids.slice(0, 8).map((id) => JSON.stringify(id)).join(', ') + (ids.length > 8 ? ', \u2026' : '');
        throw new Error('no image with id ' + JSON.stringify(a ? bId : aId) + ' on this page (its ids: ' + known + ')');
      }
      const changed = a !== state.a || b !== state.b;
      state.a = a;
      state.b = b;
      pickA.value = a.id;
      pickB.value = b.id;
      ensureLoaded(a);
      ensureLoaded(b);
      for (const e of entries.values()) {
        for (const t of e.thumbs) {
          t.classList.toggle('is-a', e === a);
          t.classList.toggle('is-b', e === b);
          t.querySelector('.vri-thumb-tag').textContent = e === a && e === b ? 'A B' : e === a ? 'A' : e === b ? 'B' : '';
        }
      }
      if (changed) {
        state.errorScale = null;
        if (document.activeElement !== errorTop) errorTop.value = ''; // the new pair's default fills it
        shownTop = null;
        const geometry = sizeOf(a).join('x') + '/' + sizeOf(b).join('x');
        if (geometry !== state.geometry) { // same sizes: keep the zoom and probe, to compare many images at one spot
          fit();
          state.probe = null; // it may lie outside the new picture; the pointer's next move probes again
          state.probeWhere = 'none';
        }
        state.geometry = geometry;
      }
      const diff = a.heat && entries.get(a.run) && entries.get(a.reference) ? a
        : b.heat && entries.get(b.run) && entries.get(b.reference) ? b : null;
      pairButton.hidden = !diff;
      if (diff) {
        pairButton.textContent = 'compare its run and reference';
        pairButton.onclick = () => setPair(diff.run, diff.reference);
      }
      draw();
    }

    function pickOne(id, which) {
      setPair(which === 'a' ? id : state.a.id, which === 'b' ? id : state.b.id);
    }

    // The default pair [A, B]: the run and reference of the first difference image that has both; else two
    // renders of one row (scene) and one size, B in the first column named like a reference ("exact",
    // "ref") and A in the next column of that size that is not one (else the next), or else the row's first
    // two images of one size; else the first two images of one size; else the first two, or the only one
    // twice.
    function defaultPair() {
      for (const e of entries.values()) {
        if (e.heat && entries.has(e.run) && entries.has(e.reference)) return [e.run, e.reference];
      }
      const sameSize = (x, y) => x.width === y.width && x.height === y.height;
      const isReference = (column) => /exact|ref/i.test(column);
      // The Renders grid first; difference images never.
      const ordered = grids.filter((g) => g.name === 'Renders').concat(grids.filter((g) => g.name !== 'Renders'));
      const rowsOf = ordered.map((g) => {
        const list = g.list.filter((e) => !e.heat);
        const rows = g.rows.concat(list.map((e) => e.row).filter((r) => !g.rows.includes(r)));
        const columns = g.columns.concat(list.map((e) => e.column).filter((c) => !g.columns.includes(c)));
        // Each row's images in column order.
        return rows.map((r) => {
          const cells = [];
          for (const c of columns) for (const e of list) if (e.row === r && e.column === c) cells.push(e);
          return cells;
        });
      });
      for (const rows of rowsOf) {
        for (const cells of rows) {
          const k = cells.findIndex((e) => isReference(e.column));
          if (k < 0) continue;
          const b = cells[k];
          const after = cells.slice(k + 1).concat(cells.slice(0, k)).filter((e) => sameSize(e, b));
          const a = after.find((e) => !isReference(e.column)) || after[0];
          if (a) return [a.id, b.id];
        }
      }
      for (const rows of rowsOf) {
        for (const cells of rows) {
          for (let i = 0; i < cells.length; ++i) {
            const b = cells.slice(i + 1).find((e) => sameSize(e, cells[i]));
            if (b) return [cells[i].id, b.id];
          }
        }
      }
      const all = [...entries.values()];
      for (let i = 0; i < all.length; ++i) {
        const b = all.slice(i + 1).find((e) => sameSize(e, all[i]));
        if (b) return [all[i].id, b.id];
      }
      return [ids[0], ids[Math.min(1, ids.length - 1)]];
    }

    function setMode(mode) {
      if (!MODES.some((m) => m[0] === mode)) throw new Error('unknown mode ' + JSON.stringify(mode));
      if (mode === 'flip' && state.mode !== 'flip') state.flipB = false;
      state.mode = mode;
      modeSelect.value = mode;
      if (state.fitted) fit(); // side by side halves the panel: a fitted view fits it again
      draw();
    }

    function flip() {
      if (state.mode === 'flip') state.flipB = !state.flipB;
      else {
        state.flipB = state.mode !== 'b';
        state.mode = 'flip';
        modeSelect.value = 'flip';
      }
      draw();
    }

    // -------- geometry
    // The view is (cx, cy): the image point at each panel's centre, and s: CSS pixels per image pixel. All
    // panels and modes share it, so A and B stay registered (top-left corners together).

    // An entry's size as drawn: its decoded floats, else its PNG, else the size the data gives.
    function sizeOf(entry) {
      if (entry.floats) return [entry.floats.width, entry.floats.height];
      if (entry.picture) return [entry.picture.naturalWidth, entry.picture.naturalHeight];
      return [entry.width || 1, entry.height || 1];
    }

    function layout() {
      const dpr = window.devicePixelRatio || 1;
      // Width a multiple of 4 and height even, so that every panel centre is a whole CSS pixel: zoomTo then
      // puts an image pixel exactly on a 16x16 block (say) of canvas pixels.
      // The canvas also starts on a whole device pixel: text above it may have left a fraction, and a
      // canvas drawn across pixel boundaries blurs and shifts screenshots by a row.
      const wrap = canvasWrap.getBoundingClientRect();
      const nudge = (v) => {
        const f = (((v * dpr) % 1) + 1) % 1;
        return f > 1e-3 && f < 1 - 1e-3 ? (1 - f) / dpr : 0;
      };
      const left = nudge(wrap.left + window.scrollX);
      const top = nudge(wrap.top + window.scrollY);
      canvas.style.marginLeft = left + 'px';
      canvas.style.marginTop = top + 'px';
      const W = Math.max(200, Math.floor((canvasWrap.clientWidth - 1) / 4) * 4);
      const H = Math.max(240, 2 * Math.floor(clamp(window.innerHeight * 0.62, 240, 900) / 2));
      if (W !== state.W || H !== state.H || dpr !== state.dpr) {
        state.W = W;
        state.H = H;
        state.dpr = dpr;
        canvas.style.width = W + 'px';
        canvas.style.height = H + 'px';
        canvas.width = Math.round(W * dpr);
        canvas.height = Math.round(H * dpr);
      }
    }

    function panels() {
      const { W, H } = state;
      if (state.mode === 'side-by-side') {
        const w = (W - PANEL_GAP) / 2;
        return [{ x: 0, y: 0, w, h: H }, { x: w + PANEL_GAP, y: 0, w, h: H }];
      }
      return [{ x: 0, y: 0, w: W, h: H }];
    }

    function originOf(panel) {
      return { x: panel.x + panel.w / 2 - state.cx * state.s, y: panel.y + panel.h / 2 - state.cy * state.s };
    }

    // The size of the picture: the larger of A and B in each direction.
    function pictureSize() {
      let w = 1;
      let h = 1;
      for (const e of [state.a, state.b]) {
        if (!e) continue;
        const [ew, eh] = sizeOf(e);
        w = Math.max(w, ew);
        h = Math.max(h, eh);
      }
      return [w, h];
    }

    function fit() {
      layout();
      const p = panels()[0];
      const [w, h] = pictureSize();
      state.s = clamp(Math.min(p.w / w, p.h / h), MIN_SCALE, MAX_SCALE);
      state.cx = w / 2;
      state.cy = h / 2;
      state.fitted = true;
    }

    // Keeps a quarter of the picture on the panel in each direction (a quarter of the panel when the picture
    // is larger than it), so that panning or zooming out never loses the picture. A view centred on a
    // pixel of the picture, as fit and zoomTo make, is never moved.
    function clampView() {
      const p = panels()[0];
      const [w, h] = pictureSize();
      const halfX = p.w / (2 * state.s);
      const halfY = p.h / (2 * state.s);
      const needX = Math.min(w, 2 * halfX) / 4;
      const needY = Math.min(h, 2 * halfY) / 4;
      state.cx = clamp(state.cx, needX - halfX, w - needX + halfX);
      state.cy = clamp(state.cy, needY - halfY, h - needY + halfY);
    }

    // Zoom by `factor` keeping the image point under (mx, my) (canvas CSS pixels, in `panel`) in place.
    function zoomAbout(panel, mx, my, factor) {
      const o = originOf(panel);
      const ix = (mx - o.x) / state.s;
      const iy = (my - o.y) / state.s;
      const s = clamp(state.s * factor, MIN_SCALE, MAX_SCALE);
      state.cx = (panel.x + panel.w / 2 - (mx - ix * s)) / s;
      state.cy = (panel.y + panel.h / 2 - (my - iy * s)) / s;
      state.s = s;
      state.fitted = false;
    }

    function panelAt(mx, my) {
      return panels().find((p) => mx >= p.x && mx < p.x + p.w && my >= p.y && my < p.y + p.h) || null;
    }

    function canvasPoint(event) {
      const r = canvas.getBoundingClientRect();
      return { mx: event.clientX - r.left, my: event.clientY - r.top };
    }

    // -------- drawing

    function lookKey() {
      const l = state.look;
      return [l.exposure, l.srgb ? 'srgb' : l.gamma, l.background].join('\u0000');
    }

    // What a picked image shows now: its floats through the look, else its PNG, else a message.
    function sourceOf(entry) {
      if (entry.floats) {
        const key = entry.id + '\u0000' + lookKey();
        let c = toneCache.get(key);
        if (c) toneCache.delete(key);
        else c = toneMap(entry.floats, state.look);
        toneCache.set(key, c);
        while (toneCache.size > TONE_CACHE_SIZE) toneCache.delete(toneCache.keys().next().value);
        return { image: c, w: entry.floats.width, h: entry.floats.height };
      }
      if (entry.picture) return { image: entry.picture, w: entry.picture.naturalWidth, h: entry.picture.naturalHeight };
      if (entry.pictureState === 'loading' || entry.floatState === 'loading') return { message: 'loading ' + entry.id + '\u2026' };
      return { message: entry.pictureError || 'nothing to show for ' + entry.id };
    }

    function pairKey() {
      return state.a.id + '\u0000' + state.b.id;
    }

    // Why an entry that is not loading has no float data.
    function noFloatsReason(entry) {
      if (entry.heat) return 'a heat map (PNG only)';
      if (entry.floatState === 'error') return entry.floatError;
      return 'PNG only (its step wrote no EXR)';
    }

    // Why the error view cannot be drawn, or '' when it can. A loading problem is 'loading float data...'.
    function errorProblem() {
      const { a, b } = state;
      for (const e of [a, b]) {
        if (e.floatState === 'loading' || (e.floatState === 'none' && e.floatsPath)) return 'loading float data\u2026';
      }
      const missing = [['A', a], ['B', b]].filter(([, e]) => !e.floats);
      if (missing.length) {
        const who = missing.map(([name, e]) => name + ' (' + e.id + ')');
        const reasons = missing.map(([, e]) => (e.floatMissing ? e.floatsPath + ' is missing' : noFloatsReason(e)));
        const head = 'the error view needs float data of A and B; ' +
          (missing.length === 2 ? 'neither ' + who[0] + ' nor ' + who[1] + ' has it' : who[0] + ' has none');
        const hint = missing.some(([, e]) => e.floatMissing) ? '; ' + refreshHint : '';
        if (missing.length === 2 && reasons[0] === reasons[1]) return head + ': ' + reasons[0] + hint;
        return head + ': ' + missing.map(([name], k) => (missing.length === 2 ? name + ': ' : '') + reasons[k]).join('; ') + hint;
      }
      if (a.floats.width !== b.floats.width || a.floats.height !== b.floats.height) {
        return 'sizes differ (A ' + a.floats.width + '\u00d7' + a.floats.height + ', B ' + b.floats.width + '\u00d7' +
          b.floats.height + '): no per-pixel error';
      }
      if (!a.floats.channels.some((c) => b.floats.channels.includes(c))) return 'A and B share no channel';
      return '';
    }

    function currentErrorField() {
      if (!errorCache || errorCache.key !== pairKey()) errorCache = { key: pairKey(), field: errorField(state.a.floats, state.b.floats) };
      return errorCache.field;
    }

    // The pair's default scale: the heat settings of a difference image of this pair (either way round), or
    // of a picked difference image, else linear up to the pair's largest finite error.
    function defaultErrorScale(field) {
      const { a, b } = state;
      for (const e of entries.values()) {
        if (e.heat && ((e.run === a.id && e.reference === b.id) || (e.run === b.id && e.reference === a.id))) return { ...e.heat };
      }
      if (a.heat) return { ...a.heat };
      if (b.heat) return { ...b.heat };
      const top = field && field.max > 0 && Number.isFinite(field.max) ? field.max : 1;
      return { log: false, top, decades: 3 };
    }

    function syncErrorControls() {
      const sc = state.errorScale;
      errorScaleSelect.value = sc.log ? 'log' : 'linear';
      // The top shows to 4 significant digits; until it is edited, the exact top it stands for is kept.
      if (document.activeElement !== errorTop && !(shownTop && shownTop.top === sc.top && errorTop.value === shownTop.text)) {
        errorTop.value = formatG(sc.top, 4);
        shownTop = { text: errorTop.value, top: sc.top };
      }
      errorDecades.value = String(sc.decades);
      errorDecades.disabled = !sc.log;
    }

    function drawErrorBar(field) {
      const sc = state.errorScale;
      const bctx = bar.getContext('2d');
      for (let x = 0; x < bar.width; ++x) {
        const rgb = viridisBytes(x / (bar.width - 1));
        bctx.fillStyle = 'rgb(' + rgb.join(',') + ')';
        bctx.fillRect(x, 0, 1, bar.height);
      }
      barTicks.replaceChildren(...ticksOf(sc).map((t) => el('span', { style: 'left:' + (t.at * 100).toFixed(3) + '%', text: t.label })));
      if (!field) {
        errorInfo.textContent = '';
        return;
      }
      const parts = ['max |A \u2212 B| = ' + (Number.isNaN(field.max) ? 'n/a' : formatValue(field.max)) +
        (field.maxX >= 0 ? ' at (' + field.maxX + ', ' + field.maxY + ')' : ''),
      'mean of max |A \u2212 B| over channels ' + (Number.isNaN(field.mean) ? 'n/a' : formatValue(field.mean)) +
        (field.inf ? ' (finite pixels)' : ''),
      'channels ' + field.channels.join(' ')];
      if (field.inf) parts.push(field.inf + ' infinite');
      errorInfo.textContent = parts.join('; ');
    }

    function drawImageIn(panel, source, clip) {
      ctx.save();
      ctx.beginPath();
      ctx.rect(clip.x, clip.y, clip.w, clip.h);
      ctx.clip();
      if (source.image) {
        const o = originOf(panel);
        ctx.imageSmoothingEnabled = false;
        ctx.drawImage(source.image, o.x, o.y, source.w * state.s, source.h * state.s);
      } else {
        ctx.fillStyle = '#ccc';
        ctx.font = '14px system-ui, sans-serif';
        ctx.textAlign = 'center';
        ctx.textBaseline = 'middle';
        ctx.fillText(source.message, clip.x + clip.w / 2, clip.y + clip.h / 2, clip.w - 16);
      }
      ctx.restore();
    }

    function tag(text, x, y) {
      ctx.save();
      ctx.font = 'bold 13px system-ui, sans-serif';
      ctx.textBaseline = 'top';
      const w = ctx.measureText(text).width + 10;
      ctx.fillStyle = 'rgba(0,0,0,0.6)';
      ctx.fillRect(x, y, w, 20);
      ctx.fillStyle = '#fff';
      ctx.fillText(text, x + 5, y + 4);
      ctx.restore();
    }

    function draw() {
      if (!state.a) return;
      pairInfo.replaceChildren(
        el('span', { class: 'vri-a', text: 'A' }), ' ' + describe(state.a) + '   ',
        el('span', { class: 'vri-b', text: 'B' }), ' ' + describe(state.b),
        ...(entries.size === 1 ? [el('span', { class: 'vri-only-one', text: '   only one image on this page: A and B are the same' })] : []));
      layout();
      clampView();
      const { a, b, mode, W, H } = state;
      ctx.setTransform(state.dpr, 0, 0, state.dpr, 0, 0);
      ctx.fillStyle = '#3a3a3a';
      ctx.fillRect(0, 0, W, H);
      const ps = panels();
      const messages = [];
      let hint = false; // a shown image's float data is missing: say once how to write it
      const note = (entry, name, src) => {
        if (src.message) messages.push(name + ': ' + src.message);
        else if (!entry.floats) {
          messages.push(name + ' shows its PNG: ' + (entry.floatState === 'loading' ? 'loading float data\u2026' : noFloatsReason(entry)));
          hint = hint || entry.floatMissing;
        }
      };
      let barShown = false;
      if (mode === 'a' || mode === 'b' || mode === 'flip') {
        const showB = mode === 'b' || (mode === 'flip' && state.flipB);
        const entry = showB ? b : a;
        const src = sourceOf(entry);
        drawImageIn(ps[0], src, ps[0]);
        tag((showB ? 'B' : 'A') + (mode === 'flip' ? ' (flip)' : ''), 4, 4);
        note(entry, showB ? 'B' : 'A', src);
      } else if (mode === 'side-by-side') {
        const sa = sourceOf(a);
        const sb = sourceOf(b);
        drawImageIn(ps[0], sa, ps[0]);
        drawImageIn(ps[1], sb, ps[1]);
        ctx.fillStyle = '#111';
        ctx.fillRect(ps[0].w, 0, PANEL_GAP, H);
        tag('A', 4, 4);
        tag('B', ps[1].x + 4, 4);
        note(a, 'A', sa);
        note(b, 'B', sb);
      } else if (mode === 'swipe') {
        const p = ps[0];
        const dx = p.x + state.swipe * p.w;
        const sa = sourceOf(a);
        const sb = sourceOf(b);
        drawImageIn(p, sa, { x: p.x, y: p.y, w: dx - p.x, h: p.h });
        drawImageIn(p, sb, { x: dx, y: p.y, w: p.x + p.w - dx, h: p.h });
        ctx.fillStyle = '#000';
        ctx.fillRect(dx - 2, 0, 4, H);
        ctx.fillStyle = '#fff';
        ctx.fillRect(dx - 1, 0, 2, H);
        ctx.fillRect(dx - 6, H / 2 - 14, 12, 28);
        tag('A', 4, 4);
        tag('B', W - 26, 4);
        note(a, 'A', sa);
        note(b, 'B', sb);
      } else {
        const problem = errorProblem();
        const field = problem ? null : currentErrorField();
        if (!state.errorScale) {
          if (problem && (a.floatState === 'loading' || b.floatState === 'loading')) {
            // the default top waits for the data
          } else {
            state.errorScale = defaultErrorScale(field);
          }
        }
        if (state.errorScale) {
          syncErrorControls();
          if (field) drawErrorBar(field);
        }
        barShown = !!(field && state.errorScale);
        if (problem) {
          // The reason goes below the picture, once, where it wraps and can be copied.
          const loading = problem.startsWith('loading');
          drawImageIn(ps[0], { message: loading ? problem : 'no error view: see the note below' }, ps[0]);
          if (!loading) messages.push(problem);
        } else {
          const sc = state.errorScale;
          const key = pairKey() + '\u0000' + [sc.log, sc.top, sc.decades].join('\u0000');
          if (!errorImageCache || errorImageCache.key !== key) errorImageCache = { key, canvas: colouriseError(field, sc) };
          drawImageIn(ps[0], { image: errorImageCache.canvas, w: field.width, h: field.height }, ps[0]);
          tag('|A \u2212 B|', 4, 4);
        }
      }
      colorbar.hidden = !barShown;
      if (hint) messages.push(refreshHint);
      message.textContent = messages.join(' \u00b7 ');
      zoomLevel.textContent = 'zoom ' + formatG(state.s, 3) + '\u00d7';
      drawProbeOutline(ps);
      renderProbe();
      canvas.dataset.mode = mode;
      canvas.dataset.drawn = String(++state.drawn);
      canvas.dataset.busy = state.pending ? '1' : '0';
      if (!state.pending && idleWaiters.length) {
        const waiters = idleWaiters;
        idleWaiters = [];
        for (const w of waiters) w();
      }
    }

    function describe(entry) {
      const [w, h] = sizeOf(entry);
      const floats = entry.floats ? 'float data' : entry.floatState === 'loading' ? 'loading float data' : entry.heat ? 'heat map' : 'PNG only';
      return entry.id + ' (' + w + '\u00d7' + h + ', ' + floats + ')';
    }

    // -------- probe

    function probeLine(node, name, entry, x, y) {
      node.dataset.x = String(x);
      node.dataset.y = String(y);
      const f = entry.floats;
      let values = [];
      let text;
      if (!f) {
        text = entry.heat ? 'a heat map: no float values' : entry.floatState === 'loading' ? 'loading float data\u2026'
          : noFloatsReason(entry);
      } else if (x < 0 || y < 0 || x >= f.width || y >= f.height) {
        text = 'outside (' + f.width + '\u00d7' + f.height + ')';
      } else {
        const i = (y * f.width + x) * f.channels.length;
        values = Array.from(f.data.subarray(i, i + f.channels.length));
        text = f.channels.map((c, k) => c + ' ' + formatValue(values[k])).join('  ');
      }
      node.dataset.values = valuesJson(values);
      node.dataset.channels = JSON.stringify(f ? f.channels : []);
      node.replaceChildren(el('b', { text: name }), ' ', el('span', { class: 'vri-probe-id', text: entry.id }), ': ' + text);
      return values;
    }

    // The probe's lines for the last pixel probed inside the picture, marked when the pointer is no longer on
    // it: never a position outside the picture.
    function renderProbe() {
      const where = state.probeWhere;
      probe.dataset.where = where;
      probe.classList.toggle('is-stale', !!state.probe && where !== 'in');
      if (!state.probe) {
        probeXY.textContent = where === 'outside' ? 'outside the image' : 'Hover over the picture to read its pixels.';
        return;
      }
      const { x, y } = state.probe;
      const at = 'x ' + x + ', y ' + y;
      probeXY.textContent = where === 'in' ? at
        : where === 'outside' ? 'outside the image (below: the last pixel probed, ' + at + ')'
          : at + ' (the last pixel probed; the pointer has left the picture)';
      const va = probeLine(probeA, 'A', state.a, x, y);
      const vb = probeLine(probeB, 'B', state.b, x, y);
      probeErr.dataset.x = String(x);
      probeErr.dataset.y = String(y);
      const fa = state.a.floats;
      const fb = state.b.floats;
      let values = [];
      let channels = [];
      let text;
      if (!va.length || !vb.length) text = 'needs float values of A and B here';
      else if (fa.width !== fb.width || fa.height !== fb.height) text = 'sizes differ: no per-pixel error';
      else {
        fa.channels.forEach((c, k) => {
          const kb = fb.channels.indexOf(c);
          if (kb < 0) return;
          channels.push(c);
          values.push(absoluteError(va[k], vb[kb]));
        });
        const max = Math.max(0, ...values);
        probeErr.dataset.max = values.length ? valuesJson([max]).slice(1, -1) : '';
        text = channels.map((c, k) => c + ' ' + formatValue(values[k])).join('  ') + '  max ' + (values.length ? formatValue(max) : 'n/a');
      }
      if (!values.length) delete probeErr.dataset.max;
      probeErr.dataset.values = valuesJson(values);
      probeErr.dataset.channels = JSON.stringify(channels);
      probeErr.replaceChildren(el('b', { text: '|A\u2212B|' }), ' ' + text);
    }

    // Probes the pixel under canvas point (mx, my): inside the picture it becomes the probed pixel; outside
    // it (or between the panels) the last one stays, marked. Redraws when the outline must move.
    function probeAt(mx, my) {
      const p = panelAt(mx, my);
      const before = state.probe;
      const whereBefore = state.probeWhere;
      state.probeWhere = 'outside';
      if (p) {
        const o = originOf(p);
        const x = Math.floor((mx - o.x) / state.s);
        const y = Math.floor((my - o.y) / state.s);
        const [w, h] = pictureSize();
        if (x >= 0 && y >= 0 && x < w && y < h) {
          state.probeWhere = 'in';
          if (!before || before.x !== x || before.y !== y) state.probe = { x, y };
        }
      }
      if (state.s >= OUTLINE_SCALE && (state.probe !== before || state.probeWhere !== whereBefore)) draw();
      else renderProbe();
    }

    function leaveProbe() {
      if (drag || state.probeWhere === 'none') return;
      state.probeWhere = 'left';
      if (state.s >= OUTLINE_SCALE && state.probe) draw();
      else renderProbe();
    }

    // A thin outline around the probed pixel in each panel, once pixels are large enough to see it: solid
    // while the pointer is on the pixel, dashed when it is the last one probed.
    function drawProbeOutline(ps) {
      if (!state.probe || state.s < OUTLINE_SCALE) return;
      const s = state.s;
      for (const p of ps) {
        const o = originOf(p);
        const x = o.x + state.probe.x * s;
        const y = o.y + state.probe.y * s;
        ctx.save();
        ctx.beginPath();
        ctx.rect(p.x, p.y, p.w, p.h);
        ctx.clip();
        ctx.lineWidth = 1;
        if (state.probeWhere !== 'in') ctx.setLineDash([3, 3]);
        ctx.strokeStyle = '#000';
        ctx.strokeRect(x - 0.5, y - 0.5, s + 1, s + 1);
        ctx.strokeStyle = '#fff';
        ctx.strokeRect(x + 0.5, y + 0.5, s - 1, s - 1);
        ctx.restore();
      }
    }

    // -------- events

    pickA.addEventListener('change', () => setPair(pickA.value, state.b.id));
    pickB.addEventListener('change', () => setPair(state.a.id, pickB.value));
    modeSelect.addEventListener('change', () => setMode(modeSelect.value));
    swapButton.addEventListener('click', () => setPair(state.b.id, state.a.id));
    flipButton.addEventListener('click', flip);
    fitButton.addEventListener('click', () => {
      fit();
      draw();
    });
    oneButton.addEventListener('click', () => {
      state.s = 1 / state.dpr;
      state.fitted = false;
      draw();
    });
    swipeRange.addEventListener('input', () => {
      state.swipe = Number(swipeRange.value) / 1000;
      if (state.mode !== 'swipe') setMode('swipe');
      else draw();
    });
    exposure.addEventListener('input', () => {
      state.look.exposure = Math.round(Number(exposure.value) * 10) / 10;
      exposureValue.textContent = state.look.exposure.toFixed(1);
      draw();
    });
    gamma.addEventListener('input', () => {
      const g = Number(gamma.value);
      gamma.classList.toggle('invalid', !(g > 0 && g <= 10));
      if (g > 0 && g <= 10) {
        state.look.gamma = g;
        draw();
      }
    });
    srgb.addEventListener('change', () => {
      state.look.srgb = srgb.checked;
      gamma.disabled = srgb.checked;
      draw();
    });
    background.addEventListener('change', () => {
      state.look.background = background.value;
      draw();
    });
    const errorControlsChanged = () => {
      // Read the controls first: entering the error mode fills them with the pair's default scale.
      const log = errorScaleSelect.value === 'log';
      const topText = errorTop.value.trim();
      // The rounded top as shown stands for the exact one it was made from.
      const top = shownTop && topText === shownTop.text ? shownTop.top : topText ? Number(topText) : NaN;
      const decades = Number(errorDecades.value);
      if (state.mode !== 'error') setMode('error');
      if (!state.errorScale) return; // the float data is still loading; its default scale comes first
      const topOk = top > 0 && Number.isFinite(top);
      state.errorScale = {
        log,
        top: topOk ? top : state.errorScale.top,
        decades: Number.isInteger(decades) && decades >= 1 && decades <= 12 ? decades : state.errorScale.decades,
      };
      if (!topOk) { // an unusable top reverts to the one in use
        errorTop.value = formatG(state.errorScale.top, 4);
        shownTop = { text: errorTop.value, top: state.errorScale.top };
      }
      draw();
    };
    errorScaleSelect.addEventListener('change', errorControlsChanged);
    errorTop.addEventListener('change', errorControlsChanged);
    errorDecades.addEventListener('change', errorControlsChanged);

    canvas.addEventListener('wheel', (ev) => {
      const { mx, my } = canvasPoint(ev);
      const p = panelAt(mx, my);
      if (!p) return;
      ev.preventDefault();
      const delta = ev.deltaY * (ev.deltaMode === 1 ? 16 : ev.deltaMode === 2 ? 400 : 1);
      zoomAbout(p, mx, my, Math.pow(2, -clamp(delta, -300, 300) / 200));
      draw();
      probeAt(mx, my);
    }, { passive: false });
    canvas.addEventListener('pointerdown', (ev) => {
      if (ev.button !== 0) return;
      const { mx, my } = canvasPoint(ev);
      const p = panels()[0];
      const divider = state.mode === 'swipe' && Math.abs(mx - (p.x + state.swipe * p.w)) <= 8;
      drag = { divider, mx, my, cx: state.cx, cy: state.cy };
      canvas.setPointerCapture(ev.pointerId);
      canvas.classList.add('dragging');
    });
    canvas.addEventListener('pointermove', (ev) => {
      const { mx, my } = canvasPoint(ev);
      if (drag) {
        if (drag.divider) {
          const p = panels()[0];
          state.swipe = clamp((mx - p.x) / p.w, 0, 1);
          swipeRange.value = String(Math.round(state.swipe * 1000));
        } else {
          state.cx = drag.cx - (mx - drag.mx) / state.s;
          state.cy = drag.cy - (my - drag.my) / state.s;
          state.fitted = false;
        }
        draw();
      }
      probeAt(mx, my);
    });
    const endDrag = () => {
      drag = null;
      canvas.classList.remove('dragging');
    };
    canvas.addEventListener('pointerup', (ev) => {
      endDrag();
      // A drag that ended off the canvas: the pointer has left it.
      const { mx, my } = canvasPoint(ev);
      if (mx < 0 || my < 0 || mx >= state.W || my >= state.H) leaveProbe();
    });
    canvas.addEventListener('pointercancel', endDrag);
    canvas.addEventListener('pointerleave', leaveProbe);
    canvas.addEventListener('dblclick', () => {
      fit();
      draw();
    });
    document.addEventListener('keydown', (ev) => {
      if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
      const t = ev.target;
      if (t && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA' || t.isContentEditable)) return;
      const keys = { '1': () => setMode('a'), '2': () => setMode('b'), s: () => setMode('side-by-side'),
        w: () => setMode('swipe'), e: () => setMode('error'), f: flip, '0': () => { fit(); draw(); } };
      const action = keys[ev.key.length === 1 ? ev.key.toLowerCase() : ''];
      if (action) {
        ev.preventDefault();
        action();
      }
    });
    window.addEventListener('resize', () => {
      const wasFitted = state.fitted;
      layout();
      if (wasFitted) fit();
      draw();
    });

    // -------- the API for tests (and the console)

    let resolveReady;
    const ready = new Promise((resolve) => (resolveReady = resolve));
    const api = {
      ready,
      whenIdle,
      // A bad id or mode rejects the promise (with the message), as a failed load would; nothing throws.
      pick(aId, bId) {
        try {
          setPair(str(aId), str(bId));
        } catch (e) {
          return Promise.reject(new Error('vriViewer.pick: ' + e.message));
        }
        return whenIdle();
      },
      setMode(mode) {
        try {
          setMode(str(mode));
        } catch (e) {
          return Promise.reject(new Error('vriViewer.setMode: ' + e.message + ' (modes: ' + MODES.map((m) => m[0]).join(', ') + ')'));
        }
        return whenIdle();
      },
      // Centre image pixel (x, y) in the (first) panel at `ppp` CSS pixels per image pixel: with a whole
      // ppp the pixel covers exactly a ppp x ppp block of the canvas.
      zoomTo(x, y, ppp) {
        state.s = clamp(Number(ppp) || 1, MIN_SCALE, MAX_SCALE);
        state.cx = Number(x) + 0.5;
        state.cy = Number(y) + 0.5;
        state.fitted = false;
        draw();
        return whenIdle();
      },
      fit() {
        fit();
        draw();
      },
      // Where image pixel (x, y)'s centre is in the first panel: x, y in viewport CSS pixels (as
      // mouse events take them), pageX, pageY with the page's scroll, canvasX, canvasY within #view.
      canvasPointOf(x, y) {
        const o = originOf(panels()[0]);
        const canvasX = o.x + (Number(x) + 0.5) * state.s;
        const canvasY = o.y + (Number(y) + 0.5) * state.s;
        const r = canvas.getBoundingClientRect();
        return { x: r.left + canvasX, y: r.top + canvasY, pageX: r.left + window.scrollX + canvasX,
          pageY: r.top + window.scrollY + canvasY, canvasX, canvasY };
      },
      state() {
        return { a: state.a.id, b: state.b.id, mode: state.mode, cx: state.cx, cy: state.cy, s: state.s,
          look: { ...state.look }, errorScale: state.errorScale && { ...state.errorScale } };
      },
    };

    function start() {
      layout();
      const [a, b] = defaultPair();
      setPair(a, b);
      whenIdle().then(() => {
        document.body.dataset.ready = '1';
        resolveReady();
      });
    }

    return { section, api, start, pickOne };
  }

  // ---------------------------------------------------------------- start

  function start() {
    // The page's own sentence for a browser that never runs this script (results_viewer.cpp): not needed here.
    const fallback = document.getElementById('vri-fallback');
    if (fallback) fallback.remove();
    try {
      const experiment = document.getElementById('vri-experiment');
      const index = document.getElementById('vri-index');
      if (experiment) experimentPage(parseJsonScript(experiment));
      else if (index) indexPage(parseJsonScript(index));
    } catch (e) {
      fatal(e);
    }
  }

  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
  else start();
})();
