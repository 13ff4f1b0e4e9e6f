// GeoTIFF, structure-aware: directory entries (tag, type, count, value/offset), the tags the
// loader reads (size, bits, sample format, compression, predictor, strips, tiles, rows per
// strip, pixel scale, tiepoint, geokeys, GDAL no-data 42113 as text and as wrong types), the
// blocks themselves (cut short, corrupted, dropped, forged offsets and byte counts), data
// recompressed as none/deflate/LZW, byte order and BigTIFF. Seeds: the four fixtures and small
// ones written here in both byte orders, classic and BigTIFF, strips and tiles.
import { fixtureFile, grid } from '../fixtures.js';
import {
  readTiff, writeTiff, buildTiff, setEntry, entryOf, values, compress, TYPES, TAGS, TYPE_SIZE,
} from '../formats/tiff_file.js';
import { inflateSync, constants } from 'node:zlib';
import { nearSize, EDGE_UINTS, NUMBER_TEXTS } from '../values.js';
import { applySteps } from './steps.js';

export const extension = 'tif';

export function seeds() {
  const out = ['everest_i16_strips.tif', 'canyon_u16_tiled_deflate.tif', 'etopo_i32_strips_lzw.tif', 'jacksboro_f32_tiled_lzw.tif']
    .map((name) => ({ files: [fixtureFile(name)] }));
  const land = grid('everest', 40, 30, 80, 80), sea = grid('etopo', 40, 30, 100, 40);
  // Big-endian seeds have one strip or tile, whose offset fits in its directory entry: geotiff
  // 3.0.5 reads offset tables stored elsewhere as little-endian whatever the file's byte order
  // (its DeferredArray), so a big-endian file with several blocks is refused; v1 shows that.
  const variants = [
    // byte order, BigTIFF, sample type, layout, compression, georeference, no-data
    [true, false, 'u16', { rowsPerStrip: 7 }, 1, 'projected'],
    [false, false, 'i16', { rowsPerStrip: 1 }, 8, 'geographic', '-32768'],
    [true, true, 'f32', { tile: 16 }, 5, 'geographic', '-9999'],
    [false, true, 'f64', { rowsPerStrip: 30 }, 1, 'projected'],
    [true, false, 'u8', { tile: 16 }, 8, null],
    [false, false, 'i32', { tile: 64 }, 5, 'geographic'],
    [true, false, 'u32', { rowsPerStrip: 4 }, 5, null],
    [true, false, 'f32', { rowsPerStrip: 5 }, 32946, 'projected', 'nan'],
    [false, false, 'u16', { tile: 48 }, 5, 'geographic'],
    [true, true, 'i16', { rowsPerStrip: 30 }, 8, null],
    [false, false, 'f32', { rowsPerStrip: 30 }, 8, 'geographic', '-9999'],
    [false, false, 'u16', { rowsPerStrip: 30 }, 1, null],
  ];
  variants.forEach(([le, big, type, layout, compression, geo, nodata], i) => {
    const g = type === 'i16' || type === 'i32' || type.startsWith('f') ? sea : land;
    const vals = type === 'u8' ? g.values.map((v) => (v - 4000) / 20) : g.values;
    if (nodata === '-9999') vals[7] = vals[8] = -9999;
    const model = buildTiff({ le, big, width: g.width, height: g.height, type, values: vals, ...layout, compression, geo, nodata });
    out.push({ files: [{ name: `v${i}_${type}.tif`, bytes: writeTiff(model) }], model });
  });
  return out;
}

/** A deep enough copy of a model to change it freely. */
function copyModel(m) {
  return { ...m, entries: m.entries.map((e) => ({ ...e })), blocks: m.blocks.slice(), plain: m.plain?.slice() };
}

const KNOWN_TAGS = Object.values(TAGS);
const doubles = (r, n) => Array.from({ length: n }, () => r.pick([0, -30, 30, 1 / 120, NaN, Infinity, -Infinity, 1e-300, 1e300, 90, 1000, -1e9]));

