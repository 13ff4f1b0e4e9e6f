// Streaming a Cloud-Optimized GeoTIFF by ranges (web/tiles/cog_source.js) against the range
// server of lib/range_server.js, with latency: opening reads only the header and directories,
// every tile equals the same window of the file decoded whole, and each fault reaches the
// caller as its kind with a message that says what to do.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, writeFileSync, copyFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { fromArrayBuffer } from 'geotiff';
import { openCog } from '../../web/tiles/cog_source.js';
import { decodeGeoTiff } from '../../web/loaders/geotiff.js';
import { defaultAllocate } from '../../web/loaders/common.js';
import { startRangeServer } from '../../lib/range_server.js';

const fixtures = fileURLToPath(new URL('../fixtures/cog/', import.meta.url));
const HIMALAYA = 'himalaya_1024_i16.tif'; // 1024^2 int16, 256^2 tiles, overviews 512 and 256
const NO_OVERVIEWS = 'jacksboro_403x344_f32_no_overviews.tif'; // float32, 128^2 tiles, partial edge tiles
const STRIPS = 'jacksboro_403x344_f32_strips.tif';
const LATENCY_MS = 5;
const FAST_RETRIES = { retries: 2, backoffMs: 5 }; // three tries, a few milliseconds apart

const bytesOf = (name) => new Uint8Array(readFileSync(join(fixtures, name)));
let dir, server;

/** The tile offsets and byte counts of one image of a file, read whole by the geotiff library. */
async function tilesOf(bytes, image) {
  const dirOf = (await (await fromArrayBuffer(bytes.slice().buffer)).getImage(image)).fileDirectory;
  return { offsets: Array.from(await dirOf.loadValue('TileOffsets')), counts: Array.from(await dirOf.loadValue('TileByteCounts')) };
}

before(() => {
  dir = mkdtempSync(join(tmpdir(), 'hexlod-cog-'));
  for (const name of [HIMALAYA, NO_OVERVIEWS, STRIPS]) copyFileSync(join(fixtures, name), join(dir, name));
  writeFileSync(join(dir, 'not_a_tiff.tif'), '{"width": 2}');
});
after(() => rmSync(dir, { recursive: true, force: true }));

/** Runs body with a range server over the test folder, closed afterwards. */
async function withServer(options, body) {
  server = await startRangeServer(dir, { latencyMs: LATENCY_MS, ...options });
  try {
    return await body(server);
  } finally {
    await server.close();
  }
}

/** Tile (tx, ty) of a level against the same window of a whole image: every sample of the level's extent. */
function assertTileEquals(tile, whole, wholeWidth, wholeHeight, level, tx, ty) {
  const x0 = tx * level.tileWidth, y0 = ty * level.tileHeight;
  const cols = Math.min(level.tileWidth, wholeWidth - x0), rows = Math.min(level.tileHeight, wholeHeight - y0);
  assert.ok(cols > 0 && rows > 0);
  for (let y = 0; y < rows; y++) {
    for (let x = 0; x < cols; x++) {
      const got = tile[y * level.tileWidth + x], want = whole[(y0 + y) * wholeWidth + x0 + x];
      if (!Object.is(got, want)) assert.fail(`tile (${tx}, ${ty}) sample (${x}, ${y}): ${got}, the whole image has ${want}`);
    }
  }
}

test('opening a COG by URL reads only its header and directories (under 2 % of the file)', () => withServer({}, async () => {
  const size = bytesOf(HIMALAYA).length;
  const cog = await openCog(`${server.url}/${HIMALAYA}`);
  assert.equal(cog.width, 1024);
  assert.equal(cog.height, 1024);
  assert.equal(cog.sampleType, 'i16');
  assert.equal(cog.nodata, -32768);
  assert.equal(cog.tileWidth, 256);
  assert.equal(cog.tileHeight, 256);
  assert.deepEqual(cog.levels.map((l) => [l.width, l.height, l.scale, l.tilesAcross, l.tilesDown]),
    [[1024, 1024, 1, 4, 4], [512, 512, 2, 2, 2], [256, 256, 4, 1, 1]]);
  assert.equal(cog.hasOverviews, true);
  assert.equal(cog.georef.crs.epsg, 4326);
  assert.ok(Math.abs(cog.georef.dx - 1 / 120) < 1e-12 && Math.abs(cog.georef.dy + 1 / 120) < 1e-12);
  // Sample centres: the crop starts 512 cells east and south of the 2048 field's north-west corner.
  assert.ok(Math.abs(cog.georef.x0 - (72.93333333333334 + 512.5 / 120)) < 1e-9);
  assert.equal(cog.size, size);
  assert.ok(cog.stats.bytes < 0.02 * size, `${cog.stats.bytes} of ${size} bytes read to open`);
  assert.deepEqual(server.stats(`/${HIMALAYA}`), cog.stats, 'the server sent what the reader counted');
}));

