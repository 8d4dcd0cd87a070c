// Page-side helpers shared by the adapters' page modules.

// The canvas an adapter draws into: exactly the card's size in pixels (the page runs at device pixel
// ratio 1), inside #view.
export function makeCanvas(width, height) {
  const view = document.getElementById('view');
  view.style.width = `${width}px`;
  view.style.height = `${height}px`;
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  canvas.style.width = `${width}px`;
  canvas.style.height = `${height}px`;
  view.appendChild(canvas);
  return canvas;
}

export async function fetchBytes(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  return response.arrayBuffer();
}

// Waits for the GPU: a one-pixel readPixels from what is bound cannot return before the frame is drawn.
export function waitForGpu(gl, float) {
  if (float) gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.FLOAT, new Float32Array(4));
  else gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
}

// Seconds of each of `frames` frames after one warm-up frame; frame() draws, wait() blocks until drawn.
export function timeFrames(frames, frame, wait) {
  frame();
  wait();
  const seconds = [];
  for (let i = 0; i < frames; i++) {
    const start = performance.now();
    frame();
    wait();
    seconds.push((performance.now() - start) / 1000);
  }
  return seconds;
}

// A typed array's bytes as base64, to cross from the page to Node in one string.
export function toBase64(typed) {
  const bytes = new Uint8Array(typed.buffer, typed.byteOffset, typed.byteLength);
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(text);
}

export function webglRenderer(gl) {
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  return gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
}