/** What to set a tag to: [type, values] or [ASCII, text]. */
function valueFor(tag, m, r) {
  const S = TYPES.SHORT, L = TYPES.LONG;
  const sizeType = () => r.pick([S, L, L, TYPES.LONG8, TYPES.DOUBLE, TYPES.SLONG]);
  // An earlier step may have made the tag text: its values are then a string, not numbers.
  const held = entryOf(m, tag) ? values(m, entryOf(m, tag)) : [];
  const current = typeof held === 'string' ? [] : Array.from(held);
  switch (tag) {
    case TAGS.ImageWidth: case TAGS.ImageLength: return [sizeType(), [nearSize(r, current[0] ?? 40)]];
    case TAGS.BitsPerSample: return [S, r.chance(0.8) ? [r.pick([0, 1, 7, 8, 12, 16, 24, 32, 64, 128])] : [16, 16, 16]];
    case TAGS.SampleFormat: return [S, r.chance(0.9) ? [r.pick([0, 1, 2, 3, 4, 5, 6, 99])] : [3, 3]];
    case TAGS.Compression: return [S, [r.pick([0, 1, 2, 5, 6, 7, 8, 32773, 32946, 34887, 50000])]];
    case TAGS.Predictor: return [S, [r.pick([0, 1, 2, 3, 4])]];
    case TAGS.RowsPerStrip: return [sizeType(), [nearSize(r, current[0] ?? 7)]];
    case TAGS.TileWidth: case TAGS.TileLength: return [sizeType(), [r.pick([0, 1, 8, 15, 16, 17, 64, 65535, 0xffffffff, nearSize(r, 16)])]];
    case TAGS.SamplesPerPixel: return [S, [r.pick([0, 1, 2, 3, 4, 255])]];
    case TAGS.PlanarConfiguration: return [S, [r.pick([0, 1, 2, 3])]];
    case TAGS.Photometric: return [S, [r.pick([0, 1, 2, 3, 5, 32844])]];
    case TAGS.ModelPixelScale: return [TYPES.DOUBLE, doubles(r, r.pick([3, 3, 2, 1, 0]))];
    case TAGS.ModelTiepoint: return [TYPES.DOUBLE, doubles(r, r.pick([6, 6, 12, 3]))];
    case TAGS.ModelTransformation: return [TYPES.DOUBLE, doubles(r, 16)];
    case TAGS.GeoKeyDirectory: {
      const keys = current.length >= 4 ? current : [1, 1, 0, 1, 1024, 0, 1, 2];
      for (let k = r.range(1, 3); k > 0; k--) keys[r.int(keys.length)] = r.pick([0, 1, 2, 3, 1024, 1025, 2048, 3072, 3076, 34736, 34737, 32767, 65535, r.int(65536)]);
      if (r.chance(0.2)) keys.length = r.int(keys.length);
      return [S, keys];
    }
    case TAGS.GdalNoData: return r.chance(0.5) ? [TYPES.ASCII, r.pick(NUMBER_TEXTS)]
      : [r.pick([S, L, TYPES.DOUBLE, TYPES.BYTE, TYPES.SSHORT, TYPES.FLOAT]), [r.pick([0, 1, 9999, 65535, -9999, NaN])].slice(0, r.pick([0, 1, 1, 2]))];
    case TAGS.GdalMetadata: return [TYPES.ASCII, r.pick(['<GDALMetadata>', '<GDALMetadata><Item name="SCALE">2</Item></GDALMetadata>', ''])];
    default: return [r.pick([S, L, TYPES.ASCII, TYPES.DOUBLE]), [r.int(65536)]];
  }
}

/**
 * Whether the image is in strips. Claims that a cut block must be refused are made for strips
 * alone: a tile at the image's edge is padded, and a cut may take only padding.
 */
const stripped = (m) => !entryOf(m, TAGS.TileOffsets) && !entryOf(m, TAGS.TileWidth);
/**
 * True when a compressed block cut short still decodes to all it held: a cut of the zlib
 * checksum, or of the last bits after the data, loses nothing (libtiff and we read the block
 * whole). Deflate is inflated here to see; for LZW a cut of at most the end-of-information
 * code's two bytes makes no claim either way.
 */
function stillWhole(m, whole, cut) {
  const entry = entryOf(m, TAGS.Compression);
  const compression = entry ? Number(values(m, entry)[0] ?? 1) : 1;
  if (compression === 5) return whole.length - cut.length <= 2;
  if (compression !== 8 && compression !== 32946) return false;
  // zlib with a sync flush at the end gives what a cut stream holds instead of failing on it.
  const inflated = (bytes) => {
    try { return inflateSync(bytes, { finishFlush: constants.Z_SYNC_FLUSH }); } catch { return Buffer.alloc(0); }
  };
  return inflated(whole).equals(inflated(cut));
}
/** Tags that say how many bytes a strip needs: once one changes, no claim about a cut strip holds. */
const GEOMETRY = [256, 257, 258, 259, 277, 278, 284, 317, 322, 323, 339];

