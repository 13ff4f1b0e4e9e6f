// The browser's own JPEG decoder as a function from a complete JPEG stream to RGBA pixels, for
// the blocks of JPEG-compressed TIFF images (tiff_jpeg_band.js): createImageBitmap decodes off
// the main thread in native code, and one reused 2D canvas reads the pixels back.

/**
 * @returns {import('./tiff_jpeg_band.js').JpegDecoder | null} null where the browser lacks
 *   createImageBitmap or OffscreenCanvas (Node, old browsers: the geotiff library decodes then)
 */
export function browserJpegDecoder() {
  if (typeof createImageBitmap !== 'function' || typeof OffscreenCanvas !== 'function') return null;
  let canvas = null, context = null;
  return async (stream) => {
    // No colour management: the samples are map colours, to be shown as stored.
    const bitmap = await createImageBitmap(new Blob([stream], { type: 'image/jpeg' }),
      { premultiplyAlpha: 'none', colorSpaceConversion: 'none' });
    try {
      const { width, height } = bitmap;
      if (!canvas || canvas.width !== width || canvas.height !== height) {
        canvas = new OffscreenCanvas(width, height);
        // Read back on every block: a canvas in CPU memory makes getImageData a copy, not a GPU readback.
        context = canvas.getContext('2d', { willReadFrequently: true });
        context.globalCompositeOperation = 'copy';
      }
      // Drawing and reading with no await between: decodes running at once share the canvas safely.
      context.drawImage(bitmap, 0, 0);
      const { data } = context.getImageData(0, 0, width, height);
      return { width, height, rgba: new Uint8Array(data.buffer, data.byteOffset, data.length) };
    } finally {
      bitmap.close();
    }
  };
}
