// Heights stored scaled, as GDAL states them (its metadata's SCALE and OFFSET: metres = raw x
// scale + offset), loaded whole and streamed as a COG. The fixture holds the Himalaya fixture's
// central 512 x 512 samples as int16 half-metres offset by 500 m (scripts/make_cog_fixtures.sh),
// so each height must come back within a quarter metre (half a raw unit) of the original.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { createNodeCore } from '../../lib/node_core.js';
import { loadHeightfield } from '../../web/loaders/index.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';
import { openCog } from '../../web/tiles/cog_source.js';
import { openTiledTerrain } from '../../web/tiles/tiled_terrain.js';
import { heightScaling } from '../../web/geo/tiff_fields.js';

const fixture = (name) => ({ name, bytes: new Uint8Array(readFileSync(new URL(`../fixtures/cog/${name}`, import.meta.url))) });
const SCALED = 'himalaya_512_scaled_i16.tif', ORIGINAL = 'himalaya_1024_i16.tif'; // the scaled one is the window 256..767 of the original
let core, original;
before(async () => {
  core = await createNodeCore();
  original = await loadHeightfield([fixture(ORIGINAL)]);
});

const originalAt = (column, row) => original.samples[(row + 256) * original.width + column + 256];

test('a scaled GeoTIFF loaded whole: its heights in metres, in the field and in the core', async () => {
  const field = await loadHeightfield([fixture(SCALED)]);
  assert.deepEqual([field.heightScale, field.heightOffset], [0.5, -500]);
  let worst = 0;
  for (let row = 0; row < 512; row++) {
    for (let column = 0; column < 512; column++) {
      const metres = field.samples[row * 512 + column] * 0.5 - 500;
      worst = Math.max(worst, Math.abs(metres - originalAt(column, row)));
    }
  }
  assert.ok(worst <= 0.25, `within half a raw unit: ${worst} m`);
  const { terrain } = await loadTerrain(core, [fixture(SCALED)]);
  for (const [column, row] of [[0, 0], [100, 400], [511, 511], [300, 200]]) {
    const at = terrain.heightAt(column * terrain.spacingX, row * terrain.spacingY);
    assert.ok(Math.abs(at - originalAt(column, row)) <= 0.25, `the core's height at (${column}, ${row}): ${at} m, ${originalAt(column, row)} m`);
  }
  terrain.destroy();
});

test('a scaled COG streamed: the scale and offset reach the core, and GDAL\'s raw statistics become metres', async () => {
  const source = await openCog(new Blob([fixture(SCALED).bytes]), { name: SCALED });
  assert.deepEqual([source.heightScale, source.heightOffset], [0.5, -500]);
  const raw = await source.readTile(0, 1, 0);
  assert.ok(Math.abs(raw[0] * 0.5 - 500 - originalAt(256, 0)) <= 0.25);
  // The range the core is told, seen on its way in.
  const declared = [];
  const spied = Object.create(core);
  spied.createTiledTerrain = (...args) => {
    const made = core.createTiledTerrain(...args);
    const declare = made.declareHeightRange.bind(made);
    made.declareHeightRange = (low, high) => { declared.push([low, high]); declare(low, high); };
    return made;
  };
  const { terrain, field, tiles } = await openTiledTerrain(spied, source);
  assert.deepEqual([field.heightScale, field.heightOffset], [0.5, -500]);
  // GDAL's STATISTICS_MINIMUM/MAXIMUM (1158 and 17162) are of the raw values: 79 m and 8,081 m.
  assert.deepEqual(declared, [[79, 8081]]);
  // The coarsest level, in metres too (raw values would be over 1,000).
  assert.ok(terrain.minHeight >= 79 - 0.25 && terrain.minHeight < 500 && terrain.maxHeight <= 8081.25 && terrain.maxHeight > 7000,
    `the overview's range ${terrain.minHeight}..${terrain.maxHeight} m`);
  tiles.close();
  terrain.destroy();
});

test('bad scale and offset items are refused by name', () => {
  const fail = (problem) => { throw new Error(problem); };
  assert.deepEqual(heightScaling(null, fail), { heightScale: 1, heightOffset: 0 });
  assert.deepEqual(heightScaling({ SCALE: '0.1', OFFSET: '-10' }, fail), { heightScale: 0.1, heightOffset: -10 });
  assert.throws(() => heightScaling({ SCALE: 'abc' }, fail), /SCALE is not a number/);
  assert.throws(() => heightScaling({ OFFSET: '' }, fail), /OFFSET is not a number/);
  assert.throws(() => heightScaling({ SCALE: '0' }, fail), /SCALE is 0/);
});
