// A world DEM in one COG, opened lazily: a virtual BigTIFF of 1,296,000 x 626,400 samples at 1″
// (13 levels, 3.1 million full-resolution tiles, 66 MB of tile tables, 2.2 TB in all) made on
// demand by lib/world_cog_server.js. Opening it and reading its coarsest level (what the first
// frame draws) must fetch a few requests and well under 2 MB, whatever the tile count; a
// full-resolution tile anywhere then costs its own bytes and one block of each table, and holds
// the samples the file holds there (tile offsets past 2^32 included). Through the page's stack
// (web/tiles/tiled_terrain.js over the WASM core) the core takes it and draws a first mesh from
// the coarsest level within the same budget, watertight, and asks for finer tiles from there.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { openCog } from '../../web/tiles/cog_source.js';
import { openTiledTerrain } from '../../web/tiles/tiled_terrain.js';
import { createNodeCore } from '../../lib/node_core.js';
import { startWorldCogServer, worldHeight } from '../../lib/world_cog_server.js';
import { FRAME } from '../../web/core/core.js';
import { EARTH_GEOGRAPHIC, earthShapeOf } from '../../web/geo/index.js';
import { horizonReach, lodCameraOnEarth } from '../../web/cameras/on_the_earth.js';

const TABLE_BLOCK = 16384; // header_source.js HEADER_BLOCK_BYTES
const FLIGHT_CAP_BYTES = 96 * 2 ** 20; // the orbit-to-valley flight's fetches, all told
let server;
before(async () => { server = await startWorldCogServer({ latencyMs: 5 }); });
after(() => server?.close());

/** The samples of full-resolution tile (tx, ty) as the world function gives them. */
function expectedTile(tx, ty) {
  const samples = new Int16Array(512 * 512);
  for (let row = 0; row < 512; row++) {
    for (let col = 0; col < 512; col++) {
      samples[row * 512 + col] = worldHeight(-180 + (tx * 512 + col + 0.5) / 3600, 90 - (ty * 512 + row + 0.5) / 3600);
    }
  }
  return samples;
}

test('the world COG opens and its coarsest level is read in a few requests and under 2 MB, though its tile tables are 66 MB', async () => {
  server.reset();
  const cog = await openCog(server.url);
  assert.equal(cog.width, 1296000);
  assert.equal(cog.height, 626400);
  assert.equal(cog.levels.length, 13);
  assert.equal(cog.sampleType, 'i16');
  assert.ok(Math.abs(cog.spacingX - 30.85) < 0.05, `1″ across at the middle row (${cog.spacingX} m)`);
  const opened = server.stats();
  const top = cog.levels.length - 1;
  for (let ty = 0; ty < cog.levels[top].tilesDown; ty++) {
    for (let tx = 0; tx < cog.levels[top].tilesAcross; tx++) await cog.readTile(top, tx, ty);
  }
  const first = server.stats();
  const tables = server.layout.dataAt - server.layout.tablesAt;
  console.log(`world COG: open ${opened.requests} requests, ${opened.bytes} bytes; with its coarsest level ${first.requests} requests, ` +
    `${first.bytes} bytes; its tile tables are ${tables} bytes`);
  assert.ok(tables > 60e6, 'the file has the tables of a world DEM');
  assert.ok(first.requests <= 10, `${first.requests} requests before the first frame`);
  assert.ok(first.bytes <= 2e6, `${first.bytes} bytes before the first frame`);
});

test('a full-resolution tile anywhere: its samples, for one block of each table and the tile itself', async () => {
  const cog = await openCog(server.url);
  // Near 86.9° E, 27.9° N, then the last tile of the last row (its offset is past 2^32; so is every tile's here).
  const everest = [Math.floor((86.9 + 180) * 3600 / 512), Math.floor((90 - 27.9) * 3600 / 512)];
  const last = [cog.levels[0].tilesAcross - 1, cog.levels[0].tilesDown - 1];
  for (const [tx, ty] of [everest, last]) {
    server.reset();
    const samples = await cog.readTile(0, tx, ty);
    const { requests, bytes } = server.stats();
    assert.deepEqual(samples, expectedTile(tx, ty), `tile (${tx}, ${ty})`);
    assert.ok(requests <= 3, `tile (${tx}, ${ty}): ${requests} requests (one block of each table, the tile)`);
    assert.ok(bytes <= 512 * 512 * 2 + 2 * TABLE_BLOCK, `tile (${tx}, ${ty}): ${bytes} bytes`);
  }
  // A neighbour of the first: its table entries are in the blocks already read.
  server.reset();
  await cog.readTile(0, everest[0] + 1, everest[1]);
  assert.equal(server.stats().requests, 1, 'only the tile itself');
});

