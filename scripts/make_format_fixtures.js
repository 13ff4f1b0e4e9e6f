#!/usr/bin/env node
// Writes the format fixtures of tests/fixtures/formats/ from the real DEMs of the shared data
// folder (run once by a developer; the tests read only the committed output):
//   node scripts/make_format_fixtures.js /path/to/dem/
// Each crop is written as <crop>.f32 (the original float32 heights, the reference the
// tests compare against) and in the formats listed in manifest.json, with the quantisation
// each format implies. The writers here are independent of web/loaders: a fixture that a
// loader misreads fails its test.
import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { encode as encodePng } from 'fast-png';
import { zlibSync } from 'fflate';

if (!process.argv[2]) {
  console.error('usage: node scripts/make_format_fixtures.js /path/to/dem/ (the source DEMs are not in the project)');
  process.exit(2);
}
const demDir = process.argv[2].endsWith('/') ? process.argv[2] : `${process.argv[2]}/`;
const outDir = new URL('../tests/fixtures/formats/', import.meta.url).pathname;
mkdirSync(outDir, { recursive: true });

function readDem(name) {
  const meta = JSON.parse(readFileSync(`${demDir}/${name}.json`, 'utf8'));
  const b = readFileSync(`${demDir}/${name}.f32`);
  return { meta, data: new Float32Array(b.buffer, b.byteOffset, b.length / 4) };
}

function crop({ meta, data }, x0, y0, width, height) {
  const out = new Float32Array(width * height);
  for (let y = 0; y < height; y++) out.set(data.subarray((y0 + y) * meta.width + x0, (y0 + y) * meta.width + x0 + width), y * width);
  return out;
}

const write = (file, bytes) => writeFileSync(`${outDir}${file}`, bytes);
const manifest = [];
const minMax = (h) => h.reduce(([lo, hi], v) => (Number.isNaN(v) ? [lo, hi] : [Math.min(lo, v), Math.max(hi, v)]), [Infinity, -Infinity]);
const json = (o) => new TextEncoder().encode(JSON.stringify(o, null, 1));

// --- crops -------------------------------------------------------------------------------
const jacksboroDem = readDem('jacksboro_fault');
const globeDem = readDem('globe_himalaya_2048');
const canyonDem = readDem('grandcanyon_512');
const etopoDem = readDem('etopo5_global_2160x1080');
const volcanoDem = readDem('volcano_maungawhau');

const crops = {
  // 3" USGS NED, geographic; 250 x 190 so 64-sample tiles end part-way.
  jacksboro: { data: crop(jacksboroDem, 100, 80, 250, 190), width: 250, height: 190,
    west: -84.41375 + 100 / 1200, north: 36.73291666666667 - 80 / 1200, step: 1 / 1200 },
  // 30" GLOBE around Everest (27.99N 86.93E), geographic.
  everest: { data: crop(globeDem, 1580, 1090, 200, 200), width: 200, height: 200,
    west: 72.93333333333334 + 1580 / 120, north: 37.916666666666664 - 1090 / 120, step: 1 / 120 },
  // Terrain Tiles zoom 11, Web Mercator metres.
  canyon: { data: crop(canyonDem, 160, 160, 192, 192), width: 192, height: 192, mercatorStep: 76.437 },
  // 10' ETOPO5 over Japan and its trench: land and sea floor, negative heights.
  etopo: { data: crop(etopoDem, 780, 240, 240, 120), width: 240, height: 120,
    west: 780 / 6, north: 89.9167 - 240 / 6 + 1 / 12, step: 1 / 6 },
  volcano: { data: volcanoDem.data.slice(), width: 87, height: 61 },
};
// The references, named <crop>.f32; jacksboro.f32 doubles as the .f32 + .json fixture.
for (const [name, c] of Object.entries(crops)) write(`${name}.f32`, new Uint8Array(c.data.buffer));

