// TIFF deflate blocks (compression 8 and 32946) for the geotiff library, through inflate.js
// instead of the library's pako: the same inflater that counted every block before the field
// was allocated (tiff_blocks.js), so a block that passed that check decodes. pako refused, after
// the field was allocated, blocks whose zlib checksum is wrong, which the check (fflate) and the
// PNG decoder accept.

import { BaseDecoder } from 'geotiff';
import { inflate } from './inflate.js';

/** The library's decoder interface; parameters as tiff_blocks.js gives them (bytesPerPixel included). */
export class TiffDeflateDecoder extends BaseDecoder {
  /** The block's bytes, in an array of its full size (a bottom strip's missing rows stay zero). */
  async decodeBlock(buffer) {
    const { tileWidth, tileHeight, bytesPerPixel } = this.parameters;
    const out = new Uint8Array(tileWidth * tileHeight * bytesPerPixel);
    let length = 0;
    const error = await inflate([new Uint8Array(buffer)], (chunk) => {
      out.set(chunk.subarray(0, out.length - length), length);
      length += Math.min(chunk.length, out.length - length);
      return length < out.length;
    });
    if (error) throw new Error(error);
    return out.buffer;
  }
}
