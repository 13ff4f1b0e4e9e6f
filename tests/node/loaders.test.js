// Tests of web/loaders: the PNG and f32+json height-field loaders.
// Run: node --test tests/node/
//
// fast-png is the oracle for PNG decoding; the .f32 files are the originals the
// fixture PNGs were quantised from. Mutated files of every format, each within a
// time bound, are tests/node/fuzz.test.js's.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decode as fastPngDecode, encode as fastPngEncode } from 'fast-png';
import { zlibSync } from 'fflate';
import { loadHeightfield, decodePng, HeightfieldError } from '../../web/loaders/index.js';

const ROOT = new URL('../../', import.meta.url);
const FIXTURES = ['volcano_maungawhau', 'jacksboro_fault', 'grandcanyon_512'];
const GLOBE = 'public/terrain/globe_himalaya_2048';

const read = (path) => new Uint8Array(readFileSync(new URL(path, ROOT)));
const fixtureFile = (name, ext) => ({ name: `${name}.${ext}`, bytes: read(`tests/fixtures/${name}.${ext}`) });
const sidecarOf = (name) => JSON.parse(new TextDecoder().decode(read(`tests/fixtures/${name}.json`)));
const f32Of = (name) => {
  const b = read(`tests/fixtures/${name}.f32`);
  return new Float32Array(b.buffer, b.byteOffset, b.length / 4);
};
const asciiBytes = (s) => new TextEncoder().encode(s);

// ---------------------------------------------------------------------------
// A small PNG writer, for files fast-png cannot make: every filter type,
// split IDATs, sub-byte depths, grey+alpha, tRNS, bad headers.

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

function chunk(type, data = new Uint8Array(0)) {
  const out = new Uint8Array(12 + data.length);
  const view = new DataView(out.buffer);
  view.setUint32(0, data.length);
  out.set(asciiBytes(type), 4);
  out.set(data, 8);
  view.setUint32(8 + data.length, crc32(out.subarray(4, 8 + data.length)));
  return out;
}

function concat(parts) {
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let o = 0;
  for (const p of parts) { out.set(p, o); o += p.length; }
  return out;
}

function ihdr(width, height, bitDepth, colourType, interlace = 0) {
  const d = new Uint8Array(13);
  const v = new DataView(d.buffer);
  v.setUint32(0, width);
  v.setUint32(4, height);
  d.set([bitDepth, colourType, 0, 0, interlace], 8);
  return chunk('IHDR', d);
}

