// Bad height-field files of every format: each is refused with a HeightfieldError whose one
// line names the file and the problem (truncated, empty, wrong type, absurd declared size,
// too big for memory, all no-data). Mutated files of every format, each within a time bound,
// are tests/node/fuzz.test.js's.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync, mkdtempSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { deflateRawSync, constants as zlibConstants } from 'node:zlib';
import { loadHeightfield, HeightfieldError } from '../../web/loaders/index.js';
import { checkSize } from '../../web/loaders/common.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';
import { createNodeCore } from '../../lib/node_core.js';

const ROOT = new URL('../../', import.meta.url);
const DIR = 'tests/fixtures/formats/';
const read = (path) => new Uint8Array(readFileSync(new URL(path, ROOT)));
const file = (name) => ({ name, bytes: read(DIR + name) });
const text = (s) => new TextEncoder().encode(s);

/** Expects files to be refused with a one-line HeightfieldError naming `name` and matching `problem`; counts allocations. */
async function refused(files, name, problem, options = {}) {
  let allocations = 0;
  const allocate = (type, w, h) => { allocations++; return new { u8: Uint8Array, u16: Uint16Array, i16: Int16Array, f32: Float32Array }[type](w * h); };
  await assert.rejects(loadHeightfield(files, { allocate, ...options }), (e) => {
    assert.ok(e instanceof HeightfieldError, `expected a HeightfieldError, got ${e?.name}: ${e?.message}`);
    assert.ok(e.message.startsWith(`${name}: `), `message does not name ${name}: ${e.message}`);
    assert.match(e.message, problem);
    assert.ok(!e.message.includes('\n'), 'one line');
    return true;
  });
  return allocations;
}

/**
 * A copy of a TIFF fixture with entries of its first directory replaced: tag -> { type, count,
 * value } (a SHORT or SSHORT value sits in the entry's first 2 bytes), or { double } for a value
 * typed DOUBLE, appended to the file and pointed at.
 */
function withTiffTags(name, tags) {
  return withTiffBytes(read(DIR + name), tags);
}

/** Where the values of a tag stored out of its entry lie in a little-endian TIFF. */
function tagValuesAt(bytes, tag) {
  const v = new DataView(bytes.buffer, bytes.byteOffset, bytes.length), ifd = v.getUint32(4, true);
  for (let i = 0; i < v.getUint16(ifd, true); i++) {
    if (v.getUint16(ifd + 2 + 12 * i, true) === tag) return v.getUint32(ifd + 2 + 12 * i + 8, true);
  }
  throw new Error(`no tag ${tag}`);
}

/** withTiffTags on the bytes of a TIFF. */
function withTiffBytes(src, tags) {
  const doubles = Object.values(tags).filter((t) => 'double' in t);
  const b = new Uint8Array(src.length + 8 * doubles.length);
  b.set(src);
  const v = new DataView(b.buffer), ifd = v.getUint32(4, true);
  let end = src.length;
  for (let i = 0; i < v.getUint16(ifd, true); i++) {
    const e = ifd + 2 + 12 * i, t = tags[v.getUint16(e, true)];
    if (!t) continue;
    let { type, count, value } = t;
    if ('double' in t) { v.setFloat64(end, t.double, true); [type, count, value] = [12, 1, end]; end += 8; }
    if (type !== undefined) v.setUint16(e + 2, type, true);
    if (count !== undefined) v.setUint32(e + 4, count, true);
    if (value === undefined) continue;
    const short = [3, 8].includes(v.getUint16(e + 2, true)) && v.getUint32(e + 4, true) === 1;
    if (short) v.setUint16(e + 8, value & 0xffff, true); else v.setUint32(e + 8, value >>> 0, true);
  }
  return b;
}

/** A PNG chunk with its CRC. */
function pngChunk(type, data) {
  const body = concatBytes([text(type), typeof data === 'string' ? text(data) : data]);
  const out = new Uint8Array(body.length + 8), v = new DataView(out.buffer);
  v.setUint32(0, body.length - 4);
  out.set(body, 4);
  let c = 0xffffffff;
  for (const b of body) { c ^= b; for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1; }
  v.setUint32(out.length - 4, (c ^ 0xffffffff) >>> 0);
  return out;
}

function concatBytes(parts) {
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  parts.reduce((o, p) => { out.set(p, o); return o + p.length; }, 0);
  return out;
}

const formats = ['x.png', 'x.tif', 'x.hgt', 'x.asc', 'x.pgm', 'x.r16'];

test('empty files of every format', async () => {
  for (const name of formats) await refused([{ name, bytes: new Uint8Array(0) }], name, /^[^:]+: empty file$/);
});

