// ESRI ASCII grids (.asc): a header of "key value" lines (ncols, nrows, xllcorner|xllcenter,
// yllcorner|yllcenter, cellsize or dx/dy, optional NODATA_value), then nrows lines of ncols
// numbers, north row first. Heights become float32 metres; NODATA cells are filled later.
// The numbers are parsed straight from the bytes: no string per value, no copy of the text.

import { HeightfieldError, DEFAULT_MAX_SAMPLES, checkSize } from './common.js';
import { degreesToMetres, crsOfEpsg, makeGeoref, UNKNOWN_CRS } from '../geo/index.js';
import { SampleSink, pacer } from './pacing.js';

const KEYS = ['ncols', 'nrows', 'xllcorner', 'xllcenter', 'yllcorner', 'yllcenter', 'cellsize', 'dx', 'dy', 'nodata_value'];

/** True when the text starts with an ncols or nrows line. */
export function hasAscHeader(bytes) {
  const head = String.fromCharCode(...bytes.subarray(0, 6)).toLowerCase();
  return head.startsWith('ncols') || head.startsWith('nrows');
}

/**
 * @returns {Promise<{ width, height, sampleType: 'f32', samples: Float32Array, nodata: number|null,
 *   spacingX: number, spacingY: number, geographic: boolean }>} spacing in metres. A cell size is in
 *   the grid's own units; a grid whose cell size and corner look like degrees (cell <= 0.1, corner
 *   within -180..360 / -90..90, the whole grid on the globe) is taken as geographic.
 */
export async function decodeAsc(bytes, name, allocate, options = {}) {
  const fail = (problem) => { throw new HeightfieldError(name, problem); };
  const n = bytes.length;
  let pos = 0, line = 1;

  /** Next whitespace-separated token as [start, end), or null at the end. Counts lines. */
  const token = () => {
    while (pos < n) {
      const c = bytes[pos];
      if (c === 0x0a) line++;
      else if (c !== 0x20 && c !== 0x09 && c !== 0x0d) break;
      pos++;
    }
    if (pos >= n) return null;
    const start = pos;
    while (pos < n && bytes[pos] > 0x20) pos++;
    return [start, pos];
  };
  const text = ([s, e]) => String.fromCharCode(...bytes.subarray(s, Math.min(e, s + 40)));

  // Header: key/value pairs until the first token that is not a known key.
  const header = {};
  for (;;) {
    const save = pos, saveLine = line;
    const key = token();
    if (!key) fail('truncated: the file ends in its header');
    const k = text(key).toLowerCase();
    if (!KEYS.includes(k)) { pos = save; line = saveLine; break; }
    const value = token();
    const v = value ? Number(text(value)) : NaN;
    if (!Number.isFinite(v)) fail(`bad header: ${k} on line ${line} is not a number`);
    header[k] = v;
  }
  for (const k of ['ncols', 'nrows']) if (!(k in header)) fail(`bad header: no ${k} line (is this an ESRI ASCII grid?)`);
  const width = header.ncols, height = header.nrows;
  if (!Number.isInteger(width) || !Number.isInteger(height) || width < 0 || height < 0) {
    fail(`bad header: ncols ${width}, nrows ${height} must be whole numbers`);
  }
  checkSize(name, width, height, options.maxSamples ?? DEFAULT_MAX_SAMPLES);
  const dx = header.cellsize ?? header.dx, dy = header.cellsize ?? header.dy ?? dx;
  if (!(dx > 0) || !(dy > 0)) fail('bad header: cellsize missing or not positive');
  // Samples are float32: no-data must be one too, or -3.4028235e+38 would not match its samples.
  const nodata = 'nodata_value' in header ? Math.fround(header.nodata_value) : null;
  if (nodata !== null && !Number.isFinite(nodata)) fail(`bad header: NODATA_value ${header.nodata_value} is beyond the float32 range`);
  // Every value takes at least two bytes (a digit and a separator): a quick answer for a file cut short.
  if ((n - pos) < width * height * 2 - 1) fail(`truncated: ${n - pos} bytes cannot hold ${width}x${height} values`);
  // The proof of the declared size before memory is reserved (WebAssembly memory never
  // shrinks): the text holds exactly ncols x nrows values. Counting is a fraction of parsing.
  const { count, control } = await countValues(bytes, pos, line, pacer(options.onCheckProgress));
  if (control) {
    fail(`line ${control.line}: control character 0x${control.byte.toString(16).padStart(2, '0')} (values are separated by spaces, tabs and line ends)`);
  }
  if (count < width * height) {
    fail(`truncated: ${count} of ${width * height} values (ends on row ${Math.floor(count / width) + 1})`);
  }
  if (count > width * height) fail(`more values than ncols x nrows (${width}x${height})`);

  const sink = new SampleSink(allocate, 'f32', width, height, options);
  for (let y = 0; y < height; y++) {
    const samples = sink.samples, row = y * width;
    for (let x = 0; x < width; x++) {
      const t = token();
      if (!t) fail(`truncated: ${row + x} of ${width * height} values (ends on row ${y + 1})`);
      const v = parseNumber(bytes, t[0], t[1]);
      if (Number.isNaN(v)) fail(`line ${line}: '${text(t)}' is not a number`);
      samples[row + x] = v;
      // 1e999 parses to Infinity, 1e39 becomes Infinity as a float32: both are damage.
      if (!Number.isFinite(samples[row + x])) fail(`line ${line}: '${text(t)}' is not a finite float32 height (beyond ±3.4e38)`);
    }
    await sink.pace(y / height);
  }
  if (token()) fail(`more values than ncols x nrows (${width}x${height})`);

  const x0 = header.xllcorner ?? header.xllcenter ?? 0, y0 = header.yllcorner ?? header.yllcenter ?? 0;
  const geographic = dx <= 0.1 && dy <= 0.1 && x0 >= -180 && x0 + width * dx <= 360 &&
    y0 >= -90 && y0 + height * dy <= 90;
  const spacing = geographic ? degreesToMetres(dx, dy, y0 + (height * dy) / 2) : { spacingX: dx, spacingY: dy };
  // The header places the south-west cell, by its corner or its centre; rows are written north first.
  // An ASCII grid names no CRS (that is its .prj's job, loaders/index.js): degrees are taken as
  // WGS 84, anything else is unknown.
  const corner = header.xllcenter === undefined ? 0.5 : 0;
  const georef = 'xllcorner' in header || 'xllcenter' in header
    ? makeGeoref(geographic ? crsOfEpsg(4326, true) : UNKNOWN_CRS, x0 + corner * dx, y0 + corner * dy + (height - 1) * dy, dx, -dy, 'ASCII header')
    : null;
  return { width, height, sampleType: 'f32', samples: sink.samples, nodata, ...spacing, geographic, georef };
}

