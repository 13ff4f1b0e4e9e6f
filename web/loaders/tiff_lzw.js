// TIFF LZW decoding (TIFF 6.0 §13) for the geotiff library, replacing its own decoder: that one
// collects the output in a plain JS array with no bound, so a damaged block can grow it until
// the JS engine aborts the whole process (seen in our fuzz tests). This one writes into a
// typed array of the block's known size and stops there; a bad code is an exception.

import { BaseDecoder } from 'geotiff';

const CLEAR = 256, END = 257, FIRST_FREE = 258, MAX_CODES = 4096;

/**
 * Decodes one strip or tile.
 * @param {Uint8Array} input LZW codes, most significant bit first
 * @param {number} size bytes the block holds when decoded
 * @returns {Uint8Array}
 */
export function lzwDecode(input, size) {
  const out = new Uint8Array(size);
  const prefix = new Uint16Array(MAX_CODES), last = new Uint8Array(MAX_CODES);
  const first = new Uint8Array(MAX_CODES), length = new Uint16Array(MAX_CODES);
  for (let i = 0; i < 256; i++) { last[i] = i; first[i] = i; length[i] = 1; }
  const totalBits = input.length * 8;
  let bit = 0, width = 9, next = FIRST_FREE, old = -1, o = 0;

  /** Writes the string of `code` at out[o..], clipped to the block; returns its length. */
  const put = (code) => {
    const n = length[code];
    for (let c = code, k = o + n - 1; k >= o; k--, c = prefix[c]) if (k < size) out[k] = last[c];
    return n;
  };

  while (o < size) {
    if (bit + width > totalBits) throw new Error(`LZW data ends after ${o} of ${size} bytes`);
    let code = 0;
    for (let k = 0; k < width; k++, bit++) code = (code << 1) | ((input[bit >> 3] >> (7 - (bit & 7))) & 1);
    if (code === END) break;
    if (code === CLEAR) { next = FIRST_FREE; width = 9; old = -1; continue; }
    if (old < 0) {
      if (code > 255) throw new Error(`bad LZW code ${code} after a clear`);
      out[o++] = code;
      old = code;
      continue;
    }
    let head;
    if (code < next) {
      o += put(code);
      head = first[code];
    } else if (code === next && next < MAX_CODES) {
      // The code being defined: the previous string plus its own first byte.
      o += put(old);
      if (o < size) out[o] = first[old];
      o++;
      head = first[old];
    } else {
      throw new Error(`bad LZW code ${code} (table holds ${next})`);
    }
    if (next < MAX_CODES) {
      prefix[next] = old; last[next] = head; first[next] = first[old]; length[next] = length[old] + 1;
      next++;
    }
    if (next + 1 >= 1 << width && width < 12) width++; // TIFF switches one code early
    old = code;
  }
  return out;
}

/** Block geometry for the decoder; strips never taller than the image. */
export async function lzwParameters(dir) {
  const tiled = dir.hasTag('TileOffsets');
  const imageHeight = await dir.loadValue('ImageLength');
  const bits = Array.from(await dir.loadValue('BitsPerSample') ?? [1]);
  const planar = (await dir.loadValue('PlanarConfiguration')) ?? 1;
  return {
    tileWidth: await dir.loadValue(tiled ? 'TileWidth' : 'ImageWidth'),
    tileHeight: tiled ? await dir.loadValue('TileLength')
      : Math.min(imageHeight, (await dir.loadValue('RowsPerStrip')) || imageHeight),
    planarConfiguration: planar,
    bitsPerSample: bits,
    predictor: (await dir.loadValue('Predictor')) || 1,
    bytesPerPixel: Math.ceil((planar === 2 ? bits[0] : bits.reduce((a, b) => a + b, 0)) / 8),
  };
}

export class TiffLzwDecoder extends BaseDecoder {
  decodeBlock(buffer) {
    const { tileWidth, tileHeight, bytesPerPixel } = this.parameters;
    return lzwDecode(new Uint8Array(buffer), tileWidth * tileHeight * bytesPerPixel).buffer;
  }
}
