// TIFF and BigTIFF as a model the fuzzer can change and write back: the byte order, the first
// image directory's entries (tag, type, count, value bytes) and the image blocks (strips or
// tiles). Writing lays the blocks, the out-of-line values and the directory out again and
// points the offset tags at the blocks, unless a mutation forged them. Written for this tool,
// independent of the geotiff library the loader uses.
import { zlibSync } from 'fflate';
import { lzwEncode } from './lzw.js';

export const TYPES = { BYTE: 1, ASCII: 2, SHORT: 3, LONG: 4, RATIONAL: 5, SBYTE: 6, UNDEFINED: 7, SSHORT: 8, SLONG: 9,
  SRATIONAL: 10, FLOAT: 11, DOUBLE: 12, IFD: 13, LONG8: 16, SLONG8: 17, IFD8: 18 };
/** Bytes per value of each type; unknown types are written as bytes. */
export const TYPE_SIZE = { 1: 1, 2: 1, 3: 2, 4: 4, 5: 8, 6: 1, 7: 1, 8: 2, 9: 4, 10: 8, 11: 4, 12: 8, 13: 4, 16: 8, 17: 8, 18: 8 };
export const TAGS = { ImageWidth: 256, ImageLength: 257, BitsPerSample: 258, Compression: 259, Photometric: 262,
  StripOffsets: 273, SamplesPerPixel: 277, RowsPerStrip: 278, StripByteCounts: 279, PlanarConfiguration: 284,
  Predictor: 317, TileWidth: 322, TileLength: 323, TileOffsets: 324, TileByteCounts: 325, ExtraSamples: 338,
  SampleFormat: 339, ModelPixelScale: 33550, ModelTiepoint: 33922, ModelTransformation: 34264,
  GeoKeyDirectory: 34735, GeoDoubleParams: 34736, GeoAsciiParams: 34737, GdalMetadata: 42112, GdalNoData: 42113 };

const size = (type) => TYPE_SIZE[type] ?? 1;

/** Reads a numeric value of `type` at p. */
function getValue(view, p, type, le) {
  switch (type) {
    case 3: return view.getUint16(p, le);
    case 8: return view.getInt16(p, le);
    case 4: case 13: return view.getUint32(p, le);
    case 9: return view.getInt32(p, le);
    case 5: return view.getUint32(p, le) / view.getUint32(p + 4, le);
    case 10: return view.getInt32(p, le) / view.getInt32(p + 4, le);
    case 11: return view.getFloat32(p, le);
    case 12: return view.getFloat64(p, le);
    case 16: case 18: return Number(view.getBigUint64(p, le));
    case 17: return Number(view.getBigInt64(p, le));
    case 6: return view.getInt8(p);
    default: return view.getUint8(p);
  }
}

function setValue(view, p, type, le, v) {
  switch (type) {
    case 3: case 8: view.setUint16(p, v & 0xffff, le); break;
    case 4: case 9: case 13: view.setUint32(p, v >>> 0, le); break;
    case 5: case 10: view.setUint32(p, v >>> 0, le); view.setUint32(p + 4, 1, le); break;
    case 11: view.setFloat32(p, v, le); break;
    case 12: view.setFloat64(p, v, le); break;
    case 16: case 17: case 18: view.setBigUint64(p, BigInt.asUintN(64, BigInt(Math.trunc(Number.isFinite(v) ? v : 0))), le); break;
    default: view.setUint8(p, v & 0xff);
  }
}

/** The numbers of an entry (an ASCII entry's text is a string). */
export function values(model, entry) {
  if (entry.type === TYPES.ASCII) return new TextDecoder('latin1').decode(entry.data).replace(/\0+$/, '');
  const view = new DataView(entry.data.buffer, entry.data.byteOffset, entry.data.length);
  const out = [];
  for (let p = 0; p + size(entry.type) <= entry.data.length; p += size(entry.type)) out.push(getValue(view, p, entry.type, model.le));
  return out;
}

/** Sets an entry (added when missing) to numbers of a type, or to a text with type ASCII. */
export function setEntry(model, tag, type, value) {
  let data;
  if (typeof value === 'string') {
    data = Uint8Array.from(`${value}\0`, (c) => c.charCodeAt(0) & 0xff);
  } else {
    data = new Uint8Array(value.length * size(type));
    const view = new DataView(data.buffer);
    value.forEach((v, i) => setValue(view, i * size(type), type, model.le, v));
  }
  const entry = { tag, type, count: data.length / size(type), data };
  const i = model.entries.findIndex((e) => e.tag === tag);
  if (i >= 0) model.entries[i] = entry; else model.entries.push(entry);
  return entry;
}

