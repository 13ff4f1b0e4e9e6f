// Every height-field format on real data: the fixtures of tests/fixtures/formats (written by
// scripts/make_format_fixtures.js from real DEMs) must decode to their reference heights
// (<crop>.f32, the original float32 metres) within the quantisation of their format; no-data
// voids are filled without spikes; spacing comes from the file where it has one.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decode as decodePngOracle } from 'fast-png';
import { loadHeightfield, HeightfieldError, SizeNeededError } from '../../web/loaders/index.js';

const ROOT = new URL('../../', import.meta.url);
const DIR = 'tests/fixtures/formats/';
const read = (path) => new Uint8Array(readFileSync(new URL(path, ROOT)));
const file = (name) => ({ name, bytes: read(DIR + name) });
const floats = (bytes) => new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length));
const manifest = JSON.parse(new TextDecoder().decode(read(`${DIR}manifest.json`)));

/** Ground spacing (x, y) in metres the file must yield, from published cell sizes: 1' of
 *  latitude is 1852 m, and a degree of longitude shrinks with cos(latitude). */
const EXPECTED_SPACING = {
  'everest_i16_strips.tif': [926.6 * Math.cos((28.0 * Math.PI) / 180), 926.6], // 30", mid-latitude 28.0N
  'etopo_i32_strips_lzw.tif': [18532 * Math.cos((40.0 * Math.PI) / 180), 18532], // 10', mid-latitude 40.0N
  'jacksboro_voids.asc': [74.4, 92.6], // 3" at 36.6N, from the DEM's sidecar
  'jacksboro_f32_tiled_lzw.tif': [74.4, 92.6],
  'canyon_u16_tiled_deflate.tif': [76.437, 76.437], // EPSG:3857 metres, as the file says
};

/** Metres of sample i. */
const metres = (h, i) => h.samples[i] * h.heightScale + h.heightOffset;

/** Checks every non-void sample against ref within tol, and the filled voids for sanity. */
function checkHeights(h, ref, tol, voids = []) {
  assert.equal(h.samples.length, ref.length);
  const isVoid = new Uint8Array(ref.length);
  for (const i of voids) isVoid[i] = 1;
  let worst = 0;
  for (let i = 0; i < ref.length; i++) {
    if (isVoid[i]) continue;
    const err = Math.abs(metres(h, i) - ref[i]);
    worst = Math.max(worst, err);
    if (!(err <= tol + Math.abs(ref[i]) * 2 ** -22)) assert.fail(`sample ${i}: ${metres(h, i)} m, expected ${ref[i]} m ± ${tol}`);
  }
  if (voids.length) checkFill(h, ref, voids);
  return worst;
}

/** Filled voids: no spike (inside the valid heights' range) and close to the truth on average. */
function checkFill(h, ref, voids) {
  assert.equal(h.missing, voids.length, 'every void is counted as filled');
  const marked = [];
  for (let k = 0; k < h.width * h.height; k++) if ((h.missingMask[k >> 3] >> (k & 7)) & 1) marked.push(k);
  assert.deepEqual(marked, [...voids].sort((a, b) => a - b), 'the mask marks the voids, and only them');
  let lo = Infinity, hi = -Infinity;
  for (const v of ref) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  let sum = 0;
  for (const i of voids) {
    const m = metres(h, i);
    assert.ok(Number.isFinite(m) && m >= lo - 1 && m <= hi + 1, `void ${i} filled with ${m} m, outside ${lo}..${hi}`);
    sum += Math.abs(m - ref[i]);
  }
  const mean = sum / voids.length;
  assert.ok(mean < 0.1 * (hi - lo), `filled voids are ${mean.toFixed(1)} m off on average (range ${hi - lo} m)`);
}

for (const entry of manifest) {
  const name = entry.files[0];
  test(`${name}: heights match the original within ${entry.toleranceM.toPrecision(3)} m`, async (t) => {
    const h = await loadHeightfield(entry.files.map(file), entry.options ?? {});
    const ref = floats(read(`${DIR}${entry.ref}.f32`));
    assert.equal(h.source, name);
    assert.equal(h.sampleType, entry.sampleType);
    if (entry.encoding) assert.equal(h.encoding, entry.encoding);
    const worst = checkHeights(h, ref, entry.toleranceM, entry.voids);
    t.diagnostic(`${h.format} ${h.width}x${h.height} ${h.sampleType}: worst error ${worst.toFixed(4)} m`);
    const spacing = entry.spacing ?? EXPECTED_SPACING[name];
    if (spacing) {
      assert.equal(h.spacingFromFile, true);
      assert.ok(Math.abs(h.spacingX / spacing[0] - 1) < 0.005 && Math.abs(h.spacingY / spacing[1] - 1) < 0.005,
        `spacing ${h.spacingX} x ${h.spacingY} m, expected ${spacing[0].toFixed(1)} x ${spacing[1].toFixed(1)}`);
    }
  });
}