const STEPS = [
  [8, function setTag(m, r) {
    const tag = r.pick(KNOWN_TAGS);
    const [type, value] = valueFor(tag, m, r);
    setEntry(m, tag, type, type === TYPES.ASCII ? String(value) : value);
    if (GEOMETRY.includes(tag)) m.geometryChanged = true;
    return `tag ${tag} = ${type === TYPES.ASCII ? JSON.stringify(value) : `type ${type} [${value.slice(0, 6).join(', ')}]`}`;
  }],
  [6, function entryField(m, r) {
    const e = r.pick(m.entries);
    if (!e) return null;
    const field = r.pick(['tag', 'type', 'count', 'offset']);
    if (field === 'tag') e.tag = r.chance(0.5) ? r.pick(KNOWN_TAGS) : r.int(65536);
    else if (field === 'type') e.type = r.pick([0, 1, 2, 3, 4, 5, 7, 8, 9, 11, 12, 13, 16, 17, 18, 19, 255, 65535]);
    else if (field === 'count') e.countOverride = r.pick([0, 1, e.count + 1, e.count - 1, e.count * 2, ...EDGE_UINTS.slice(-6)]) >>> 0;
    else e.offsetOverride = r.pick(EDGE_UINTS);
    e.auto = false;
    m.geometryChanged = true;
    return `entry ${e.tag} ${field} forged`;
  }],
  [2, function removeEntry(m, r) {
    const [e] = m.entries.splice(r.int(m.entries.length), 1);
    m.geometryChanged = true;
    return e ? `entry ${e.tag} removed` : null;
  }],
  [1, function duplicateOrShuffle(m, r) {
    const i = r.int(m.entries.length), j = r.int(m.entries.length);
    m.geometryChanged = true;
    if (r.chance(0.5)) { m.entries.splice(j, 0, { ...m.entries[i], auto: false }); return `entry ${m.entries[i]?.tag} twice`; }
    [m.entries[i], m.entries[j]] = [m.entries[j], m.entries[i]];
    return 'entries out of order';
  }],
  [5, function blocks(m, r) {
    const i = r.int(m.blocks.length);
    const b = m.blocks[i];
    const op = r.pick(['cut', 'cut', 'flip', 'empty', 'drop', 'swap', 'pad']);
    if (!b) return null;
    // An empty block is a sparse one (GDAL's SPARSE_OK), read as no-data: no claim for those.
    if (op === 'cut') {
      m.blocks[i] = b.slice(0, r.int(b.length));
      m.invalid = stripped(m) && m.blocks[i].length > 0 && !stillWhole(m, b, m.blocks[i]) && `strip ${i} was cut short`;
    }
    else if (op === 'flip') { const c = b.slice(); for (let k = r.range(1, 8); k > 0; k--) c[r.int(c.length)] ^= 1 << r.int(8); m.blocks[i] = c; }
    else if (op === 'empty') m.blocks[i] = new Uint8Array(0);
    else if (op === 'drop') { m.blocks.splice(i, 1); m.invalid = `block ${i} is missing`; }
    else if (op === 'swap') { const j = r.int(m.blocks.length); [m.blocks[i], m.blocks[j]] = [m.blocks[j], m.blocks[i]]; }
    else { const c = new Uint8Array(b.length + r.smallLength()); c.set(b); m.blocks[i] = c; }
    return `block ${i}: ${op}`;
  }],
  [3, function forgeBlockTables(m, r) {
    const tiled = entryOf(m, TAGS.TileOffsets);
    const tag = r.chance(0.5) ? (tiled ? TAGS.TileOffsets : TAGS.StripOffsets) : tiled ? TAGS.TileByteCounts : TAGS.StripByteCounts;
    const e = entryOf(m, tag);
    if (!e) return null;
    writeTiff(m); // fills the entry with the true values first
    const list = values(m, e);
    if (typeof list === 'string') return null; // an earlier step made it text
    const op = r.pick(['fewer', 'more', 'value', 'zero', 'past end']);
    if (op === 'fewer') list.length = r.int(list.length);
    else if (op === 'more') list.push(...Array.from({ length: r.range(1, 100) }, () => r.pick(EDGE_UINTS)));
    else if (op === 'value') list[r.int(list.length)] = r.pick(EDGE_UINTS);
    else if (op === 'zero') list.fill(0);
    else list[r.int(list.length)] += 1 << 24;
    setEntry(m, tag, r.chance(0.8) ? e.type : r.pick([TYPES.SHORT, TYPES.LONG, TYPES.LONG8]), list);
    m.geometryChanged = true; // the tables no longer describe the blocks
    return `${tag === TAGS.TileOffsets || tag === TAGS.StripOffsets ? 'offsets' : 'byte counts'}: ${op}`;
  }],
  [3, function recompress(m, r) {
    // The same samples in another compression (accepted), or short data compressed validly.
    if (!m.plain) return null;
    const compression = r.pick([1, 5, 8]);
    const short = r.chance(0.3) ? r.int(m.plain[0].length) : -1;
    m.blocks = m.plain.map((p, i) => compress(short >= 0 && i === 0 ? p.subarray(0, short) : p, compression));
    if (short >= 0) m.invalid = stripped(m) && (short > 0 || compression !== 1) && 'strip 0 holds fewer bytes than its rows when decoded';
    setEntry(m, TAGS.Compression, TYPES.SHORT, [compression]);
    return `recompressed as ${compression}${short >= 0 ? ` with block 0 cut to ${short} bytes` : ''}`;
  }],
  [1, function byteOrderOrBig(m, r) {
    if (r.chance(0.5)) { m.big = !m.big; return m.big ? 'as BigTIFF' : 'as classic TIFF'; }
    m.le = !m.le;
    m.geometryChanged = true;
    return 'byte order flipped, values not converted';
  }],
];

