// Reads a vri scene card (docs/scene-card.md) and the voxels it names, and evaluates its transfer
// function. Everything here follows the card's documentation only: an adapter is a renderer's author
// reading the card, not a caller of vri.
import fs from 'node:fs';
import path from 'node:path';

export class CardError extends Error {}

const VOXEL_BYTES = { uint8: 1, uint16: 2, float32: 4 };

function need(condition, what) {
  if (!condition) throw new CardError(what);
}

function isVec3(v) {
  return Array.isArray(v) && v.length === 3 && v.every(Number.isFinite);
}

function isMat4(m) {
  return Array.isArray(m) && m.length === 4 && m.every((row) => Array.isArray(row) && row.length === 4 && row.every(Number.isFinite));
}

// The card, checked for what the adapters read; a card of another format or version is refused.
export function loadCard(cardPath) {
  let card;
  try {
    card = JSON.parse(fs.readFileSync(cardPath, 'utf8'));
  } catch (e) {
    throw new CardError(`${cardPath}: cannot read the card: ${e.message}`);
  }
  need(card && card.format === 'vri-scene-card' && card.version === 1, `${cardPath}: not a version 1 vri scene card`);
  const { volume, camera, transfer_function: tf } = card;
  need(volume && camera && tf && card.output, `${cardPath}: the card lacks volume, camera, transfer_function or output`);
  need(volume.kind === 'volume', `${cardPath}: volume.kind '${volume.kind}': only sampled volumes are rendered (no analytic field)`);
  need(Array.isArray(volume.dims) && volume.dims.length === 3 && volume.dims.every((n) => Number.isInteger(n) && n >= 1),
    `${cardPath}: volume.dims must be three positive integers`);
  need(volume.voxel_type in VOXEL_BYTES, `${cardPath}: volume.voxel_type '${volume.voxel_type}' is not uint8, uint16 or float32`);
  need(volume.box && isVec3(volume.box.lo) && isVec3(volume.box.hi), `${cardPath}: volume.box needs lo and hi`);
  need(['cell', 'node'].includes(volume.grid_convention), `${cardPath}: volume.grid_convention must be cell or node`);
  need(isMat4(volume.world_from_voxel_index), `${cardPath}: volume.world_from_voxel_index must be a 4x4 matrix`);
  const m = volume.world_from_voxel_index;
  need([[0, 1], [0, 2], [1, 0], [1, 2], [2, 0], [2, 1]].every(([r, c]) => m[r][c] === 0) && m[0][0] > 0 && m[1][1] > 0 && m[2][2] > 0,
    `${cardPath}: volume.world_from_voxel_index is not an axis-aligned scale and shift, which the adapters assume`);
  need(volume.value_to_s && Number.isFinite(volume.value_to_s.lo) && Number.isFinite(volume.value_to_s.inverse_range),
    `${cardPath}: volume.value_to_s needs lo and inverse_range`);
  need(Array.isArray(tf.points) && tf.points.length >= 1 &&
    tf.points.every((p) => ['s', 'r', 'g', 'b', 'tau'].every((k) => Number.isFinite(p[k]))),
  `${cardPath}: transfer_function.points must be {s, r, g, b, tau} numbers`);
  need(['color-times-extinction', 'color'].includes(tf.emission), `${cardPath}: unknown emission '${tf.emission}'`);
  need(Number.isInteger(camera.width) && Number.isInteger(camera.height) && camera.width >= 1 && camera.height >= 1,
    `${cardPath}: camera.width and camera.height must be positive integers`);
  need(isVec3(camera.eye) && isVec3(camera.target) && isVec3(camera.up) && Number.isFinite(camera.fov_y_degrees),
    `${cardPath}: camera needs eye, target, up and fov_y_degrees`);
  need(isMat4(camera.view_matrix) && isMat4(camera.projection_matrix), `${cardPath}: camera needs view_matrix and projection_matrix`);
  need(camera.basis && isVec3(camera.basis.forward) && isVec3(camera.basis.right) && isVec3(camera.basis.up),
    `${cardPath}: camera.basis needs forward, right and up`);
  return card;
}

// The voxels as a Buffer in the card's plain layout (x fastest, little-endian, no header), read from the
// file the card names relative to its own folder, and checked against the card's byte count.
export function loadVoxels(card, cardPath) {
  const { volume } = card;
  const voxels = volume.voxels;
  need(voxels && typeof voxels.file === 'string' && voxels.file.length > 0, `${cardPath}: volume.voxels.file is missing`);
  need((voxels.byte_order ?? 'little-endian') === 'little-endian', `${cardPath}: only little-endian voxels are read`);
  const file = path.resolve(path.dirname(path.resolve(cardPath)), voxels.file);
  const header = voxels.header_bytes ?? 0;
  const expected = volume.dims[0] * volume.dims[1] * volume.dims[2] * VOXEL_BYTES[volume.voxel_type];
  let data;
  try {
    data = fs.readFileSync(file);
  } catch (e) {
    throw new CardError(`${file}: cannot read the voxels: ${e.code ?? e.message}`);
  }
  need(data.length === header + expected, `${file}: ${data.length} bytes, the card says ${header} + ${expected}`);
  return data.subarray(header);
}

// (r, g, b, tau) at s: piecewise linear, constant beyond the ends, the right-hand point at a jump.
export function makeTransferFunction(card) {
  const points = card.transfer_function.points;
  return (s) => {
    const n = points.length;
    if (!(s >= points[0].s)) return [points[0].r, points[0].g, points[0].b, points[0].tau];
    if (!(s < points[n - 1].s)) return [points[n - 1].r, points[n - 1].g, points[n - 1].b, points[n - 1].tau];
    let i = 0;
    while (i + 1 < n - 1 && points[i + 1].s <= s) i++;
    const a = points[i];
    const b = points[i + 1];
    const w = (s - a.s) / (b.s - a.s);
    return ['r', 'g', 'b', 'tau'].map((k) => a[k] + w * (b[k] - a[k]));
  };
}

// The voxel value v (the voxels' own units) whose s is s: the inverse of the card's s = (v - lo) inverse_range.
export function sToValue(card, s) {
  const { lo, inverse_range: inv } = card.volume.value_to_s;
  return lo + s / inv;
}

// The step in voxels that the adapter should use: --step, else the card's fixed step, else null (the
// renderer's own default).
export function requestedStep(card, override) {
  if (override !== undefined) return override;
  const step = card.method?.step;
  return Number.isFinite(step) && step > 0 ? step : null;
}

// The world length of one voxel of the card's step along a world direction d. The card measures steps on the
// ray's texture-space segment scaled by method.dims_for_placement (else dims), so one voxel along d is
// |d| / |d dims / (hi - lo)| world units: the cell size for an axis-aligned d. A renderer whose voxel is the
// texture's cell passes dims = volume.dims.
export function worldPerVoxelAlong(card, d, dims = card.method?.dims_for_placement ?? card.volume.dims) {
  const { lo, hi } = card.volume.box;
  const voxels = Math.hypot(...[0, 1, 2].map((a) => (d[a] * dims[a]) / (hi[a] - lo[a])));
  return Math.hypot(d[0], d[1], d[2]) / voxels;
}