test('truncated files of every format, refused before anything is allocated', async () => {
  const cut = (name, keep) => { const b = read(DIR + name); return b.subarray(0, Math.floor(b.length * keep)); };
  const cases = [
    ['canyon_terrain-rgb.png', 0.5, /truncated/],
    ['everest_i16_strips.tif', 0.6, /truncated: the image directory at byte \d+ lies past the end \(\d+ bytes\)/],
    ['canyon_u16_tiled_deflate.tif', 0.9, /truncated: the image directory/],
    ['everest.pgm', 0.7, /truncated: \d+ bytes of samples, 80000 needed for 200x200 at 16 bits/],
    ['jacksboro_voids.asc', 0.3, /truncated: \d+ bytes cannot hold 250x190 values/],
  ];
  for (const [name, keep, problem] of cases) {
    assert.equal(await refused([{ name, bytes: cut(name, keep) }], name, problem), 0, `${name} allocated`);
  }
  // An ASCII grid cut near its end passes the byte estimate: its values are counted before
  // anything is allocated. So are values beyond ncols x nrows.
  assert.equal(await refused([{ name: 'j.asc', bytes: cut('jacksboro_voids.asc', 0.97) }], 'j.asc',
    /truncated: \d+ of 47500 values \(ends on row 1\d\d\)$/), 0);
  const asc = new TextDecoder().decode(read(`${DIR}jacksboro_voids.asc`)).replace('nrows 190', 'nrows 189');
  assert.equal(await refused([{ name: 'k.asc', bytes: text(asc) }], 'k.asc', /more values than ncols x nrows \(250x189\)$/), 0);
  // The count reads four bytes at a time: any alignment of the file's bytes, any separators.
  const grid = text('ncols 5\r\nnrows 3\r\ncellsize 1\r\n1 22  333\t4444 55555\r\n6\t\t7 8 9 10\n11 12 13 14 15   \n');
  for (let at = 0; at < 4; at++) {
    const padded = new Uint8Array(grid.length + 8);
    padded.set(grid, at);
    const h = await loadHeightfield([{ name: 'g.asc', bytes: padded.subarray(at, at + grid.length) }]);
    assert.deepEqual(Array.from(h.samples), [1, 22, 333, 4444, 55555, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15], `at ${at}`);
    for (const keep of [grid.length - 12, grid.length - 6]) {
      assert.equal(await refused([{ name: 'g.asc', bytes: padded.subarray(at, at + keep) }], 'g.asc',
        keep === grid.length - 6 ? /truncated: 14 of 15 values \(ends on row 3\)$/ : /truncated: 12 of 15 values \(ends on row 3\)$/), 0);
    }
  }
  // Other control characters are no separators (a NUL between two values made them two).
  for (const c of [0, 0x0c]) {
    const bad = grid.slice();
    bad[grid.indexOf(0x39)] = c; // the 9 of the second row
    assert.equal(await refused([{ name: 'c.asc', bytes: bad }], 'c.asc',
      new RegExp(`^c\\.asc: line 5: control character 0x0${c.toString(16)} \\(values are separated by spaces, tabs and line ends\\)$`)), 0);
  }
  await refused([{ name: 'N27E086.hgt', bytes: new Uint8Array(1201 * 1201 * 2 - 2) }], 'N27E086.hgt',
    /truncated: 2884800 bytes, but an SRTM tile has 1201x1201 or 3601x3601 16-bit samples/);
  await refused([{ name: 'c.r16', bytes: cut('canyon.r16', 0.5).subarray(1) }], 'c.r16', /odd length 36863 bytes/);
  await refused([{ name: 'c.pgm', bytes: text('P5\n200 ') }], 'c.pgm', /truncated: header ends before its height/);
});

test('wrong types: the file is not what its name says', async () => {
  const png = read(`${DIR}everest_16bit.png`);
  await refused([{ name: 'a.tif', bytes: png }], 'a.tif', /not a TIFF file \(bad signature\)/);
  await refused([{ name: 'a.pgm', bytes: png }], 'a.pgm', /not a PGM file/);
  await refused([{ name: 'a.asc', bytes: png }], 'a.asc', /bad header: no ncols line \(is this an ESRI ASCII grid\?\)/);
  await refused([{ name: 'a.png', bytes: read(`${DIR}everest_i16_strips.tif`) }], 'a.png', /not a PNG file \(bad signature; looks like TIFF data\)/);
  await refused([{ name: 'N27E086.hgt', bytes: png }], 'N27E086.hgt', /truncated: \d+ bytes, but an SRTM tile has/);
  await refused([{ name: 'a.pgm', bytes: text('P2\n2 2\n255\n1 2 3 4\n') }], 'a.pgm', /unsupported PGM: ASCII \(P2\)/);
  await refused([{ name: 'a.pgm', bytes: text('P6\n2 2\n255\n') }], 'a.pgm', /not a grayscale PGM \(magic P6; expected P5\)/);
  await refused([{ name: 'a.asc', bytes: text('ncols 2\nnrows 2\ncellsize 1\n1 2\nx 4\n') }], 'a.asc', /line 5: 'x' is not a number/);
  await refused([{ name: 'README', bytes: text('hello') }], 'README', /unsupported file type \(looks like text\); expected \.png, \.tif/);
  // An RGBA GeoTIFF (a photo) is no height field.
  const rgb = read(`${DIR}everest_i16_strips.tif`).slice();
  const view = new DataView(rgb.buffer);
  const ifd = view.getUint32(4, true);
  for (let i = 0; i < view.getUint16(ifd, true); i++) {
    if (view.getUint16(ifd + 2 + 12 * i, true) === 339) view.setUint16(ifd + 2 + 12 * i + 8, 3, true); // int16 -> "float16"
  }
  await refused([{ name: 'h.tif', bytes: rgb }], 'h.tif', /unsupported TIFF sample type: float 16-bit/);
});

