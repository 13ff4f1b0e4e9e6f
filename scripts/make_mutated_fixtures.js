#!/usr/bin/env node
// Writes the mutated fixtures of tests/fixtures/mutated/ from the format fixtures of
// tests/fixtures/formats/: each is one of our valid files with a few header bytes changed, the
// reproducer of a loader defect a mutation fuzzer found (tests/fixtures/mutated/README.md says
// what each mutation is). Deterministic; run it again after changing a source fixture:
//   node scripts/make_mutated_fixtures.js
import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';

const formats = new URL('../tests/fixtures/formats/', import.meta.url);
const outDir = new URL('../tests/fixtures/mutated/', import.meta.url);
mkdirSync(outDir, { recursive: true });
const read = (name) => new Uint8Array(readFileSync(new URL(name, formats)));
const write = (name, bytes) => writeFileSync(new URL(name, outDir), bytes);

// --- PNG: IHDR fields, with the chunk's CRC made valid again ------------------------------

function crc32(bytes) {
  let c = -1;
  for (const b of bytes) {
    c ^= b;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  }
  return (c ^ -1) >>> 0;
}

/** A copy of a PNG with IHDR's width, height and bit depth replaced (IHDR is the first chunk). */
function withIhdr(png, { width, height, bitDepth }) {
  const b = png.slice(), v = new DataView(b.buffer);
  if (width !== undefined) v.setUint32(16, width);
  if (height !== undefined) v.setUint32(20, height);
  if (bitDepth !== undefined) b[24] = bitDepth;
  v.setUint32(29, crc32(b.subarray(12, 29)));
  return b;
}

// --- TIFF: entries of the first image directory (little-endian classic TIFF) ---------------

/** A copy of a TIFF with the entries of `tags` (tag -> { type, count, value }) replaced;
 *  `double` appends an 8-byte float at the end of the file and points the entry at it. */
function withTags(tiff, tags) {
  const extra = Object.values(tags).filter((t) => t.double !== undefined).length;
  const b = new Uint8Array(tiff.length + 8 * extra);
  b.set(tiff);
  const v = new DataView(b.buffer), ifd = v.getUint32(4, true);
  let end = tiff.length;
  for (let i = 0; i < v.getUint16(ifd, true); i++) {
    const e = ifd + 2 + 12 * i, t = tags[v.getUint16(e, true)];
    if (!t) continue;
    if (t.double !== undefined) {
      v.setFloat64(end, t.double, true);
      Object.assign(t, { type: 12, count: 1, value: end });
      end += 8;
    }
    if (t.type !== undefined) v.setUint16(e + 2, t.type, true);
    if (t.count !== undefined) v.setUint32(e + 4, t.count, true);
    if (t.value !== undefined) {
      if (v.getUint16(e + 2, true) === 3 || v.getUint16(e + 2, true) === 8) v.setUint16(e + 8, t.value & 0xffff, true);
      else v.setUint32(e + 8, t.value >>> 0, true);
    }
  }
  return b;
}

const WIDTH = 256, HEIGHT = 257, ROWS_PER_STRIP = 278, TILE_WIDTH = 322, TILE_LENGTH = 323, GDAL_NODATA = 42113;
const TILE_OFFSETS = 324, TILE_BYTE_COUNTS = 325;
const SHORT = 3, SSHORT = 8;

/**
 * A sparse copy of a tiled TIFF (little-endian, LONG tile tables): declared `size` x `size`,
 * its tile tables rewritten at the end of the file, the tiles at the new indices of `keep`
 * (new index -> original tile index) pointing at the original's data, every other tile empty.
 */
function sparseTiles(tiff, tileSize, size, keep) {
  const v = new DataView(tiff.buffer, tiff.byteOffset, tiff.byteLength), ifd = v.getUint32(4, true);
  const tableOf = (tag) => {
    for (let i = 0; i < v.getUint16(ifd, true); i++) {
      const e = ifd + 2 + 12 * i;
      if (v.getUint16(e, true) === tag) return v.getUint32(e + 8, true);
    }
    throw new Error(`no tag ${tag}`);
  };
  const offsetsAt = tableOf(TILE_OFFSETS), countsAt = tableOf(TILE_BYTE_COUNTS);
  const tiles = (size / tileSize) ** 2;
  const b = new Uint8Array(tiff.length + 8 * tiles);
  b.set(tiff);
  const out = new DataView(b.buffer);
  for (const [index, original] of Object.entries(keep)) {
    out.setUint32(tiff.length + 4 * index, v.getUint32(offsetsAt + 4 * original, true), true);
    out.setUint32(tiff.length + 4 * (tiles + Number(index)), v.getUint32(countsAt + 4 * original, true), true);
  }
  return withTags(b, { [WIDTH]: { value: size }, [HEIGHT]: { value: size },
    [TILE_OFFSETS]: { count: tiles, value: tiff.length }, [TILE_BYTE_COUNTS]: { count: tiles, value: tiff.length + 4 * tiles } });
}

// --- text ---------------------------------------------------------------------------------