/** The core allocator's bytes in use (hexlod_diag_heap). */
function heapInUse(core) {
  const at = core.module._malloc(16);
  try {
    assert.equal(core.module._hexlod_diag_heap(at), 0, core.lastError());
    return new Float64Array(core.buffer, at, 1)[0];
  } finally {
    core.module._free(at);
  }
}

test('through the page stack the core takes the world COG and draws its first mesh from the coarsest level: under 2 MB and 10 requests, watertight', async () => {
  const core = await createNodeCore();
  const heapBefore = heapInUse(core);
  server.reset();
  const start = performance.now();
  const source = await openCog(server.url);
  const { terrain, tiles } = await openTiledTerrain(core, source);
  try {
    assert.equal(terrain.tiled, true);
    assert.deepEqual([terrain.width, terrain.height], [1296000, 626400]);
    terrain.resetMesh('exact');
    terrain.configure({ tauPx: 1, morphFrames: 8 });
    // From 2,000 km above the middle of the world, looking north at a slant.
    const w = (terrain.width - 1) * terrain.spacingX, d = (terrain.height - 1) * terrain.spacingY;
    const camera = { eye: [0.5 * w, 2e6, 0.5 * d], target: [0.5 * w, 0, 0.5 * d - 1.5e6], up: [0, 1, 0], fovY: Math.PI / 3,
      aspect: 16 / 9, viewportHeight: 720, near: 1000, far: 1e8 };
    const first = terrain.frame(camera);
    const firstMeshMs = performance.now() - start;
    const { requests, bytes } = server.stats();
    const heap = heapInUse(core) - heapBefore;
    const wasmBytes = core.buffer.byteLength;
    const stream = terrain.checkStream(); // throws on a crack, a T-junction or a hole
    terrain.checkMesh();
    console.log(`world COG through the page stack: first mesh after ${requests} requests, ${bytes} bytes, ` +
      `${firstMeshMs.toFixed(0)} ms (wall clock); ${first.triangles} triangles; the core allocated ` +
      `${(heap / 2 ** 20).toFixed(1)} MiB (WASM memory ${(wasmBytes / 2 ** 20).toFixed(0)} MiB)`);
    assert.ok(requests <= 10, `${requests} requests before the first mesh`);
    assert.ok(bytes <= 2e6, `${bytes} bytes before the first mesh`);
    assert.ok(first.triangles > 0 && stream.triangles === first.triangles, `a first mesh of ${first.triangles} triangles`);
    assert.equal(stream.loops, 1, 'one outline');
    assert.ok(heap < 64 * 2 ** 20, `the core holds ${heap} bytes for a field of 3.1 million tiles`);

    // From there the view asks for finer tiles, which come in and keep the surface watertight.
    for (let frame = 0; frame < 40; frame++) {
      terrain.frame(null);
      terrain.checkStream();
      tiles.tick();
      if (tiles.waiting > 0) await new Promise((resolve) => setTimeout(resolve, 5));
    }
    assert.ok(tiles.tilesIn > 0, 'finer tiles came');
    terrain.checkMesh();
  } finally {
    tiles.close();
    terrain.destroy();
  }
});

