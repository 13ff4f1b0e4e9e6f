// Grayscale PNG height fields (and 8-bit RGB Terrain-RGB/Terrarium), decoded straight into the caller's array.
//
// Memory is the point of this decoder: a 16385x16385 16-bit field is 512 MB,
// so it can afford neither the whole inflated stream nor a second copy of the
// pixels. The file is walked once to check its structure (chunk lengths, CRCs,
// IHDR, tEXt, IDAT positions) without allocating anything. Then the IDAT stream
// is inflated once and counted, keeping nothing, to prove that it holds every row
// the IHDR declares (a forged IHDR must not reserve memory: WebAssembly memory
// never shrinks). Only then is the field allocated, and the IDAT chunks, as views
// into the file, are inflated again (inflate.js), each inflated row unfiltered
// against the previous one and written into the destination. Only two rows of
// scratch are kept.

import { Unzlib } from 'fflate';
import {
  HeightfieldError, DEFAULT_MAX_SAMPLES, checkSize, describeContent,
} from './common.js';
import { SampleSink, pacer } from './pacing.js';
import { inflate, isInflateError } from '../geo/index.js';
import { ENCODINGS, encodingFromName, detectEncoding } from './terrain_rgb.js';

const SIGNATURE = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];
const COLOUR_TYPES = { 0: 'grayscale', 2: 'RGB', 3: 'palette', 4: 'grayscale+alpha', 6: 'RGBA' };
// Compressed bytes handed to fflate per call when counting the rows of a truncated file.
const SLICE = 64 * 1024;
// Deflate cannot expand data by more than this factor (258-byte matches in 2 bits).
const MAX_DEFLATE_RATIO = 1032;

/** True when bytes start with the 8-byte PNG signature. */
export function hasPngSignature(bytes) {
  return bytes.length >= 8 && SIGNATURE.every((v, i) => bytes[i] === v);
}

/**
 * Decodes a grayscale PNG (colour type 0, bit depth 1/2/4/8/16, or colour
 * type 4 grey+alpha with the alpha ignored) into an array from allocate(),
 * or an 8-bit RGB(A) PNG holding Terrain-RGB or Terrarium heights into float32 metres.
 *
 * @param {Uint8Array} bytes the whole file
 * @param {string} name file name, used in error messages
 * @param {(sampleType: string, width: number, height: number) => ArrayLike<number>} allocate
 *   called once, after the file structure has been validated, with 'u16' for
 *   16-bit files, 'f32' for encoded RGB and 'u8' otherwise; must return a typed array of width*height
 * @param {object} [options]
 * @param {number} [options.maxSamples] reject width*height above this
 * @param {import('./sidecar.js').Sidecar} [options.sidecar] if given, its width/height must
 *   match and its min/max (metres) give the height range when the PNG has no min_m/max_m tEXt
 * @param {'terrain-rgb'|'terrarium'|'auto'} [options.encoding] how an RGB(A) PNG holds heights;
 *   'auto' (default) takes it from the file name, else from the first row's colours
 * @param {(fraction: number) => void} [options.onProgress] see SampleSink
 * @param {() => ArrayLike<number>} [options.reacquire] see SampleSink
 * @returns {{ width: number, height: number, sampleType: 'u8'|'u16', samples: Uint8Array|Uint16Array,
 *   bitDepth: number, heightScale: number, heightOffset: number, heightFromFile: boolean,
 *   nodata: number|null, encoding: string|null }} heights in metres are raw*heightScale + heightOffset; nodata is the
 *   raw grey value named by a tRNS chunk, if any
 * @throws {HeightfieldError} for any malformed, truncated or unsupported file
 */
