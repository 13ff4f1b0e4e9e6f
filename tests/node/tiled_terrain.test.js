// A terrain streamed from a COG on a range server with latency (web/tiles/tiled_terrain.js
// over the core's tiled terrain): the first frame comes from the overviews, the tiles the view
// needs follow, the stream stays watertight while they come, far fewer bytes than the file are
// fetched, and the mesh converges to the one of the same file loaded whole.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { createNodeCore } from '../../lib/node_core.js';
import { startRangeServer } from '../../lib/range_server.js';
import { openCog } from '../../web/tiles/cog_source.js';
import { openTiledTerrain } from '../../web/tiles/tiled_terrain.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';

const fixtures = fileURLToPath(new URL('../fixtures/cog/', import.meta.url));
const HIMALAYA = 'himalaya_1024_i16.tif'; // 1024^2 int16, 256^2 tiles, overviews 512 and 256
const NO_OVERVIEWS = 'jacksboro_403x344_f32_no_overviews.tif';
let core, server;

before(async () => {
  core = await createNodeCore();
  server = await startRangeServer(fixtures, { latencyMs: 10 });
});
after(() => server.close());

const settings = { tauPx: 1, morphFrames: 8 };
// Looking down on the south-west of the field from high up: about a tenth of it in view.
function cameraFor(terrain) {
  const w = (terrain.width - 1) * terrain.spacingX, d = (terrain.height - 1) * terrain.spacingY;
  return { eye: [0.2 * w, 0.12 * w, 0.8 * d], target: [0.2 * w, 0, 0.8 * d - 0.02 * w], up: [0, 1, 0], fovY: Math.PI / 3,
    aspect: 16 / 9, viewportHeight: 720, near: 10, far: 1e8 };
}

/** Frames until nothing is waited for and the mesh converged, each checked watertight. */
async function runToRest(terrain, tiles, camera, { maxFrames = 2000, onFrame = () => {} } = {}) {
  let quiet = 0, frames = 0;
  for (; frames < maxFrames && quiet < 3; frames++) {
    const stats = terrain.frame(frames === 0 ? camera : null);
    terrain.checkStream();
    onFrame(stats, frames);
    const arrived = tiles ? tiles.tick() : 0;
    const waiting = tiles ? tiles.waiting : 0;
    quiet = waiting === 0 && arrived === 0 && stats.converged && stats.pendingMerges === 0 ? quiet + 1 : 0;
    if (waiting > 0) await new Promise((resolve) => setTimeout(resolve, 2)); // let the requests in flight land
  }
  assert.equal(quiet, 3, `still waiting or refining after ${frames} frames`);
  return frames;
}

test('a COG streamed over HTTP: overviews first, only the needed tiles, watertight throughout, the whole file\'s mesh', async () => {
  const url = `${server.url}/${HIMALAYA}`;
  const source = await openCog(url);
  const opened = await openTiledTerrain(core, source);
  const { terrain, tiles } = opened;
  assert.equal(terrain.tiled, true);
  assert.deepEqual([terrain.width, terrain.height], [1024, 1024]);
  const afterOpen = source.stats.bytes;
  assert.ok(afterOpen < 0.15 * source.size, `the header and the coarsest level: ${afterOpen} of ${source.size} bytes`);

  terrain.resetMesh('exact');
  terrain.configure(settings);
  const camera = cameraFor(terrain);
  let firstTriangles = 0;
  await runToRest(terrain, tiles, camera, { onFrame: (stats, k) => { if (k === 0) firstTriangles = stats.triangles; } });
  assert.ok(firstTriangles > 0, 'the first frame draws from the overviews');
  assert.ok(tiles.tilesIn > 0, 'the view asked for finer tiles');
  const fetched = source.stats.bytes;
  // Measured: 8 tiles after the opening, 38 % of the bytes (the header and coarsest level included).
  assert.ok(fetched < 0.5 * source.size, `a corner view fetches part of the file: ${fetched} of ${source.size} bytes`);

  // The same file loaded whole, same view and settings: the same cells, and where the full
  // resolution came, the same heights; every tile in, the very same mesh.
  const whole = (await loadTerrain(core, [{ name: HIMALAYA, bytes: new Uint8Array(readFileSync(fixtures + HIMALAYA)) }])).terrain;
  whole.resetMesh('exact');
  whole.configure(settings);
  await runToRest(whole, null, camera);
  const wholeStats = whole.query(16);
  const streamed = terrain.query(16);
  assert.equal(streamed.triangles, wholeStats.triangles, 'the same cells as the whole file');
  // Every full-resolution tile in: the whole file's mesh, heights included.
  const level = source.levels[0];
  for (let ty = 0; ty < level.tilesDown; ty++) {
    for (let tx = 0; tx < level.tilesAcross; tx++) {
      terrain.tileBuffer(0, tx, ty).set(await source.readTile(0, tx, ty));
      terrain.commitTile(0, tx, ty);
    }
  }
  for (let k = 0; k < 3 || !terrain.query().converged; k++) {
    terrain.frame(null);
    terrain.checkStream();
    assert.ok(k < 200);
  }
  assert.equal(terrain.query(16).hash(), whole.query(16).hash());
  tiles.close();
  terrain.destroy();
  whole.destroy();
});