/** Patches of the written file: the header's directory offset, BigTIFF's byte size, next IFD. */
function patchHeader(bytes, m, r) {
  const view = new DataView(bytes.buffer);
  const op = r.pick(['ifd offset', 'bytesize', 'next ifd', 'version']);
  const ifd = m.big ? Number(view.getBigUint64(8, m.le)) : view.getUint32(4, m.le);
  if (op === 'ifd offset') {
    const v = r.pick([0, 1, 7, 8, bytes.length - 2, bytes.length, ...EDGE_UINTS.slice(-4)]);
    if (m.big) view.setBigUint64(8, BigInt(v), m.le); else view.setUint32(4, v, m.le);
  } else if (op === 'bytesize' && m.big) {
    view.setUint16(4, r.pick([0, 4, 16, 65535]), m.le);
  } else if (op === 'next ifd') {
    const at = bytes.length - (m.big ? 8 : 4);
    const v = r.pick([ifd, 8, bytes.length, r.int(bytes.length)]); // itself: a loop
    if (m.big) view.setBigUint64(at, BigInt(v), m.le); else view.setUint32(at, v, m.le);
  } else {
    view.setUint16(2, r.pick([42, 43, 44, 0]), m.le);
  }
  return `header ${op} patched`;
}

export function mutate(seed, random) {
  const main = seed.files[0];
  seed.parsed ??= seed.model ?? readTiff(main.bytes);
  const m = copyModel(seed.parsed);
  const how = applySteps(m, random, STEPS, { counts: [[5, 1], [3, 2], [2, 3]], lastVerdict: true });
  const bytes = writeTiff(m);
  if (random.chance(0.1)) { how.push(patchHeader(bytes, m, random)); m.invalid = null; }
  return { files: [{ name: main.name, bytes }], options: {}, how, invalid: (!m.geometryChanged && m.invalid) || null };
}

/**
 * Directory entries' values and blocks as the minimiser's parts, written back with counts and
 * offsets made right (null when the file cannot be walked plainly).
 */
export function split(bytes) {
  let m;
  try { m = readTiff(bytes); } catch { return null; }
  const n = m.entries.length;
  return {
    parts: [...m.entries.map((e) => e.data), ...m.blocks],
    join: (parts) => writeTiff({ ...m,
      entries: m.entries.flatMap((e, i) => (parts[i] ? [{ ...e, data: parts[i], count: Math.floor(parts[i].length / (TYPE_SIZE[e.type] ?? 1)) }] : [])),
      blocks: parts.slice(n).filter(Boolean) }),
    shrinkInside: true,
  };
}

/** ImageWidth x ImageLength of the first directory, or null when it cannot be read plainly. */
export function declaredSize(files) {
  try {
    const m = readTiff(files[0].bytes);
    const w = m.entries.filter((e) => e.tag === TAGS.ImageWidth), h = m.entries.filter((e) => e.tag === TAGS.ImageLength);
    if (w.length !== 1 || h.length !== 1) return null;
    return { width: values(m, w[0])[0], height: values(m, h[0])[0] };
  } catch {
    return null;
  }
}