test('Terrain-RGB and Terrarium are told apart by their colours when the name does not say', async () => {
  for (const [fixture, encoding, ref, tol] of [['canyon_terrain-rgb.png', 'terrain-rgb', 'canyon', 0.0501], ['etopo_terrarium.png', 'terrarium', 'etopo', 0.003]]) {
    const h = await loadHeightfield([{ name: 'tile.png', bytes: read(DIR + fixture) }]);
    assert.equal(h.encoding, encoding);
    checkHeights(h, floats(read(`${DIR}${ref}.f32`)), tol);
    // The wrong encoding, chosen by hand, is obeyed (and gives other heights).
    const other = encoding === 'terrarium' ? 'terrain-rgb' : 'terrarium';
    const forced = await loadHeightfield([{ name: 'tile.png', bytes: read(DIR + fixture) }], { encoding: other });
    assert.equal(forced.encoding, other);
    assert.notEqual(forced.samples[0], h.samples[0]);
  }
});

test('RAW: a square file needs no size; an oblong one asks for it, and a wrong size is refused', async () => {
  const sq = await loadHeightfield([file('canyon.r16')]);
  assert.deepEqual([sq.width, sq.height, sq.heightScale, sq.spacingFromFile], [192, 192, 1, false]);
  await assert.rejects(loadHeightfield([file('volcano.r16')]), (e) => e instanceof SizeNeededError && e.needsSize &&
    e.message === 'volcano.r16: 5307 samples do not make a square: give its width and height');
  const byWidth = await loadHeightfield([file('volcano.r16')], { width: 87 });
  assert.equal(byWidth.height, 61);
  await assert.rejects(loadHeightfield([file('volcano.r16')], { width: 80, height: 61 }),
    /volcano\.r16: size 80x61 does not fit 5307 16-bit samples \(10614 bytes\)/);
});

// SRTM tiles are 1201^2 at least: the test writes one from the project's own Himalaya PNG.
function voidsOf(width, height) {
  const voids = new Set();
  const cx = 500, cy = 600, r = 14;
  for (let y = cy - r; y <= cy + r; y++) for (let x = cx - r; x <= cx + r; x++) if ((x - cx) ** 2 + (y - cy) ** 2 <= r * r) voids.add(y * width + x);
  for (let k = 0; k < 40; k++) voids.add(((k * 7919) % height) * width + ((k * 104729) % width));
  return [...voids].sort((a, b) => a - b);
}
function makeHgt() {
  const png = decodePngOracle(read('public/terrain/globe_himalaya_2048.png')); // 0..8752 m over 0..65535
  const side = 1201, x0 = 847, y0 = 600;
  const ref = new Float32Array(side * side);
  for (let y = 0; y < side; y++) for (let x = 0; x < side; x++) ref[y * side + x] = (png.data[(y0 + y) * 2048 + x0 + x] / 65535) * 8752;
  const voids = voidsOf(side, side);
  const bytes = new Uint8Array(side * side * 2);
  const view = new DataView(bytes.buffer);
  ref.forEach((h, i) => view.setInt16(2 * i, Math.round(h), false));
  for (const i of voids) view.setInt16(2 * i, -32768, false);
  return { bytes, ref, voids };
}

