// Real coordinates of points of a field (web/geo/coordinates.js) against GDAL's: the
// numbers below are gdaltransform's output (GDAL 3.6.2), printed by
// scripts/make_measure_fixtures.sh and for the .hgt tile by `gdaltransform N27E086.hgt`.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadHeightfield } from '../../web/loaders/index.js';
import { geoCoordinates, formatCoordinates, crsToLocal, localLabel } from '../../web/geo/coordinates.js';
import { crsOfEpsg, resolveCrs, UNKNOWN_CRS } from '../../web/geo/index.js';
import { useNodeCrsDefinitions } from '../../lib/crs_definitions.js';

useNodeCrsDefinitions(); // latitude and longitude need the CRSs' definitions

const ROOT = new URL('../../', import.meta.url);
const read = (path) => new Uint8Array(readFileSync(new URL(path, ROOT)));
const load = (path) => loadHeightfield([{ name: path.split('/').pop(), bytes: read(path) }]);
const near = (a, b, eps, what) => assert.ok(Math.abs(a - b) <= eps, `${what}: ${a} vs ${b}`);
const DEG = 1e-8; // about a millimetre

test('an SRTM tile\'s corner samples are at its whole degrees, as GDAL places them', async () => {
  const bytes = new Uint8Array(1201 * 1201 * 2);
  for (let k = 1; k < bytes.length; k += 2) bytes[k] = 100; // 100 m everywhere (big-endian)
  const field = await loadHeightfield([{ name: 'N27E086.hgt', bytes }]);
  const { georef, spacingX, spacingY } = field;
  // gdaltransform N27E086.hgt: pixel (0.5, 0.5) -> 86 28, (1200.5, 1200.5) -> 87 27, (600.5, 300.5) -> 86.5 27.75.
  for (const [column, row, lon, lat] of [[0, 0, 86, 28], [1200, 1200, 87, 27], [600, 300, 86.5, 27.75]]) {
    const c = geoCoordinates(georef, column * spacingX, row * spacingY, spacingX, spacingY);
    near(c.lon, lon, DEG, `lon of sample (${column}, ${row})`);
    near(c.lat, lat, DEG, `lat of sample (${column}, ${row})`);
    assert.equal(c.geographic, true);
    assert.equal(c.easting, null);
  }
  const corner = geoCoordinates(georef, 0, 0, spacingX, spacingY);
  assert.equal(formatCoordinates(corner), '28.0000° N 86.0000° E (EPSG:4326)');
});

test('a UTM GeoTIFF\'s samples have GDAL\'s eastings, northings, latitudes and longitudes', async () => {
  const field = await load('tests/fixtures/measure/everest_utm45.tif');
  const { georef } = field;
  assert.equal(georef.crs.label, 'EPSG:32645');
  // Any spacing the terrain is given: x / spacingX is the column.
  for (const [sx, sy] of [[field.spacingX, field.spacingY], [30, 40]]) {
    for (const [column, row, e, n, lon, lat] of [
      [0, 0, 410500, 3189500, 86.0826260995817, 28.8300285594634],
      [80, 100, 490500, 3089500, 86.9034411736594, 27.930434207429],
    ]) {
      const c = geoCoordinates(georef, column * sx, row * sy, sx, sy);
      near(c.easting, e, 1e-6, 'easting');
      near(c.northing, n, 1e-6, 'northing');
      near(c.lon, lon, DEG, 'lon');
      near(c.lat, lat, DEG, 'lat');
      const [x, z] = crsToLocal(georef, e, n, sx, sy);
      near(x, column * sx, 1e-6, 'x back from the easting');
      near(z, row * sy, 1e-6, 'z back from the northing');
    }
  }
  const c = geoCoordinates(georef, 80 * field.spacingX, 100 * field.spacingY, field.spacingX, field.spacingY);
  assert.equal(formatCoordinates(c), 'E 490 500 m N 3 089 500 m (EPSG:32645) · 27.9304° N 86.9034° E');
});

test('a Web Mercator GeoTIFF\'s samples have GDAL\'s latitudes and longitudes', async () => {
  const field = await load('tests/fixtures/formats/canyon_u16_tiled_deflate.tif');
  // gdaltransform: pixel (10.5, 20.5) -> -12588681.7215 4330272.3115 -> -113.086051973395 36.2151942415803
  const c = geoCoordinates(field.georef, 10 * field.spacingX, 20 * field.spacingY, field.spacingX, field.spacingY);
  near(c.easting, -12588681.7215, 1e-3, 'easting');
  near(c.northing, 4330272.3115, 1e-3, 'northing');
  near(c.lon, -113.086051973395, DEG, 'lon');
  near(c.lat, 36.2151942415803, DEG, 'lat');
  assert.match(formatCoordinates(c), /^E -12 588 682 m N 4 330 272 m \(EPSG:3857\) · 36\.2152° N 113\.0861° W$/);
});

test('southern UTM, NAD83 and ETRS89 zones invert; an unknown CRS keeps its eastings only', async () => {
  const at = async (epsg) => ({ crs: epsg ? await resolveCrs(crsOfEpsg(epsg)) : UNKNOWN_CRS, x0: 500000, y0: 0, dx: 1, dy: -1 });
  // The central meridian's point at the false easting: the equator (north) or 10 000 km south of the false northing.
  const north = geoCoordinates(await at(32633), 0, 0, 1, 1);
  near(north.lon, 15, DEG, 'zone 33 central meridian'), near(north.lat, 0, DEG, 'equator');
  const south = geoCoordinates({ ...await at(32733), y0: 10000000 }, 0, 0, 1, 1);
  near(south.lon, 15, DEG, 'zone 33 south central meridian'), near(south.lat, 0, DEG, 'equator from the south');
  near(geoCoordinates(await at(26915), 0, 0, 1, 1).lon, -93, DEG, 'NAD83 zone 15');
  near(geoCoordinates(await at(25832), 0, 0, 1, 1).lon, 9, DEG, 'ETRS89 zone 32');
  const unknown = geoCoordinates(await at(null), 3, 4, 1, 1);
  assert.deepEqual(unknown, { easting: 500003, northing: -4, lat: null, lon: null, crsLabel: 'unknown', geographic: false });
  assert.equal(formatCoordinates(unknown), 'E 500 003 m N -4 m (unknown)');
  assert.equal(geoCoordinates(null, 1, 2, 1, 1), null);
  assert.equal(formatCoordinates(null), localLabel);
  assert.equal(localLabel, 'local metres (no CRS)');
});