// --- PNG: 16-bit grey, 8-bit grey, Terrain-RGB, Terrarium ----------------------------------
function quantise(h, bits) {
  const [min, max] = minMax(h);
  const top = 2 ** bits - 1;
  return { min, max, values: h.map((v) => Math.round(((v - min) / (max - min)) * top)) };
}
{
  const q = quantise(crops.everest.data, 16);
  write('everest_16bit.png', encodePng({ width: 200, height: 200, data: Uint16Array.from(q.values), depth: 16, channels: 1,
    text: { min_m: String(q.min), max_m: String(q.max) } }));
  manifest.push({ files: ['everest_16bit.png'], ref: 'everest', toleranceM: (q.max - q.min) / 65535 / 2, sampleType: 'u16' });
}
{
  const q = quantise(crops.jacksboro.data, 8);
  write('jacksboro_8bit.png', encodePng({ width: 250, height: 190, data: Uint8Array.from(q.values), depth: 8, channels: 1,
    text: { min_m: String(q.min), max_m: String(q.max) } }));
  manifest.push({ files: ['jacksboro_8bit.png'], ref: 'jacksboro', toleranceM: (q.max - q.min) / 255 / 2, sampleType: 'u8' });
}
function encodedPng(h, width, height, encode) {
  const rgb = new Uint8Array(width * height * 3);
  h.forEach((v, i) => rgb.set(encode(v), i * 3));
  return encodePng({ width, height, data: rgb, depth: 8, channels: 3 });
}
const terrainRgb = (h) => { const v = Math.round((h + 10000) * 10); return [(v >> 16) & 255, (v >> 8) & 255, v & 255]; };
const terrarium = (h) => { const v = Math.round((h + 32768) * 256); return [(v >> 16) & 255, (v >> 8) & 255, v & 255]; };
write('canyon_terrain-rgb.png', encodedPng(crops.canyon.data, 192, 192, terrainRgb));
manifest.push({ files: ['canyon_terrain-rgb.png'], ref: 'canyon', toleranceM: 0.05 + 1e-4, sampleType: 'f32', encoding: 'terrain-rgb' });
write('etopo_terrarium.png', encodedPng(crops.etopo.data, 240, 120, terrarium));
manifest.push({ files: ['etopo_terrarium.png'], ref: 'etopo', toleranceM: 1 / 512 + 1e-3, sampleType: 'f32', encoding: 'terrarium' });

// --- RAW / R16 and PGM: 16-bit ranges given by a sidecar -----------------------------------
function u16Bytes(values, littleEndian) {
  const out = new Uint8Array(values.length * 2);
  const view = new DataView(out.buffer);
  values.forEach((v, i) => view.setUint16(i * 2, v, littleEndian));
  return out;
}
{
  const q = quantise(crops.volcano.data, 16);
  write('volcano.r16', u16Bytes(q.values, true));
  write('volcano.json', json({ min: q.min, max: q.max, cell_size_m: 10, note: 'no width/height: the loader must be told 87x61' }));
  manifest.push({ files: ['volcano.r16', 'volcano.json'], options: { width: 87, height: 61 }, ref: 'volcano',
    toleranceM: (q.max - q.min) / 65535 / 2, sampleType: 'u16' });
}
{
  const q = quantise(crops.canyon.data, 16);
  write('canyon.r16', u16Bytes(q.values, true));
  write('canyon.json', json({ min: q.min, max: q.max, cell_size_m: 61.7 }));
  manifest.push({ files: ['canyon.r16', 'canyon.json'], ref: 'canyon', toleranceM: (q.max - q.min) / 65535 / 2, sampleType: 'u16' });
}
function pgm(width, height, maxval, body) {
  const header = new TextEncoder().encode(`P5\n# hexlod fixture\n${width} ${height}\n${maxval}\n`);
  const out = new Uint8Array(header.length + body.length);
  out.set(header);
  out.set(body, header.length);
  return out;
}
{
  const q = quantise(crops.everest.data, 16);
  write('everest.pgm', pgm(200, 200, 65535, u16Bytes(q.values, false)));
  write('everest.json', json({ min: q.min, max: q.max }));
  manifest.push({ files: ['everest.pgm', 'everest.json'], ref: 'everest', toleranceM: (q.max - q.min) / 65535 / 2, sampleType: 'u16' });
  const q8 = quantise(crops.jacksboro.data, 8);
  write('jacksboro_8bit.pgm', pgm(250, 190, 255, Uint8Array.from(q8.values)));
  write('jacksboro_8bit.json', json({ min: q8.min, max: q8.max, cell_size_x_m: 74.4, cell_size_y_m: 92.6 }));
  manifest.push({ files: ['jacksboro_8bit.pgm', 'jacksboro_8bit.json'], ref: 'jacksboro', toleranceM: (q8.max - q8.min) / 255 / 2, sampleType: 'u8' });
}

