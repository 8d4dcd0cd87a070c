// three.js's volume ray caster, VolumeRenderShader1 (examples/jsm/shaders/VolumeShader.js), on the card's
// scene, set up as three.js's own example webgl_texture3d does (a box of the volume's size in voxels,
// drawn with its back faces) and drawn into a float render target.
import * as THREE from 'three';
import { VolumeRenderShader1 } from 'three/addons/shaders/VolumeShader.js';
import { fetchBytes, makeCanvas, timeFrames as time, toBase64, waitForGpu, webglRenderer } from './common.js';

let state = null;

function patch(source, from, to) {
  if (source.split(from).length !== 2) throw new Error(`VolumeRenderShader1 has changed: '${from}' is not in it once`);
  return source.replace(from, to);
}

// VolumeRenderShader1 has MIP (u_renderstyle 0) and isosurface (1) modes only. The emission-absorption
// mode (2) added here walks the very samples the shader's own modes walk (its start_loc, step, nsteps and
// sample1, through its apply_colormap) and composites them front to back. Its step size, a constant of
// the shader, becomes a uniform so that the card's step can be set; its loop bound grows to match.
const DVR = `
uniform vec3 u_box_world;   // the box's world size: a texture-space step times it is the step in world units
uniform int u_emission;     // 0: source = colour x extinction (Max), 1: source = colour
void cast_dvr(vec3 start_loc, vec3 step, int nsteps) {
	float dx = length(step * u_box_world);
	vec3 colour = vec3(0.0);
	float transparency = 1.0;
	vec3 loc = start_loc;
	for (int iter = 0; iter < MAX_STEPS; iter++) {
		if (iter >= nsteps)
			break;
		vec4 tf = apply_colormap(sample1(loc));   // r, g, b, extinction per world unit
		float alpha = 1.0 - exp(-tf.a * dx);
		float weight = u_emission == 0 ? alpha : (tf.a > 0.0 ? alpha / tf.a : dx);
		colour += transparency * weight * tf.rgb;
		transparency *= 1.0 - alpha;
		loc += step;
	}
	gl_FragColor = vec4(colour, 1.0 - transparency);   // premultiplied
}
`;

function fragmentShader(texelCentres) {
  let s = VolumeRenderShader1.fragmentShader;
  s = patch(s, 'const int MAX_STEPS = 887;', 'const int MAX_STEPS = 1048576;');
  s = patch(s, 'const float relative_step_size = 1.0;', 'uniform float relative_step_size;');
  s = patch(s, 'void cast_iso(vec3 start_loc, vec3 step, int nsteps, vec3 view_ray);',
    'void cast_iso(vec3 start_loc, vec3 step, int nsteps, vec3 view_ray);\nvoid cast_dvr(vec3 start_loc, vec3 step, int nsteps);');
  s = patch(s, 'cast_iso(start_loc, step, nsteps, view_ray);\n',
    'cast_iso(start_loc, step, nsteps, view_ray);\n\t\t\t\t\t\telse if (u_renderstyle == 2)\n\t\t\t\t\t\t\t\tcast_dvr(start_loc, step, nsteps);\n');
  // The discard of faint fragments belongs to the MIP and ISO modes: it would cut the integral's tails.
  s = patch(s, 'if (gl_FragColor.a < 0.05)', 'if (u_renderstyle != 2 && gl_FragColor.a < 0.05)');
  if (texelCentres) { // the diagnostic --texel-centres: voxel i's texel centre at object position i
    s = patch(s, 'return texture(u_data, texcoords.xyz).r;', 'return texture(u_data, texcoords.xyz + 0.5 / u_size).r;');
  }
  return s + DVR;
}

function volumeTexture(scene, raw) {
  const [nx, ny, nz] = scene.dims;
  // uint8 stays an R8 texture (normalised to v / 255, as three.js uploads it); uint16 and float32 become R32F
  // (WebGL2 filters no 16-bit integer format without EXT_texture_norm16).
  const data = scene.voxelType === 'uint8' ? new Uint8Array(raw)
    : scene.voxelType === 'uint16' ? Float32Array.from(new Uint16Array(raw)) : new Float32Array(raw);
  const texture = new THREE.Data3DTexture(data, nx, ny, nz);
  texture.format = THREE.RedFormat;
  texture.type = scene.voxelType === 'uint8' ? THREE.UnsignedByteType : THREE.FloatType;
  texture.minFilter = texture.magFilter = THREE.LinearFilter;
  texture.unpackAlignment = 1;
  texture.needsUpdate = true;
  return texture;
}