export function entryOf(model, tag) {
  return model.entries.find((e) => e.tag === tag);
}

/** Reads a TIFF's header, first directory and blocks. Throws on a file it cannot walk. */
export function readTiff(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.length);
  const le = bytes[0] === 0x49;
  const big = view.getUint16(2, le) === 43;
  let p = big ? Number(view.getBigUint64(8, le)) : view.getUint32(4, le);
  const n = big ? Number(view.getBigUint64(p, le)) : view.getUint16(p, le);
  p += big ? 8 : 2;
  const model = { le, big, entries: [], blocks: [] };
  for (let i = 0; i < n; i++, p += big ? 20 : 12) {
    const tag = view.getUint16(p, le), type = view.getUint16(p + 2, le);
    const count = big ? Number(view.getBigUint64(p + 4, le)) : view.getUint32(p + 4, le);
    const bytesLong = count * size(type), slot = p + (big ? 12 : 8);
    const at = bytesLong <= (big ? 8 : 4) ? slot : big ? Number(view.getBigUint64(slot, le)) : view.getUint32(slot, le);
    model.entries.push({ tag, type, count, data: bytes.slice(at, at + bytesLong) });
  }
  const tiled = entryOf(model, TAGS.TileOffsets);
  const offsets = values(model, tiled ?? entryOf(model, TAGS.StripOffsets));
  const counts = values(model, entryOf(model, tiled ? TAGS.TileByteCounts : TAGS.StripByteCounts));
  model.blocks = offsets.map((o, i) => bytes.slice(o, o + counts[i]));
  for (const e of model.entries) if ([273, 279, 324, 325].includes(e.tag)) e.auto = true;
  return model;
}

/**
 * Writes the model. Entries with `auto` (the block offsets and byte counts) are filled from
 * the blocks; an entry may carry `countOverride` or `offsetOverride` (the count or value/offset
 * field to write instead of the true one).
 */
export function writeTiff(model) {
  const { le, big } = model;
  const inline = big ? 8 : 4, entrySize = big ? 20 : 12;
  let pos = big ? 16 : 8;
  const blockAt = model.blocks.map((b) => { const at = pos; pos += b.length + (b.length & 1); return at; });
  for (const e of model.entries) {
    if (!e.auto) continue;
    const offsetsTag = e.tag === 273 || e.tag === 324;
    const type = big ? TYPES.LONG8 : TYPES.LONG;
    const fresh = setEntry({ ...model, entries: [] }, e.tag, type, offsetsTag ? blockAt : model.blocks.map((b) => b.length));
    Object.assign(e, { type, count: fresh.count, data: fresh.data });
  }
  const outOfLine = new Map();
  for (const e of model.entries) {
    if (e.data.length > inline && e.offsetOverride === undefined) { outOfLine.set(e, pos); pos += e.data.length + (e.data.length & 1); }
  }
  const ifd = pos;
  const total = ifd + (big ? 8 : 2) + model.entries.length * entrySize + inline;
  const out = new Uint8Array(total);
  const view = new DataView(out.buffer);
  out.set(le ? [0x49, 0x49] : [0x4d, 0x4d]);
  view.setUint16(2, big ? 43 : 42, le);
  if (big) { view.setUint16(4, 8, le); view.setBigUint64(8, BigInt(ifd), le); } else view.setUint32(4, ifd, le);
  model.blocks.forEach((b, i) => out.set(b, blockAt[i]));
  if (big) view.setBigUint64(ifd, BigInt(model.entries.length), le); else view.setUint16(ifd, model.entries.length, le);
  model.entries.forEach((e, i) => {
    const p = ifd + (big ? 8 : 2) + i * entrySize;
    view.setUint16(p, e.tag, le);
    view.setUint16(p + 2, e.type, le);
    const count = e.countOverride ?? e.count;
    if (big) view.setBigUint64(p + 4, BigInt(count), le); else view.setUint32(p + 4, count >>> 0, le);
    const slot = p + (big ? 12 : 8);
    if (e.offsetOverride !== undefined) {
      if (big) view.setBigUint64(slot, BigInt(e.offsetOverride), le); else view.setUint32(slot, e.offsetOverride >>> 0, le);
    } else if (outOfLine.has(e)) {
      const at = outOfLine.get(e);
      out.set(e.data, at);
      if (big) view.setBigUint64(slot, BigInt(at), le); else view.setUint32(slot, at, le);
    } else {
      out.set(e.data, slot);
    }
  });
  return out;
}

