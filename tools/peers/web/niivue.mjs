#!/usr/bin/env node
// NiiVue's 3D render view on a vri scene card, in headless Chromium (docs/peers-web.md).
//   node tools/peers/web/niivue.mjs CARD.json OUTPUT.f32|OUTPUT.png STATS.json [--step H] [--frames N]
import { makeTransferFunction, sToValue, worldPerVoxelAlong } from './lib/card.mjs';
import { makeNifti } from './lib/nifti.mjs';
import { packageVersion, runAdapter } from './lib/run.mjs';

const LUT = 256; // NiiVue's colour maps: 256 RGBA entries of 8 bits

const times = (m, v) => m.map((row) => row.reduce((sum, x, i) => sum + x * v[i], 0));
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const degrees = (radians) => (radians * 180) / Math.PI;

// NiiVue's screen up is always its mm +Z (superior) seen from the view direction. A proper signed axis
// permutation P takes the card's world to NiiVue's mm with the card's up axis on +Z (X = s x_b, Y = x_c,
// Z = s x_a: a cyclic permutation, and two sign flips when s = -1, so det P = +1 and nothing is mirrored).
function upToSuperior(up) {
  const a = [0, 1, 2].reduce((best, i) => (Math.abs(up[i]) > Math.abs(up[best]) ? i : best), 0);
  const s = Math.sign(up[a]);
  const P = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  P[0][(a + 1) % 3] = s;
  P[1][(a + 2) % 3] = 1;
  P[2][a] = s;
  return { P, axisAligned: up.filter((x) => x !== 0).length === 1 };
}