function colourMap(scene) {
  const n = scene.tfTexels.length / 4;
  const texture = new THREE.DataTexture(new Float32Array(scene.tfTexels), n, 1, THREE.RGBAFormat, THREE.FloatType);
  texture.minFilter = texture.magFilter = THREE.LinearFilter;
  texture.needsUpdate = true;
  return texture;
}

export async function setup(scene) {
  const { width, height } = scene;
  const canvas = makeCanvas(width, height);
  const renderer = new THREE.WebGLRenderer({ canvas, alpha: true, antialias: false });
  renderer.setPixelRatio(1);
  renderer.setSize(width, height, false);
  const float = renderer.extensions.has('EXT_color_buffer_float');
  const target = new THREE.WebGLRenderTarget(width, height, {
    type: float ? THREE.FloatType : THREE.UnsignedByteType, depthBuffer: false,
    minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
  });

  const [nx, ny, nz] = scene.dims;
  const uniforms = THREE.UniformsUtils.clone(VolumeRenderShader1.uniforms);
  uniforms.u_data.value = volumeTexture(scene, await fetchBytes('/data/voxels'));
  uniforms.u_size.value.set(nx, ny, nz);
  uniforms.u_clim.value.set(scene.clim[0], scene.clim[1]);
  uniforms.u_cmdata.value = colourMap(scene);
  uniforms.u_renderstyle.value = 2;
  uniforms.relative_step_size = { value: scene.step };
  uniforms.u_box_world = { value: new THREE.Vector3(...scene.boxWorld) };
  uniforms.u_emission = { value: scene.emission === 'color' ? 1 : 0 };
  const material = new THREE.ShaderMaterial({
    uniforms, vertexShader: VolumeRenderShader1.vertexShader, fragmentShader: fragmentShader(scene.texelCentres),
    side: THREE.BackSide,
    blending: THREE.NoBlending, // the mode writes premultiplied RGBA; NormalBlending would weight it by alpha again
    depthTest: false, depthWrite: false,
  });
  // As three.js's example: voxel i at object position i, the box from -0.5 to n - 0.5 in voxels.
  const geometry = new THREE.BoxGeometry(nx, ny, nz);
  geometry.translate(nx / 2 - 0.5, ny / 2 - 0.5, nz / 2 - 0.5);
  const mesh = new THREE.Mesh(geometry, material);
  mesh.matrixAutoUpdate = false;
  mesh.matrix.set(...scene.worldFromVoxel.flat()); // the card's voxel index -> world
  mesh.matrixWorldNeedsUpdate = true; // with matrixAutoUpdate off, three.js copies matrix only when told
  mesh.frustumCulled = false;
  const world = new THREE.Scene();
  world.add(mesh);

  // The card's OpenGL matrices as they are (rows; Matrix4.set takes rows): the zoom is in the projection.
  const camera = new THREE.PerspectiveCamera();
  camera.matrixAutoUpdate = false;
  camera.matrix.set(...scene.view.flat()).invert();
  camera.matrixWorldNeedsUpdate = true;
  camera.projectionMatrix.set(...scene.projection.flat());
  camera.projectionMatrixInverse.copy(camera.projectionMatrix).invert();

  const gl = renderer.getContext();
  const frame = () => {
    renderer.setRenderTarget(target);
    renderer.setClearColor(0x000000, 0);
    renderer.clear();
    renderer.render(world, camera);
  };
  state = { renderer, target, frame, gl, float, width, height };
  return {
    webglRenderer: webglRenderer(gl),
    settings: {
      render_target: float ? 'RGBA32F (EXT_color_buffer_float)' : 'RGBA8 (no EXT_color_buffer_float)',
      float_texture_filtering: renderer.extensions.has('OES_texture_float_linear'),
    },
    notes: float ? [] : ['no EXT_color_buffer_float: read back from an 8-bit render target'],
  };
}

export function timeFrames(frames) {
  return time(frames, state.frame, () => waitForGpu(state.gl, state.float));
}

export function readPixels() {
  const { renderer, target, width, height, float } = state;
  const pixels = float ? new Float32Array(width * height * 4) : new Uint8Array(width * height * 4);
  renderer.readRenderTargetPixels(target, 0, 0, width, height, pixels);
  return { format: float ? 'float32' : 'uint8', base64: toBase64(pixels) };
}