// --- .f32 + .json ------------------------------------------------------------------------
write('jacksboro.json', json({ width: 250, height: 190, cell_size_x_m: 74.4, cell_size_y_m: 92.6 }));
manifest.push({ files: ['jacksboro.f32', 'jacksboro.json'], ref: 'jacksboro', toleranceM: 0, sampleType: 'f32' });

// --- ESRI ASCII grid in degrees, with NODATA voids ----------------------------------------
/** Indices of a disc of voids and a few single ones: what the no-data tests fill. */
function voidsOf(width, height) {
  const voids = new Set();
  const cx = Math.floor(width * 0.4), cy = Math.floor(height * 0.5), r = 9;
  for (let y = cy - r; y <= cy + r; y++) for (let x = cx - r; x <= cx + r; x++) if ((x - cx) ** 2 + (y - cy) ** 2 <= r * r) voids.add(y * width + x);
  for (let k = 0; k < 12; k++) voids.add(((k * 7919) % height) * width + ((k * 104729) % width));
  for (let x = 0; x < 30; x++) voids.add(x); // along the north edge
  return voids;
}
{
  const c = crops.jacksboro, voids = voidsOf(c.width, c.height);
  const lines = [`ncols ${c.width}`, `nrows ${c.height}`, `xllcorner ${c.west}`, `yllcorner ${c.north - c.height * c.step}`,
    `cellsize ${c.step}`, 'NODATA_value -9999'];
  for (let y = 0; y < c.height; y++) {
    const row = [];
    for (let x = 0; x < c.width; x++) row.push(voids.has(y * c.width + x) ? '-9999' : String(c.data[y * c.width + x]));
    lines.push(row.join(' '));
  }
  write('jacksboro_voids.asc', new TextEncoder().encode(lines.join('\n') + '\n'));
  manifest.push({ files: ['jacksboro_voids.asc'], ref: 'jacksboro', toleranceM: 0, sampleType: 'f32', voids: [...voids].sort((a, b) => a - b),
    spacing: [74.4, 92.6] });
}

// SRTM .hgt has no small form (1201 x 1201 at least, 2.9 MB): tests/node/formats.test.js
// writes one at run time from public/terrain/globe_himalaya_2048.png instead.

// --- GeoTIFF: the four sample types, strips and tiles, none / deflate / LZW -----------------
const TIFF = { SHORT: 3, LONG: 4, DOUBLE: 12, ASCII: 2 };

/** TIFF LZW as libtiff writes it (MSB-first codes, 256 clears, 257 ends). */
function lzwEncode(input) {
  const out = [];
  let acc = 0, bits = 0, width = 9;
  const emit = (code) => {
    acc = (acc << width) | code; bits += width;
    while (bits >= 8) { out.push((acc >>> (bits - 8)) & 255); bits -= 8; }
    acc &= (1 << bits) - 1;
  };
  let table = new Map(), next = 258;
  emit(256);
  let prefix = -1;
  for (const byte of input) {
    if (prefix < 0) { prefix = byte; continue; }
    const key = prefix * 256 + byte;
    const code = table.get(key);
    if (code !== undefined) { prefix = code; continue; }
    emit(prefix);
    table.set(key, next++);
    if (next === 512) width = 10; else if (next === 1024) width = 11; else if (next === 2048) width = 12;
    if (next === 4094) { emit(256); table = new Map(); next = 258; width = 9; }
    prefix = byte;
  }
  if (prefix >= 0) emit(prefix);
  emit(257);
  if (bits > 0) out.push((acc << (8 - bits)) & 255);
  return Uint8Array.from(out);
}

