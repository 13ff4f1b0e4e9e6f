// The reproducers of tests/fixtures/mutated/ (valid fixtures with a few header bytes changed, as a
// mutation fuzzer found them): each is refused with a one-line message naming the file, and none
// leaves the core's WebAssembly memory larger than before, by more than 10 %. WebAssembly memory
// never shrinks: a field reserved for a forged header before its data proved the size would hold
// the tab's memory for good (a forged 5.6 MB PNG grew it from 64 MB to 1.8 GB).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { HeightfieldError } from '../../web/loaders/index.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';
import { createNodeCore } from '../../lib/node_core.js';

const ROOT = new URL('../../', import.meta.url);
const MUTATED = new URL('tests/fixtures/mutated/', ROOT);
const read = (url) => new Uint8Array(readFileSync(url));

/** Every reproducer and the problem its message must name (see tests/fixtures/mutated/README.md). */
const REPRODUCERS = {
  'everest_16bit_ihdr_6000x6000.png': /corrupt IDAT data \(bad filter type \d+ on row 1\) after 1 of 6000 rows$/,
  'everest_16bit_ihdr_3007x12000.png': /truncated: IDAT data ends after 13 of 12000 rows$/,
  'jacksboro_8bit_ihdr_1bit_16056x17000.png': /truncated: IDAT data ends after 23 of 17000 rows$/,
  'canyon_terrain-rgb_ihdr_1346x14000.png': /truncated: IDAT data ends after 27 of 14000 rows$/,
  'etopo_i32_strips_lzw_width_58095.tif': /bad TIFF: strip 0 decodes to 6720 bytes, but its 58095x7 samples need 1626660 \(is the image size right\?\)$/,
  'etopo_i32_strips_lzw_width_120.tif': /bad TIFF: strip 0 decodes to more than 3360 bytes, but its 120x7 samples need 3360/,
  'etopo_i32_strips_lzw_3000x12000.tif': /bad TIFF: strip 0 decodes to 6720 bytes, but its 3000x700 samples need 8400000/,
  'canyon_u16_tiled_deflate_tiles_2048.tif': /bad TIFF: tile 0 decodes to 8192 bytes, but its 2048x2048 samples need 8388608 \(is the tile size right\?\)$/,
  'jacksboro_f32_tiled_lzw_tiles_2048.tif': /bad TIFF: tile 0 decodes to 16384 bytes, but its 2048x2048 samples need 16777216/,
  'everest_i16_strips_400x100.tif': /bad TIFF: strip 0 holds 6400 bytes, but its 400x16 samples need 12800/,
  'everest_i16_strips_width_100.tif': /bad TIFF: strip 0 holds 6400 bytes, but its 100x16 samples need 3200/,
  'everest_i16_strips_width_double_-200.tif': /width -200 is not a positive whole number \(declared size -200x200\)$/,
  'everest_i16_strips_height_sshort_-200.tif': /height -200 is not a positive whole number \(declared size 200x-200\)$/,
  'everest_i16_strips_rows_per_strip_double_16.5.tif': /bad TIFF: RowsPerStrip 16\.5 is not a positive whole number$/,
  'everest_i16_strips_nodata_short.tif': /bad TIFF: the no-data tag \(42113\) holds 7, not the text of a number$/,
  'canyon_u16_tiled_deflate_sparse_8192_corners.tif':
    /too sparse to open: only 2 of the 16384 tiles around its data hold samples \(at least 1 in 16 must\); cut the area you need with gdal_translate -srcwin$/,
  'jacksboro_voids_4rows_1e999.asc': /line 10: '1e999' is not a finite float32 height/,
  'jacksboro_voids_4rows_1e39.asc': /line 10: '1e39' is not a finite float32 height/,
};

/** Reproducers that are valid files, and what they load as now. */
const ACCEPTED = {
  // One tile of data in a declared 8192 x 8192: the field is the data's extent, that tile.
  'canyon_u16_tiled_deflate_sparse_8192_one_tile.tif': { width: 64, height: 64, cropped: { column: 2816, row: 128, width: 8192, height: 8192 } },
};

test('every mutated fixture is refused with a message naming it, or loads as its data, and the core memory stays within 10 %', async (t) => {
  const files = readdirSync(MUTATED).filter((name) => name !== 'README.md').sort();
  assert.deepEqual(files, [...Object.keys(REPRODUCERS), ...Object.keys(ACCEPTED)].sort(), 'the tables above list every file of tests/fixtures/mutated/');
  const readme = new TextDecoder().decode(read(new URL('README.md', MUTATED)));
  for (const name of files) assert.ok(readme.includes(`\`${name}\``), `README.md says what ${name} is`);

  const core = await createNodeCore();
  const valid = await loadTerrain(core, [{ name: 'everest_16bit.png', bytes: read(new URL('tests/fixtures/formats/everest_16bit.png', ROOT)) }]);
  valid.terrain.destroy();
  const before = core.buffer.byteLength;
  const MB = (bytes) => `${(bytes / 2 ** 20).toFixed(0)} MB`;

  // The reproducers, and a RAW file given a height of -1 through the JS API (it became a flat 2 x 2 terrain).
  const cases = Object.keys(REPRODUCERS).map((name) => [[{ name, bytes: read(new URL(name, MUTATED)) }], {}, REPRODUCERS[name]]);
  cases.push([[{ name: 'volcano.r16', bytes: read(new URL('tests/fixtures/formats/volcano.r16', ROOT)) }], { height: -1 },
    /height -1 is not a positive whole number$/]);
  for (const [input, options, problem] of cases) {
    const name = input[0].name;
    await assert.rejects(loadTerrain(core, input, options), (e) => {
      assert.ok(e instanceof HeightfieldError, `${name}: ${e?.name}: ${e?.message}`);
      assert.ok(e.message.startsWith(`${name}: `), `the message names ${name}: ${e.message}`);
      assert.ok(!e.message.includes('\n'), `${name}: one line`);
      assert.match(e.message, problem);
      return true;
    });
    const after = core.buffer.byteLength;
    assert.ok(after <= before * 1.1, `${name} grew the core's memory from ${MB(before)} to ${MB(after)}`);
  }
  for (const [name, expected] of Object.entries(ACCEPTED)) {
    const loaded = await loadTerrain(core, [{ name, bytes: read(new URL(name, MUTATED)) }]);
    assert.deepEqual({ width: loaded.terrain.width, height: loaded.terrain.height, cropped: loaded.field.cropped }, expected, name);
    loaded.terrain.destroy();
    assert.ok(core.buffer.byteLength <= before * 1.1, `${name} grew the core's memory from ${MB(before)} to ${MB(core.buffer.byteLength)}`);
  }
  t.diagnostic(`core memory ${MB(before)} after a valid file, ${MB(core.buffer.byteLength)} after ${cases.length} refused files`);

  // The core is as usable as before.
  const again = await loadTerrain(core, [{ name: 'everest_16bit.png', bytes: read(new URL('tests/fixtures/formats/everest_16bit.png', ROOT)) }]);
  assert.equal(again.terrain.width, 200);
  again.terrain.destroy();
});
