// PNG as a list of chunks, for the fuzzer: read a file into { type, data } chunks, write chunks
// back with lengths and CRCs recomputed (so a mutation reaches the decoder instead of being
// stopped by a CRC check), and encode a small image from raw rows. Written for this tool alone,
// independent of web/loaders/png.js, which it tests.
import { zlibSync } from 'fflate';

export const SIGNATURE = Uint8Array.of(0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a);

let table = null;
/** CRC-32 of the PNG and zlib specifications. */
export function crc32(bytes) {
  if (!table) {
    table = new Uint32Array(256);
    for (let n = 0; n < 256; n++) {
      let c = n;
      for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
      table[n] = c >>> 0;
    }
  }
  let c = 0xffffffff;
  for (const b of bytes) c = table[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

const ascii = (type) => Uint8Array.from(type, (c) => c.charCodeAt(0) & 0xff);

/**
 * The chunks of a PNG, as far as its chunk structure can be walked.
 * @returns {{ chunks: Array<{ type: string, data: Uint8Array }>, rest: Uint8Array }} rest: bytes
 *   after the last whole chunk (a truncated tail), or everything after the signature when the
 *   file is not a PNG
 */
export function readChunks(bytes) {
  const chunks = [];
  let p = 8;
  if (bytes.length < 8) return { chunks, rest: bytes.subarray(0) };
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.length);
  while (p + 12 <= bytes.length) {
    const length = view.getUint32(p);
    if (p + 12 + length > bytes.length) break;
    const type = String.fromCharCode(...bytes.subarray(p + 4, p + 8));
    chunks.push({ type, data: bytes.slice(p + 8, p + 8 + length) });
    p += 12 + length;
  }
  return { chunks, rest: bytes.slice(p) };
}

/**
 * A PNG file from chunks. A chunk may carry `length` (the length field to write instead of the
 * data's) or `badCrc` (write a wrong CRC): the two forgeries a decoder must catch itself.
 */
export function writeChunks(chunks, { signature = SIGNATURE, rest = new Uint8Array(0) } = {}) {
  const size = signature.length + chunks.reduce((s, c) => s + 12 + c.data.length, 0) + rest.length;
  const out = new Uint8Array(size);
  const view = new DataView(out.buffer);
  out.set(signature);
  let p = signature.length;
  for (const c of chunks) {
    view.setUint32(p, c.length ?? c.data.length);
    const body = new Uint8Array(4 + c.data.length);
    body.set(ascii(c.type.padEnd(4, ' ').slice(0, 4)));
    body.set(c.data, 4);
    out.set(body, p + 4);
    const crc = crc32(body);
    view.setUint32(p + 8 + c.data.length, c.badCrc ? crc ^ 1 : crc);
    p += 12 + c.data.length;
  }
  out.set(rest, p);
  return out;
}

/** Rewrites every CRC of a file whose chunk structure can be walked (for the minimiser). */
export function fixCrcs(bytes) {
  if (bytes.length < 8) return bytes;
  const { chunks, rest } = readChunks(bytes);
  return writeChunks(chunks, { signature: bytes.subarray(0, 8), rest });
}

/** The 13 bytes of an IHDR chunk. */
export function ihdrData({ width, height, bitDepth, colourType, compression = 0, filter = 0, interlace = 0 }) {
  const data = new Uint8Array(13);
  const view = new DataView(data.buffer);
  view.setUint32(0, width >>> 0);
  view.setUint32(4, height >>> 0);
  data.set([bitDepth, colourType, compression, filter, interlace], 8);
  return data;
}

/** IHDR fields of a chunk's data (13 bytes, or fewer when it was cut). */
export function parseIhdr(data) {
  if (data.length < 13) return null;
  const view = new DataView(data.buffer, data.byteOffset, data.length);
  return { width: view.getUint32(0), height: view.getUint32(4), bitDepth: data[8], colourType: data[9],
    compression: data[10], filter: data[11], interlace: data[12] };
}

export const CHANNELS = { 0: 1, 2: 3, 3: 1, 4: 2, 6: 4 };

/** Bytes of one row without its filter byte. */
export function rowBytes(width, bitDepth, colourType) {
  return Math.ceil((width * bitDepth * (CHANNELS[colourType] ?? 1)) / 8);
}

/**
 * Encodes samples as a PNG (filter type None, one zlib stream split into IDAT chunks).
 * @param {{ width, height, bitDepth, colourType, rows: Uint8Array, text?: object, idatSize?: number }} o
 *   rows: the packed row bytes, height * rowBytes, big-endian for 16 bits
 */
export function encodePng(o) {
  const { width, height, bitDepth, colourType, rows } = o;
  const stride = rowBytes(width, bitDepth, colourType);
  const raw = new Uint8Array(height * (stride + 1));
  for (let y = 0; y < height; y++) raw.set(rows.subarray(y * stride, (y + 1) * stride), y * (stride + 1) + 1);
  const chunks = [{ type: 'IHDR', data: ihdrData(o) }];
  for (const [key, value] of Object.entries(o.text ?? {})) {
    chunks.push({ type: 'tEXt', data: ascii(`${key}\0${value}`) });
  }
  if (o.trns !== undefined) chunks.push({ type: 'tRNS', data: Uint8Array.of(o.trns >> 8, o.trns & 255) });
  const stream = zlibSync(raw);
  const size = o.idatSize ?? stream.length;
  for (let p = 0; p < stream.length; p += size) chunks.push({ type: 'IDAT', data: stream.slice(p, p + size) });
  chunks.push({ type: 'IEND', data: new Uint8Array(0) });
  return writeChunks(chunks);
}

/** The text of a chunk type as bytes, for tEXt and friends. */
export function textChunk(key, value) {
  return { type: 'tEXt', data: ascii(`${key}\0${value}`) };
}