export async function decodePng(bytes, name, allocate, options = {}) {
  const maxSamples = options.maxSamples ?? DEFAULT_MAX_SAMPLES;
  const fail = (problem) => { throw new HeightfieldError(name, problem); };
  if (!(bytes instanceof Uint8Array)) fail('file contents are not a Uint8Array');
  if (bytes.length === 0) fail('empty file');
  if (bytes.length < 8 && SIGNATURE.slice(0, bytes.length).every((v, i) => bytes[i] === v)) {
    fail(`truncated: file ends inside the PNG signature (${bytes.length} of 8 bytes)`);
  }
  if (!hasPngSignature(bytes)) {
    const what = describeContent(bytes);
    if (what === 'PNG data') fail('not a PNG file (bad signature: the PNG signature bytes are damaged)');
    fail(`not a PNG file (bad signature${what ? `; looks like ${what}` : ''})`);
  }

  const png = readStructure(bytes, name, maxSamples);
  const { width, height, bitDepth, colourType } = png.ihdr;
  const rgb = colourType === 2 || colourType === 6;
  let encoding = null;
  if (rgb) {
    encoding = options.encoding && options.encoding !== 'auto' ? options.encoding : encodingFromName(name);
    if (encoding && !ENCODINGS[encoding]) throw new TypeError(`unknown encoding '${encoding}'`);
    encoding ??= detectEncoding(await firstRow(png), png.ihdr.channels);
    if (!encoding) {
      fail(`colour PNG whose first row is neither Terrain-RGB nor Terrarium heights; choose the encoding (or save heights as grayscale)`);
    }
  }

  const sidecar = options.sidecar;
  if (sidecar && ((sidecar.width !== undefined && sidecar.width !== width) ||
                  (sidecar.height !== undefined && sidecar.height !== height))) {
    fail(`size ${width}x${height} does not match ${sidecar.width ?? "?"}x${sidecar.height ?? "?"} from ${sidecar.name}`);
  }

  // Height range: tEXt min_m/max_m, else the sidecar's min/max, else raw units.
  const maxRaw = 2 ** bitDepth - 1;
  let heightScale = 1, heightOffset = 0, heightFromFile = false;
  const range = rgb ? null : png.range ?? (sidecar && sidecar.min !== undefined ? { min: sidecar.min, max: sidecar.max } : null);
  if (range) {
    heightOffset = range.min;
    heightScale = (range.max - range.min) / maxRaw;
    heightFromFile = true;
  }

  const proof = await proveRows(png, pacer(options.onCheckProgress));
  if (proof.problem) fail(`corrupt IDAT data (${proof.problem}) after ${proof.rows} of ${height} rows`);
  if (proof.rows < height) fail(`truncated: IDAT data ends after ${proof.rows} of ${height} rows`);

  const sampleType = rgb ? 'f32' : bitDepth === 16 ? 'u16' : 'u8';
  const sink = new SampleSink(allocate, sampleType, width, height, options);
  const rows = await inflateRows({ ...png, decodeRgb: ENCODINGS[encoding] }, sink);
  if (rows.error) fail(`corrupt IDAT data (${rows.error}) after ${rows.done} of ${height} rows`);
  if (rows.done < height) fail(`truncated: IDAT data ends after ${rows.done} of ${height} rows`);
  return { width, height, sampleType, samples: sink.samples, bitDepth, heightScale, heightOffset,
    heightFromFile: heightFromFile || rgb, nodata: rgb ? null : png.nodata, encoding };
}

/**
 * Walks the chunks, checking everything that can be checked without
 * inflating. Returns { ihdr, idat: Uint8Array[] (views into bytes), range, nodata }.
 */