const LITTLE_ENDIAN_HOST = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

/**
 * The values in bytes[start..]: runs of bytes above 0x20, as token() reads them, and the first
 * control character other than tab, CR and LF (which token() would take for part of a value).
 * Four bytes at a time, three to four times faster than byte by byte: bit 7 of each byte of a
 * word is set when the byte belongs to a value, and a value starts where such a byte follows
 * one that does not; only words holding a byte below 0x20 (a line end) are looked at byte by
 * byte. Pauses every few megabytes.
 * @returns {Promise<{ count: number, control: { line: number, byte: number } | null }>}
 */
async function countValues(bytes, start, line, pace) {
  let count = 0, inValue = 0; // inValue: 1 when the byte before is part of a value
  /** Counts lines; false at a control character no grid holds. */
  const separator = (c) => {
    if (c === 0x0a) line++;
    return c === 0x0a || c === 0x0d || c === 0x09;
  };
  const byByte = (from, to) => {
    for (let i = from; i < to; i++) {
      const c = bytes[i];
      if (c < 0x20 && !separator(c)) return { line, byte: c };
      const v = c > 0x20 ? 1 : 0;
      count += v & (inValue ^ 1);
      inValue = v;
    }
    return null;
  };
  let i = Math.min(bytes.length, start + ((4 - ((bytes.byteOffset + start) & 3)) & 3)); // to a word boundary
  let control = byByte(start, i);
  if (LITTLE_ENDIAN_HOST && !control) {
    const words = new Uint32Array(bytes.buffer, bytes.byteOffset + i, (bytes.length - i) >> 2);
    let carry = inValue << 7; // bit 7: the byte before the word is part of a value
    for (let w0 = 0; w0 < words.length; w0 += 1 << 20) {
      for (let k = w0, end = Math.min(words.length, w0 + (1 << 20)); k < end; k++) {
        const w = words[k];
        if (((((w & 0x7f7f7f7f) + 0x60606060) | w) & 0x80808080) !== 0x80808080) { // a byte below 0x20
          for (let b = 0; b < 32; b += 8) {
            const c = (w >>> b) & 0xff;
            if (c < 0x20 && !separator(c)) return { count, control: { line, byte: c } };
          }
        }
        const value = (((w & 0x7f7f7f7f) + 0x5f5f5f5f) | w) & 0x80808080; // per byte: above 0x20
        const starts = value & ~((value << 8) | carry);
        carry = value >>> 24;
        count += Math.imul(starts >>> 7, 0x01010101) >>> 24; // bits set in starts
      }
      await pace((i + 4 * w0) / bytes.length);
    }
    inValue = carry >>> 7;
    i += words.length * 4;
  }
  control ??= byByte(i, bytes.length);
  return { count, control };
}

/** A decimal number (sign, digits, fraction, exponent) from bytes[s, e); NaN if malformed. */
function parseNumber(bytes, s, e) {
  let i = s, sign = 1;
  if (bytes[i] === 0x2d) { sign = -1; i++; } else if (bytes[i] === 0x2b) i++;
  let value = 0, digits = 0;
  while (i < e && bytes[i] >= 0x30 && bytes[i] <= 0x39) { value = value * 10 + (bytes[i++] - 0x30); digits++; }
  if (i < e && bytes[i] === 0x2e) {
    i++;
    let scale = 1, frac = 0;
    while (i < e && bytes[i] >= 0x30 && bytes[i] <= 0x39) { frac = frac * 10 + (bytes[i++] - 0x30); scale *= 10; digits++; }
    value += frac / scale;
  }
  if (digits === 0) return NaN;
  if (i < e && (bytes[i] === 0x65 || bytes[i] === 0x45)) {
    // Rare in grids: hand the whole token to Number() for exact exponent handling.
    return Number(String.fromCharCode(...bytes.subarray(s, e)));
  }
  return i === e ? sign * value : NaN;
}
