// The GPU layout of a draped image (web/imagery/image_tiling.js) and its size checks, decided
// before anything is decoded; and the header reader that gives the size.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { planImageTiling, tileSource, APRON } from '../../web/imagery/image_tiling.js';
import { readImageHeader } from '../../web/imagery/image_header.js';
import { ImageError } from '../../web/imagery/image_error.js';

const GPU = { maxTextureSize: 8192, maxLayers: 256, name: 'i.jpg', wholeDecode: true };

test('an image within the texture limit is one layer of its own size', () => {
  const t = planImageTiling(1000, 500, GPU);
  assert.deepEqual([t.tileWidth, t.tileHeight, t.tilesX, t.tilesY, t.apron, t.overview], [1000, 500, 1, 1, 0, null]);
  assert.equal(t.gpuBytes, Math.round(1000 * 500 * 4 * 4 / 3));
});

test('a larger image is cut into tiles whose aprons overlap, covering every pixel once at the core', () => {
  const t = planImageTiling(20000, 9000, { ...GPU, maxTextureSize: 4096 });
  assert.deepEqual([t.tilesX, t.tilesY], [5, 3], 'as few tiles as 4096² allows');
  assert.deepEqual([t.strideX, t.strideY, t.tileWidth, t.tileHeight], [4000, 3000, 4000 + 2 * APRON, 3000 + 2 * APRON], 'and no larger than they need be');
  assert.deepEqual(t.overview, { width: 4016, height: 3016 }, 'the overview: one more layer of the tiles\' size');
  assert.equal(t.gpuBytes, Math.round(16 * 4016 * 3016 * 4 * 4 / 3), 'fifteen tiles and the overview');
  const covered = new Uint8Array(20000);
  for (let tx = 0; tx < t.tilesX; tx++) {
    const [x0, , x1] = tileSource(t, tx, 0);
    assert.ok(x1 - x0 <= 4096);
    for (let x = Math.max(x0, tx * t.strideX); x < Math.min(x1, (tx + 1) * t.strideX); x++) covered[x]++;
    if (tx > 0) assert.equal(x0, tx * t.strideX - APRON, 'the apron repeats the neighbour\'s last pixels');
  }
  assert.ok(covered.every((c) => c === 1), 'every column belongs to exactly one tile core');
});

test('too big is said before decoding: the browser\'s decode cap, the GPU\'s layers and the memory budget', () => {
  const refused = (w, h, limits, problem) => assert.throws(() => planImageTiling(w, h, { ...GPU, ...limits }),
    (e) => e instanceof ImageError && e.message.startsWith('i.jpg: ') && problem.test(e.message));
  refused(60000, 60000, {}, /^i\.jpg: 60000 × 60000 pixels \(3600 Mpx\) is more than the browser can decode at once \(268 Mpx\); save it as a tiled GeoTIFF, read in bands, or at 15000 × 15000 or less$/);
  refused(60000, 60000, { wholeDecode: false }, /need \d+\.\d GB of GPU memory with mipmaps, more than the 1\.5 GB an image may take; use one of at most \d+ × \d+ \(e\.g\. gdal_translate -outsize \d+% \d+%\)/);
  refused(30000, 30000, { wholeDecode: false, maxTextureSize: 1024, maxLayers: 256 }, /need 900 tiles \(at most 1024² each\), more than this GPU's 256/);
  // A 16384² image at the 8192 limit: 3 x 3 tiles within 1 % of the image's own memory, and its overview.
  const big = planImageTiling(16384, 16384, { ...GPU, wholeDecode: false });
  assert.ok(big.gpuBytes < (16384 * 16384 * 1.01 + 5478 * 5478) * 4 * 4 / 3, `${big.gpuBytes} bytes`);
});

test('image headers give the kind and size without decoding', () => {
  const png = new Uint8Array(readFileSync(new URL('../../public/terrain/globe_himalaya_2048.png', import.meta.url)));
  assert.deepEqual(readImageHeader(png.subarray(0, 64), 'h.png'), { format: 'png', width: 2048, height: 2048 });
  assert.deepEqual(readImageHeader(new Uint8Array([0x49, 0x49, 42, 0, 8, 0, 0, 0]), 't.tif'), { format: 'tiff' });
  assert.throws(() => readImageHeader(new TextEncoder().encode('hello, not an image'), 'x.png'),
    (e) => e instanceof ImageError && /^x\.png: not an image hexlod can drape/.test(e.message));
});
