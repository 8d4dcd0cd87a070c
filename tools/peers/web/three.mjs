#!/usr/bin/env node
// three.js's VolumeRenderShader1 on a vri scene card, in headless Chromium (docs/peers-web.md).
//   node tools/peers/web/three.mjs CARD.json OUTPUT.f32|OUTPUT.png STATS.json [--step H] [--frames N]
//                                  [--texel-centres]
// --texel-centres is a diagnostic, not three.js: it moves the shader's texture look-up by half a texel so that
// voxel i is read at object position i, to measure how much of the error is the shader's half-voxel shift.
import { makeTransferFunction, sToValue } from './lib/card.mjs';
import { packageVersion, runAdapter } from './lib/run.mjs';

const DEFAULT_STEP = 1.0; // the shader's relative_step_size: one voxel
const TF_TEXELS = 256; // as three.js's colour maps (cm_viridis.png and cm_gray.png are 256 x 1)

function prepare(card, voxels, step, flags) {
  const { volume, camera } = card;
  const h = step ?? DEFAULT_STEP;
  const tf = makeTransferFunction(card);
  // apply_colormap reads texel k at normalised value k / (n - 1); the normalised value is s when u_clim
  // spans s in [0, 1], in the texture's units (an R8 texture holds v / 255).
  const texels = [];
  for (let k = 0; k < TF_TEXELS; k++) texels.push(...tf(k / (TF_TEXELS - 1)));
  const unit = volume.voxel_type === 'uint8' ? 255 : 1;
  const clim = [sToValue(card, 0) / unit, sToValue(card, 1) / unit];
  const m = volume.world_from_voxel_index;
  const spacing = [m[0][0], m[1][1], m[2][2]];
  const boxWorld = volume.dims.map((n, a) => n * spacing[a]); // the shader's box is n voxels wide
  const maxSamples = Math.hypot(...volume.dims) / h + 2;
  if (maxSamples > 1048576) throw new Error(`a step of ${h} voxels needs ${Math.ceil(maxSamples)} samples a ray, more than the 1048576 allowed`);

  const notes = [
    'VolumeRenderShader1 has only MIP and isosurface modes: the adapter adds an emission-absorption mode to its fragment shader that composites the samples the shader itself walks (its ray set-up, box clipping, step count, trilinear texture sample and apply_colormap), front to back with alpha = 1 - exp(-tau dx)',
    `placement: the shader's own, not the card's '${card.method?.placement ?? 'none'}': n = int(L/h + 0.5) samples at t_k = k L / n, k = 0 ... n - 1, from the entry face (a left Riemann sum, L the ray's length in voxels); none of paper A's four`,
    flags['texel-centres']
      ? 'DIAGNOSTIC --texel-centres: the shader\'s half-voxel shift is corrected (texture coordinate p / n + 0.5 / n): this is not three.js\'s image'
      : 'the shader clips rays to [-0.5, n - 0.5] (voxel i centred at i) but samples texture coordinate p / n, where texel i is centred at p = i + 0.5: the volume is read half a voxel off along each axis (the shader\'s, kept)',
    `transfer function: a ${TF_TEXELS}-texel float RGBA texture (r, g, b, tau) sampled at s = k / ${TF_TEXELS - 1}, linearly filtered: points between texels are smoothed`,
  ];
  if (volume.grid_convention === 'node') notes.push('node grid: the shader\'s box is the cell box around the nodes, half a voxel beyond the card\'s box on each side');
  if (volume.voxel_type === 'uint16') notes.push('uint16 voxels are uploaded as float32 (WebGL2 filters no 16-bit integer texture)');
  const { lo, hi } = volume.box;
  if (camera.eye.every((e, a) => e >= lo[a] && e <= hi[a])) notes.push('the eye is inside the box: the shader does not start rays at the eye');
  if (step === null) notes.push(`the card has no fixed step: the shader's default, ${DEFAULT_STEP} voxel`);

  return {
    scene: {
      width: camera.width, height: camera.height, dims: volume.dims, voxelType: volume.voxel_type,
      tfTexels: texels, clim, step: h, boxWorld, emission: card.transfer_function.emission,
      worldFromVoxel: m, view: camera.view_matrix, projection: camera.projection_matrix,
      texelCentres: Boolean(flags['texel-centres']),
    },
    data: { '/data/voxels': voxels },
    settings: {
      step_voxels: h,
      step_mapping: 'relative_step_size = h: the shader steps in object units, which are voxel indices (componentwise, like the card\'s voxels)',
      placement: 'left endpoint: t_k = k L / n, n = int(L / h + 0.5)',
      opacity_correction: 'alpha = 1 - exp(-tau dx), dx = |step in texture units x box size in world units| (exact for the step taken)',
      transfer_function_texture: `${TF_TEXELS} x 1 RGBA32F, linear, u_clim = [${clim[0]}, ${clim[1]}]`,
      volume_texture: volume.voxel_type === 'uint8' ? 'R8 (normalised), linear' : 'R32F, linear',
      interpolation: 'trilinear (the GPU\'s texture filtering)',
      camera: 'the card\'s view_matrix and projection_matrix as they are',
      blending: 'none: the mode writes premultiplied RGBA over a (0, 0, 0, 0) clear',
    },
    notes,
  };
}

process.exitCode = await runAdapter({
  name: 'three',
  renderer: { name: 'three.js VolumeRenderShader1', version: packageVersion('three') },
  pageModule: '/page/three.js',
  flags: ['--texel-centres'],
  prepare,
});
