// The adapter's two outputs, each written under a temporary name in its own folder and then renamed, so
// that a reader never sees half a file and a failed run leaves nothing behind.
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';

function writeAtomically(file, bytes) {
  const tmp = path.join(path.dirname(file), `.${path.basename(file)}.tmp.${process.pid}`);
  try {
    fs.writeFileSync(tmp, bytes);
    fs.renameSync(tmp, file);
  } catch (e) {
    fs.rmSync(tmp, { force: true });
    throw e;
  }
}

// An 8-bit RGBA PNG (colour type 6), rows top to bottom.
function encodePng(width, height, rgba8) {
  const chunk = (type, data) => {
    const head = Buffer.alloc(8);
    head.writeUInt32BE(data.length, 0);
    head.write(type, 4, 'latin1');
    const crc = Buffer.alloc(4);
    crc.writeUInt32BE(zlib.crc32(Buffer.concat([head.subarray(4), data])) >>> 0, 0);
    return Buffer.concat([head, data, crc]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0);
  ihdr.writeUInt32BE(height, 4);
  ihdr.set([8, 6, 0, 0, 0], 8); // 8 bits, RGBA, deflate, no filter method, no interlace
  const rows = Buffer.alloc(height * (1 + 4 * width));
  for (let y = 0; y < height; y++) {
    rows[y * (1 + 4 * width)] = 0; // filter: none
    rows.set(rgba8.subarray(y * 4 * width, (y + 1) * 4 * width), y * (1 + 4 * width) + 1);
  }
  const signature = Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]);
  return Buffer.concat([signature, chunk('IHDR', ihdr), chunk('IDAT', zlib.deflateSync(rows)), chunk('IEND', Buffer.alloc(0))]);
}

// image: { width, height, rgba: Float32Array (0..1, premultiplied, row 0 at the top), quantisation }.
// OUTPUT.f32: raw little-endian float32 RGBA, premultiplied. OUTPUT.png: 8-bit RGBA with straight alpha, as
// the PNG standard defines it (docs/outside-renderers.md): colour divided by alpha. Returns the quantisation.
export function writeImage(file, image) {
  const { width, height, rgba } = image;
  if (file.endsWith('.f32')) {
    const bytes = Buffer.alloc(rgba.length * 4);
    rgba.forEach((v, i) => bytes.writeFloatLE(v, i * 4));
    writeAtomically(file, bytes);
    return image.quantisation;
  }
  const rgba8 = Buffer.alloc(rgba.length);
  const byte = (v) => Math.round(Math.min(Math.max(v, 0), 1) * 255);
  for (let p = 0; p < rgba.length; p += 4) {
    const alpha = rgba[p + 3];
    for (let c = 0; c < 3; c++) rgba8[p + c] = alpha > 0 ? byte(rgba[p + c] / alpha) : 0;
    rgba8[p + 3] = byte(alpha);
  }
  writeAtomically(file, encodePng(width, height, rgba8));
  return '8-bit';
}

export function writeJson(file, value) {
  writeAtomically(file, JSON.stringify(value, null, 2) + '\n');
}
