// PNG, structure-aware: IHDR fields (size, bit depth, colour type, methods), chunk lengths,
// order, duplicates and strangers, tEXt height ranges, tRNS, the IDAT stream split, cut or
// corrupted at the zlib level or below it (filter bytes, rows), with every CRC recomputed so
// that the mutation reaches the decoder. Seeds: the fixtures (16/8-bit grey, Terrain-RGB,
// Terrarium) and small ones written here (1/2/4-bit, grey+alpha, tRNS, RGBA, split IDAT).
import { zlibSync, unzlibSync } from 'fflate';
import { fixtureFile, demFile, grid, quantise } from '../fixtures.js';
import {
  readChunks, writeChunks, encodePng, parseIhdr, ihdrData, rowBytes, textChunk, fixCrcs, CHANNELS,
} from '../formats/png_chunks.js';
import { nearSize, NUMBER_TEXTS } from '../values.js';
import { mutateSidecar } from './sidecar.js';
import { applySteps } from './steps.js';

export const extension = 'png';

/** Packs whole-number samples (with `alpha` appended per pixel for grey+alpha/RGBA) into rows. */
function pack(samples, width, height, bitDepth, channels) {
  const stride = Math.ceil((width * bitDepth * channels) / 8);
  const rows = new Uint8Array(stride * height);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      for (let c = 0; c < channels; c++) {
        const v = samples[(y * width + x) * channels + c];
        const bit = (x * channels + c) * bitDepth;
        if (bitDepth === 16) { rows[y * stride + bit / 8] = v >> 8; rows[y * stride + bit / 8 + 1] = v & 255; }
        else if (bitDepth === 8) rows[y * stride + bit / 8] = v;
        else rows[y * stride + (bit >> 3)] |= v << (8 - bitDepth - (bit & 7));
      }
    }
  }
  return rows;
}

const terrainRgb = (h) => { const v = Math.round((h + 10000) * 10); return [(v >> 16) & 255, (v >> 8) & 255, v & 255]; };
const terrarium = (h) => { const v = Math.round((h + 32768) * 256); return [(v >> 16) & 255, (v >> 8) & 255, v & 255]; };

export function seeds() {
  const out = ['everest_16bit.png', 'jacksboro_8bit.png', 'canyon_terrain-rgb.png', 'etopo_terrarium.png']
    .map((name) => ({ files: [fixtureFile(name)] }));
  // The real DEMs with their sidecars (height range, spacing); the larger ones less often.
  for (const [name, weight] of [['volcano_maungawhau', 1], ['jacksboro_fault', 0.5], ['grandcanyon_512', 0.25]]) {
    out.push({ files: [demFile(`${name}.png`), demFile(`${name}.json`)], weight });
  }
  const g = grid('everest', 24, 16, 90, 90);
  const [w, h] = [g.width, g.height];
  const png = (name, o) => out.push({ files: [{ name, bytes: encodePng({ width: w, height: h, ...o }) }] });
  for (const bitDepth of [16, 8, 4, 2, 1]) {
    const { q, min, max } = quantise(g.values, 2 ** bitDepth - 1);
    png(`grey${bitDepth}.png`, { bitDepth, colourType: 0, rows: pack(q, w, h, bitDepth, 1),
      text: bitDepth >= 8 ? { min_m: min, max_m: max } : undefined, trns: bitDepth === 16 ? 0 : undefined });
  }
  for (const bitDepth of [8, 16]) {
    const { q } = quantise(g.values, 2 ** bitDepth - 1);
    png(`grey_alpha${bitDepth}.png`, { bitDepth, colourType: 4, rows: pack(q.flatMap((v) => [v, 2 ** bitDepth - 1]), w, h, bitDepth, 2) });
  }
  png('small_terrain-rgb.png', { bitDepth: 8, colourType: 6, rows: pack(Array.from(g.values).flatMap((v) => [...terrainRgb(v), 255]), w, h, 8, 4) });
  // No encoding in the name: the loader must tell Terrarium from the first row's colours.
  png('small.png', { bitDepth: 8, colourType: 2, rows: pack(Array.from(g.values).flatMap(terrarium), w, h, 8, 3), idatSize: 7 });
  return out;
}

