// A ?src= TIFF that cannot be opened tile by tile (ui/tiled_open.js afterTilesFailed): a server
// that ignores Range or a TIFF in strips is loaded whole if it fits the tile cache, with advice
// for when it does not; a file known to be larger fails at once; any other failure ends the load.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { afterTilesFailed } from '../../web/ui/tiled_open.js';
import { TileError } from '../../web/tiles/tile_error.js';

const MB = 2 ** 20;

test('no Range or no tiles: a whole load within the tile cache, with advice naming why and how to make a COG', () => {
  const noRange = afterTilesFailed(new TileError('no-range', 'ignores Range', { size: 10 * MB }), 'a.tif', 64 * MB);
  assert.equal(noRange.whole.maxBytes, 64 * MB);
  assert.match(noRange.whole.advice, /its server ignores Range requests\. Make it a Cloud-Optimized GeoTIFF \(gdal_translate/);
  const strips = afterTilesFailed(new TileError('not-cog', 'strips'), 'b.tif', 64 * MB);
  assert.match(strips.whole.advice, /it is not tiled/);
});

test('a file known to be larger than the tile cache fails at once; other failures end the load with their message', () => {
  const big = afterTilesFailed(new TileError('no-range', 'ignores Range', { size: 100 * MB }), 'big.tif', 64 * MB);
  assert.match(big.failed, /^big\.tif: 100(\.0)? MB, more than the 64(\.0)? MB tile cache, too big to load whole/);
  const missing = afterTilesFailed(new TileError('http', 'HTTP 404', { status: 404 }), 'gone.tif', 64 * MB);
  assert.deepEqual(missing, { failed: 'gone.tif: cannot stream it (HTTP 404)' });
});