/**
 * Writes a one-band little-endian GeoTIFF.
 * @param {{ width, height, type: 'i16'|'u16'|'i32'|'f32', values: ArrayLike<number>, tile?: number,
 *   rowsPerStrip?: number, compression: 1|5|8, predictor?: 1|2, geographic?: {west, north, step},
 *   projected?: {x0, y0, step}, nodata?: string }} o
 */
function geotiff(o) {
  const { width, height } = o;
  const Array_ = { i16: Int16Array, u16: Uint16Array, i32: Int32Array, f32: Float32Array }[o.type];
  const bytesPer = Array_.BYTES_PER_ELEMENT;
  const [blockW, blockH] = o.tile ? [o.tile, o.tile] : [width, o.rowsPerStrip];
  const blocks = [];
  for (let by = 0; by < height; by += blockH) {
    for (let bx = 0; bx < (o.tile ? width : 1); bx += blockW) {
      const h = o.tile ? blockH : Math.min(blockH, height - by); // tiles are padded, the last strip is not
      const block = new Array_(blockW * h);
      for (let y = 0; y < h; y++) for (let x = 0; x < blockW; x++) {
        if (by + y < height && bx + x < width) block[y * blockW + x] = o.values[(by + y) * width + bx + x];
      }
      if (o.predictor === 2) for (let y = 0; y < h; y++) for (let x = blockW - 1; x > 0; x--) block[y * blockW + x] -= block[y * blockW + x - 1];
      const raw = new Uint8Array(block.buffer);
      blocks.push(o.compression === 8 ? zlibSync(raw) : o.compression === 5 ? lzwEncode(raw) : raw);
    }
  }
  const tags = [
    [256, TIFF.LONG, [width]], [257, TIFF.LONG, [height]], [258, TIFF.SHORT, [bytesPer * 8]],
    [259, TIFF.SHORT, [o.compression]], [262, TIFF.SHORT, [1]], [277, TIFF.SHORT, [1]], [284, TIFF.SHORT, [1]],
    [339, TIFF.SHORT, [{ i16: 2, u16: 1, i32: 2, f32: 3 }[o.type]]],
  ];
  if (o.predictor) tags.push([317, TIFF.SHORT, [o.predictor]]);
  const offsetsTag = o.tile ? 324 : 273, countsTag = o.tile ? 325 : 279;
  if (o.tile) tags.push([322, TIFF.SHORT, [o.tile]], [323, TIFF.SHORT, [o.tile]]);
  else tags.push([278, TIFF.LONG, [o.rowsPerStrip]]);
  tags.push([offsetsTag, TIFF.LONG, blocks.map(() => 0)], [countsTag, TIFF.LONG, blocks.map((b) => b.length)]);
  if (o.geographic) {
    const g = o.geographic;
    tags.push([33550, TIFF.DOUBLE, [g.step, g.step, 0]], [33922, TIFF.DOUBLE, [0, 0, 0, g.west, g.north, 0]],
      [34735, TIFF.SHORT, [1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326]]);
  } else if (o.projected) {
    const p = o.projected;
    tags.push([33550, TIFF.DOUBLE, [p.step, p.step, 0]], [33922, TIFF.DOUBLE, [0, 0, 0, p.x0, p.y0, 0]],
      [34735, TIFF.SHORT, [1, 1, 0, 4, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 3857, 3076, 0, 1, 9001]]);
  }
  if (o.nodata !== undefined) tags.push([42113, TIFF.ASCII, o.nodata]);
  tags.sort((a, b) => a[0] - b[0]);

  // Layout: header, blocks, out-of-line tag values, IFD.
  const size = { [TIFF.SHORT]: 2, [TIFF.LONG]: 4, [TIFF.DOUBLE]: 8, [TIFF.ASCII]: 1 };
  const valueBytes = (t) => (t[1] === TIFF.ASCII ? t[2].length + 1 : t[2].length * size[t[1]]);
  let pos = 8;
  const blockOffsets = blocks.map((b) => { const at = pos; pos += b.length + (b.length & 1); return at; });
  tags.find((t) => t[0] === offsetsTag)[2] = blockOffsets;
  const extOffsets = new Map();
  for (const t of tags) if (valueBytes(t) > 4) { extOffsets.set(t, pos); pos += valueBytes(t) + (valueBytes(t) & 1); }
  const ifd = pos;
  const total = ifd + 2 + tags.length * 12 + 4;
  const out = new Uint8Array(total);
  const v = new DataView(out.buffer);
  out.set([0x49, 0x49, 42, 0]);
  v.setUint32(4, ifd, true);
  blocks.forEach((b, i) => out.set(b, blockOffsets[i]));
  const putValues = (t, at) => {
    if (t[1] === TIFF.ASCII) { out.set(new TextEncoder().encode(t[2]), at); return; }
    t[2].forEach((x, i) => {
      if (t[1] === TIFF.SHORT) v.setUint16(at + 2 * i, x, true);
      else if (t[1] === TIFF.LONG) v.setUint32(at + 4 * i, x, true);
      else v.setFloat64(at + 8 * i, x, true);
    });
  };
  v.setUint16(ifd, tags.length, true);
  tags.forEach((t, i) => {
    const e = ifd + 2 + i * 12;
    v.setUint16(e, t[0], true); v.setUint16(e + 2, t[1], true);
    v.setUint32(e + 4, t[1] === TIFF.ASCII ? t[2].length + 1 : t[2].length, true);
    if (extOffsets.has(t)) { v.setUint32(e + 8, extOffsets.get(t), true); putValues(t, extOffsets.get(t)); } else putValues(t, e + 8);
  });
  v.setUint32(total - 4, 0, true);
  return out;
}
{
  const c = crops.everest, voids = voidsOf(c.width, c.height);
  const values = Int16Array.from(c.data, (h, i) => (voids.has(i) ? -32768 : Math.round(h)));
  write('everest_i16_strips.tif', geotiff({ width: c.width, height: c.height, type: 'i16', values, rowsPerStrip: 16,
    compression: 1, geographic: c, nodata: '-32768' }));
  manifest.push({ files: ['everest_i16_strips.tif'], ref: 'everest', toleranceM: 0.5, sampleType: 'i16',
    voids: [...voids].sort((a, b) => a - b) });
}
{
  const c = crops.canyon;
  // uint16 decimetres would need a scale tag GeoTIFF lacks; whole metres it is.
  const values = Uint16Array.from(c.data, (h) => Math.round(h));
  write('canyon_u16_tiled_deflate.tif', geotiff({ width: c.width, height: c.height, type: 'u16', values, tile: 64,
    compression: 8, predictor: 2, projected: { x0: -12601714.23 + 160 * 76.437, y0: 4344069.19 - 160 * 76.437, step: c.mercatorStep } }));
  manifest.push({ files: ['canyon_u16_tiled_deflate.tif'], ref: 'canyon', toleranceM: 0.5, sampleType: 'u16', spacing: [76.437, 76.437] });
}
{
  const c = crops.etopo;
  const values = Int32Array.from(c.data, (h) => Math.round(h)); // ETOPO5 is whole metres
  write('etopo_i32_strips_lzw.tif', geotiff({ width: c.width, height: c.height, type: 'i32', values, rowsPerStrip: 7,
    compression: 5, predictor: 2, geographic: c }));
  manifest.push({ files: ['etopo_i32_strips_lzw.tif'], ref: 'etopo', toleranceM: 0.5, sampleType: 'f32' });
}
{
  const c = crops.jacksboro, voids = voidsOf(c.width, c.height);
  const values = Float32Array.from(c.data, (h, i) => (voids.has(i) ? -9999 : h));
  write('jacksboro_f32_tiled_lzw.tif', geotiff({ width: c.width, height: c.height, type: 'f32', values, tile: 64,
    compression: 5, geographic: c, nodata: '-9999' }));
  manifest.push({ files: ['jacksboro_f32_tiled_lzw.tif'], ref: 'jacksboro', toleranceM: 0, sampleType: 'f32',
    voids: [...voids].sort((a, b) => a - b), spacing: [74.4, 92.6] });
}

write('manifest.json', json(manifest));
console.log(`wrote ${manifest.length} fixtures to ${outDir}`);
