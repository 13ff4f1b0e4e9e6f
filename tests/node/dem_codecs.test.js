// Every codec and sample layout published DEMs come in (GDAL's COG driver: DEFLATE with the
// floating-point predictor, LZW with the horizontal one, ZSTD, LERC, LERC_ZSTD, LERC_DEFLATE,
// PackBits; int16, uint16, int32, float32; a BigTIFF), loaded whole and streamed tile by tile
// from one 192 x 160 window of the GLOBE Himalaya (scripts/make_cog_fixtures.sh): every one
// gives the window's heights exactly, at full resolution and in its overview.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadHeightfield } from '../../web/loaders/index.js';
import { openCog } from '../../web/tiles/cog_source.js';

const file = (path) => ({ name: path.split('/').pop(), bytes: new Uint8Array(readFileSync(new URL(`../fixtures/cog/${path}`, import.meta.url))) });
// The reference: the window's columns 1000..1191 and rows 900..1059 of the 2048 field are the
// 1024 fixture's columns 488.. and rows 388.. (it starts at 512, 512).
const reference = await loadHeightfield([file('himalaya_1024_i16.tif')]);
const expected = (column, row) => reference.samples[(row + 388) * reference.width + column + 488];
const CODECS = {
  deflate_pred3_f32: 'f32', lzw_pred2_i16: 'i16', zstd_i16: 'i16', lerc_f32: 'f32', lerc_zstd_f32: 'f32',
  lerc_deflate_f32: 'f32', packbits_u16: 'u16', none_i32_bigtiff: 'f32',
};

for (const [name, sampleType] of Object.entries(CODECS)) {
  test(`${name}: loaded whole and streamed by tiles, the same heights`, async () => {
    const bytes = file(`codecs/${name}.tif`);
    const field = await loadHeightfield([bytes]);
    assert.deepEqual([field.width, field.height, field.sampleType], [192, 160, sampleType]);
    for (let row = 0; row < 160; row++) {
      for (let column = 0; column < 192; column++) {
        if (field.samples[row * 192 + column] !== expected(column, row)) {
          assert.fail(`whole: (${column}, ${row}) is ${field.samples[row * 192 + column]}, GDAL wrote ${expected(column, row)}`);
        }
      }
    }
    const cog = await openCog(new Blob([bytes.bytes]), { name });
    assert.equal(cog.levels.length, 2, 'the full resolution and one overview');
    for (let ty = 0; ty < 2; ty++) {
      for (let tx = 0; tx < 2; tx++) {
        const tile = await cog.readTile(0, tx, ty);
        for (let row = 0; row < 128 && ty * 128 + row < 160; row++) {
          for (let column = 0; column < 128 && tx * 128 + column < 192; column++) {
            const got = tile[row * 128 + column], want = expected(tx * 128 + column, ty * 128 + row);
            if (got !== want) assert.fail(`tile (${tx}, ${ty}): (${column}, ${row}) is ${got}, GDAL wrote ${want}`);
          }
        }
      }
    }
    const overview = await cog.readTile(1, 0, 0);
    assert.ok(overview.slice(0, 96).every((v) => v > 0 && v < 9000), 'the overview holds heights');
  });
}
