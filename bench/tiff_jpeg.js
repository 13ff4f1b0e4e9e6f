#!/usr/bin/env node
// Benchmark of JPEG-compressed GeoTIFF images read for draping in the page (headless Chromium):
// the geotiff library's JavaScript decoder against the browser's own (web/imagery/
// browser_jpeg.js), in the same run, on a SIZE x SIZE image in 256 x 256 JPEG tiles made by
// repeating the tiles of the real satellite fixture (RGB, or YCbCr with --ycbcr). Prints
// milliseconds per megapixel of each and their ratio. With --against COMMIT, the page's modules
// of that commit (git archive into tests/out/) are timed on the same file too.
// Usage: node bench/tiff_jpeg.js [--size 4096] [--ycbcr] [--against COMMIT]
import { mkdirSync, readFileSync, writeFileSync, rmSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { fromArrayBuffer } from 'geotiff';
import { startViewer, openPage, projectDir, outDir } from '../lib/page_harness.js';

const args = process.argv.slice(2);
const option = (name) => (args.includes(name) ? args[args.indexOf(name) + 1] : undefined);
const SIZE = Number(option('--size')) || 4096;
const TILE = 256;
const SOURCE = `${projectDir}tests/fixtures/imagery/haiti_rgb_5m_tiled_jpeg${args.includes('--ycbcr') ? '_ycbcr' : ''}.tif`;

/** A little-endian tiled TIFF of SIZE x SIZE pixels whose JPEG tiles repeat the source's. */
async function repeatedTiff() {
  const source = readFileSync(SOURCE);
  const image = await (await fromArrayBuffer(source.buffer.slice(source.byteOffset, source.byteOffset + source.length))).getImage(0);
  const dir = image.fileDirectory;
  const [offsets, counts, tables] = await Promise.all(['TileOffsets', 'TileByteCounts', 'JPEGTables'].map((k) => dir.loadValue(k)));
  const photometric = await dir.loadValue('PhotometricInterpretation');
  const tiles = Array.from(offsets, (o, i) => source.subarray(o, o + counts[i]));
  const n = (SIZE / TILE) ** 2;
  // tag, type (3 SHORT, 4 LONG, 7 UNDEFINED), values
  const entries = [[256, 4, [SIZE]], [257, 4, [SIZE]], [258, 3, [8, 8, 8]], [259, 3, [7]], [262, 3, [photometric]],
    [277, 3, [3]], [284, 3, [1]], [322, 3, [TILE]], [323, 3, [TILE]], [324, 4, new Array(n).fill(0)],
    [325, 4, Array.from({ length: n }, (_, i) => tiles[i % tiles.length].length)], [347, 7, Array.from(tables)]];
  const size = { 3: 2, 4: 4, 7: 1 };
  const ifdBytes = 2 + entries.length * 12 + 4;
  let extra = 8 + ifdBytes;
  const placed = entries.map(([tag, type, values]) => {
    const bytes = values.length * size[type];
    const at = bytes > 4 ? extra : null;
    if (at !== null) extra += bytes + (bytes & 1);
    return { tag, type, values, at };
  });
  let next = extra;
  const tileOffsets = placed.find((e) => e.tag === 324).values;
  for (let i = 0; i < n; i++) { tileOffsets[i] = next; next += tiles[i % tiles.length].length; }
  const out = Buffer.alloc(next);
  out.write('II', 0, 'latin1'); out.writeUInt16LE(42, 2); out.writeUInt32LE(8, 4); out.writeUInt16LE(entries.length, 8);
  const put = (type, value, at) => (type === 3 ? out.writeUInt16LE(value, at) : type === 4 ? out.writeUInt32LE(value, at) : out.writeUInt8(value, at));
  placed.forEach(({ tag, type, values, at }, k) => {
    const e = 10 + k * 12;
    out.writeUInt16LE(tag, e); out.writeUInt16LE(type, e + 2); out.writeUInt32LE(values.length, e + 4);
    if (at === null) values.forEach((v, j) => put(type, v, e + 8 + j * size[type]));
    else { out.writeUInt32LE(at, e + 8); values.forEach((v, j) => put(type, v, at + j * size[type])); }
  });
  for (let i = 0; i < n; i++) tiles[i % tiles.length].copy(out, tileOffsets[i]);
  return out;
}

mkdirSync(outDir, { recursive: true });
const file = `${outDir}/bench_tiff_jpeg_${SIZE}.tif`;
writeFileSync(file, await repeatedTiff());
const against = option('--against');
const beforeDir = `${outDir}/bench-tiff-jpeg-${against}`;
if (against) {
  rmSync(beforeDir, { recursive: true, force: true });
  mkdirSync(beforeDir, { recursive: true });
  execFileSync('sh', ['-c', `git -C "${projectDir}" archive ${against} web | tar -x -C "${beforeDir}"`]);
}

const viewer = await startViewer();
try {
  // A page of the dev server (a fixture's text) to import the modules into, without the viewer.
  const { page } = await openPage(viewer.browser, `${viewer.url}${viewer.fixturesUrl.slice(1)}imagery/README.md`);
  const time = (web, browserDecoder) => page.evaluate(async ({ web, url, browserDecoder }) => {
    const { readTiffImage } = await import(`${web}imagery/image_tiff.js`);
    const decodeJpeg = browserDecoder ? (await import(`${web}imagery/browser_jpeg.js`)).browserJpegDecoder() : null;
    const bytes = new Uint8Array(await (await fetch(url)).arrayBuffer());
    let checksum = 0;
    const start = performance.now();
    await readTiffImage(bytes, 'bench.tif', { decodeJpeg, begin: () => {}, onBand: (y, rows, rgba) => { checksum += rgba[rgba.length >> 1]; } });
    return { ms: performance.now() - start, checksum };
  }, { web, url: `/@fs${file}`, browserDecoder });
  const megapixels = (SIZE * SIZE) / 1e6;
  const runs = [['browser decoder', `/@fs${projectDir}web/`, true], ['geotiff library', `/@fs${projectDir}web/`, false]];
  if (against) runs.push([`library at ${against}`, `/@fs${beforeDir}/web/`, false]);
  const results = {};
  for (const [name, web, browserDecoder] of runs) {
    results[name] = await time(web, browserDecoder);
    console.log(`${name.padEnd(24)} ${(results[name].ms / megapixels).toFixed(0).padStart(7)} ms/Mpx  (${(results[name].ms / 1000).toFixed(2)} s for ${SIZE}² = ${megapixels.toFixed(1)} Mpx)`);
  }
  for (const [name] of runs.slice(1)) {
    console.log(`${name} / browser decoder: ${(results[name].ms / results['browser decoder'].ms).toFixed(1)}x`);
  }
} finally {
  await viewer.close();
  rmSync(file, { force: true });
  if (against) rmSync(beforeDir, { recursive: true, force: true });
}