const SIGNATURE = new Uint8Array([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);

function textChunk(key, value) {
  return chunk('tEXt', concat([asciiBytes(key), new Uint8Array([0]), asciiBytes(value)]));
}

// Textbook Paeth (PNG spec 9.4), written independently of the decoder's.
function paeth(a, b, c) {
  const p = a + b - c;
  const pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

/** Filters raw (unfiltered) row bytes with the given filter type; returns filter byte + row. */
function filterRow(type, raw, prevRaw, bpp) {
  const out = new Uint8Array(raw.length + 1);
  out[0] = type;
  for (let i = 0; i < raw.length; i++) {
    const a = i >= bpp ? raw[i - bpp] : 0, b = prevRaw[i], c = i >= bpp ? prevRaw[i - bpp] : 0;
    const pred = [0, a, b, (a + b) >> 1, paeth(a, b, c)][type];
    out[i + 1] = (raw[i] - pred) & 0xff;
  }
  return out;
}

/**
 * Builds a PNG from raw row bytes. filterOf(row) picks each row's filter;
 * idatSize splits the zlib stream into IDAT chunks of that many bytes.
 */
function makePng({ width, height, bitDepth, colourType, rows, filterOf = (r) => r % 5, level = 6,
  idatSize = Infinity, before = [], after = [], interlace = 0, zlibEdit = (z) => z }) {
  const bpp = Math.max(1, (bitDepth * (colourType === 4 ? 2 : 1)) >> 3);
  let prev = new Uint8Array(rows[0].length);
  const filtered = rows.map((raw, r) => {
    const f = filterRow(filterOf(r), raw, prev, bpp);
    prev = raw;
    return f;
  });
  const z = zlibEdit(zlibSync(concat(filtered), { level }));
  const idats = [];
  for (let p = 0; p < z.length; p += Math.min(idatSize, z.length)) idats.push(chunk('IDAT', z.subarray(p, p + idatSize)));
  return concat([SIGNATURE, ihdr(width, height, bitDepth, colourType, interlace), ...before, ...idats, ...after, chunk('IEND')]);
}

/** Raw rows of 16-bit big-endian grey samples (channels=2 adds an alpha sample after each). */
function rows16(values, width, height, channels = 1) {
  return Array.from({ length: height }, (_, y) => {
    const row = new Uint8Array(width * 2 * channels);
    for (let x = 0; x < width; x++) {
      const v = values[y * width + x];
      row[x * 2 * channels] = v >> 8;
      row[x * 2 * channels + 1] = v & 0xff;
      if (channels === 2) { row[x * 4 + 2] = (x * 7) & 0xff; row[x * 4 + 3] = y & 0xff; }
    }
    return row;
  });
}

function rows8(values, width, height, channels = 1) {
  return Array.from({ length: height }, (_, y) => {
    const row = new Uint8Array(width * channels);
    for (let x = 0; x < width; x++) {
      row[x * channels] = values[y * width + x];
      if (channels === 2) row[x * 2 + 1] = (x * 13 + y) & 0xff;
    }
    return row;
  });
}

/** Packs samples of 1, 2 or 4 bits, most significant first. */
function rowsPacked(values, width, height, depth) {
  return Array.from({ length: height }, (_, y) => {
    const row = new Uint8Array(Math.ceil((width * depth) / 8));
    for (let x = 0; x < width; x++) {
      const bit = x * depth;
      row[bit >> 3] |= values[y * width + x] << (8 - depth - (bit & 7));
    }
    return row;
  });
}

/** Positions of the chunks of a PNG: [{ type, start, data, end }] (end = after the CRC). */
function chunksOf(png) {
  const v = new DataView(png.buffer, png.byteOffset, png.byteLength);
  const out = [];
  for (let p = 8; p + 12 <= png.length;) {
    const len = v.getUint32(p);
    const type = String.fromCharCode(...png.subarray(p + 4, p + 8));
    out.push({ type, start: p, data: png.subarray(p + 8, p + 8 + len), end: p + 12 + len });
    p += 12 + len;
  }
  return out;
}

function firstMismatch(a, b) {
  if (a.length !== b.length) return `length ${a.length} vs ${b.length}`;
  for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return `index ${i}: ${a[i]} vs ${b[i]}`;
  return null;
}

/** Expects loadHeightfield(files) to reject with a HeightfieldError naming `file` and matching `problem`. */
async function rejects(files, file, problem, options = {}) {
  let calls = 0;
  const allocate = (type, w, h) => { calls++; return new { u8: Uint8Array, u16: Uint16Array, f32: Float32Array }[type](w * h); };
  await assert.rejects(loadHeightfield(files, { allocate, ...options }), (e) => {
    assert.ok(e instanceof HeightfieldError, `expected HeightfieldError, got ${e && e.name}: ${e && e.message}`);
    assert.equal(e.file, file);
    if (file) assert.ok(e.message.startsWith(`${file}: `), `message does not name ${file}: ${e.message}`);
    assert.match(e.message, problem);
    assert.ok(!e.message.includes('\n'), 'message is one line');
    return true;
  });
  return calls;
}

// -------------------------------------------------------------------------
// Correct files.

for (const name of FIXTURES) {
  test(`${name}.png + .json: heights match the .f32 within half a quantum`, async () => {
    const meta = sidecarOf(name);
    const h = await loadHeightfield([fixtureFile(name, 'png'), fixtureFile(name, 'json')]);
    assert.equal(h.width, meta.width);
    assert.equal(h.height, meta.height);
    assert.equal(h.sampleType, 'u16');
    assert.ok(h.samples instanceof Uint16Array);
    assert.equal(h.format, 'png');
    assert.equal(h.source, `${name}.png`);
    assert.equal(h.spacingX, meta.cell_size_x_m ?? meta.cell_size_m);
    assert.equal(h.spacingY, meta.cell_size_y_m ?? meta.cell_size_m);
    assert.equal(h.spacingFromFile, true);
    assert.equal(h.nodata, null);
    assert.equal(h.heightOffset, meta.min);
    assert.equal(h.heightScale, (meta.max - meta.min) / 65535);
    const ref = f32Of(name);
    const halfStep = (meta.max - meta.min) / 65535 / 2;
    for (let i = 0; i < ref.length; i++) {
      const err = Math.abs(h.samples[i] * h.heightScale + h.heightOffset - ref[i]);
      if (err > halfStep + Math.abs(ref[i]) * 2 ** -23) assert.fail(`sample ${i}: error ${err} m > ${halfStep} m`);
    }
  });

  test(`${name}.png: same samples as fast-png`, async () => {
    const bytes = read(`tests/fixtures/${name}.png`);
    const ours = await decodePng(bytes, `${name}.png`, (t, w, h) => new Uint16Array(w * h));
    const ref = fastPngDecode(bytes);
    assert.equal(ref.depth, 16);
    assert.equal(ref.channels, 1);
    assert.equal(firstMismatch(ours.samples, ref.data), null);
  });

  test(`${name}.f32 + .json: exactly the raw floats`, async () => {
    const meta = sidecarOf(name);
    const h = await loadHeightfield([fixtureFile(name, 'json'), fixtureFile(name, 'f32')]);
    assert.equal(h.sampleType, 'f32');
    assert.equal(h.format, 'f32');
    assert.equal(h.source, `${name}.f32`);
    assert.deepEqual([h.width, h.height], [meta.width, meta.height]);
    assert.deepEqual([h.heightScale, h.heightOffset, h.nodata], [1, 0, null]);
    assert.deepEqual([h.spacingX, h.spacingY, h.spacingFromFile],
      [meta.cell_size_x_m ?? meta.cell_size_m, meta.cell_size_y_m ?? meta.cell_size_m, true]);
    assert.equal(firstMismatch(h.samples, f32Of(name)), null);
  });
}

test('globe_himalaya_2048.png: same samples as fast-png, spacing from its sidecar', async () => {
  const png = read(`${GLOBE}.png`);
  const h = await loadHeightfield([
    { name: 'globe_himalaya_2048.png', bytes: png },
    { name: 'globe_himalaya_2048.json', bytes: read(`${GLOBE}.json`) },
  ]);
  assert.deepEqual([h.width, h.height, h.sampleType], [2048, 2048, 'u16']);
  assert.deepEqual([h.spacingX, h.spacingY], [806.9, 926.0]);
  assert.deepEqual([h.heightOffset, h.heightScale], [0, 8752 / 65535]);
  assert.equal(firstMismatch(h.samples, fastPngDecode(png).data), null);
});

test('PNG alone: height range from tEXt, spacing defaults to 1', async () => {
  const h = await loadHeightfield([fixtureFile('volcano_maungawhau', 'png')]);
  assert.deepEqual([h.spacingX, h.spacingY, h.spacingFromFile], [1, 1, false]);
  assert.deepEqual([h.heightOffset, h.heightScale], [94, 101 / 65535]);
});

test('PNG without min_m/max_m: range from the sidecar, else raw units', async () => {
  const ref = fastPngDecode(read('tests/fixtures/volcano_maungawhau.png'));
  const bare = fastPngEncode({ width: ref.width, height: ref.height, data: ref.data, depth: 16, channels: 1 });
  const withJson = await loadHeightfield([{ name: 'v.png', bytes: bare }, { name: 'v.json', bytes: asciiBytes('{"min": 94, "max": 195, "cell_size_m": 10}') }]);
  assert.deepEqual([withJson.heightOffset, withJson.heightScale, withJson.spacingX], [94, 101 / 65535, 10]);
  const alone = await loadHeightfield([{ name: 'v.png', bytes: bare }]);
  assert.deepEqual([alone.heightOffset, alone.heightScale, alone.spacingFromFile], [0, 1, false]);
  assert.equal(firstMismatch(alone.samples, ref.data), null);
  // A sidecar without spacing fields leaves spacing defaulted.
  const noSpacing = await loadHeightfield([{ name: 'v.png', bytes: bare }, { name: 'v.json', bytes: asciiBytes('{"width": 87}') }]);
  assert.equal(noSpacing.spacingFromFile, false);
});

test('8-bit grayscale (fast-png encoder) round-trips exactly', async () => {
  const meta = sidecarOf('jacksboro_fault');
  const ref = f32Of('jacksboro_fault');
  const q = Uint8Array.from(ref, (h) => Math.round(((h - meta.min) / (meta.max - meta.min)) * 255));
  const png = fastPngEncode({ width: meta.width, height: meta.height, data: q, depth: 8, channels: 1,
    text: { min_m: String(meta.min), max_m: String(meta.max) } }); // tEXt after IDAT, as fast-png writes it
  const h = await loadHeightfield([{ name: 'j8.png', bytes: png }]);
  assert.equal(h.sampleType, 'u8');
  assert.equal(firstMismatch(h.samples, q), null);
  assert.deepEqual([h.heightOffset, h.heightScale], [meta.min, (meta.max - meta.min) / 255]);
  const halfStep = (meta.max - meta.min) / 255 / 2;
  for (let i = 0; i < ref.length; i++) {
    assert.ok(Math.abs(h.samples[i] * h.heightScale + h.heightOffset - ref[i]) <= halfStep + 1e-9);
  }
});

test('every filter type 0-4, at 8 and 16 bits, grey and grey+alpha, agrees with fast-png', async () => {
  const { width, height, data } = fastPngDecode(read('tests/fixtures/volcano_maungawhau.png'));
  const v8 = Uint8Array.from(data, (v) => v >> 8);
  const cases = [
    { bitDepth: 16, colourType: 0, rows: rows16(data, width, height), expect: data },
    { bitDepth: 8, colourType: 0, rows: rows8(v8, width, height), expect: v8 },
    { bitDepth: 16, colourType: 4, rows: rows16(data, width, height, 2), expect: data },
    { bitDepth: 8, colourType: 4, rows: rows8(v8, width, height, 2), expect: v8 },
  ];
  const filterings = [(r) => r % 5, () => 0, () => 1, () => 2, () => 3, () => 4, (r) => (r * 3 + 1) % 5];
  for (const c of cases) {
    for (const filterOf of filterings) {
      const png = makePng({ width, height, ...c, filterOf });
      const h = await loadHeightfield([{ name: 'f.png', bytes: png }]);
      assert.equal(h.sampleType, c.bitDepth === 16 ? 'u16' : 'u8');
      assert.equal(firstMismatch(h.samples, c.expect), null, `depth ${c.bitDepth} colour ${c.colourType} ${filterOf}`);
      const oracle = fastPngDecode(png);
      const grey = c.colourType === 4 ? oracle.data.filter((_, i) => i % 2 === 0) : oracle.data;
      assert.equal(firstMismatch(h.samples, grey), null, 'fast-png disagrees');
    }
  }
});

test('bit depths 1, 2, 4 expand to u8 raw values', async () => {
  const width = 37, height = 11; // odd width: rows end mid-byte
  for (const depth of [1, 2, 4]) {
    const values = Uint8Array.from({ length: width * height }, (_, i) => (i * 7 + (i >> 3)) % (1 << depth));
    const png = makePng({ width, height, bitDepth: depth, colourType: 0, rows: rowsPacked(values, width, height, depth),
      before: [textChunk('min_m', '-5'), textChunk('max_m', '10')] });
    const h = await loadHeightfield([{ name: `d${depth}.png`, bytes: png }]);
    assert.equal(h.sampleType, 'u8');
    assert.equal(firstMismatch(h.samples, values), null, `depth ${depth}`);
    assert.deepEqual([h.heightOffset, h.heightScale], [-5, 15 / (2 ** depth - 1)]);
  }
});

test('stream handling: IDAT split into tiny chunks, stored and max compression, tRNS as nodata', async () => {
  const width = 300, height = 40;
  const values = Uint16Array.from({ length: width * height }, (_, i) => (i * 2654435761) >>> 16);
  for (const [idatSize, level] of [[1, 6], [7, 9], [1000, 0], [Infinity, 0], [Infinity, 9]]) {
    const png = makePng({ width, height, bitDepth: 16, colourType: 0, rows: rows16(values, width, height), idatSize, level,
      before: [chunk('tRNS', new Uint8Array([0x12, 0x34]))] });
    const h = await loadHeightfield([{ name: 's.png', bytes: png }]);
    assert.equal(firstMismatch(h.samples, values), null, `IDAT size ${idatSize}, level ${level}`);
    assert.equal(h.nodata, 0x1234);
  }
  // A big flat field: very high compression ratio, many rows per inflate call.
  const flat = new Uint16Array(2000 * 600).fill(4242);
  const h = await loadHeightfield([{ name: 'flat.png', bytes: makePng({ width: 2000, height: 600, bitDepth: 16, colourType: 0, rows: rows16(flat, 2000, 600), level: 9 }) }]);
  assert.equal(firstMismatch(h.samples, flat), null);
});

test('allocate is called once, after validation, and its array is the result', async () => {
  for (const [files, type, w, h] of [
    [[fixtureFile('volcano_maungawhau', 'png')], 'u16', 87, 61],
    [[fixtureFile('volcano_maungawhau', 'f32'), fixtureFile('volcano_maungawhau', 'json')], 'f32', 87, 61],
  ]) {
    // Simulate a view into WebAssembly memory: an offset inside a larger buffer.
    const heap = new ArrayBuffer(64 + w * h * 4 + 64);
    const calls = [];
    let given = null;
    const allocate = (t, width, height) => {
      calls.push([t, width, height]);
      given = t === 'f32' ? new Float32Array(heap, 16, width * height) : new Uint16Array(heap, 18, width * height);
      return given;
    };
    const result = await loadHeightfield(files, { allocate });
    assert.deepEqual(calls, [[type, w, h]]);
    assert.equal(result.samples, given);
  }
});

test('f32 source bytes at an unaligned offset are read correctly', async () => {
  const f32 = read('tests/fixtures/volcano_maungawhau.f32');
  const shifted = new Uint8Array(f32.length + 3);
  shifted.set(f32, 3);
  const h = await loadHeightfield([{ name: 'v.f32', bytes: shifted.subarray(3) }, { name: 'v.json', bytes: read('tests/fixtures/volcano_maungawhau.json') }]);
  assert.equal(firstMismatch(h.samples, f32Of('volcano_maungawhau')), null);
});

test('f32 NaN samples and the sidecar nodata are filled from their neighbours', async () => {
  const values = new Float32Array([1, 2, 3, 4, NaN, 6, 7, 8, -9999]);
  const h = await loadHeightfield([{ name: 'n.f32', bytes: new Uint8Array(values.buffer) },
    { name: 'n.json', bytes: asciiBytes('{"width": 3, "height": 3, "nodata": -9999}') }]);
  // The centre: its row and its column both interpolate to 5. The corner: its row gives 8
  // (nearest, no right end), its column 6 (nearest, no lower end): the mean is 7.
  assert.deepEqual([...h.samples], [1, 2, 3, 4, 5, 6, 7, 8, 7]);
  assert.equal(h.missing, 2);
  // Which samples were filled, a bit each (the page's no-data holes): samples 4 and 8.
  assert.deepEqual([...h.missingMask], [0b00010000, 0b00000001]);
  assert.equal(h.nodata, -9999);
  assert.equal(h.spacingFromFile, false);
});

test('a wrong allocate() return value is a programming error, not a HeightfieldError', async () => {
  await assert.rejects(loadHeightfield([fixtureFile('volcano_maungawhau', 'png')], { allocate: () => new Float32Array(87 * 61) }),
    (e) => !(e instanceof HeightfieldError) && /allocate\('u16', 87, 61\) returned Float32Array/.test(e.message));
});

// -------------------------------------------------------------------------
// Bad input: each must be a HeightfieldError naming the file and the problem.

const volcanoPng = read('tests/fixtures/volcano_maungawhau.png');
const volcanoF32 = read('tests/fixtures/volcano_maungawhau.f32');
const volcanoJson = read('tests/fixtures/volcano_maungawhau.json');

test('bad input: no files, empty files, unsupported types', async () => {
  await rejects([], '', /no files given/);
  await rejects('x.png', '', /expected an array/);
  await rejects([{ name: 'e.png', bytes: new Uint8Array(0) }], 'e.png', /^e\.png: empty file$/);
  await rejects([{ name: 'e.f32', bytes: new Uint8Array(0) }, { name: 'e.json', bytes: volcanoJson }], 'e.f32', /empty file/);
  await rejects([{ name: 'x.png', bytes: 'not bytes' }], 'x.png', /bytes must be a Uint8Array/);
  await rejects([{ name: 'x.tif', bytes: new Uint8Array([0x49, 0x49, 0x2a, 0, 1, 2]) }], 'x.tif', /truncated: 6 bytes, no TIFF header/);
  await rejects([{ name: 'x.gif', bytes: new Uint8Array([0x47, 0x49, 0x46, 0x38, 1, 2]) }], 'x.gif', /unsupported file type \(looks like GIF data\)/);
  await rejects([{ name: 'photo.jpg', bytes: new Uint8Array([0xff, 0xd8, 0xff, 0xe0, 0, 16]) }], 'photo.jpg', /unsupported file type \(looks like JPEG data\)/);
  await rejects([{ name: 'README', bytes: asciiBytes('hello') }], 'README', /unsupported file type/);
  // Without an extension, a PNG is recognised by its signature.
  const h = await loadHeightfield([{ name: 'blob', bytes: volcanoPng }]);
  assert.equal(h.format, 'png');
});

test('bad input: not a PNG (bad signature, text, JPEG)', async () => {
  const flipped = volcanoPng.slice();
  flipped[1] ^= 0x20;
  await rejects([{ name: 'v.png', bytes: flipped }], 'v.png', /not a PNG file \(bad signature\)/);
  const damaged = volcanoPng.slice();
  damaged[6] = 0x0a; // \x1a lost, as in a text-mode transfer
  await rejects([{ name: 'd.png', bytes: damaged }], 'd.png', /not a PNG file \(bad signature: the PNG signature bytes are damaged\)/);
  await rejects([{ name: 'notes.png', bytes: asciiBytes('these are not pixels\n') }], 'notes.png', /not a PNG file \(bad signature; looks like text\)/);
  await rejects([{ name: 'photo.png', bytes: new Uint8Array([0xff, 0xd8, 0xff, 0xe0, 0, 16, 0x4a, 0x46, 0x49, 0x46, 0, 1]) }], 'photo.png', /not a PNG file \(bad signature; looks like JPEG data\)/);
});

test('bad input: truncated PNGs at many cut points never allocate', async () => {
  const jacksboro = read('tests/fixtures/jacksboro_fault.png');
  const idat = chunksOf(jacksboro).find((c) => c.type === 'IDAT');
  const cuts = [[volcanoPng, 3], [volcanoPng, 8], [volcanoPng, 20], [volcanoPng, 33], [volcanoPng, volcanoPng.length - 1],
    [jacksboro, idat.start + 4], [jacksboro, idat.start + 9], [jacksboro, idat.start + 5000]];
  for (const png of [volcanoPng, jacksboro]) for (let n = 1; n < png.length; n += 997) cuts.push([png, n]);
  for (const [png, n] of cuts) {
    const calls = await rejects([{ name: 'cut.png', bytes: png.subarray(0, n) }], 'cut.png', /truncated/);
    assert.equal(calls, 0, `cut at ${n} allocated`);
  }
  await rejects([{ name: 's.png', bytes: volcanoPng.subarray(0, 5) }], 's.png', /truncated: file ends inside the PNG signature \(5 of 8 bytes\)/);
  await rejects([{ name: 'h.png', bytes: volcanoPng.subarray(0, 20) }], 'h.png', /truncated: file ends after 20 bytes, inside the IHDR chunk$/);
  await rejects([{ name: 'i.png', bytes: jacksboro.subarray(0, idat.start + 5000) }], 'i.png',
    /truncated: file ends after \d+ bytes, inside the IDAT chunk \(image data: \d+ of 344 rows\)/);
  await rejects([{ name: 'e.png', bytes: volcanoPng.subarray(0, volcanoPng.length - 12) }], 'e.png',
    /truncated: file ends after \d+ bytes, before the IEND chunk \(image data: 61 of 61 rows\)/);
});

test('bad input: truncated zlib stream inside complete chunks', async () => {
  const { width, height, data } = fastPngDecode(volcanoPng);
  const png = makePng({ width, height, bitDepth: 16, colourType: 0, rows: rows16(data, width, height),
    zlibEdit: (z) => z.subarray(0, z.length >> 1) });
  await rejects([{ name: 'z.png', bytes: png }], 'z.png', /truncated: IDAT data ends after ([1-9]|[1-5][0-9]) of 61 rows$/);
});

test('bad input: corrupt IDAT contents with valid CRCs', async () => {
  const { width, height, data } = fastPngDecode(volcanoPng);
  const rows = rows16(data, width, height);
  // All refused before anything is allocated: the data is inflated once to check it first.
  assert.equal(await rejects([{ name: 'h.png', bytes: makePng({ width, height, bitDepth: 16, colourType: 0, rows, zlibEdit: (z) => { const c = z.slice(); c[0] = 0x79; return c; } }) }],
    'h.png', /corrupt IDAT data \(bad zlib header\)/), 0);
  assert.equal(await rejects([{ name: 'd.png', bytes: makePng({ width, height, bitDepth: 16, colourType: 0, rows, zlibEdit: (z) => { const c = z.slice(); c[2] |= 6; return c; } }) }],
    'd.png', /corrupt IDAT data \(zlib: invalid block type\) after 0 of 61 rows/), 0);
  assert.equal(await rejects([{ name: 'f.png', bytes: makePng({ width, height, bitDepth: 16, colourType: 0, rows, level: 0, zlibEdit: (z) => {
    const c = z.slice(); c[7 + (1 + 2 * width) * 5] = 9; return c; // stored block: 2 zlib + 5 block header bytes, then row 5's filter byte
  } }) }], 'f.png', /corrupt IDAT data \(bad filter type 9 on row 5\) after 5 of 61 rows/), 0);
});

test('a forged IHDR is refused before anything is allocated: the IDAT data must hold every row', async () => {
  // The IHDR of a valid file with a larger size: once far beyond the data (filter bytes fall
  // on image data), once with rows of exactly three original rows (every filter byte is
  // valid, only the length of the data shows the forgery), at 16 and 8 bits and at 1 bit.
  const forged = (png, width, height, bitDepth = 16) =>
    concat([SIGNATURE, ihdr(width, height, bitDepth, 0), png.subarray(chunksOf(png)[0].end)]);
  const grey8 = fastPngEncode({ width: 87, height: 61, data: Uint8Array.from({ length: 87 * 61 }, (_, i) => Math.imul(i, 2654435761) >>> 24), depth: 8, channels: 1 });
  const cases = [
    [forged(volcanoPng, 1000, 2000), /corrupt IDAT data \(bad filter type \d+ on row \d+\) after \d+ of 2000 rows/],
    [forged(volcanoPng, 262, 1000), /truncated: IDAT data ends after 20 of 1000 rows$/], // 2 x 262 + 1 = 3 x 175 bytes a row
    [forged(grey8, 263, 1000, 8), /truncated: IDAT data ends after 20 of 1000 rows$/], // 263 + 1 = 3 x 88
    [forged(grey8, 8 * 263, 5000, 1), /truncated: IDAT data ends after 20 of 5000 rows$/], // 1 bit: 263 + 1 = 3 x 88
  ];
  for (const [bytes, problem] of cases) assert.equal(await rejects([{ name: 'f.png', bytes }], 'f.png', problem), 0);
});

test('the native inflater and fflate decode the same; fflate goes on where the native stream fails', async () => {
  const globe = read(`${GLOBE}.png`);
  const native = await decodePng(globe, 'g.png', (t, w, h) => new Uint16Array(w * h));
  // A stream cut in half: the native stream fails part-way, fflate goes on from there.
  const { width, height, data } = fastPngDecode(volcanoPng);
  const cut = makePng({ width, height, bitDepth: 16, colourType: 0, rows: rows16(data, width, height),
    zlibEdit: (z) => z.subarray(0, z.length >> 1) });
  const problem = async () => (await decodePng(cut, 'z.png', () => assert.fail('allocated')).catch((e) => e)).message;
  const nativeProblem = await problem();
  assert.match(nativeProblem, /^z\.png: truncated: IDAT data ends after [1-9]\d* of 61 rows$/);
  const { DecompressionStream } = globalThis;
  globalThis.DecompressionStream = undefined; // as in a browser without it: fflate alone
  try {
    const fflate = await decodePng(globe, 'g.png', (t, w, h) => new Uint16Array(w * h));
    assert.equal(firstMismatch(native.samples, fflate.samples), null);
    assert.equal(await problem(), nativeProblem);
  } finally {
    globalThis.DecompressionStream = DecompressionStream;
  }
});

test('bad input: bad CRC, broken chunk layout', async () => {
  const idat = chunksOf(volcanoPng).find((c) => c.type === 'IDAT');
  const flipped = volcanoPng.slice();
  flipped[idat.start + 100] ^= 1;
  await rejects([{ name: 'c.png', bytes: flipped }], 'c.png', /bad CRC in IDAT chunk at byte \d+/);
  const noIhdr = concat([SIGNATURE, chunk('tEXt', asciiBytes('a\0b')), chunk('IEND')]);
  await rejects([{ name: 'n.png', bytes: noIhdr }], 'n.png', /IHDR chunk missing \(first chunk is tEXt\)/);
  const noIdat = concat([SIGNATURE, ihdr(4, 4, 8, 0), chunk('IEND')]);
  await rejects([{ name: 'n.png', bytes: noIdat }], 'n.png', /no IDAT chunk/);
  const junkType = volcanoPng.slice();
  junkType[idat.start + 5] = 0x31;
  await rejects([{ name: 'j.png', bytes: junkType }], 'j.png', /corrupt chunk structure at byte \d+ \(invalid chunk type\)/);
  const critical = concat([SIGNATURE, ihdr(4, 4, 8, 0), chunk('ABCD'), chunk('IEND')]);
  await rejects([{ name: 'k.png', bytes: critical }], 'k.png', /unknown critical chunk ABCD/);
});

test('bad input: absurd, zero and unsupported IHDRs (never allocate)', async () => {
  const withHeader = (header) => concat([SIGNATURE, header, chunk('IDAT', zlibSync(new Uint8Array(100))), chunk('IEND')]);
  const cases = [
    [ihdr(100000, 100000, 16, 0), /declared size 100000x100000 is absurd/],
    [ihdr(0, 61, 16, 0), /zero width/],
    [ihdr(87, 0, 16, 0), /zero height/],
    [ihdr(0x80000000, 1, 8, 0), /exceeds the PNG limit/],
    [ihdr(87, 61, 16, 2), /unsupported PNG: 16-bit RGB; heights are grayscale, or 8-bit RGB/],
    [ihdr(87, 61, 8, 3), /unsupported PNG: colour type 3 \(palette\)/],
    [ihdr(87, 61, 16, 6), /unsupported PNG: 16-bit RGBA/],
    [ihdr(87, 61, 8, 5), /colour type 5 does not exist/],
    [ihdr(87, 61, 12, 0), /bit depth 12 is not allowed/],
    [ihdr(87, 61, 16, 0, 1), /interlaced \(Adam7\)/],
    [ihdr(30000, 30000, 16, 0), /IDAT holds only \d+ bytes, too few for 30000x30000 samples/],
  ];
  for (const [header, problem] of cases) {
    const calls = await rejects([{ name: 'i.png', bytes: withHeader(header) }], 'i.png', problem);
    assert.equal(calls, 0, `${problem} allocated`);
  }
  // The limit is configurable.
  await rejects([fixtureFile('volcano_maungawhau', 'png')], 'volcano_maungawhau.png', /declared size 87x61 is absurd \(5307 samples; limit 5000\)/, { maxSamples: 5000 });
  // A real RGB file from fast-png.
  // A real RGB file from fast-png that holds no heights (R = 50: neither encoding fits).
  const rgb = fastPngEncode({ width: 4, height: 3, data: new Uint8Array(36).fill(50), depth: 8, channels: 3 });
  await rejects([{ name: 'rgb.png', bytes: rgb }], 'rgb.png', /colour PNG whose first row is neither Terrain-RGB nor Terrarium/);
});

test('bad input: tEXt height range', async () => {
  const { width, height, data } = fastPngDecode(volcanoPng);
  const rows = rows16(data, width, height);
  const withText = (...before) => [{ name: 't.png', bytes: makePng({ width, height, bitDepth: 16, colourType: 0, rows, before }) }];
  await rejects(withText(textChunk('min_m', 'low'), textChunk('max_m', '3')), 't.png', /tEXt min_m is not a number \("low"\)/);
  await rejects(withText(textChunk('max_m', '3')), 't.png', /tEXt max_m given without min_m/);
  await rejects(withText(textChunk('min_m', '5'), textChunk('max_m', '3')), 't.png', /max_m \(3\) is below min_m \(5\)/);
});

test('bad input: f32 and sidecar problems', async () => {
  const json = { name: 'volcano_maungawhau.json', bytes: volcanoJson };
  await rejects([{ name: 'volcano_maungawhau.f32', bytes: volcanoF32.subarray(4) }, json], 'volcano_maungawhau.f32',
    /^volcano_maungawhau\.f32: size 21224 bytes does not match 87x61 float32 samples \(21228 bytes\) from volcano_maungawhau\.json$/);
  await rejects([{ name: 'v.f32', bytes: volcanoF32 }], 'v.f32', /missing sidecar v\.json/);
  await rejects([{ name: 'v.f32', bytes: volcanoF32 }, { name: 'v.json', bytes: asciiBytes('{"width": 87, "height": 61,') }], 'v.json', /not valid JSON/);
  await rejects([{ name: 'v.f32', bytes: volcanoF32 }, { name: 'v.json', bytes: asciiBytes('[87, 61]') }], 'v.json', /expected a JSON object/);
  await rejects([{ name: 'v.f32', bytes: volcanoF32 }, { name: 'v.json', bytes: asciiBytes('{"width": -87, "height": 61}') }], 'v.json', /width must be a positive integer \(got -87\)/);
  await rejects([{ name: 'v.f32', bytes: volcanoF32 }, { name: 'v.json', bytes: asciiBytes('{"width": 87.5, "height": 61}') }], 'v.json', /width must be a positive integer/);
  await rejects([{ name: 'v.f32', bytes: volcanoF32 }, { name: 'v.json', bytes: asciiBytes('{"height": 61}') }], 'v.json', /width missing \(needed to read v\.f32\)/);
  await rejects([{ name: 'v.f32', bytes: volcanoF32 }, { name: 'v.json', bytes: asciiBytes('{"width": 100000, "height": 100000}') }], 'v.json', /declared size 100000x100000 is absurd/);
  await rejects([{ name: 'v.f32', bytes: volcanoF32 }, { name: 'v.json', bytes: asciiBytes('{"width": 87, "height": 61, "cell_size_m": -10}') }], 'v.json', /cell_size_m must be a positive number/);
  await rejects([{ name: 'v.f32', bytes: volcanoF32 }, { name: 'v.json', bytes: asciiBytes('{"width": 87, "height": 61, "cell_size_x_m": 10}') }], 'v.json', /cell_size_x_m given without cell_size_y_m or cell_size_m/);
  const inf = new Float32Array([1, 2, Infinity, 4]);
  await rejects([{ name: 'i.f32', bytes: new Uint8Array(inf.buffer) }, { name: 'i.json', bytes: asciiBytes('{"width": 2, "height": 2}') }], 'i.f32', /sample at row 1, column 0 is Infinity/);
  await rejects([json], 'volcano_maungawhau.json', /sidecar alone is not a height field/);
  await rejects([fixtureFile('volcano_maungawhau', 'png'), { name: 'other.json', bytes: volcanoJson }], 'other.json', /does not belong to volcano_maungawhau\.png/);
  await rejects([fixtureFile('volcano_maungawhau', 'png'), fixtureFile('volcano_maungawhau', 'f32')], 'volcano_maungawhau.png',
    /several height fields make a mosaic only of \.hgt \(SRTM\) and GeoTIFF tiles; open volcano_maungawhau\.png on its own/);
  await rejects([fixtureFile('jacksboro_fault', 'png'), { name: 'jacksboro_fault.json', bytes: volcanoJson }], 'jacksboro_fault.png',
    /size 403x344 does not match 87x61 from jacksboro_fault\.json/);
});
