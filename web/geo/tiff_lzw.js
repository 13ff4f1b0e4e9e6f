// TIFF LZW decoding (TIFF 6.0 §13) for the geotiff library, replacing its own decoder: that one
// collects the output in a plain JS array with no bound, so a damaged block can grow it until
// the JS engine aborts the whole process (seen in our fuzz tests). This one writes into a
// typed array of the block's known size and stops there; a bad code is an exception. The same
// code walk also counts a block's bytes without writing them, for the check of every block's
// size before the field is allocated (tiff_blocks.js).

import { BaseDecoder } from 'geotiff';

const CLEAR = 256, END = 257, FIRST_FREE = 258, MAX_CODES = 4096;

/** The `width`-bit code (9..12) at bit offset `bit`, most significant bit first, from a 24-bit window. */
function codeAt(input, bit, width) {
  const p = bit >> 3;
  const window = (input[p] << 16) | (input[p + 1] << 8) | input[p + 2]; // past the end reads as 0
  return (window >>> (24 - (bit & 7) - width)) & ((1 << width) - 1);
}

/**
 * Decodes one strip or tile. Data that ends before `size` bytes (a bottom strip holding only
 * the image's remaining rows) leaves the rest zero: lzwLength has checked what each block holds.
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
    if (bit + width > totalBits) break;
    const code = codeAt(input, bit, width);
    bit += width;
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

/**
 * Bytes a strip or tile decodes to, counted without writing them: the same walk as lzwDecode,
 * with only the lengths of the table's strings. Stops counting at `limit`.
 * @param {Uint8Array} input LZW codes
 * @param {number} limit
 * @returns {number} bytes, at most limit
 * @throws {Error} on a code the table does not hold
 */
export function lzwLength(input, limit) {
  const length = new Uint16Array(MAX_CODES).fill(1, 0, 256);
  const totalBits = input.length * 8;
  let bit = 0, width = 9, next = FIRST_FREE, old = -1, o = 0;
  while (o < limit && bit + width <= totalBits) {
    const code = codeAt(input, bit, width);
    bit += width;
    if (code === END) break;
    if (code === CLEAR) { next = FIRST_FREE; width = 9; old = -1; continue; }
    if (old < 0) {
      if (code > 255) throw new Error(`bad LZW code ${code} after a clear`);
      o++;
      old = code;
      continue;
    }
    if (code < next) o += length[code];
    else if (code === next && next < MAX_CODES) o += length[old] + 1;
    else throw new Error(`bad LZW code ${code} (table holds ${next})`);
    if (next < MAX_CODES) length[next++] = length[old] + 1;
    if (next + 1 >= 1 << width && width < 12) width++;
    old = code;
  }
  return Math.min(o, limit);
}

/** The library's decoder interface; parameters as tiff_blocks.js gives them (bytesPerPixel included). */
export class TiffLzwDecoder extends BaseDecoder {
  decodeBlock(buffer) {
    const { tileWidth, tileHeight, bytesPerPixel } = this.parameters;
    return lzwDecode(new Uint8Array(buffer), tileWidth * tileHeight * bytesPerPixel).buffer;
  }
}