test('absurd declared sizes are refused before anything is allocated', async () => {
  const cases = [
    [{ name: 'a.pgm', bytes: text('P5\n100000 100000\n65535\n\0\0') }, /declared size 100000x100000 is absurd/],
    [{ name: 'a.pgm', bytes: text('P5\n0 10\n255\n\0') }, /zero width/],
    [{ name: 'a.asc', bytes: text('ncols 100000\nnrows 100000\ncellsize 1\n1 2 3\n') }, /declared size 100000x100000 is absurd/],
    [{ name: 'a.asc', bytes: text('ncols 2.5\nnrows 2\ncellsize 1\n1 2 3\n') }, /ncols 2.5, nrows 2 must be whole numbers/],
    [{ name: 'a.asc', bytes: text('ncols 2\nnrows 2\ncellsize -1\n1 2 3 4\n') }, /cellsize missing or not positive/],
  ];
  // A GeoTIFF claiming 1,000,000 x 1,000,000 samples, and one claiming more than its strips hold.
  const tif = (width, height) => {
    const b = read(`${DIR}everest_i16_strips.tif`).slice();
    const v = new DataView(b.buffer), ifd = v.getUint32(4, true);
    for (let i = 0; i < v.getUint16(ifd, true); i++) {
      const e = ifd + 2 + 12 * i, tag = v.getUint16(e, true);
      if (tag === 256) v.setUint32(e + 8, width, true);
      if (tag === 257) v.setUint32(e + 8, height, true);
    }
    return b;
  };
  cases.push([{ name: 'w.tif', bytes: tif(1000000, 1000000) }, /declared size 1000000x1000000 is absurd/]);
  cases.push([{ name: 'w.tif', bytes: tif(20000, 200) }, /bad TIFF: strip 0 holds 6400 bytes, but its 20000x16 samples need 640000 \(is the image size right\?\)/]);
  for (const [f, problem] of cases) assert.equal(await refused([f], f.name, problem), 0, `${f.name} allocated`);
  // RAW sizes that do not fit the bytes.
  await refused([file('volcano.r16')], 'volcano.r16', /size 100000x100000 does not fit 5307/, { width: 100000, height: 100000 });
});

test('every size is a positive whole number, whoever declares it (file, sidecar, JS options)', async () => {
  // checkSize itself.
  for (const [w, h, problem] of [[-1, 2, /width -1 is not a positive whole number \(declared size -1x2\)/],
    [2, NaN, /height NaN is not/], [2.5, 2, /width 2.5 is not/], ['3', 2, /width "3" is not/], [0, 2, /zero width/]]) {
    assert.throws(() => checkSize('f.x', w, h, 1e9), (e) => e instanceof HeightfieldError && problem.test(e.message) && e.message.startsWith('f.x: '));
  }
  // RAW sizes through the JS API: a height of -1 made a width of -5307 and a flat 2x2 terrain.
  const r16 = file('volcano.r16');
  for (const [options, problem] of [[{ height: -1 }, /^volcano\.r16: height -1 is not a positive whole number$/],
    [{ width: -87, height: -61 }, /width -87 is not/], [{ width: NaN }, /width NaN is not/],
    [{ width: '87', height: '61' }, /width "87" is not/], [{ width: 87.5 }, /width 87.5 is not/]]) {
    assert.equal(await refused([r16], 'volcano.r16', problem, options), 0, JSON.stringify(options));
  }
  // ... and through a sidecar.
  for (const json of ['{"width": -87}', '{"width": 87, "height": 60.5}', '{"height": "61"}']) {
    await refused([r16, { name: 'volcano.json', bytes: text(json) }], 'volcano.json', /must be a positive integer/);
  }
  // GeoTIFF sizes of other types than LONG: a DOUBLE or SSHORT of -200 reached allocate() as a RangeError.
  const [WIDTH, HEIGHT, SSHORT] = [256, 257, 8];
  for (const [tags, problem] of [[{ [WIDTH]: { double: -200 } }, /width -200 is not a positive whole number \(declared size -200x200\)/],
    [{ [WIDTH]: { double: 200.5 } }, /width 200\.5 is not/], [{ [HEIGHT]: { double: NaN } }, /height NaN is not|zero height/],
    [{ [HEIGHT]: { type: SSHORT, value: -200 } }, /height -200 is not/], [{ [WIDTH]: { double: 2 ** 40 } }, /is absurd/]]) {
    assert.equal(await refused([{ name: 's.tif', bytes: withTiffTags('everest_i16_strips.tif', tags) }], 's.tif', problem), 0);
  }
  // A DOUBLE that holds a whole number is a size like any other.
  const h = await loadHeightfield([{ name: 'd.tif', bytes: withTiffTags('everest_i16_strips.tif', { [WIDTH]: { double: 200 } }) }]);
  assert.deepEqual([h.width, h.height], [200, 200]);
});

