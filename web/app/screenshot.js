// Screenshots: the current view drawn again into an offscreen framebuffer at 1x or 2x the
// canvas's size (the LOD stays the screen's), read back, and saved as a PNG through a link.
import { FLAT_EARTH } from '../geo/index.js';
import { placeOnEarth } from '../cameras/on_the_earth.js';

/**
 * Renders with `drawAt(width, height)` into a framebuffer of scale x the canvas size and
 * returns the PNG as a Blob, with `caption` (the tile layers' attribution) in its bottom right
 * corner. Throws when the GPU cannot hold that size.
 * @param {WebGL2RenderingContext} gl
 */
export async function captureView(gl, scale, drawAt, caption = '') {
  const width = gl.drawingBufferWidth * scale, height = gl.drawingBufferHeight * scale;
  const limit = Math.min(gl.getParameter(gl.MAX_RENDERBUFFER_SIZE), gl.getParameter(gl.MAX_VIEWPORT_DIMS)[0]);
  if (width > limit || height > limit) throw new Error(`a ${width} × ${height} screenshot is larger than this GPU allows (${limit})`);
  const framebuffer = gl.createFramebuffer();
  const color = gl.createRenderbuffer(), depth = gl.createRenderbuffer();
  gl.bindRenderbuffer(gl.RENDERBUFFER, color);
  gl.renderbufferStorage(gl.RENDERBUFFER, gl.RGBA8, width, height);
  gl.bindRenderbuffer(gl.RENDERBUFFER, depth);
  gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, width, height);
  gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
  gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, color);
  gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, depth);
  const pixels = new Uint8ClampedArray(width * height * 4);
  try {
    drawAt(width, height);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  } finally {
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.deleteFramebuffer(framebuffer);
    gl.deleteRenderbuffer(color);
    gl.deleteRenderbuffer(depth);
  }
  // GL rows run bottom-up; an image's top-down.
  const canvas = new OffscreenCanvas(width, height);
  const image = new ImageData(width, height);
  const row = width * 4;
  for (let y = 0; y < height; ++y) image.data.set(pixels.subarray((height - 1 - y) * row, (height - y) * row), y * row);
  const context = canvas.getContext('2d');
  context.putImageData(image, 0, 0);
  if (caption) drawCaption(context, caption, width, height, scale);
  return canvas.convertToBlob({ type: 'image/png' });
}

/** The caption on a light band in the bottom right corner, as the page shows it. */
function drawCaption(context, caption, width, height, scale) {
  const size = 11 * scale, pad = 4 * scale;
  context.font = `${size}px sans-serif`;
  const textWidth = Math.min(context.measureText(caption).width, width - 2 * pad);
  context.fillStyle = 'rgba(255, 255, 255, 0.75)';
  context.fillRect(width - textWidth - 2 * pad, height - size - 2 * pad, textWidth + 2 * pad, size + 2 * pad);
  context.fillStyle = '#1a1f29';
  context.textBaseline = 'bottom';
  context.fillText(caption, width - textWidth - pad, height - pad, width - 2 * pad);
}

/** Saves a Blob as a file through a temporary link. */
export function download(blob, name) {
  const url = URL.createObjectURL(blob);
  const link = Object.assign(document.createElement('a'), { href: url, download: name });
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

/**
 * The page's screenshot: the active camera's view drawn again at `scale` x the canvas, saved as
 * hexlod-<terrain>-<scale>x.png. Resolves to the file name; throws when the GPU cannot hold it.
 */
export function screenshotTaker({ gl, rig, renderer, view, state, layers, attribution, requestRender }) {
  return async (scale) => {
    const camera = rig.active;
    const blob = await captureView(gl, scale, (width, height) => {
      camera.update(width / height);
      placeOnEarth(camera, layers.ground?.earth ?? FLAT_EARTH); // as the frame pipeline places it
      renderer.draw(camera, width, height, view, layers);
    }, attribution.text);
    const name = `hexlod-${(state.terrain?.name ?? 'view').replace(/\.[^.]*$/, '')}-${scale}x.png`;
    download(blob, name);
    requestRender();
    return name;
  };
}