function readStructure(bytes, name, maxSamples) {
  const fail = (problem) => { throw new HeightfieldError(name, problem); };
  const n = bytes.length;
  const u32 = (p) => ((bytes[p] << 24) | (bytes[p + 1] << 16) | (bytes[p + 2] << 8) | bytes[p + 3]) >>> 0;
  let ihdr = null;
  const idat = [];
  let idatBytes = 0;
  let idatEnded = false; // a non-IDAT chunk followed the IDAT run
  const text = {};
  let nodata = null;
  let pos = 8;
  let truncatedIn = null; // set when the file ends before IEND

  for (;;) {
    if (pos === n) { truncatedIn = ihdr ? 'before the IEND chunk' : 'before the IHDR chunk'; break; }
    if (pos + 8 > n) { truncatedIn = 'inside a chunk header'; break; }
    const length = u32(pos);
    const type = String.fromCharCode(bytes[pos + 4], bytes[pos + 5], bytes[pos + 6], bytes[pos + 7]);
    if (!/^[A-Za-z]{4}$/.test(type)) fail(`corrupt chunk structure at byte ${pos} (invalid chunk type)`);
    if (length > 0x7fffffff) fail(`bad length ${length} of ${type} chunk at byte ${pos}`);
    if (!ihdr && type !== 'IHDR') fail(`IHDR chunk missing (first chunk is ${type})`);
    const data = pos + 8, end = data + length;
    if (end + 4 > n) {
      truncatedIn = `inside the ${type} chunk`;
      if (type === 'IDAT' && !idatEnded && data < n) idat.push(bytes.subarray(data, Math.min(end, n)));
      break;
    }
    if (crc32(bytes, pos + 4, end) !== u32(end)) fail(`bad CRC in ${type} chunk at byte ${pos}`);

    if (type === 'IHDR') {
      if (ihdr) fail('second IHDR chunk');
      if (length !== 13) fail(`bad IHDR chunk length ${length} (expected 13)`);
      ihdr = parseIhdr(bytes, data, u32, name, maxSamples);
    } else if (type === 'IDAT') {
      if (idatEnded) fail('IDAT chunks are not consecutive');
      idat.push(bytes.subarray(data, end));
      idatBytes += length;
    } else if (type === 'IEND') {
      break;
    } else {
      if (idat.length) idatEnded = true;
      if (type === 'tEXt') {
        const zero = bytes.subarray(data, end).indexOf(0);
        if (zero > 0) text[latin1(bytes, data, data + zero)] = latin1(bytes, data + zero + 1, end);
      } else if (type === 'tRNS' && ihdr.colourType === 0) {
        if (length !== 2) fail(`bad tRNS chunk length ${length} (expected 2 for grayscale)`);
        nodata = ((bytes[data] << 8) | bytes[data + 1]) & (2 ** ihdr.bitDepth - 1);
      } else if (type === 'PLTE') {
        // A suggested palette is allowed in RGB files, never in grayscale ones.
        if (ihdr.colourType === 0 || ihdr.colourType === 4) fail('PLTE chunk in a grayscale PNG');
      } else if (/^[A-Z]/.test(type)) {
        // Critical chunks we do not know change how the image must be read.
        fail(`unsupported PNG: unknown critical chunk ${type}`);
      }
    }
    pos = end + 4;
  }

  if (truncatedIn) {
    let problem = `truncated: file ends after ${n} bytes, ${truncatedIn}`;
    if (ihdr) problem += ` (image data: ${idat.length ? countRows({ ihdr, idat }) : 0} of ${ihdr.height} rows)`;
    fail(problem);
  }
  if (!idat.length) fail('no IDAT chunk (the file holds no image data)');
  const rawBytes = ihdr.height * (ihdr.rowBytes + 1);
  if (rawBytes > idatBytes * MAX_DEFLATE_RATIO + MAX_DEFLATE_RATIO) {
    fail(`truncated: IDAT holds only ${idatBytes} bytes, too few for ${ihdr.width}x${ihdr.height} samples`);
  }
  return { ihdr, idat, range: heightRange(text, fail), nodata };
}

/** Validates IHDR; throws on anything the decoder does not handle. */
function parseIhdr(bytes, p, u32, name, maxSamples) {
  const fail = (problem) => { throw new HeightfieldError(name, problem); };
  const width = u32(p), height = u32(p + 4);
  const bitDepth = bytes[p + 8], colourType = bytes[p + 9];
  const compression = bytes[p + 10], filter = bytes[p + 11], interlace = bytes[p + 12];
  if (width > 0x7fffffff || height > 0x7fffffff) fail(`bad IHDR: declared size ${width}x${height} exceeds the PNG limit of 2^31-1`);
  checkSize(name, width, height, maxSamples);
  if (!(colourType in COLOUR_TYPES)) fail(`bad IHDR: colour type ${colourType} does not exist`);
  if (colourType === 3) {
    fail(`unsupported PNG: colour type 3 (palette); expected grayscale, or RGB with Terrain-RGB/Terrarium heights`);
  }
  const depths = colourType === 0 ? [1, 2, 4, 8, 16] : [8, 16];
  if (!depths.includes(bitDepth)) fail(`bad IHDR: bit depth ${bitDepth} is not allowed for colour type ${colourType}`);
  if ((colourType === 2 || colourType === 6) && bitDepth !== 8) {
    fail(`unsupported PNG: 16-bit ${COLOUR_TYPES[colourType]}; heights are grayscale, or 8-bit RGB (Terrain-RGB/Terrarium)`);
  }
  if (compression !== 0) fail(`bad IHDR: compression method ${compression} (only 0, deflate, exists)`);
  if (filter !== 0) fail(`bad IHDR: filter method ${filter} (only 0 exists)`);
  if (interlace === 1) fail('unsupported PNG: interlaced (Adam7); re-save it without interlacing');
  if (interlace !== 0) fail(`bad IHDR: interlace method ${interlace} does not exist`);
  const channels = { 0: 1, 2: 3, 4: 2, 6: 4 }[colourType];
  const bitsPerPixel = bitDepth * channels;
  return {
    width, height, bitDepth, colourType, channels,
    rowBytes: Math.ceil((width * bitsPerPixel) / 8),
    bpp: Math.max(1, bitsPerPixel >> 3), // filter distance in bytes
  };
}