test('every TIFF strip or tile decodes to exactly what its geometry needs, checked before anything is allocated', async () => {
  const [WIDTH, HEIGHT, ROWS_PER_STRIP, TILE_WIDTH, TILE_LENGTH] = [256, 257, 278, 322, 323];
  const cases = [
    // LZW strips of an inflated width loaded as 58095 x 120 of garbage (heights down to -44 005 m);
    // a narrower width, from the first half of every strip.
    ['etopo_i32_strips_lzw.tif', { [WIDTH]: { value: 58095 } }, /bad TIFF: strip 0 decodes to 6720 bytes, but its 58095x7 samples need 1626660 \(is the image size right\?\)$/],
    ['etopo_i32_strips_lzw.tif', { [WIDTH]: { value: 120 } }, /bad TIFF: strip 0 decodes to more than 3360 bytes, but its 120x7 samples need 3360/],
    ['etopo_i32_strips_lzw.tif', { [WIDTH]: { value: 3000 }, [HEIGHT]: { value: 12000 }, [ROWS_PER_STRIP]: { value: 700 } },
      /strip 0 decodes to 6720 bytes, but its 3000x700 samples need 8400000/],
    // Uncompressed strips, short and long.
    ['everest_i16_strips.tif', { [WIDTH]: { value: 400 }, [HEIGHT]: { value: 100 } }, /bad TIFF: strip 0 holds 6400 bytes, but its 400x16 samples need 12800/],
    ['everest_i16_strips.tif', { [WIDTH]: { value: 100 } }, /bad TIFF: strip 0 holds 6400 bytes, but its 100x16 samples need 3200/],
    // Tiles of a forged size, deflate and LZW.
    ['canyon_u16_tiled_deflate.tif', { [WIDTH]: { value: 6144 }, [HEIGHT]: { value: 6144 }, [TILE_WIDTH]: { value: 2048 }, [TILE_LENGTH]: { value: 2048 } },
      /bad TIFF: tile 0 decodes to 8192 bytes, but its 2048x2048 samples need 8388608 \(is the tile size right\?\)$/],
    ['jacksboro_f32_tiled_lzw.tif', { [WIDTH]: { value: 8000 }, [HEIGHT]: { value: 6000 }, [TILE_WIDTH]: { value: 2048 }, [TILE_LENGTH]: { value: 2048 } },
      /bad TIFF: tile 0 decodes to 16384 bytes, but its 2048x2048 samples need 16777216/],
    // Block sizes that are no sizes.
    ['everest_i16_strips.tif', { [ROWS_PER_STRIP]: { double: 16.5 } }, /bad TIFF: RowsPerStrip 16\.5 is not a positive whole number$/],
    ['everest_i16_strips.tif', { [ROWS_PER_STRIP]: { value: 0 } }, /bad TIFF: RowsPerStrip 0 is not a positive whole number$/],
    ['canyon_u16_tiled_deflate.tif', { [TILE_WIDTH]: { value: 0 } }, /bad TIFF: TileWidth 0 is not a positive whole number$/],
    ['canyon_u16_tiled_deflate.tif', { [TILE_LENGTH]: { double: 64.5 } }, /bad TIFF: TileLength 64\.5 is not a positive whole number$/],
    ['canyon_u16_tiled_deflate.tif', { [TILE_LENGTH]: { double: 2 ** 40 } }, /bad TIFF: tiles of 64x1099511627776 samples are absurd \(over 2 GB each\)$/],
  ];
  for (const [source, tags, problem] of cases) {
    assert.equal(await refused([{ name: 'm.tif', bytes: withTiffTags(source, tags) }], 'm.tif', problem), 0, `${source} ${JSON.stringify(tags)} allocated`);
  }
  // Directory entries that claim more than the file holds: the library made an array of the
  // claimed count first (gigabytes), so they are refused before it reads them.
  await refused([{ name: 'c.tif', bytes: withTiffTags('everest_i16_strips.tif', { [HEIGHT]: { count: 2 ** 31 - 1 } }) }], 'c.tif',
    /^c\.tif: bad TIFF: tag 257 holds 2147483647 values \(8589934588 bytes from byte \d+\), past the end of the file \(80410 bytes\)$/);
  const entries = read(`${DIR}everest_i16_strips.tif`).slice();
  new DataView(entries.buffer).setUint16(new DataView(entries.buffer).getUint32(4, true), 0xffff, true);
  await refused([{ name: 'e.tif', bytes: entries }], 'e.tif', /^e\.tif: truncated: the image directory's 65535 entries run past the end \(80410 bytes\)$/);
  // Predictors the library cannot undo (it threw after the field was allocated, or left garbage).
  const PREDICTOR = 317;
  for (const [value, problem] of [[5, /unsupported TIFF predictor 5$/], [3, /bad TIFF: predictor 3 is for floating-point samples$/]]) {
    assert.equal(await refused([{ name: 'p.tif', bytes: withTiffTags('etopo_i32_strips_lzw.tif', { [PREDICTOR]: { value } }) }], 'p.tif', problem), 0);
  }
  // A deflate tile whose zlib checksum is wrong: the check (fflate) takes it, and so does the decode now (pako refused it).
  const adler = read(`${DIR}canyon_u16_tiled_deflate.tif`).slice(), av = new DataView(adler.buffer);
  const tile4 = av.getUint32(tagValuesAt(adler, 324) + 16, true) + av.getUint32(tagValuesAt(adler, 325) + 16, true);
  adler[tile4 - 1] ^= 0xff;
  const [good, checked] = [await loadHeightfield([file('canyon_u16_tiled_deflate.tif')]), await loadHeightfield([{ name: 'a.tif', bytes: adler }])];
  assert.ok(good.samples.every((v, i) => v === checked.samples[i]), 'the same samples');
  // A sparse file (empty blocks are no-data): the field is the data's extent, its empty
  // blocks inside filled; with no block that is not empty, nothing.
  const whole = await loadHeightfield([file('everest_i16_strips.tif')]);
  const sparse = read(`${DIR}everest_i16_strips.tif`).slice(), pv = new DataView(sparse.buffer);
  const countsAt = tagValuesAt(sparse, 279);
  const keepStrips = (kept) => { for (let s = 0; s < 13; s++) pv.setUint32(countsAt + 4 * s, kept.includes(s) ? (s === 12 ? 3200 : 6400) : 0, true); };
  keepStrips([5]);
  const one = await loadHeightfield([{ name: 'p.tif', bytes: sparse }]);
  assert.deepEqual([one.width, one.height, one.cropped], [200, 16, { column: 0, row: 80, width: 200, height: 200 }], 'strip 5 alone');
  const raw = (strip) => new Int16Array(sparse.slice(pv.getUint32(tagValuesAt(sparse, 273) + 4 * strip, true)).buffer, 0, 3200);
  const voids = raw(5).filter((v) => v === -32768).length;
  assert.ok(voids > 0 && one.missing === voids, 'its voids filled');
  assert.ok(one.samples.every((v, i) => v === whole.samples[80 * 200 + i] || raw(5)[i] === -32768), 'strip 5 as it is in the whole file');
  keepStrips([3, 9]);
  const two = await loadHeightfield([{ name: 'p.tif', bytes: sparse }]);
  assert.deepEqual([two.width, two.height], [200, 7 * 16], 'strips 3 to 9');
  const strip3 = raw(3);
  assert.ok(two.samples.subarray(0, 3200).every((v, i) => v === whole.samples[48 * 200 + i] || strip3[i] === -32768), 'strip 3 first');
  assert.ok(two.missing >= 5 * 3200, 'the empty strips between them filled');
  keepStrips([]);
  assert.equal(await refused([{ name: 'p.tif', bytes: sparse }], 'p.tif', /^p\.tif: every strip is empty \(a sparse file with no data\): nothing to show$/), 0);
  // A strip cut short whose byte count was kept reads the directory's values as samples.
  const shifted = read(`${DIR}everest_i16_strips.tif`).slice(), sv = new DataView(shifted.buffer);
  const offsetsAt = tagValuesAt(shifted, 273);
  sv.setUint32(offsetsAt + 4 * 12, sv.getUint32(offsetsAt + 4 * 12, true) + 100, true); // the last strip, 100 bytes on
  assert.equal(await refused([{ name: 's.tif', bytes: shifted }], 's.tif',
    new RegExp(`bad TIFF: strip 12 \\(bytes \\d+\\.\\.\\d+\\) overlaps the values of tag 273 \\(bytes ${offsetsAt}\\.\\.${offsetsAt + 51}\\)$`)), 0);
  // Corrupt block data: the codec's reason, and the block.
  const corrupt = (source, tag, k, edit) => {
    const b = read(DIR + source).slice(), v = new DataView(b.buffer), ifd = v.getUint32(4, true);
    for (let i = 0; i < v.getUint16(ifd, true); i++) {
      const e = ifd + 2 + 12 * i;
      if (v.getUint16(e, true) === tag) edit(b, v.getUint32(v.getUint32(e + 8, true) + 4 * k, true));
    }
    return b;
  };
  const badLzw = corrupt('etopo_i32_strips_lzw.tif', 273, 3, (b, at) => { b[at] = 0xff; });
  assert.equal(await refused([{ name: 'l.tif', bytes: badLzw }], 'l.tif', /corrupt strip 3 \(bad LZW code 510 after a clear\)$/), 0);
  const badDeflate = corrupt('canyon_u16_tiled_deflate.tif', 324, 4, (b, at) => { b[at + 2] |= 6; });
  assert.equal(await refused([{ name: 'd.tif', bytes: badDeflate }], 'd.tif', /corrupt tile 4 \(zlib: invalid block type\)$/), 0);
});

test('no error of the geotiff library leaks: a no-data tag of any type', async () => {
  const NODATA = 42113, SHORT = 3;
  for (const [tags, problem] of [[{ [NODATA]: { type: SHORT, count: 1, value: 7 } }, /bad TIFF: the no-data tag \(42113\) holds 7, not the text of a number$/],
    [{ [NODATA]: { double: -32768 } }, /the no-data tag \(42113\) holds -32768, not the text of a number/]]) {
    await refused([{ name: 'n.tif', bytes: withTiffTags('everest_i16_strips.tif', tags) }], 'n.tif', problem);
  }
  // Many values of another type (here the file's first 4000 bytes as doubles): the first few, and how many.
  await refused([{ name: 'm.tif', bytes: withTiffTags('everest_i16_strips.tif', { [NODATA]: { type: 12, count: 500, value: 0 } }) }], 'm.tif',
    /^m\.tif: bad TIFF: the no-data tag \(42113\) holds \[[^\]]{0,120}, … 500 values\], not the text of a number$/);
  // Text, as GDAL writes it: a number ("-32768" and its NUL), "nan"; not words. Each text is
  // appended to the file and the tag pointed at it.
  const nodataText = (value) => {
    const src = read(`${DIR}everest_i16_strips.tif`), b = new Uint8Array(src.length + value.length);
    b.set(src);
    b.set(text(value), src.length);
    return withTiffBytes(b, { [NODATA]: { count: value.length, value: src.length } });
  };
  const nodataOf = async (bytes) => (await loadHeightfield([{ name: 'v.tif', bytes }])).nodata;
  assert.equal(await nodataOf(nodataText('-32768\0')), -32768);
  assert.equal(await nodataOf(nodataText('-32768')), -32768, 'without its NUL the library read -3276');
  assert.equal(await nodataOf(nodataText('nan\0\0\0')), null);
  await refused([{ name: 'w.tif', bytes: nodataText('abc\0\0\0') }], 'w.tif', /bad TIFF: the no-data tag \(42113\) is not a number \("abc"\)$/);
});