test('a full-resolution tile read by range equals the file decoded whole by the loader, fetching only its bytes', () => withServer({}, async () => {
  const bytes = bytesOf(HIMALAYA);
  const whole = await decodeGeoTiff(bytes, HIMALAYA, defaultAllocate);
  const { counts } = await tilesOf(bytes, 0);
  const cog = await openCog(`${server.url}/${HIMALAYA}`);
  for (const [tx, ty] of [[0, 0], [1, 2], [3, 3]]) {
    const before = { ...cog.stats };
    const tile = await cog.readTile(0, tx, ty);
    assert.ok(tile instanceof Int16Array);
    assert.equal(cog.stats.requests - before.requests, 1);
    assert.equal(cog.stats.bytes - before.bytes, counts[ty * 4 + tx], 'exactly the tile\'s bytes');
    assertTileEquals(tile, whole.samples, 1024, 1024, cog.levels[0], tx, ty);
  }
}));

test('overview tiles equal their overview image decoded whole', () => withServer({}, async () => {
  const bytes = bytesOf(HIMALAYA);
  const tiff = await fromArrayBuffer(bytes.slice().buffer);
  const cog = await openCog(`${server.url}/${HIMALAYA}`);
  for (const [level, tx, ty] of [[1, 1, 0], [1, 0, 1], [2, 0, 0]]) {
    const image = await tiff.getImage(level);
    const [whole] = await image.readRasters();
    assert.equal(image.getWidth(), cog.levels[level].width);
    const tile = await cog.readTile(level, tx, ty);
    assertTileEquals(tile, whole, image.getWidth(), image.getHeight(), cog.levels[level], tx, ty);
  }
  // A coarser level is a different picture of the same ground, not a copy of the full resolution.
  const coarse = await cog.readTile(2, 0, 0), fine = await cog.readTile(0, 0, 0);
  assert.notDeepEqual(coarse.subarray(0, 256), fine.subarray(0, 256));
}));

test('from a Blob: the same samples, read by slice, one slice a request', async () => {
  const bytes = bytesOf(HIMALAYA);
  let slices = 0;
  class CountingBlob extends Blob {
    slice(...args) { slices++; return super.slice(...args); }
  }
  const cog = await openCog(new CountingBlob([bytes]), { name: HIMALAYA });
  assert.equal(cog.levels.length, 3);
  assert.equal(slices, cog.stats.requests);
  assert.ok(cog.stats.bytes < 0.02 * bytes.length);
  const whole = await decodeGeoTiff(bytes, HIMALAYA, defaultAllocate);
  assertTileEquals(await cog.readTile(0, 2, 1), whole.samples, 1024, 1024, cog.levels[0], 2, 1);
  const [overview] = await (await (await fromArrayBuffer(bytes.slice().buffer)).getImage(1)).readRasters();
  assertTileEquals(await cog.readTile(1, 1, 1), overview, 512, 512, cog.levels[1], 1, 1);
  assert.equal(slices, cog.stats.requests);
});

test('a COG without overviews opens with one level, flagged, and its partial edge tiles are right', () => withServer({}, async () => {
  const bytes = bytesOf(NO_OVERVIEWS);
  const cog = await openCog(`${server.url}/${NO_OVERVIEWS}`);
  assert.equal(cog.levels.length, 1);
  assert.equal(cog.hasOverviews, false);
  assert.equal(cog.sampleType, 'f32');
  assert.equal(cog.nodata, null);
  const whole = await decodeGeoTiff(bytes, NO_OVERVIEWS, defaultAllocate);
  for (const [tx, ty] of [[0, 0], [3, 2], [3, 0]]) {
    const tile = await cog.readTile(0, tx, ty);
    assert.ok(tile instanceof Float32Array);
    assertTileEquals(tile, whole.samples, 403, 344, cog.levels[0], tx, ty);
  }
  // The real DEM, not zeros: the Jacksboro heights are 236..1076 m.
  const raw = new Float32Array(readFileSync(new URL('../fixtures/jacksboro_fault.f32', import.meta.url)).buffer.slice(0));
  assert.equal((await cog.readTile(0, 1, 1))[0], raw[128 * 403 + 128]);
}));

test('a TIFF in strips is refused as not cloud-optimized, with the GDAL command that makes one', () => withServer({}, async () => {
  await assert.rejects(openCog(`${server.url}/${STRIPS}`), (e) => {
    assert.equal(e.kind, 'not-cog');
    assert.match(e.message, /strips/);
    assert.match(e.message, /gdal_translate -of COG in\.tif out\.tif/);
    return true;
  });
}));

test('a file that is not a TIFF is refused by its signature', () => withServer({}, async () => {
  await assert.rejects(openCog(`${server.url}/not_a_tiff.tif`), { kind: 'bad-tiff', message: /not a TIFF file/ });
}));

test('a 404 is retried, then reported with its status after the last try', () => withServer({ failPaths: [`/${HIMALAYA}`] }, async () => {
  await assert.rejects(openCog(`${server.url}/${HIMALAYA}`, FAST_RETRIES), (e) => {
    assert.equal(e.kind, 'http');
    assert.equal(e.status, 404);
    assert.match(e.message, /HTTP 404.*3 tries/);
    return true;
  });
  assert.equal(server.stats(`/${HIMALAYA}`).requests, 3);
}));