function prepare(card, voxels, step) {
  const { volume, camera } = card;
  const { P, axisAligned } = upToSuperior(camera.up);
  const W = volume.world_from_voxel_index.slice(0, 3);
  const srow = P.map((row) => [0, 1, 2, 3].map((c) => row[0] * W[0][c] + row[1] * W[1][c] + row[2] * W[2][c]));
  const spacing = [W[0][0], W[1][1], W[2][2]];

  // NiiVue's ray for azimuth az and elevation el is (cos el sin az, cos el cos az, -sin el) in mm (from its
  // model matrix: rotateX(270 - el) after rotateZ(az - 180); the page checks it).
  const { forward, right, up } = camera.basis;
  const f = times(P, forward);
  const elevation = degrees(Math.asin(-f[2]));
  const azimuth = degrees(Math.atan2(f[0], f[1]));
  // The orthographic stand-in for the card's perspective: the card's view at the target's depth D, centred
  // on the point the image centre sees there, as high (or, in a portrait image, as wide) as the card's.
  const depth = dot(camera.target.map((t, i) => t - camera.eye[i]), forward);
  const [cx, cy] = camera.zoom_centre_pixels;
  const x = (2 * cx / camera.width - 1) * camera.tan_half_fov_x;
  const y = (1 - 2 * cy / camera.height) * camera.tan_half_fov_y;
  const centre = camera.eye.map((e, i) => e + depth * (forward[i] + x * right[i] + y * up[i]));
  const halfExtent = (depth * (camera.width >= camera.height ? camera.tan_half_fov_y : camera.tan_half_fov_x)) / camera.zoom;

  // NiiVue steps one voxel (in voxel index units) and applies the colour map's alpha per step, without
  // correction; the colour map's entry k is read at s = (k + 0.5) / 256 (a linearly filtered 256-texel map).
  const dx = worldPerVoxelAlong(card, forward, volume.dims); // NiiVue's voxel: one texel of its texture
  const tf = makeTransferFunction(card);
  const colormap = { R: [], G: [], B: [], A: [], I: [] };
  for (let k = 0; k < LUT; k++) {
    const [r, g, b, tau] = tf((k + 0.5) / LUT);
    const byte = (v) => Math.round(Math.min(Math.max(v, 0), 1) * 255);
    colormap.R.push(byte(r));
    colormap.G.push(byte(g));
    colormap.B.push(byte(b));
    colormap.A.push(byte(1 - Math.exp(-tau * dx)));
    colormap.I.push(k);
  }

  const notes = [
    'NiiVue\'s 3D view is orthographic: every ray runs along the card\'s forward direction; the view is scaled to match the card\'s perspective at the target\'s depth only',
    `NiiVue's step is fixed at one voxel along the ray${step !== null && step !== 1 ? `: the step ${step} is not honoured` : ''}`,
    'placement: NiiVue\'s own, not the card\'s: a per-pixel pseudo-random start (a hash of the pixel) within the first voxel, then one voxel apart until the exit',
    'pre-classification: each voxel is coloured through the 8-bit colour map first and the RGBA is interpolated; samples with alpha below 0.01 are skipped',
    'opacity: the colour map\'s alpha is taken per one-voxel step, 1 - exp(-tau dx) with dx the central ray\'s voxel length, quantised to 8 bits',
    'NiiVue stops a ray when its alpha passes 0.95 and divides every ray\'s alpha by 0.95 (opacity x 1/0.95)',
    'NiiVue\'s volume shader writes premultiplied colour but draws it with blendFunc(SRC_ALPHA, ONE_MINUS_SRC_ALPHA): the framebuffer holds colour x alpha\' and alpha\'^2 (alpha\' = alpha / 0.95)',
    'the image is NiiVue\'s 8-bit canvas framebuffer',
  ];
  // NiiVue skips samples whose alpha is below 0.01: where the map's 8-bit alpha rounds below that, a visible
  // medium (tau > 0) vanishes.
  const lost = colormap.A.map((a, k) => ({ a, s: (k + 0.5) / LUT, tau: tf((k + 0.5) / LUT)[3] })).filter((e) => e.tau > 0 && e.a / 255 < 0.01);
  if (lost.length) notes.push(`where 0 < tau dx and the 8-bit alpha is below 0.01 (${lost.length} of ${LUT} map entries, s from ${lost[0].s.toFixed(3)}), NiiVue skips the sample: that medium is not drawn`);
  if (!axisAligned) notes.push('the card\'s up is not along an axis: NiiVue\'s screen up is the nearest axis seen from the view direction (the roll differs)');
  if (volume.grid_convention === 'node') notes.push('node grid: NiiVue\'s box is the cell box around the voxels, half a voxel beyond the card\'s box on each side');
  if (new Set(spacing).size > 1) notes.push('unequal spacings: alpha is set for the central ray\'s voxel length on every ray');
  if (card.transfer_function.emission === 'color') notes.push('emission \'color\' is not honoured: NiiVue composites alpha x colour');
  if (card.transfer_function.points.some((p) => [p.r, p.g, p.b].some((c) => c < 0 || c > 1))) notes.push('colours outside [0, 1] are clamped by the 8-bit colour map');

  return {
    scene: {
      width: camera.width, height: camera.height, colormap,
      calMin: sToValue(card, 0), calMax: sToValue(card, 1),
      azimuth, elevation, forwardMM: f, centreMM: times(P, centre), halfExtent,
    },
    data: { '/data/volume.nii': makeNifti(volume.dims, volume.voxel_type, voxels, srow, spacing) },
    settings: {
      step_voxels: 1,
      step_mapping: 'none: NiiVue\'s step is one voxel, fixed',
      placement: 'pseudo-random start within the first voxel, then one voxel apart',
      opacity_correction: 'none in NiiVue (per-step alpha); the colour map\'s alpha is 1 - exp(-tau dx) for dx = one voxel along the central ray',
      colour_map: `${LUT} RGBA entries, 8 bits, entry k at s = (k + 0.5) / ${LUT}; cal_min and cal_max span s in [0, 1]`,
      interpolation: 'trilinear on the classified RGBA8 volume (pre-classification)',
      camera: `orthographic, azimuth ${azimuth} and elevation ${elevation} degrees; world to NiiVue mm by a signed axis permutation putting the card's up on +Z`,
      volume_file: 'NIfTI-1 made from the card\'s voxels, sform = P x world_from_voxel_index (float32)',
      early_termination: 'alpha > 0.95 (NiiVue\'s, fixed)',
    },
    notes,
  };
}

process.exitCode = await runAdapter({
  name: 'niivue',
  renderer: { name: 'NiiVue', version: packageVersion('@niivue/niivue') },
  pageModule: '/page/niivue.js',
  prepare,
});