test('non-finite heights are refused in every text and float format, naming the line or sample', async () => {
  const grid = (values, nodata = '') => text(`ncols 3\nnrows 2\ncellsize 1\n${nodata}1 2 3\n4 ${values} 6\n`);
  // 1e999 is Infinity as a number, 1e39 as a float32: the grid became a field with an infinite height.
  for (const v of ['1e999', '1e39', '-1e39', '-3.5e38']) {
    await refused([{ name: 'i.asc', bytes: grid(v) }], 'i.asc', new RegExp(`^i\\.asc: line 5: '${v.replace('.', '\\.')}' is not a finite float32 height`));
  }
  await refused([{ name: 'i.asc', bytes: grid('5', 'NODATA_value 1e39\n') }], 'i.asc', /bad header: NODATA_value 1e\+39 is beyond the float32 range$/);
  const inf = new Float32Array(6);
  inf[5] = -Infinity;
  await refused([{ name: 'i.f32', bytes: new Uint8Array(inf.buffer) }, { name: 'i.json', bytes: text('{"width": 3, "height": 2}') }],
    'i.f32', /sample at row 1, column 2 is -Infinity/);
  // A float32 GeoTIFF: the 16-bit strips read as 100 float32 samples a row, one of them +Infinity.
  const tif = withTiffTags('everest_i16_strips.tif', { 256: { value: 100 }, 258: { value: 32 }, 339: { value: 3 } });
  new DataView(tif.buffer).setFloat32(8 + (2 * 100 + 5) * 4, Infinity, true);
  await refused([{ name: 'f.tif', bytes: tif }], 'f.tif', /sample at row 2, column 5 is Infinity/);
  // Height ranges whose span overflows make an infinite height scale.
  const withRange = (min, max) => {
    const png = read(`${DIR}everest_16bit.png`), v = new DataView(png.buffer, png.byteOffset);
    const parts = [png.subarray(0, 8)];
    for (let p = 8; p < png.length;) {
      const len = v.getUint32(p), type = String.fromCharCode(...png.subarray(p + 4, p + 8));
      if (type !== 'tEXt') parts.push(png.subarray(p, p + 12 + len));
      if (type === 'IHDR') parts.push(pngChunk('tEXt', `min_m\0${min}`), pngChunk('tEXt', `max_m\0${max}`));
      p += 12 + len;
    }
    return concatBytes(parts);
  };
  await refused([{ name: 'r.png', bytes: withRange(-1e308, 1e308) }], 'r.png', /tEXt min_m -1e\+308 and max_m 1e\+308 span more than a number can hold$/);
  await refused([file('everest.pgm'), { name: 'everest.json', bytes: text('{"min": -1e308, "max": 1e308}') }], 'everest.json',
    /min -1e\+308 and max 1e\+308 span more than a number can hold$/);
});