/** min_m / max_m tEXt -> { min, max } in metres, or null when absent. */
function heightRange(text, fail) {
  const hasMin = 'min_m' in text, hasMax = 'max_m' in text;
  if (!hasMin && !hasMax) return null;
  if (hasMin !== hasMax) fail(`tEXt ${hasMin ? 'min_m' : 'max_m'} given without ${hasMin ? 'max_m' : 'min_m'}`);
  const parse = (key) => {
    const s = text[key].trim();
    const v = s === '' ? NaN : Number(s);
    if (!Number.isFinite(v)) fail(`tEXt ${key} is not a number (${JSON.stringify(text[key].slice(0, 40))})`);
    return v;
  };
  const min = parse('min_m'), max = parse('max_m');
  if (max < min) fail(`tEXt max_m (${max}) is below min_m (${min})`);
  if (!Number.isFinite(max - min)) fail(`tEXt min_m ${min} and max_m ${max} span more than a number can hold`);
  return { min, max };
}

function latin1(bytes, start, end) {
  let s = '';
  for (let i = start; i < end; i++) s += String.fromCharCode(bytes[i]);
  return s;
}

/**
 * Inflates the IDAT stream and unfilters it row by row into the sink's samples (pausing
 * through the sink between slices), or, with no sink, only up to the first row, which it
 * returns as `first` (pixel bytes without the filter byte).
 * Returns { done: rows completed, error: inflate/unfilter problem or null, first }.
 */
async function inflateRows({ ihdr, idat, decodeRgb }, sink) {
  const { width, height, rowBytes, bpp } = ihdr;
  const rowLen = rowBytes + 1; // filter-type byte + row
  let cur = new Uint8Array(rowLen);
  let prev = new Uint8Array(rowLen); // all zero: the row above row 0
  let filled = 0, done = 0, error = null, first = null;
  const headerProblem = zlibHeaderProblem(idat);
  if (headerProblem) return { done, error: headerProblem, first };
  const wanted = sink ? height : 1;

  const onChunk = (chunk) => {
    let p = 0;
    while (p < chunk.length && done < wanted) {
      const take = Math.min(rowLen - filled, chunk.length - p);
      cur.set(chunk.subarray(p, p + take), filled);
      filled += take;
      p += take;
      if (filled === rowLen) {
        if (cur[0] > 4) { error = `bad filter type ${cur[0]} on row ${done}`; return false; }
        unfilter(cur, prev, bpp);
        if (sink) storeRow(cur, sink.samples, done * width, ihdr, decodeRgb);
        else first = cur.slice(1);
        [cur, prev] = [prev, cur];
        filled = 0;
        done++;
      }
    }
    return done < wanted; // anything after the last row is ignored
  };
  const pace = sink ? () => sink.pace(done / height) : undefined;
  error = (await inflate(idat, onChunk, pace)) ?? error;
  return { done, error, first };
}

/**
 * Inflates the whole IDAT stream, keeping nothing, to prove before anything is allocated that
 * it holds every row the IHDR declares, each with a valid filter type (the decode that follows
 * then has nothing left to refuse). Returns { rows: complete rows before the first problem,
 * problem: what is wrong with the data, or null }.
 */
async function proveRows({ ihdr, idat }, pace) {
  const header = zlibHeaderProblem(idat);
  if (header) return { rows: 0, problem: header };
  const rowLen = ihdr.rowBytes + 1, enough = ihdr.height * rowLen;
  let length = 0, bad = null;
  const onChunk = (chunk) => {
    // The filter byte of every row that starts in this chunk.
    const end = Math.min(length + chunk.length, enough);
    for (let p = Math.ceil(length / rowLen) * rowLen; p < end; p += rowLen) {
      if (chunk[p - length] > 4) { bad = { row: p / rowLen, type: chunk[p - length] }; return false; }
    }
    length += chunk.length;
    return length < enough;
  };
  const error = await inflate(idat, onChunk, () => pace(Math.min(1, length / enough)));
  if (bad) return { rows: bad.row, problem: `bad filter type ${bad.type} on row ${bad.row}` };
  return { rows: Math.min(ihdr.height, Math.floor(length / rowLen)), problem: error };
}

/** Complete rows in a (truncated) IDAT stream, counted without keeping any of them. */
function countRows({ ihdr, idat }) {
  if (zlibHeaderProblem(idat)) return 0;
  let inflated = 0;
  const inflater = new Unzlib((chunk) => { inflated += chunk.length; });
  try {
    for (const part of idat) for (let p = 0; p < part.length; p += SLICE) inflater.push(part.subarray(p, p + SLICE), false);
  } catch (e) {
    if (!isInflateError(e)) throw e;
  }
  return Math.min(ihdr.height, Math.floor(inflated / (ihdr.rowBytes + 1)));
}