test('SRTM .hgt: big-endian metres, voids filled, latitude from the tile name', async () => {
  const { bytes, ref, voids } = makeHgt();
  const h = await loadHeightfield([{ name: 'N27E086.hgt', bytes }]);
  assert.deepEqual([h.width, h.height, h.sampleType, h.nodata, h.format], [1201, 1201, 'i16', -32768, 'hgt']);
  checkHeights(h, ref, 0.5 + 1e-3, voids);
  // 3" tile at 27.5N: 92.6 m north-south (1852 m / 20), times cos(27.5) east-west.
  assert.equal(h.spacingFromFile, true);
  assert.ok(Math.abs(h.spacingY - 92.6) < 0.3 && Math.abs(h.spacingX - 92.6 * Math.cos((27.5 * Math.PI) / 180)) < 0.3, `${h.spacingX} x ${h.spacingY}`);
  const south = await loadHeightfield([{ name: 'dir/s45w070.HGT', bytes }]);
  assert.ok(Math.abs(south.spacingX - 92.6 * Math.cos((44.5 * Math.PI) / 180)) < 0.3, `${south.spacingX}`);
  const unnamed = await loadHeightfield([{ name: 'tile.hgt', bytes }]);
  assert.equal(unnamed.spacingFromFile, false);
  // Names no tile has (a cosine of 95.5 degrees made a spacing of 0.0001 m) give no spacing either.
  for (const name of ['N95E000.hgt', 'S91W010.hgt', 'N27E181.hgt', 'N60W180.hgt']) {
    const h = await loadHeightfield([{ name, bytes }]);
    assert.equal(h.spacingFromFile, name === 'N60W180.hgt', name);
    assert.ok(h.spacingX > 1 && h.spacingY > 1, `${name}: ${h.spacingX} x ${h.spacingY}`);
  }
});

test('GeoTIFF without a geotransform: no spacing from the file', async () => {
  // Drop the ModelPixelScale/ModelTiepoint/GeoKey tags by renaming their tag numbers to
  // private ones (65000+), which a reader ignores.
  const bytes = read(`${DIR}canyon_u16_tiled_deflate.tif`).slice();
  const view = new DataView(bytes.buffer);
  const ifd = view.getUint32(4, true);
  for (let i = 0, n = view.getUint16(ifd, true); i < n; i++) {
    const tag = view.getUint16(ifd + 2 + 12 * i, true);
    if (tag === 33550 || tag === 33922 || tag === 34735) view.setUint16(ifd + 2 + 12 * i, 65000 + i, true);
  }
  const h = await loadHeightfield([{ name: 'plain.tif', bytes }]);
  assert.deepEqual([h.spacingX, h.spacingY, h.spacingFromFile], [1, 1, false]);
});

/** A little-endian TIFF with uncompressed 16-bit strips, written big-endian: every directory
 *  field, out-of-line value and sample byte-swapped. */
function bigEndianTwin(le) {
  const be = le.slice(), view = new DataView(le.buffer, le.byteOffset, le.length);
  const swap = (at, size) => { for (let k = 0; k < size; k++) be[at + k] = le[at + size - 1 - k]; };
  const SIZES = { 1: 1, 2: 1, 3: 2, 4: 4, 5: 4, 11: 4, 12: 8 }; // a RATIONAL is two LONGs
  be.set([0x4d, 0x4d]);
  swap(2, 2); swap(4, 4);
  const ifd = view.getUint32(4, true), entries = view.getUint16(ifd, true);
  swap(ifd, 2);
  const u32 = (tag) => {
    for (let i = 0; i < entries; i++) if (view.getUint16(ifd + 2 + 12 * i, true) === tag) return ifd + 2 + 12 * i;
  };
  for (let i = 0; i < entries; i++) {
    const e = ifd + 2 + 12 * i, type = view.getUint16(e + 2, true), size = SIZES[type];
    const count = view.getUint32(e + 4, true) * (type === 5 ? 2 : 1);
    swap(e, 2); swap(e + 2, 2); swap(e + 4, 4);
    const at = size * count <= 4 ? e + 8 : view.getUint32(e + 8, true);
    if (size * count > 4) swap(e + 8, 4);
    for (let k = 0; k < count; k++) swap(at + k * size, size);
  }
  swap(ifd + 2 + 12 * entries, 4);
  const offsets = view.getUint32(u32(273) + 8, true), counts = view.getUint32(u32(279) + 8, true);
  for (let s = 0; s < view.getUint32(u32(273) + 4, true); s++) {
    const at = view.getUint32(offsets + 4 * s, true), n = view.getUint32(counts + 4 * s, true);
    for (let k = 0; k < n; k += 2) swap(at + k, 2);
  }
  return be;
}

test('a big-endian GeoTIFF loads as its little-endian twin (the library misread its strip offsets)', async () => {
  const le = read(`${DIR}everest_i16_strips.tif`);
  const be = bigEndianTwin(le);
  assert.deepEqual(Array.from(be.subarray(0, 4)), [0x4d, 0x4d, 0, 42]);
  const [a, b] = [await loadHeightfield([{ name: 'le.tif', bytes: le }]), await loadHeightfield([{ name: 'be.tif', bytes: be }])];
  assert.deepEqual([b.width, b.height, b.nodata, b.missing, b.spacingX, b.spacingY], [a.width, a.height, a.nodata, a.missing, a.spacingX, a.spacingY]);
  assert.ok(a.samples.every((v, i) => v === b.samples[i]), 'same samples');
});

