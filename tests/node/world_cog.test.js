// A world DEM in one COG, opened lazily: a virtual BigTIFF of 1,296,000 x 626,400 samples at 1″
// (13 levels, 3.1 million full-resolution tiles, 66 MB of tile tables, 2.2 TB in all) made on
// demand by lib/world_cog_server.js. Opening it and reading its coarsest level (what the first
// frame draws) must fetch a few requests and well under 2 MB, whatever the tile count; a
// full-resolution tile anywhere then costs its own bytes and one block of each table, and holds
// the samples the file holds there (tile offsets past 2^32 included).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { openCog } from '../../web/tiles/cog_source.js';
import { startWorldCogServer, worldHeight } from '../../lib/world_cog_server.js';

const TABLE_BLOCK = 16384; // header_source.js HEADER_BLOCK_BYTES
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