/**
 * The height encoding a colour PNG's first row reads as (terrain_rgb.js), or null: neither, or
 * not a colour PNG the height loader reads. Tells a Terrain-RGB tile from a photo.
 * @param {Uint8Array} bytes the whole file
 */
export async function detectPngEncoding(bytes, name) {
  let png;
  try {
    png = readStructure(bytes, name, Infinity);
  } catch (error) {
    if (error instanceof HeightfieldError) return null;
    throw error;
  }
  if (png.ihdr.bitDepth !== 8 || png.ihdr.channels < 3) return null;
  return detectEncoding(await firstRow(png), png.ihdr.channels);
}

/** The first row's pixel bytes (to guess an RGB encoding); an empty array when unreadable. */
async function firstRow(png) {
  const { first } = await inflateRows(png, null);
  return first ?? new Uint8Array(0);
}

/** Checks the 2-byte zlib header (which may straddle IDAT chunks); returns a problem or null. */
function zlibHeaderProblem(idat) {
  const head = [];
  for (const part of idat) {
    for (let i = 0; i < part.length && head.length < 2; i++) head.push(part[i]);
    if (head.length === 2) break;
  }
  if (head.length < 2) return null; // too short: truncation, reported as such
  const [cmf, flg] = head;
  if ((cmf & 15) !== 8 || cmf >> 4 > 7 || ((cmf << 8) | flg) % 31 !== 0) return 'bad zlib header';
  if (flg & 32) return 'zlib stream wants a preset dictionary';
  return null;
}

/**
 * Undoes the PNG filter of one row in place. row[0] is the filter type, the
 * pixel bytes follow; prev is the previous row after unfiltering (zeros for
 * row 0). bpp = bytes per complete pixel (at least 1). Uint8Array stores wrap
 * mod 256, which is the arithmetic PNG specifies.
 */
function unfilter(row, prev, bpp) {
  const n = row.length;
  switch (row[0]) {
    case 0: // None
      break;
    case 1: // Sub
      for (let i = 1 + bpp; i < n; i++) row[i] += row[i - bpp];
      break;
    case 2: // Up
      for (let i = 1; i < n; i++) row[i] += prev[i];
      break;
    case 3: // Average
      for (let i = 1; i <= bpp && i < n; i++) row[i] += prev[i] >> 1;
      for (let i = 1 + bpp; i < n; i++) row[i] += (row[i - bpp] + prev[i]) >> 1;
      break;
    case 4: // Paeth; with no left neighbour it reduces to Up
      for (let i = 1; i <= bpp && i < n; i++) row[i] += prev[i];
      for (let i = 1 + bpp; i < n; i++) {
        const a = row[i - bpp], b = prev[i], c = prev[i - bpp];
        const pa = Math.abs(b - c), pb = Math.abs(a - c), pc = Math.abs(a + b - 2 * c);
        row[i] += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      break;
  }
}

/** Writes one unfiltered row (row[0] is the filter byte) as samples at dest[offset..]. */
function storeRow(row, dest, offset, { width, bitDepth, channels }, decodeRgb) {
  if (decodeRgb) {
    for (let x = 0, i = 1; x < width; x++, i += channels) dest[offset + x] = decodeRgb(row[i], row[i + 1], row[i + 2]);
  } else if (bitDepth === 16) {
    const step = 2 * channels; // grey is the first sample of a pixel, big-endian
    for (let x = 0, i = 1; x < width; x++, i += step) dest[offset + x] = (row[i] << 8) | row[i + 1];
  } else if (bitDepth === 8) {
    if (channels === 1) dest.set(row.subarray(1, 1 + width), offset);
    else for (let x = 0, i = 1; x < width; x++, i += channels) dest[offset + x] = row[i];
  } else {
    // 1, 2 or 4 bits per sample, packed from the most significant bit.
    const mask = (1 << bitDepth) - 1;
    for (let x = 0; x < width; x++) {
      const bit = x * bitDepth;
      dest[offset + x] = (row[1 + (bit >> 3)] >> (8 - bitDepth - (bit & 7))) & mask;
    }
  }
}

let crcTable = null;

/** CRC-32 (the PNG/zlib polynomial) of bytes[start..end). */
function crc32(bytes, start, end) {
  if (!crcTable) {
    crcTable = new Int32Array(256);
    for (let i = 0; i < 256; i++) {
      let c = i;
      for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
      crcTable[i] = c;
    }
  }
  let c = -1;
  for (let i = start; i < end; i++) c = crcTable[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return (c ^ -1) >>> 0;
}