test('no-data filling: where row and column hold no data, the nearest row with data, found in linear time', async () => {
  const f32 = (width, values) => [{ name: 'n.f32', bytes: new Uint8Array(Float32Array.from(values).buffer) },
    { name: 'n.json', bytes: new TextEncoder().encode(JSON.stringify({ width, height: values.length / width })) }];
  // Column 1 holds no data; rows 0, 2, 4, 5 none either. Row 2 is as near row 1 as row 3: the one above.
  const N = NaN;
  const h = await loadHeightfield(f32(3, [N, N, N, 1, N, 3, N, N, N, 5, N, 7, N, N, N, N, N, N, 9, N, 9]));
  assert.deepEqual(Array.from({ length: 7 }, (_, y) => h.samples[y * 3 + 1]), [2, 2, 2, 6, 6, 9, 9]);
  // A 2 x 40000 field with one sample: searching outwards from every empty row took seconds.
  const tall = new Array(2 * 40000).fill(NaN);
  tall[2 * 20000] = 42;
  const start = performance.now();
  const t = await loadHeightfield(f32(2, tall));
  assert.ok(t.samples.every((v) => v === 42));
  assert.ok(performance.now() - start < 2000, `${(performance.now() - start).toFixed(0)} ms`);
});

test('a sidecar overrides the spacing of the file', async () => {
  const h = await loadHeightfield([file('canyon_u16_tiled_deflate.tif'),
    { name: 'canyon_u16_tiled_deflate.json', bytes: new TextEncoder().encode('{"cell_size_m": 61.7}') }]);
  assert.deepEqual([h.spacingX, h.spacingY, h.spacingFromFile], [61.7, 61.7, true]);
});

test('loaders pause and report progress, and read samples through reacquire() after each pause', async () => {
  const { bytes } = makeHgt();
  const plain = await loadHeightfield([{ name: 'N27E086.hgt', bytes }]);
  // A clock that moves 30 ms a reading: every chance to pause is taken. Each reacquire() moves
  // the samples to a new buffer and wipes the old one, as a detached view after WASM memory
  // growth would lose them: a loader that kept writing through an old view ends with holes.
  let current = null, reacquired = 0;
  const fractions = [];
  const { now } = performance;
  let clock = 0;
  performance.now = () => (clock += 30);
  let h;
  try {
    h = await loadHeightfield([{ name: 'N27E086.hgt', bytes }], {
      allocate: (type, w, hh) => (current = new Int16Array(w * hh)),
      reacquire: () => {
        reacquired++;
        const moved = Int16Array.from(current);
        current.fill(12345);
        return (current = moved);
      },
      onProgress: (f) => fractions.push(f),
    });
  } finally {
    performance.now = now;
  }
  assert.ok(reacquired >= 10, `paused ${reacquired} times`);
  assert.equal(h.samples, current, 'the field is the latest view');
  assert.ok(h.samples.every((v, i) => v === plain.samples[i]), 'every sample written through the view of its moment');
  assert.ok(fractions.length >= reacquired, `${fractions.length} progress reports`);
  assert.ok(fractions.every((f, i) => f >= 0 && f <= 1 && (i === 0 || f >= fractions[i - 1] || f === 0)), `fractions within 0..1: ${fractions.slice(0, 8)}`);
});

test('a compressed file reports checking before anything is allocated, then decoding, each within 0..1', async () => {
  const reports = [];
  let allocatedAt = -1;
  // A clock that moves 30 ms a reading: every chance to pause is taken, and reported.
  const { now } = performance;
  let clock = 0;
  performance.now = () => (clock += 30);
  try {
    await loadHeightfield([{ name: 'globe.png', bytes: read('public/terrain/globe_himalaya_2048.png') }], {
      allocate: (type, w, hh) => { allocatedAt = reports.length; return new Uint16Array(w * hh); },
      onProgress: (fraction, phase) => reports.push([phase, fraction]),
    });
  } finally {
    performance.now = now;
  }
  assert.ok(allocatedAt > 0 && allocatedAt < reports.length, `allocated after report ${allocatedAt} of ${reports.length}`);
  reports.forEach(([phase, fraction], i) => {
    assert.ok(fraction >= 0 && fraction <= 1, `${phase} ${fraction}`);
    assert.equal(phase, i < allocatedAt ? 'checking' : 'decoding', `report ${i}, allocated after ${allocatedAt}`);
  });
});