test('a COG from a Blob (a dropped file) is read by slices, never whole', async () => {
  const bytes = readFileSync(fixtures + HIMALAYA);
  let sliced = 0;
  const blob = new Blob([bytes]);
  const slice = blob.slice.bind(blob);
  blob.slice = (...args) => {
    const part = slice(...args);
    sliced += part.size;
    assert.ok(part.size < bytes.length / 2, 'no slice of half the file');
    return part;
  };
  const source = await openCog(blob, { name: HIMALAYA });
  const { terrain, tiles } = await openTiledTerrain(core, source);
  terrain.resetMesh('exact');
  terrain.configure(settings);
  await runToRest(terrain, tiles, cameraFor(terrain));
  assert.ok(sliced < 0.75 * bytes.length, `${sliced} of ${bytes.length} bytes sliced`);
  tiles.close();
  terrain.destroy();
});

test('a COG without overviews streams when it fits the cap, and is refused with the way to make one when not', async () => {
  const source = await openCog(`${server.url}/${NO_OVERVIEWS}`);
  assert.equal(source.hasOverviews, false);
  const { terrain, tiles } = await openTiledTerrain(core, source);
  terrain.resetMesh('exact');
  terrain.configure(settings);
  await runToRest(terrain, tiles, cameraFor(terrain));
  tiles.close();
  terrain.destroy();

  await assert.rejects(openTiledTerrain(core, await openCog(`${server.url}/${NO_OVERVIEWS}`), { capBytes: 100_000 }),
    (e) => e.kind === 'too-big' && /gdal_translate -of COG/.test(e.message) && /overviews/.test(e.message));
});

test('a tile that fails is reported once with its kind, and the terrain stays drawn from the coarser level', async () => {
  const failing = await startRangeServer(fixtures, { latencyMs: 5 });
  try {
    const source = await openCog(`${failing.url}/${HIMALAYA}`, { retries: 1, backoffMs: 1 });
    const { terrain, tiles } = await openTiledTerrain(core, source);
    terrain.resetMesh('exact');
    terrain.configure(settings);
    await failing.close(); // the server goes away: every later request fails
    for (let k = 0; k < 40; k++) {
      terrain.frame(k === 0 ? cameraFor(terrain) : null);
      terrain.checkStream();
      tiles.tick();
      await new Promise((resolve) => setTimeout(resolve, 5));
    }
    assert.ok(tiles.failures.length > 0, 'failed tiles are reported');
    assert.ok(tiles.failures.every((f) => f.kind === 'network' && /no answer/.test(f.message) && f.level >= 0), JSON.stringify(tiles.failures[0]));
    assert.ok(terrain.query().triangles > 0);
    tiles.close();
    terrain.destroy();
  } finally {
    await failing.close().catch(() => {});
  }
});

// Which tiles stay (never one the mesh stands on, least recently used out first) is the core's,
// held by tests/native/tiled_field_test.cpp; here, the page's exchange around it.
test('past a small cap the core lets tiles go while the view moves on, fetches them again when wanted, and stays watertight', async () => {
  const source = await openCog(`${server.url}/${HIMALAYA}`);
  const tileBytes = 256 * 256 * 2;
  const { terrain, tiles } = await openTiledTerrain(core, source, { capBytes: 6 * tileBytes });
  assert.equal(tiles.capBytes, 6 * tileBytes);
  terrain.resetMesh('exact');
  terrain.configure(settings);
  const w = (terrain.width - 1) * terrain.spacingX, d = (terrain.height - 1) * terrain.spacingY;
  // Across the field from west to east, looking down.
  const evictedAt = [];
  for (let k = 0; k < 240; k++) {
    const x = (0.1 + 0.8 * k / 240) * w;
    terrain.frame({ eye: [x, 0.12 * w, 0.5 * d], target: [x, 0, 0.5 * d - 0.02 * w], up: [0, 1, 0], fovY: Math.PI / 3,
      aspect: 16 / 9, viewportHeight: 720, near: 10, far: 1e8 });
    terrain.checkStream();
    evictedAt.push(tiles.tilesEvicted);
    tiles.tick();
    await new Promise((resolve) => setTimeout(resolve, 3));
  }
  assert.ok(tiles.tilesEvicted > 0, 'tiles were let go');
  assert.ok(evictedAt.every((n, k) => k === 0 || n >= evictedAt[k - 1]), 'the count only grows');
  assert.ok(tiles.tilesIn > 6 + tiles.tilesEvicted / 2, `${tiles.tilesIn} tiles came, ${tiles.tilesEvicted} went`);
  assert.ok(tiles.heldBytes <= 6 * tileBytes, `${tiles.heldBytes / tileBytes} tiles held at the east end, within the cap of 6`);
  // A cap of nothing, and the view climbs: the mesh coarsens, and what it left goes.
  const before = { evicted: tiles.tilesEvicted, held: tiles.heldBytes };
  tiles.setCapBytes(0);
  for (let k = 0; k < 60; k++) {
    terrain.frame(k === 0 ? { eye: [0.5 * w, 3 * w, 0.5 * d], target: [0.5 * w, 0, 0.5 * d - 0.01 * w], up: [0, 1, 0],
      fovY: Math.PI / 3, aspect: 16 / 9, viewportHeight: 720, near: 10, far: 1e8 } : null);
    terrain.checkStream();
  }
  assert.ok(tiles.tilesEvicted > before.evicted && tiles.heldBytes < before.held,
    `${before.held / tileBytes} tiles held before, ${tiles.heldBytes / tileBytes} after`);
  assert.throws(() => tiles.setCapBytes(-1), /tile cap/);
  tiles.close();
  terrain.destroy();
});