test('a path that fails twice then answers opens on the third try', () => withServer({ failPaths: { [`/${HIMALAYA}`]: 2 } }, async () => {
  const cog = await openCog(`${server.url}/${HIMALAYA}`, FAST_RETRIES);
  assert.equal(cog.levels.length, 3);
  assert.equal(cog.stats.requests, 3);
  assert.equal(server.stats(`/${HIMALAYA}`).requests, 3);
}));

test('a connection that breaks mid-answer is retried, then reported as a network error', () => withServer({ dropAfterBytes: 1000 }, async () => {
  await assert.rejects(openCog(`${server.url}/${HIMALAYA}`, FAST_RETRIES), (e) => {
    assert.equal(e.kind, 'network');
    assert.match(e.message, /connection lost.*3 tries/);
    return true;
  });
  assert.equal(server.stats(`/${HIMALAYA}`).requests, 3);
}));

test('a server that does not answer is a network error', async () => {
  const closed = await startRangeServer(dir);
  const url = `${closed.url}/${HIMALAYA}`;
  await closed.close();
  await assert.rejects(openCog(url, FAST_RETRIES), { kind: 'network', message: /no answer.*3 tries/ });
});

test('a server that ignores Range is detected on the first answer, its body cut off, the file size reported', () => withServer({ range: false }, async () => {
  const size = bytesOf(HIMALAYA).length;
  const url = `${server.url}/${HIMALAYA}`;
  await assert.rejects(openCog(url, FAST_RETRIES), (e) => {
    assert.equal(e.kind, 'no-range');
    assert.equal(e.size, size);
    assert.match(e.message, /ignores Range/);
    return true;
  });
  assert.equal(server.stats(`/${HIMALAYA}`).requests, 1, 'not retried: another try gets the same answer');
}));

test('a file truncated after its header opens, and a tile past the end is reported as truncated', async () => {
  const bytes = bytesOf(HIMALAYA);
  const { offsets, counts } = await tilesOf(bytes, 0);
  // Cut in the middle of the last full-resolution tile in the file: it and nothing after it is lost.
  const last = offsets.indexOf(Math.max(...offsets));
  const cut = offsets[last] + Math.floor(counts[last] / 2);
  writeFileSync(join(dir, 'truncated.tif'), bytes.subarray(0, cut));
  const whole = await decodeGeoTiff(bytes, HIMALAYA, defaultAllocate);
  const [tx, ty] = [last % 4, Math.floor(last / 4)];
  await withServer({}, async () => {
    const cog = await openCog(`${server.url}/truncated.tif`);
    // Tiles before the cut still read.
    const first = offsets.indexOf(Math.min(...offsets));
    assertTileEquals(await cog.readTile(0, first % 4, Math.floor(first / 4)), whole.samples, 1024, 1024, cog.levels[0], first % 4, Math.floor(first / 4));
    await assert.rejects(cog.readTile(0, tx, ty), (e) => {
      assert.equal(e.kind, 'truncated');
      assert.equal(e.size, cut);
      assert.match(e.message, new RegExp(`tile \\(${tx}, ${ty}\\) of level 0 .*the file is truncated`));
      return true;
    });
  });
  const fromBlob = await openCog(new Blob([bytes.subarray(0, cut)]), { name: 'truncated.tif' });
  await assert.rejects(fromBlob.readTile(0, tx, ty), { kind: 'truncated' });
});

test('a file cut inside its image directories is reported as truncated, from a URL and from a Blob', async () => {
  const bytes = bytesOf(HIMALAYA);
  writeFileSync(join(dir, 'cut_header.tif'), bytes.subarray(0, 600));
  const truncated = (e) => {
    assert.equal(e.kind, 'truncated');
    assert.match(e.message, /cut_header\.tif: the file ends at byte 600, inside its image directories .*: it is truncated/);
    return true;
  };
  await withServer({}, async () => {
    await assert.rejects(openCog(`${server.url}/cut_header.tif`, FAST_RETRIES), truncated);
  });
  await assert.rejects(openCog(new Blob([bytes.subarray(0, 600)]), { name: 'cut_header.tif' }), truncated);
});

test('a tile whose bytes do not decode is reported with its place', async () => {
  const bytes = bytesOf(HIMALAYA).slice();
  const { offsets, counts } = await tilesOf(bytes, 0);
  const i = 6; // tile (2, 1)
  bytes.fill(0xff, offsets[i], offsets[i] + counts[i]);
  const cog = await openCog(new Blob([bytes]), { name: 'corrupt.tif' });
  await assert.rejects(cog.readTile(0, 2, 1), { kind: 'decode', message: /corrupt\.tif: tile \(2, 1\) of level 0 does not decode/ });
  await cog.readTile(0, 1, 1); // its neighbours are sound
});

test('an aborted tile read stops with kind aborted', () => withServer({}, async () => {
  const cog = await openCog(`${server.url}/${HIMALAYA}`);
  const controller = new AbortController();
  const reading = cog.readTile(0, 1, 1, controller.signal);
  controller.abort();
  await assert.rejects(reading, { kind: 'aborted' });
}));
