// vtk.js's GPU ray caster (vtkVolume + vtkVolumeMapper, WebGL2) on the card's scene, drawn into its canvas
// and read back with vtk.js's own getPixelData (its framebuffer is 8-bit RGBA).
import '@kitware/vtk.js/Rendering/Profiles/Volume.js';
import vtkDataArray from '@kitware/vtk.js/Common/Core/DataArray.js';
import vtkImageData from '@kitware/vtk.js/Common/DataModel/ImageData.js';
import vtkPiecewiseFunction from '@kitware/vtk.js/Common/DataModel/PiecewiseFunction.js';
import vtkColorTransferFunction from '@kitware/vtk.js/Rendering/Core/ColorTransferFunction.js';
import vtkRenderer from '@kitware/vtk.js/Rendering/Core/Renderer.js';
import vtkRenderWindow from '@kitware/vtk.js/Rendering/Core/RenderWindow.js';
import vtkRenderWindowInteractor from '@kitware/vtk.js/Rendering/Core/RenderWindowInteractor.js';
import vtkVolume from '@kitware/vtk.js/Rendering/Core/Volume.js';
import vtkVolumeMapper from '@kitware/vtk.js/Rendering/Core/VolumeMapper.js';
import vtkOpenGLRenderWindow from '@kitware/vtk.js/Rendering/OpenGL/RenderWindow.js';
import { fetchBytes, timeFrames as time, toBase64, waitForGpu, webglRenderer } from './common.js';

let state = null;

// vtk.js jitters each ray's start with a texture of Math.random() values: a fixed seed (the card's) makes the
// image the same on every run (the jitter pattern stays vtk.js's).
function seedMathRandom(seed) {
  let a = seed >>> 0;
  Math.random = () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

function imageData(scene, raw) {
  const Type = { uint8: Uint8Array, uint16: Uint16Array, float32: Float32Array }[scene.voxelType];
  const image = vtkImageData.newInstance({ origin: scene.origin, spacing: scene.spacing });
  image.setExtent(0, scene.dims[0] - 1, 0, scene.dims[1] - 1, 0, scene.dims[2] - 1);
  image.getPointData().setScalars(vtkDataArray.newInstance({ name: 'scalars', numberOfComponents: 1, values: new Type(raw) }));
  return image;
}

export async function setup(scene) {
  seedMathRandom(scene.seed);
  const { width, height } = scene;
  const view = document.getElementById('view');
  view.style.width = `${width}px`;
  view.style.height = `${height}px`;

  const renderWindow = vtkRenderWindow.newInstance();
  const renderer = vtkRenderer.newInstance();
  renderer.setBackground(0, 0, 0, 0);
  renderWindow.addRenderer(renderer);
  const glWindow = vtkOpenGLRenderWindow.newInstance();
  renderWindow.addView(glWindow);
  glWindow.setContainer(view);
  glWindow.setSize(width, height);
  const interactor = vtkRenderWindowInteractor.newInstance(); // the mapper asks it whether it is animating
  interactor.setView(glWindow);
  interactor.initialize();

  const mapper = vtkVolumeMapper.newInstance();
  mapper.setInputData(imageData(scene, await fetchBytes('/data/voxels')));
  mapper.setSampleDistance(scene.sampleDistance);
  mapper.setAutoAdjustSampleDistances(false);
  mapper.setImageSampleDistance(1);
  mapper.setMaximumSamplesPerRay(scene.maximumSamples);

  const colour = vtkColorTransferFunction.newInstance();
  const opacity = vtkPiecewiseFunction.newInstance();
  for (const [v, r, g, b] of scene.colourPoints) colour.addRGBPoint(v, r, g, b);
  for (const [v, a] of scene.opacityPoints) opacity.addPoint(v, a);
  const volume = vtkVolume.newInstance();
  volume.setMapper(mapper);
  const property = volume.getProperty();
  property.setRGBTransferFunction(0, colour);
  property.setScalarOpacity(0, opacity);
  property.setScalarOpacityUnitDistance(0, scene.opacityUnitDistance);
  property.setInterpolationTypeToLinear();
  property.setShade(false);
  renderer.addVolume(volume);

  const camera = renderer.getActiveCamera();
  camera.setPosition(...scene.eye);
  camera.setFocalPoint(...scene.target);
  camera.setViewUp(...scene.up);
  camera.setViewAngle(scene.viewAngle);
  camera.setWindowCenter(...scene.windowCenter);
  camera.setClippingRange(scene.near, scene.far);

  const gl = glWindow.getContext();
  state = { renderWindow, glWindow, gl, width, height };
  return { webglRenderer: webglRenderer(gl), settings: {}, notes: [] };
}

export function timeFrames(frames) {
  return time(frames, () => state.renderWindow.render(), () => waitForGpu(state.gl, false));
}

// The drawing buffer is not preserved across tasks: render and read in the same one.
export function readPixels() {
  state.renderWindow.render();
  const pixels = state.glWindow.getPixelData(0, 0, state.width - 1, state.height - 1);
  return { format: 'uint8', base64: toBase64(pixels) };
}
