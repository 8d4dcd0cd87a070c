#!/usr/bin/env node
// vtk.js's vtkVolume / vtkVolumeMapper on a vri scene card, in headless Chromium (docs/peers-web.md).
//   node tools/peers/web/vtkjs.mjs CARD.json OUTPUT.f32|OUTPUT.png STATS.json [--step H] [--frames N]
import { makeTransferFunction, sToValue, worldPerVoxelAlong } from './lib/card.mjs';
import { packageVersion, runAdapter } from './lib/run.mjs';

const TABLE = 1024; // vtk.js's colour and opacity tables: colorTextureWidth and opacityTextureWidth

function prepare(card, voxels, step) {
  const { volume, camera, transfer_function: tfCard } = card;
  const seed = card.method?.jitter?.seed ?? 1; // vri-verify --seeds varies it card by card
  const m = volume.world_from_voxel_index;
  const spacing = [m[0][0], m[1][1], m[2][2]];
  // vtk.js samples every ray at one world distance; the card's step is in voxels along the ray. They agree
  // for equal spacings; otherwise the central ray's voxel length is used.
  const voxelLength = worldPerVoxelAlong(card, camera.basis.forward);
  const sampleDistance = step === null ? 1 : step * voxelLength; // vtk.js's default: 1 world unit

  // vtk.js builds its tables by sampling the functions at TABLE points from the first to the last x; the
  // points given here are those very x, so each table entry is the card's value there. Opacity is alpha
  // for a step of the unit distance; with the unit distance set to the sample distance, vtk.js's
  // correction 1 - (1 - a)^(d / unit) leaves alpha = 1 - exp(-tau d) as it is.
  const tf = makeTransferFunction(card);
  const points = tfCard.points.map((p) => p.s);
  const sLo = Math.min(0, points[0]);
  const sHi = Math.max(1, points[points.length - 1]);
  const colourPoints = [];
  const opacityPoints = [];
  let clamped = false;
  for (let i = 0; i < TABLE; i++) {
    const s = sLo + (i / (TABLE - 1)) * (sHi - sLo);
    const [r, g, b, tau] = tf(s);
    clamped ||= [r, g, b].some((c) => c < 0 || c > 1);
    colourPoints.push([sToValue(card, s), r, g, b]);
    opacityPoints.push([sToValue(card, s), 1 - Math.exp(-tau * sampleDistance)]);
  }
  const diagonal = Math.hypot(...volume.dims.map((n, a) => n * spacing[a]));
  const tanHalf = camera.tan_half_fov_y / camera.zoom;
  const [cx, cy] = camera.zoom_centre_pixels;

  const notes = [
    `vtk.js jitters each ray's first sample by a per-pixel random fraction of the step (its jitter texture and a hash of the pixel); the adapter seeds Math.random with ${seed} (the card's method.jitter.seed, else 1) so that the pattern repeats run to run`,
    `placement: vtk.js's own, not the card's '${card.method?.placement ?? 'none'}': a first sample at the entry weighted by the jitter fraction j, then samples at t = (j + k) d, then one at the exit weighted by the remainder`,
    'vtk.js stops a ray when its alpha passes 0.99 and then sets alpha to 1',
    `colour table: ${TABLE} texels of 8 bits per channel (vtk.js uploads colours as bytes); opacity table: ${TABLE} float texels`,
    'the image is vtk.js\'s 8-bit canvas framebuffer (no float render target in vtk.js\'s volume path)',
  ];
  if (clamped) notes.push('colours outside [0, 1] are clamped by vtk.js\'s 8-bit colour table');
  if (tfCard.emission === 'color') notes.push('emission \'color\' is not honoured: vtk.js composites alpha x colour (the color-times-extinction model)');
  if (volume.grid_convention === 'node') notes.push('node grid: vtk.js\'s box is the cell box around the points, half a voxel beyond the card\'s box on each side');
  if (new Set(spacing).size > 1) notes.push(`unequal spacings: the step is ${step ?? 1} voxels along the central ray (${sampleDistance} world units) on every ray`);
  if (step === null) notes.push('the card has no fixed step: vtk.js\'s default sample distance, 1 world unit');

  return {
    scene: {
      seed,
      width: camera.width, height: camera.height, dims: volume.dims, voxelType: volume.voxel_type,
      origin: [m[0][3], m[1][3], m[2][3]], spacing,
      sampleDistance, opacityUnitDistance: sampleDistance, maximumSamples: Math.ceil(diagonal / sampleDistance) + 16,
      colourPoints, opacityPoints,
      eye: camera.eye, target: camera.target, up: camera.up,
      viewAngle: (2 * Math.atan(tanHalf) * 180) / Math.PI,
      windowCenter: [(2 * cx / camera.width - 1) * camera.zoom, (1 - 2 * cy / camera.height) * camera.zoom],
      near: camera.near, far: camera.far,
    },
    data: { '/data/voxels': voxels },
    settings: {
      step_voxels: step,
      sample_distance_world: sampleDistance,
      step_mapping: 'setSampleDistance(h x the world length of one voxel along the central ray)',
      placement: 'jittered: entry sample weighted by j in [0.01, 1), then t = (j + k) d, then the exit weighted by the remainder',
      opacity_correction: 'vtk.js\'s 1 - (1 - a)^(d / unit distance) with unit distance = d and a = 1 - exp(-tau d): alpha = 1 - exp(-tau d)',
      transfer_function_tables: `${TABLE} points at vtk.js's table positions; colour 8-bit, opacity float32`,
      interpolation: 'linear (setInterpolationTypeToLinear), no shading',
      camera: 'position, focal point, view up, vertical view angle 2 atan(tan(fov_y / 2) / zoom), window centre for the zoom centre, clipping range = the card\'s near and far',
      grid: 'vtkImageData origin = the card\'s voxel 0, spacing = the card\'s (vtk.js bounds reach half a voxel beyond the points, the card\'s cell box)',
      early_termination: 'alpha > 0.99 (vtk.js\'s, fixed)',
    },
    notes,
  };
}

process.exitCode = await runAdapter({
  name: 'vtkjs',
  renderer: { name: 'vtk.js vtkVolumeMapper', version: packageVersion('@kitware/vtk.js') },
  pageModule: '/page/vtkjs.js',
  prepare,
});