/** The header and first `rows` rows of an ESRI ASCII grid, nrows set to match. */
function ascRows(text, rows) {
  const lines = text.split('\n');
  const header = lines.findIndex((l) => /^[-\d.]/.test(l.trim()));
  return [...lines.slice(0, header).map((l) => (/^nrows/i.test(l) ? `nrows ${rows}` : l)), ...lines.slice(header, header + rows), ''].join('\n');
}

/** Replaces the n-th whitespace-separated value of the last row of an ASCII grid. */
function withLastRowValue(text, n, value) {
  const lines = text.trimEnd().split('\n');
  const values = lines.at(-1).trim().split(/\s+/);
  values[n] = value;
  lines[lines.length - 1] = values.join(' ');
  return `${lines.join('\n')}\n`;
}

// --- the fixtures -------------------------------------------------------------------------

const png16 = read('everest_16bit.png'), png8 = read('jacksboro_8bit.png'), rgb = read('canyon_terrain-rgb.png');
// Each claims more memory than a fresh core holds (64 MB) and less than the deflate limit
// (1032 bytes out per byte in) lets through. First a square size far beyond the data (its rows'
// filter bytes fall on image data), then sizes whose row length is a whole number of the
// original rows: every filter byte stays valid and only the length of the data shows the forgery.
write('everest_16bit_ihdr_6000x6000.png', withIhdr(png16, { width: 6000, height: 6000 }));
write('everest_16bit_ihdr_3007x12000.png', withIhdr(png16, { width: 3007, height: 12000 })); // 6015 = 15 x 401 bytes a row
write('jacksboro_8bit_ihdr_1bit_16056x17000.png', withIhdr(png8, { width: 16056, height: 17000, bitDepth: 1 })); // 2008 = 8 x 251
write('canyon_terrain-rgb_ihdr_1346x14000.png', withIhdr(rgb, { width: 1346, height: 14000 })); // 4039 = 7 x 577

const lzwStrips = read('etopo_i32_strips_lzw.tif'), deflateTiles = read('canyon_u16_tiled_deflate.tif');
const lzwTiles = read('jacksboro_f32_tiled_lzw.tif'), plainStrips = read('everest_i16_strips.tif');
write('etopo_i32_strips_lzw_width_58095.tif', withTags(lzwStrips, { [WIDTH]: { value: 58095 } }));
write('etopo_i32_strips_lzw_3000x12000.tif', withTags(lzwStrips, {
  [WIDTH]: { value: 3000 }, [HEIGHT]: { value: 12000 }, [ROWS_PER_STRIP]: { value: 700 } }));
write('etopo_i32_strips_lzw_width_120.tif', withTags(lzwStrips, { [WIDTH]: { value: 120 } }));
write('canyon_u16_tiled_deflate_tiles_2048.tif', withTags(deflateTiles, {
  [WIDTH]: { value: 6144 }, [HEIGHT]: { value: 6144 }, [TILE_WIDTH]: { value: 2048 }, [TILE_LENGTH]: { value: 2048 } }));
write('jacksboro_f32_tiled_lzw_tiles_2048.tif', withTags(lzwTiles, {
  [WIDTH]: { value: 8000 }, [HEIGHT]: { value: 6000 }, [TILE_WIDTH]: { value: 2048 }, [TILE_LENGTH]: { value: 2048 } }));
write('everest_i16_strips_400x100.tif', withTags(plainStrips, { [WIDTH]: { value: 400 }, [HEIGHT]: { value: 100 } }));
write('everest_i16_strips_width_100.tif', withTags(plainStrips, { [WIDTH]: { value: 100 } }));
write('everest_i16_strips_width_double_-200.tif', withTags(plainStrips, { [WIDTH]: { double: -200 } }));
write('everest_i16_strips_height_sshort_-200.tif', withTags(plainStrips, { [HEIGHT]: { type: SSHORT, value: -200 } }));
write('everest_i16_strips_rows_per_strip_double_16.5.tif', withTags(plainStrips, { [ROWS_PER_STRIP]: { double: 16.5 } }));
write('everest_i16_strips_nodata_short.tif', withTags(plainStrips, { [GDAL_NODATA]: { type: SHORT, count: 1, value: 7 } }));
// Sparse (GDAL SPARSE_OK): an 8192 x 8192 raster of 64 x 64 tiles, 16 384 tile entries, and
// data in one tile, or in two at opposite corners. Either was a 128 MiB field of a file of
// 130 KB, all but a tile or two interpolated.
const lastTile = (8192 / 64) ** 2 - 1;
write('canyon_u16_tiled_deflate_sparse_8192_one_tile.tif', sparseTiles(deflateTiles, 64, 8192, { 300: 4 }));
write('canyon_u16_tiled_deflate_sparse_8192_corners.tif', sparseTiles(deflateTiles, 64, 8192, { 0: 0, [lastTile]: 8 }));

const asc = ascRows(new TextDecoder().decode(read('jacksboro_voids.asc')), 4);
write('jacksboro_voids_4rows_1e999.asc', withLastRowValue(asc, 100, '1e999'));
write('jacksboro_voids_4rows_1e39.asc', withLastRowValue(asc, 100, '1e39'));