test('no-data values match float32 samples, however they are written', async () => {
  // GDAL's float no-data, written with fewer digits: -3.4028235e+38 is not exactly a float32.
  const grid = text('ncols 3\nnrows 2\ncellsize 1\nNODATA_value -3.4028235e+38\n1 2 3\n4 -3.4028235e+38 6\n');
  const h = await loadHeightfield([{ name: 'n.asc', bytes: grid }]);
  assert.equal(h.missing, 1);
  assert.ok(h.samples.every((v) => v > 0 && v < 7), Array.from(h.samples).join(' '));
  const f = new Float32Array([1, 2, 3, 4, -9999.9, 6]);
  const g = await loadHeightfield([{ name: 'n.f32', bytes: new Uint8Array(f.buffer) }, { name: 'n.json', bytes: text('{"width": 3, "height": 2, "nodata": -9999.9}') }]);
  assert.equal(g.missing, 1);
  assert.ok(g.samples.every((v) => v > 0 && v < 7), Array.from(g.samples).join(' '));
});

test('what the core refuses in a file (its spacing, its heights) is refused naming the file', async () => {
  const core = await createNodeCore();
  for (const [files, problem] of [
    [[file('everest.pgm'), { name: 'everest.json', bytes: text('{"cell_size_m": 1e-300}') }], /^everest\.pgm: invalid height scale: sample spacing must be between/],
    [[{ name: 'h.asc', bytes: text('ncols 2\nnrows 2\ncellsize 1\n1 2\n3 2e9\n') }], /^h\.asc: cannot use this height field: heights must lie between -1e9 m and 1e9 m/],
  ]) {
    await assert.rejects(loadTerrain(core, files), (e) => e instanceof HeightfieldError && problem.test(e.message) && !e.message.includes('\n'));
  }
});