/** The concatenated zlib stream of the IDAT chunks. */
function idatStream(chunks) {
  const parts = chunks.filter((c) => c.type === 'IDAT').map((c) => c.data);
  const out = new Uint8Array(parts.reduce((s, p) => s + p.length, 0));
  let p = 0;
  for (const part of parts) { out.set(part, p); p += part.length; }
  return out;
}

/** Replaces the IDAT chunks by `stream` cut into pieces of the given sizes (the rest in one). */
function setIdat(chunks, stream, sizes = []) {
  let at = chunks.findIndex((c) => c.type === 'IDAT');
  if (at < 0) at = Math.max(0, chunks.findIndex((c) => c.type === 'IEND'));
  const pieces = [];
  let p = 0;
  for (const size of sizes) { pieces.push({ type: 'IDAT', data: stream.slice(p, p + size) }); p += size; }
  if (p < stream.length || !pieces.length) pieces.push({ type: 'IDAT', data: stream.slice(p) });
  const kept = chunks.filter((c, i) => c.type !== 'IDAT' || i < at);
  kept.splice(Math.min(at, kept.length), 0, ...pieces);
  chunks.splice(0, chunks.length, ...kept);
}

function inflate(stream) {
  try { return unzlibSync(stream); } catch { return null; }
}

/** Each step changes the state { chunks, name, sidecar, options } and says what it did. */
const STEPS = [
  [5, function ihdrField(s, r) {
    const ihdr = s.chunks.find((c) => c.type === 'IHDR');
    const f = ihdr && parseIhdr(ihdr.data);
    if (!f) return null;
    const key = r.pick(['width', 'height', 'width', 'height', 'bitDepth', 'colourType', 'compression', 'filter', 'interlace']);
    f[key] = key === 'width' || key === 'height' ? nearSize(r, f[key])
      : key === 'bitDepth' ? r.pick([0, 1, 2, 3, 4, 8, 16, 32, 255])
        : key === 'colourType' ? r.pick([0, 1, 2, 3, 4, 5, 6, 7, 255]) : r.pick([0, 1, 2, 255]);
    ihdr.data = ihdrData(f);
    return `IHDR ${key} ${f[key]}`;
  }],
  [2, function forgedSize(s, r) {
    // Sizes the checks before allocating must refuse for a small IDAT stream.
    const ihdr = s.chunks.find((c) => c.type === 'IHDR');
    const f = ihdr && parseIhdr(ihdr.data);
    if (!f) return null;
    [f.width, f.height] = r.pick([[20000, 20000], [32769, 32769], [16385, 16385], [4096, 4096], [1 << 20, 1024], [8192, 2048],
      [46341, 46341], [100000, 10], [2000, 2000], [1000, 1000]]);
    ihdr.data = ihdrData(f);
    return `IHDR size forged to ${f.width}x${f.height}`;
  }],
  [3, function resize(s, r) {
    // A new size with image data that matches it: odd shapes the decoder must accept.
    const ihdr = s.chunks.find((c) => c.type === 'IHDR');
    const f = ihdr && parseIhdr(ihdr.data);
    if (!f || !(f.colourType in CHANNELS) || ![1, 2, 4, 8, 16].includes(f.bitDepth)) return null;
    [f.width, f.height] = r.chance(0.1) ? r.pick([[1, 65536], [65536, 1], [2, 40000], [1, 65537]])
      : [r.pick([1, 2, 3, r.range(1, 64), r.range(1, 600)]), r.pick([1, 2, 3, r.range(1, 64), r.range(1, 400)])];
    const stride = rowBytes(f.width, f.bitDepth, f.colourType);
    const raw = new Uint8Array((stride + 1) * f.height);
    // Flat data is all zero but its first byte: with a tRNS of 0, a field of no-data.
    const flat = r.chance(0.3);
    for (let y = 0; y < f.height; y++) {
      raw[y * (stride + 1)] = flat ? 0 : r.int(5);
      for (let i = 1; i <= stride; i++) raw[y * (stride + 1) + i] = flat ? 0 : r.int(256);
    }
    if (flat) raw[1] = 7;
    ihdr.data = ihdrData(f);
    setIdat(s.chunks, zlibSync(raw, { level: r.pick([0, 1, 6, 9]) }));
    return `resized to ${f.width}x${f.height} with matching data`;
  }],
  [2, function chunkLength(s, r) {
    const c = r.pick(s.chunks);
    if (!c) return null;
    c.length = r.pick([c.data.length + 1, c.data.length - 1, 0, 13, 0x7fffffff, 0x80000000, 0xffffffff, r.int(0x100000000)]) >>> 0;
    return `${c.type} length field ${c.length} (data ${c.data.length})`;
  }],
  [3, function order(s, r) {
    const n = s.chunks.length;
    if (n < 2) return null;
    const i = r.int(n), j = r.int(n);
    const op = r.pick(['swap', 'duplicate', 'delete', 'move']);
    if (op === 'swap') [s.chunks[i], s.chunks[j]] = [s.chunks[j], s.chunks[i]];
    else if (op === 'duplicate') s.chunks.splice(j, 0, { ...s.chunks[i] });
    else if (op === 'delete') s.chunks.splice(i, 1);
    else s.chunks.splice(j, 0, s.chunks.splice(i, 1)[0]);
    return `${op} chunks ${i} ${j}`;
  }],
  [3, function insert(s, r) {
    const bytes = (n) => Uint8Array.from({ length: n }, () => r.int(256));
    const [type, data] = r.pick([
      ['ABCD', bytes(4)], ['abcD', bytes(4)], ['IEND', bytes(0)], ['IDAT', bytes(0)], ['IDAT', bytes(r.smallLength())],
      ['PLTE', bytes(3 * r.range(0, 256))], ['tRNS', bytes(r.pick([0, 1, 2, 6, 256]))], ['gAMA', bytes(4)],
      ['sBIT', bytes(r.range(1, 4))], ['acTL', bytes(8)], ['fdAT', bytes(16)], ['zTXt', bytes(12)],
      ['IHDR', s.chunks.find((c) => c.type === 'IHDR')?.data ?? bytes(13)], ['iCCP', bytes(20)],
      ['tEXt', textChunk(r.pick(['min_m', 'max_m', 'Comment']), r.pick(NUMBER_TEXTS)).data],
    ]);
    const at = r.int(s.chunks.length + 1);
    s.chunks.splice(at, 0, { type, data });
    return `insert ${type} (${data.length} bytes) at ${at}`;
  }],
  [2, function textRange(s, r) {
    const keep = s.chunks.filter((c) => c.type !== 'tEXt');
    const text = [];
    if (r.chance(0.9)) text.push(textChunk('min_m', r.pick([...NUMBER_TEXTS, '100', '-500'])));
    if (r.chance(0.9)) text.push(textChunk('max_m', r.pick([...NUMBER_TEXTS, '100', '9000'])));
    keep.splice(Math.min(1, keep.length), 0, ...text);
    s.chunks.splice(0, s.chunks.length, ...keep);
    return `tEXt ${text.map((c) => new TextDecoder('latin1').decode(c.data).replace('\0', '=')).join(' ')}`;
  }],
  [2, function split(s, r) {
    const stream = idatStream(s.chunks);
    const sizes = Array.from({ length: r.range(1, 12) }, () => (r.chance(0.2) ? 0 : r.range(1, Math.max(1, stream.length >> 2))));
    setIdat(s.chunks, stream, sizes);
    return `IDAT split into ${sizes.length + 1}`;
  }],
  [2, function cut(s, r) {
    const stream = idatStream(s.chunks);
    const p = r.int(stream.length + 1);
    setIdat(s.chunks, stream.slice(0, p));
    return `zlib stream cut at ${p} of ${stream.length}`;
  }],
  [3, function zlib(s, r) {
    const stream = idatStream(s.chunks);
    if (stream.length < 6) return null;
    const op = r.pick(['body', 'body', 'header', 'dictionary', 'adler']);
    if (op === 'body') {
      const k = r.range(1, 4);
      for (let i = 0; i < k; i++) stream[r.range(2, stream.length - 5)] ^= 1 << r.int(8);
    } else if (op === 'header') {
      stream[r.int(2)] = r.int(256);
    } else if (op === 'dictionary') {
      stream[1] |= 32; stream[1] += 31 - (((stream[0] << 8) | stream[1]) % 31); // FDICT with a valid check
    } else {
      stream[stream.length - 1 - r.int(4)] ^= 0xff;
    }
    setIdat(s.chunks, stream);
    return `zlib ${op} corrupted`;
  }],
  [4, function rows(s, r) {
    // Below the zlib layer: the filtered rows themselves, recompressed.
    const ihdr = parseIhdr(s.chunks.find((c) => c.type === 'IHDR')?.data ?? new Uint8Array(0));
    const raw = inflate(idatStream(s.chunks));
    if (!ihdr || !raw) return null;
    const stride = rowBytes(ihdr.width, ihdr.bitDepth, ihdr.colourType) + 1;
    const rowsIn = Math.floor(raw.length / stride);
    let out = raw;
    const op = r.pick(['filter', 'filter', 'fewer rows', 'more data', 'pixels', 'extreme pixels']);
    if (op === 'filter' && rowsIn) out[r.int(rowsIn) * stride] = r.pick([5, 6, 127, 255, r.int(5)]);
    else if (op === 'fewer rows') {
      out = raw.slice(0, r.int(raw.length));
      // The IHDR may declare fewer rows than the stream had: only a cut into them is a claim.
      if (out.length < ihdr.height * stride) s.invalid = `its image data ends after ${Math.floor(out.length / stride)} of ${ihdr.height} rows`;
    }
    else if (op === 'more data') { out = new Uint8Array(raw.length + r.smallLength()); out.set(raw); }
    else if (op === 'pixels') for (let k = r.range(1, 16); k > 0; k--) out[r.int(out.length)] = r.int(256);
    else out.fill(r.pick([0, 255]), r.int(out.length));
    setIdat(s.chunks, zlibSync(out, { level: r.pick([0, 6]) }));
    return `rows: ${op}`;
  }],
  [1, function badCrc(s, r) {
    const c = r.pick(s.chunks);
    if (!c) return null;
    c.badCrc = true;
    return `bad CRC on ${c.type}`;
  }],
  [1, function foreignStream(s, r) {
    const other = r.pick(s.seeds).files[0].bytes;
    setIdat(s.chunks, idatStream(readChunks(other).chunks));
    return 'IDAT from another seed';
  }],
  [1, function rename(s, r) {
    s.name = r.pick(['x.png', 'x_terrain-rgb.png', 'x_terrarium.png', 'X.PNG', 'terrarium.png', 'dir/a.b.png', 'x.terrain-rgb.png']);
    return `named ${s.name}`;
  }],
  [1, function encodingOption(s, r) {
    s.options.encoding = r.pick(['terrain-rgb', 'terrarium', 'auto']);
    return `encoding ${s.options.encoding}`;
  }],
  [1, function sidecar(s, r) {
    const base = s.sidecar ?? new TextEncoder().encode('{"min": -10, "max": 8000, "cell_size_m": 30}');
    const [bytes, how] = mutateSidecar(base, r);
    s.sidecar = bytes;
    return how;
  }],
];

