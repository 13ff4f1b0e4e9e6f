// The first sample of every strip or tile of a TIFF, decoded block by block by the geotiff
// library's codecs and predictors (the decoder tiff_blocks.js picked), and copied a row at a time
// into the field. The library's readRasters reads every sample through a DataView call: that
// took as long as inflating the blocks, and paid for the check of every block's size
// (tiff_blocks.js) that now runs before the field is allocated.

export const TYPED_ARRAYS = {
  1: { 8: Uint8Array, 16: Uint16Array, 32: Uint32Array },
  2: { 8: Int8Array, 16: Int16Array, 32: Int32Array },
  3: { 32: Float32Array, 64: Float64Array },
};
export const GETTERS = {
  1: { 8: 'getUint8', 16: 'getUint16', 32: 'getUint32' },
  2: { 8: 'getInt8', 16: 'getInt16', 32: 'getInt32' },
  3: { 32: 'getFloat32', 64: 'getFloat64' },
};
export const LITTLE_ENDIAN_HOST = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

/**
 * Reads the image into sink.samples (converting to their type: int32 and float64 to float32),
 * pausing through the sink after every row of blocks.
 * @param {import('geotiff').GeoTIFFImage} image
 * @param {Awaited<ReturnType<typeof import('./tiff_blocks.js').blockLayout>>} layout its blocks, checked
 * @param {Uint8Array} bytes the file
 * @param {import('../loaders/pacing.js').SampleSink} sink samples of the extent only
 * @param {{ x: number, y: number, width: number, height: number }} extent the part of the image
*   read (tiff_blocks.js dataExtent: whole blocks, except at the image's right and bottom edges)
 * @param {{ format: number, bits: number, nodata: number|null }} sample SampleFormat and
 *   BitsPerSample of the first sample; nodata fills a sparse file's empty blocks
 */
export async function readBlocks(image, layout, bytes, sink, extent, { format, bits, nodata }) {
  const { blockWidth, blockHeight, bytesPerPixel, offsets, counts, decoder } = layout;
  const across = Math.ceil(image.getWidth() / blockWidth);
  const { width, height } = extent;
  const firstX = extent.x / blockWidth, firstY = extent.y / blockHeight;
  const acrossExtent = Math.ceil(width / blockWidth), downExtent = Math.ceil(height / blockHeight);
  const sampleBytes = bits / 8;
  // One sample a pixel in the file's byte order is a typed array; anything else goes sample by sample.
  const Typed = bytesPerPixel === sampleBytes && image.littleEndian === LITTLE_ENDIAN_HOST ? TYPED_ARRAYS[format][bits] : null;
  const getter = GETTERS[format][bits];

  for (let by = 0; by < downExtent; by++) {
    const y0 = by * blockHeight, rows = Math.min(blockHeight, height - y0);
    for (let bx = 0; bx < acrossExtent; bx++) {
      const x0 = bx * blockWidth, cols = Math.min(blockWidth, width - x0);
      const samples = sink.samples, i = (firstY + by) * across + firstX + bx;
      const offset = offsets[i], count = counts[i];
      if (count === 0) { // a sparse file's empty block (GDAL SPARSE_OK)
        for (let y = 0; y < rows; y++) samples.fill(nodata ?? 0, (y0 + y) * width + x0, (y0 + y) * width + x0 + cols);
        continue;
      }
      const decoded = await decoder.decode(bytes.slice(offset, offset + count).buffer);
      if (Typed) {
        const values = new Typed(decoded, 0, Math.floor(decoded.byteLength / sampleBytes));
        for (let y = 0; y < rows; y++) samples.set(values.subarray(y * blockWidth, y * blockWidth + cols), (y0 + y) * width + x0);
      } else {
        const view = new DataView(decoded);
        for (let y = 0; y < rows; y++) {
          const dest = (y0 + y) * width + x0, src = y * blockWidth * bytesPerPixel;
          for (let x = 0; x < cols; x++) samples[dest + x] = view[getter](src + x * bytesPerPixel, image.littleEndian);
        }
      }
    }
    await sink.pace((y0 + rows) / height);
  }
}
