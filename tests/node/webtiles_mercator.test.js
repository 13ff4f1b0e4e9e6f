// Web Mercator as tile services use it (web/webtiles/web_mercator.js), against values from
// elsewhere: proj4's EPSG:3857, GDAL's pixel of each ground point of the tile fixture
// (tests/fixtures/webtiles/bmng_points.json), and the ground resolutions every map library lists.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import proj4 from 'proj4';
import { lonLatToWorld, worldToLonLat, metresToWorld, worldToTile, lonLatToTile, tileLonLatBounds, groundResolution,
  MAX_LATITUDE, EQUATOR_METRES } from '../../web/webtiles/web_mercator.js';
import { tileKey, tileOfKey } from '../../web/webtiles/tile_key.js';

const points = JSON.parse(readFileSync(new URL('../fixtures/webtiles/bmng_points.json', import.meta.url), 'utf8')).points;

test('world coordinates agree with proj4 EPSG:3857 to a millimetre on the ground', () => {
  for (const [lon, lat] of [[0, 0], [86.925, 27.9881], [-122.4194, 37.7749], [151.2093, -33.8688], [179.9, 85], [-179.9, -85]]) {
    const [e, n] = proj4('EPSG:4326', 'EPSG:3857', [lon, lat]);
    const [x, y] = lonLatToWorld(lon, lat), [ex, ey] = metresToWorld(e, n);
    assert.ok(Math.abs(x - ex) * EQUATOR_METRES < 1e-3 && Math.abs(y - ey) * EQUATOR_METRES < 1e-3, `${lon}, ${lat}: ${[x, y]} vs ${[ex, ey]}`);
    const [lon2, lat2] = worldToLonLat(x, y);
    assert.ok(Math.abs(lon2 - lon) < 1e-9 && Math.abs(lat2 - lat) < 1e-9, `round trip of ${lon}, ${lat}`);
  }
});

test('the map is a square: its corners, the equator and the edges of latitude', () => {
  assert.deepEqual(lonLatToWorld(0, 0), [0.5, 0.5]);
  assert.deepEqual(lonLatToWorld(-180, 0), [0, 0.5]);
  assert.ok(Math.abs(MAX_LATITUDE - 85.0511287798066) < 1e-10);
  assert.ok(Math.abs(lonLatToWorld(0, MAX_LATITUDE)[1]) < 1e-12 && Math.abs(lonLatToWorld(0, -90)[1] - 1) < 1e-12);
  assert.deepEqual(worldToTile(1, 1, 3), [7, 7], 'the south-east corner is in the last tile');
  const [w, s, e, n] = tileLonLatBounds(1, 0, 0);
  assert.ok(w === -180 && s === 0 && e === 0 && Math.abs(n - MAX_LATITUDE) < 1e-10);
});

test('each ground point of the fixture lands in the pixel GDAL put it in, at zooms 4 and 7', () => {
  for (const p of points) {
    for (const z of [4, 7]) {
      const [x, y] = lonLatToWorld(p.lon, p.lat), size = 256 * 2 ** z;
      assert.deepEqual([Math.floor(x * size), Math.floor(y * size)], p[`z${z}`].pixel, `${p.name} at zoom ${z}`);
      assert.deepEqual(lonLatToTile(p.lon, p.lat, z), p[`z${z}`].pixel.map((v) => Math.floor(v / 256)));
    }
  }
});

test('ground resolution: 156 543.03 m a texel at zoom 0 on the equator, halving a zoom, by cos(latitude)', () => {
  assert.ok(Math.abs(groundResolution(0, 0) - 156543.03392804097) < 1e-6);
  assert.ok(Math.abs(groundResolution(10, 0) - 152.87405657037) < 1e-9);
  assert.ok(Math.abs(groundResolution(10, 60) - 152.87405657037 / 2) < 1e-6);
  assert.ok(Math.abs(groundResolution(3, 0, 512) - groundResolution(4, 0)) < 1e-9);
});

test('tile keys are unique and give their tile back', () => {
  const seen = new Set();
  for (let z = 0; z <= 4; z++) for (let y = 0; y < 2 ** z; y++) for (let x = 0; x < 2 ** z; x++) {
    const key = tileKey(z, x, y);
    assert.ok(!seen.has(key));
    seen.add(key);
    assert.deepEqual(tileOfKey(key), [z, x, y]);
  }
  assert.equal(seen.size, (4 ** 5 - 1) / 3, 'keys fill 0..n-1 without gaps');
  const far = tileKey(24, 2 ** 24 - 1, 2 ** 24 - 1);
  assert.ok(Number.isSafeInteger(far));
  assert.deepEqual(tileOfKey(far), [24, 2 ** 24 - 1, 2 ** 24 - 1]);
});
