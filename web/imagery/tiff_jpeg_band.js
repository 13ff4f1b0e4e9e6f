// A band of a JPEG-compressed TIFF image decoded block by block by a decoder given from outside
// (the browser's, web/imagery/browser_jpeg.js, many times faster than the geotiff library's
// decoder in JavaScript). Each block becomes a complete JPEG stream (tiff_jpeg_stream.js); the
// blocks of the band decode at once and are copied into its rows as they come, edge blocks
// cropped (a JPEG block is always stored at full block size), so no more than about one band's
// pixels is held besides the band.

import { tiffJpegStream } from '../geo/index.js';

/**
 * @typedef {(stream: Uint8Array) => Promise<{ width: number, height: number, rgba: Uint8Array|Uint8ClampedArray }>} JpegDecoder
 *   a complete JPEG stream to RGBA pixels (grey as equal RGB, YCbCr converted to RGB, an Adobe
 *   transform 0 stream taken as RGB)
 */

/**
 * Rows y..y+rows-1 as RGBA (alpha as decoded).
 * @param {{ bytes: Uint8Array, width: number, height: number, tables: Uint8Array|null, rgb: boolean,
 *   layout: { tiled: boolean, blockWidth: number, blockHeight: number, offsets: ArrayLike<number>, counts: ArrayLike<number> } }} image
 *   the file, the image size in pixels, the JPEGTables tag, whether the samples are RGB
 *   (Photometric 2) rather than YCbCr or grey, and the block layout (web/geo/tiff_blocks.js)
 * @param {number} y the band's first row, at the top of a block row
 * @param {number} rows whole block rows, or up to the image's last row
 * @param {JpegDecoder} decode
 * @returns {Promise<Uint8Array>} width * rows * 4 bytes
 * @throws {Error} when a block is empty (sparse) or does not decode to its block size
 */
export async function decodeJpegBand({ bytes, width, height, tables, rgb, layout }, y, rows, decode) {
  const { tiled, blockWidth, blockHeight, offsets, counts } = layout;
  const kind = tiled ? 'tile' : 'strip';
  const across = Math.ceil(width / blockWidth);
  const band = new Uint8Array(width * rows * 4);
  const place = (i, x0, y0, { width: w, height: h, rgba }) => {
    const visibleRows = Math.min(blockHeight, height - y0);
    if (w !== blockWidth || (h !== blockHeight && h !== visibleRows)) {
      throw new Error(`${kind} ${i} decodes to ${w}x${h} pixels, not ${blockWidth}x${blockHeight}`);
    }
    const columns = Math.min(blockWidth, width - x0);
    for (let r = 0; r < visibleRows; r++) {
      band.set(rgba.subarray(r * w * 4, (r * w + columns) * 4), ((y0 - y + r) * width + x0) * 4);
    }
  };
  const decodes = [];
  for (let y0 = y; y0 < y + rows; y0 += blockHeight) {
    for (let bx = 0; bx < across; bx++) {
      const i = (y0 / blockHeight) * across + bx;
      // The library fills an empty block of a sparse file; that path reads such a band.
      if (counts[i] === 0) throw new Error(`${kind} ${i} is empty`);
      const stream = tiffJpegStream(tables, bytes.subarray(offsets[i], offsets[i] + counts[i]), { rgb });
      decodes.push(decode(stream).then((pixels) => place(i, bx * blockWidth, y0, pixels)));
    }
  }
  await Promise.all(decodes);
  return band;
}
