// NiiVue's 3D render view (its volume ray caster, WebGL2) on the card's scene, read back from its canvas
// (an 8-bit RGBA framebuffer). The volume arrives as the NIfTI file /data/volume.nii that the adapter made.
import { Niivue } from '@niivue/niivue';
import { makeCanvas, timeFrames as time, toBase64, waitForGpu, webglRenderer } from './common.js';

let state = null;

// The image-plane position (NDC x, y) of a mm point under NiiVue's own 3D matrices.
function ndcOf(nv, ltwh, az, el, mm) {
  const [mvp] = nv.calculateMvpMatrix(null, ltwh, az, el);
  const clip = [0, 1, 2, 3].map((r) => mvp[r] * mm[0] + mvp[4 + r] * mm[1] + mvp[8 + r] * mm[2] + mvp[12 + r]);
  return [clip[0] / clip[3], clip[1] / clip[3]];
}

export async function setup(scene) {
  const { width, height } = scene;
  const canvas = makeCanvas(width, height);
  const nv = new Niivue({
    backColor: [0, 0, 0, 0], show3Dcrosshair: false, isColorbar: false, isOrientCube: false,
    isOrientationTextVisible: false, isRuler: false, showLegend: false, isResizeCanvas: false,
    forceDevicePixelRatio: 1, logLevel: 'error', dragAndDropEnabled: false, loadingText: '', isAntiAlias: false,
  });
  await nv.attachToCanvas(canvas);
  // Everything that would re-run NiiVue's volume upload (seconds on SwiftShader) is set before the load.
  nv.setSliceType(nv.sliceTypeRender);
  if (nv.opts.gradientAmount !== 0) throw new Error('NiiVue\'s default is no longer plain compositing (gradientAmount 0)');
  nv.addColormap('vri', scene.colormap);
  await nv.loadVolumes([{ url: '/data/volume.nii', colormap: 'vri', cal_min: scene.calMin, cal_max: scene.calMax, opacity: 1 }]);
  const image = nv.volumes[0];
  if (image.cal_min !== scene.calMin || image.cal_max !== scene.calMax) {
    image.cal_min = scene.calMin;
    image.cal_max = scene.calMax;
    nv.updateGLVolume();
  }
  nv.setRenderAzimuthElevation(scene.azimuth, scene.elevation);

  // Zoom: NiiVue's orthographic view is 0.8 furthestFromPivot / volScaleMultiplier high (half-height, or
  // half-width in a portrait canvas); pan: nv.position moves the model in the view plane, which is linear in
  // NDC, so two probes find the shift that puts the card's image centre at NDC (0, 0).
  nv.setPivot3D();
  nv.scene.volScaleMultiplier = (0.8 * nv.furthestFromPivot) / scene.halfExtent;
  const ltwh = [0, 0, width, height];
  const probe = (p) => {
    nv.position = p;
    return ndcOf(nv, ltwh, scene.azimuth, scene.elevation, scene.centreMM);
  };
  const base = probe([0, 0, 0]);
  const dx = probe([1, 0, 0]);
  const dy = probe([0, 1, 0]);
  const a = [dx[0] - base[0], dy[0] - base[0], dx[1] - base[1], dy[1] - base[1]];
  const det = a[0] * a[3] - a[1] * a[2];
  nv.position = [(-base[0] * a[3] + base[1] * a[1]) / det, (base[0] * a[2] - base[1] * a[0]) / det, 0];

  // The view direction NiiVue will use must be the card's (the adapter derived azimuth and elevation from
  // NiiVue's model matrix; this catches a change of that convention).
  const ray = nv.calculateRayDirection(scene.azimuth, scene.elevation);
  if (Math.hypot(...[0, 1, 2].map((i) => ray[i] - scene.forwardMM[i])) > 1e-3) {
    throw new Error(`NiiVue's ray (${Array.from(ray)}) is not the card's forward (${scene.forwardMM}) in its mm space`);
  }
  const gl = nv.gl;
  state = { nv, gl, width, height };
  return {
    webglRenderer: webglRenderer(gl),
    settings: {
      ray_direction_mm: Array.from(ray),
      vol_scale_multiplier: nv.scene.volScaleMultiplier,
      furthest_from_pivot_mm: nv.furthestFromPivot,
      pivot_mm: Array.from(nv.pivot3D),
      pan: nv.position,
    },
    notes: [],
  };
}

export function timeFrames(frames) {
  return time(frames, () => state.nv.drawScene(), () => waitForGpu(state.gl, false));
}

// The drawing buffer is not preserved across tasks: draw and read in the same one.
export function readPixels() {
  const { nv, gl, width, height } = state;
  nv.drawScene();
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  const pixels = new Uint8Array(width * height * 4);
  gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  return { format: 'uint8', base64: toBase64(pixels) };
}