test('all no-data: refused with the reason, in every format that has no-data', async () => {
  await refused([{ name: 'v.asc', bytes: text('ncols 3\nnrows 2\ncellsize 1\nNODATA_value -9999\n-9999 -9999 -9999\n-9999 -9999 -9999\n') }],
    'v.asc', /every sample is no-data \(value -9999\): nothing to show/);
  const voids = new Uint8Array(1201 * 1201 * 2);
  for (let i = 0; i < voids.length; i += 2) voids[i] = 0x80; // -32768 big-endian
  await refused([{ name: 'N27E086.hgt', bytes: voids }], 'N27E086.hgt', /every sample is no-data \(value -32768\)/);
  const nan = new Float32Array(6).fill(NaN);
  await refused([{ name: 'n.f32', bytes: new Uint8Array(nan.buffer) }, { name: 'n.json', bytes: text('{"width": 3, "height": 2}') }],
    'n.f32', /every sample is no-data \(NaN\)/);
});

test('too big for memory: the core cannot hold the field, the file is named, nothing stays allocated', async () => {
  // A 32769^2 Terrarium PNG decodes to float32: 4 GiB + 512 MiB of samples, more than a 32-bit
  // WebAssembly memory can hold. Its IDAT is a real stream of every row (3.2 GB of zeros in
  // 3 MB: one flushed block of 1 MiB of zeros, repeated), as the loader proves before it
  // allocates.
  const side = 32769, total = side * (3 * side + 1), MIB = 1 << 20;
  const flushed = deflateRawSync(new Uint8Array(MIB), { level: 9, finishFlush: zlibConstants.Z_SYNC_FLUSH });
  const adler = new Uint8Array([(total % 65521) >> 8, (total % 65521) & 255, 0, 1]); // of zeros: a = 1, b = length
  const blocks = [new Uint8Array([0x78, 0xda]), ...Array(Math.floor(total / MIB)).fill(flushed),
    deflateRawSync(new Uint8Array(total % MIB), { level: 9 }), adler];
  const idat = new Uint8Array(blocks.reduce((n, p) => n + p.length, 0));
  blocks.reduce((o, p) => { idat.set(p, o); return o + p.length; }, 0);
  const chunk = (type, data) => {
    const out = new Uint8Array(12 + data.length), v = new DataView(out.buffer);
    v.setUint32(0, data.length);
    out.set(text(type), 4);
    out.set(data, 8);
    let c = 0xffffffff;
    for (let i = 4; i < 8 + data.length; i++) { c ^= out[i]; for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1; }
    v.setUint32(8 + data.length, (c ^ 0xffffffff) >>> 0);
    return out;
  };
  const ihdr = new Uint8Array(13);
  new DataView(ihdr.buffer).setUint32(0, side);
  new DataView(ihdr.buffer).setUint32(4, side);
  ihdr.set([8, 2, 0, 0, 0], 8);
  const parts = [new Uint8Array([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), chunk('IHDR', ihdr), chunk('IDAT', idat), chunk('IEND', new Uint8Array(0))];
  const png = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  parts.reduce((o, p) => { png.set(p, o); return o + p.length; }, 0);

  const core = await createNodeCore();
  await assert.rejects(loadTerrain(core, [{ name: 'huge_terrarium.png', bytes: png }]), (e) => {
    assert.ok(e instanceof HeightfieldError, `${e?.name}: ${e?.message}`);
    assert.equal(e.message, 'huge_terrarium.png: too big for memory: 32769x32769 f32 samples need 4096 MB');
    return true;
  });
  // The core is still usable and holds nothing from the failed load.
  const ok = await loadTerrain(core, [file('everest_16bit.png')]);
  assert.equal(ok.terrain.width, 200);
  ok.terrain.destroy();
});

test('the CLI ends a bad file with exactly one line and a non-zero exit; RAW size and encoding flags work', () => {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-bad-'));
  const cli = fileURLToPath(new URL('bin/hexlod.js', ROOT));
  const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 60000 });
  writeFileSync(join(dir, 'cut.pgm'), read(`${DIR}everest.pgm`).subarray(0, 3000));
  for (const command of ['info', 'mesh', 'bench']) {
    const extra = command === 'mesh' ? ['--max-error', '5'] : command === 'bench' ? ['--frames', '1', '--no-native'] : [];
    const r = run(command, join(dir, 'cut.pgm'), ...extra);
    assert.equal(r.status, 1, `${command}: ${r.stderr}`);
    assert.equal(r.stderr, 'hexlod: cut.pgm: truncated: 2966 bytes of samples, 80000 needed for 200x200 at 16 bits\n');
    assert.equal(r.stdout, '');
  }
  const raw = run('info', fileURLToPath(new URL(`${DIR}volcano.r16`, ROOT)), '--json');
  assert.equal(raw.status, 1);
  assert.equal(raw.stderr, 'hexlod: volcano.r16: 5307 samples do not make a square: give its width and height (--width and --height)\n');
  const sized = run('info', fileURLToPath(new URL(`${DIR}volcano.r16`, ROOT)), '--json', '--width', '87', '--height', '61');
  assert.equal(sized.status, 0, sized.stderr);
  assert.deepEqual([JSON.parse(sized.stdout).width, JSON.parse(sized.stdout).height], [87, 61]);
  const forced = run('info', fileURLToPath(new URL(`${DIR}etopo_terrarium.png`, ROOT)), '--json', '--encoding', 'terrain-rgb');
  assert.equal(forced.status, 0, forced.stderr);
  assert.ok(JSON.parse(forced.stdout).minHeight > 100000, 'Terrarium colours read as Terrain-RGB give absurd heights: the flag was obeyed');
  const wrong = run('info', join(dir, 'cut.pgm'), '--encoding', 'mapbox');
  assert.equal(wrong.status, 2);
  assert.match(wrong.stderr, /^hexlod: --encoding must be terrain-rgb or terrarium, got 'mapbox'; usage: hexlod info/);
});