// From orbit to a valley floor in one motion, through the page stack on the curved Earth (the
// camera placed on it as the page places it, web/cameras/on_the_earth.js): 2,000 km above the
// ground near 86.9° E, 27.9° N, down to 3 m, 120 frames of continuous descent whose stops hold
// the camera until every tile in view is in. The mesh stays watertight in every frame while
// tiles arrive; at each stop, converged, it keeps τ (measured by the core's error oracle); and
// the whole flight fetches a bounded number of bytes: the tiles the views need, not the file.
test('from 2,000 km to 3 m above a valley floor in one motion: watertight while tiles arrive, within τ at every stop, bytes bounded', async () => {
  const core = await createNodeCore();
  server.reset();
  const source = await openCog(server.url);
  const { terrain, tiles } = await openTiledTerrain(core, source);
  try {
    const tau = 1;
    terrain.resetMesh('exact');
    terrain.configure({ tauPx: tau, morphFrames: 0, maxOperations: 4000 });
    const earth = earthShapeOf(source.georef, terrain);
    assert.equal(earth.kind, EARTH_GEOGRAPHIC);
    terrain.setEarth(earth);
    const column = Math.round((86.9 + 180) * 3600), row = Math.round((90 - 27.9) * 3600);
    const ground = worldHeight(-180 + (column + 0.5) / 3600, 90 - (row + 0.5) / 3600);
    const x = column * terrain.spacingX, z = row * terrain.spacingY;
    const FRAMES = 120, STOPS = [0, 40, 80, 100, 119], HIGH = 2e6, LOW = 3;
    const lod = { eye: [0, 0, 0], target: [x, ground, z], up: [0, 1, 0], fovY: (50 * Math.PI) / 180, aspect: 16 / 9,
      viewportHeight: 720, near: 1, far: 1 };
    const placed = { eye: [0, 0, 0], target: [0, 0, 0], up: [0, 0, 0] };
    const report = [];
    let watertightFrames = 0, quiet = 0, waiting = 0; // quiet: frames since a tile went in
    const step = async () => {
      const stats = terrain.frame(lodCameraOnEarth(lod, earth, placed));
      terrain.checkStream(); // throws on a crack, a T-junction or a hole
      watertightFrames += 1;
      quiet = tiles.tick() > 0 ? 0 : quiet + 1;
      waiting = tiles.waiting; // as of the exchange: a tile that lands while we wait is handed in at the next
      await new Promise((resolve) => setTimeout(resolve, waiting > 0 ? 2 : 0));
      return stats;
    };
    for (let frame = 0; frame < FRAMES; frame++) {
      // Altitude falls geometrically; the eye keeps south of the place, looking down at it at a slant.
      const altitude = HIGH * (LOW / HIGH) ** (frame / (FRAMES - 1));
      lod.eye[0] = x, lod.eye[1] = ground + altitude, lod.eye[2] = z + 0.8 * altitude;
      lod.far = horizonReach(earth.radius, lod.eye[1], 9000); // as the page's far plane (on_the_earth.js)
      lod.near = Math.max(lod.far / 1e6, 0.3 * altitude);
      let stats = await step();
      if (!STOPS.includes(frame)) continue;
      const stopStart = performance.now();
      // A tile that went in takes its heights at the next frame's stream step, and the one after refines on them.
      for (let held = 0; held < 3000 && !(stats.converged && waiting === 0 && quiet >= 4); held++) stats = await step();
      const error = terrain.query(FRAME.census).achievedErrorPx;
      const { requests, bytes } = server.stats();
      report.push({ altitude, error, triangles: stats.triangles, requests, bytes, settleMs: performance.now() - stopStart });
      assert.deepEqual(tiles.failures, [], 'no tile failed');
      assert.ok(stats.converged && waiting === 0, `${altitude.toFixed(0)} m up: settled`);
      assert.ok(error <= tau * 1.001, `${altitude.toFixed(0)} m up: ${error.toFixed(3)} px against τ ${tau}`);
    }
    for (const r of report) {
      console.log(`world flight: ${(r.altitude / 1000).toFixed(3)} km up: error ${r.error.toFixed(2)} px, ${r.triangles} triangles; ` +
        `so far ${r.requests} requests, ${(r.bytes / 2 ** 20).toFixed(1)} MiB; settled in ${r.settleMs.toFixed(0)} ms`);
    }
    const { requests, bytes } = server.stats();
    console.log(`world flight: ${watertightFrames} watertight frames, ${requests} requests, ${(bytes / 2 ** 20).toFixed(1)} MiB in all, ` +
      `${tiles.tilesEvicted} tiles evicted`);
    assert.ok(bytes <= FLIGHT_CAP_BYTES, `the flight fetched ${bytes} bytes (cap ${FLIGHT_CAP_BYTES})`);
  } finally {
    tiles.close();
    terrain.destroy();
  }
});