/**
 * @param {{ files: Array<{name, bytes}>, options?: object }} seed
 * @param {import('../random.js').Random} random
 * @param {Array} seedList all seeds of the format
 * @returns {{ files, options, how: string[] }}
 */
export function mutate(seed, random, seedList) {
  const main = seed.files[0];
  const { chunks, rest } = readChunks(main.bytes);
  const s = { chunks, name: main.name, sidecar: seed.files[1]?.bytes ?? null, options: { ...seed.options }, seeds: seedList };
  const how = applySteps(s, random, STEPS, { lastVerdict: true });
  const files = [{ name: s.name, bytes: writeChunks(s.chunks, { rest }) }];
  if (s.sidecar) files.push({ name: s.name.replace(/\.[^.]*$/, '.json'), bytes: s.sidecar });
  return { files, options: s.options, how, invalid: s.invalid };
}

/** The size the file declares (its IHDR), or null when it has none. */
export function declaredSize(files) {
  const { chunks } = readChunks(files[0].bytes);
  const f = chunks[0]?.type === 'IHDR' ? parseIhdr(chunks[0].data) : null;
  return f && { width: f.width, height: f.height };
}

/** The minimiser's candidates get their CRCs rewritten, or every cut would fail the CRC check. */
export const repair = fixCrcs;

/** The chunks' data as the minimiser's parts; written back with lengths and CRCs made right. */
export function split(bytes) {
  if (bytes.length < 8) return null;
  const { chunks, rest } = readChunks(bytes);
  return {
    parts: chunks.map((c) => c.data),
    join: (parts) => writeChunks(chunks.flatMap((c, i) => (parts[i] ? [{ type: c.type, data: parts[i] }] : [])), { signature: bytes.subarray(0, 8), rest }),
    shrinkInside: true,
  };
}