/** Sample types: [SampleFormat, BitsPerSample, DataView setter]. */
const SAMPLE_TYPES = { u8: [1, 8, 'setUint8'], u16: [1, 16, 'setUint16'], i16: [2, 16, 'setInt16'], u32: [1, 32, 'setUint32'],
  i32: [2, 32, 'setInt32'], f32: [3, 32, 'setFloat32'], f64: [3, 64, 'setFloat64'] };

/** Compresses one block's bytes (1 none, 5 LZW, 8 or 32946 deflate). */
export function compress(plain, compression) {
  if (compression === 5) return lzwEncode(plain);
  if (compression === 8 || compression === 32946) return zlibSync(plain);
  return plain.slice();
}

/**
 * A one-band GeoTIFF model from samples.
 * @param {{ le: boolean, big: boolean, width: number, height: number, type: keyof SAMPLE_TYPES, values: ArrayLike<number>,
 *   tile?: number, rowsPerStrip?: number, compression: number, geo?: 'geographic'|'projected', nodata?: string }} o
 * @returns model with `plain`: the blocks before compression, in the file's byte order
 */
export function buildTiff(o) {
  const [format, bits, setter] = SAMPLE_TYPES[o.type];
  const bytesPer = bits / 8;
  const [bw, bh] = o.tile ? [o.tile, o.tile] : [o.width, o.rowsPerStrip];
  const plain = [];
  for (let by = 0; by < o.height; by += bh) {
    for (let bx = 0; bx < (o.tile ? o.width : 1); bx += bw) {
      const rows = o.tile ? bh : Math.min(bh, o.height - by); // tiles are padded, the last strip is not
      const block = new Uint8Array(bw * rows * bytesPer);
      const view = new DataView(block.buffer);
      for (let y = 0; y < rows; y++) for (let x = 0; x < bw; x++) {
        if (by + y >= o.height || bx + x >= o.width) continue;
        const v = o.values[(by + y) * o.width + bx + x];
        view[setter]((y * bw + x) * bytesPer, format === 3 ? v : Math.round(v), o.le);
      }
      plain.push(block);
    }
  }
  const model = { le: o.le, big: o.big, entries: [], blocks: plain.map((b) => compress(b, o.compression)), plain };
  const S = TYPES.SHORT, L = TYPES.LONG;
  setEntry(model, TAGS.ImageWidth, L, [o.width]);
  setEntry(model, TAGS.ImageLength, o.height < 65536 && o.le ? S : L, [o.height]);
  setEntry(model, TAGS.BitsPerSample, S, [bits]);
  setEntry(model, TAGS.Compression, S, [o.compression]);
  setEntry(model, TAGS.Photometric, S, [1]);
  setEntry(model, TAGS.SamplesPerPixel, S, [1]);
  setEntry(model, TAGS.PlanarConfiguration, S, [1]);
  setEntry(model, TAGS.SampleFormat, S, [format]);
  if (o.tile) {
    setEntry(model, TAGS.TileWidth, S, [o.tile]);
    setEntry(model, TAGS.TileLength, S, [o.tile]);
    setEntry(model, TAGS.TileOffsets, L, []).auto = true;
    setEntry(model, TAGS.TileByteCounts, L, []).auto = true;
  } else {
    setEntry(model, TAGS.RowsPerStrip, L, [o.rowsPerStrip]);
    setEntry(model, TAGS.StripOffsets, L, []).auto = true;
    setEntry(model, TAGS.StripByteCounts, L, []).auto = true;
  }
  if (o.geo === 'geographic') {
    setEntry(model, TAGS.ModelPixelScale, TYPES.DOUBLE, [1 / 120, 1 / 120, 0]);
    setEntry(model, TAGS.ModelTiepoint, TYPES.DOUBLE, [0, 0, 0, 86.5, 28.2, 0]);
    setEntry(model, TAGS.GeoKeyDirectory, S, [1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326]);
  } else if (o.geo === 'projected') {
    setEntry(model, TAGS.ModelPixelScale, TYPES.DOUBLE, [30, 30, 0]);
    setEntry(model, TAGS.ModelTiepoint, TYPES.DOUBLE, [0, 0, 0, 500000, 4000000, 0]);
    setEntry(model, TAGS.GeoKeyDirectory, S, [1, 1, 0, 4, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 32633, 3076, 0, 1, 9001]);
  }
  if (o.nodata !== undefined) setEntry(model, TAGS.GdalNoData, TYPES.ASCII, o.nodata);
  model.entries.sort((a, b) => a.tag - b.tag);
  return model;
}
