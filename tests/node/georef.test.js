// Where every format places its samples on the Earth (web/geo/georef.js): the CRS and the
// map to sample centres, from GeoTIFF tags, SRTM tile names, ESRI headers and sidecars. The
// same place read from two formats of one DEM must agree.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadHeightfield, HeightfieldError } from '../../web/loaders/index.js';
import { compareCrs, crsOfEpsg, crsToSample, parseEpsg, sampleToCrs, sameCrs, UNKNOWN_CRS } from '../../web/geo/georef.js';
import { useNodeCrsDefinitions } from '../../lib/crs_definitions.js';

useNodeCrsDefinitions(); // a loaded field's CRS gets its name and definition

const ROOT = new URL('../../', import.meta.url);
const read = (path) => new Uint8Array(readFileSync(new URL(path, ROOT)));
const load = (...paths) => loadHeightfield(paths.map((path) => ({ name: path.split('/').pop(), bytes: read(path) })));
const near = (a, b, eps, what) => assert.ok(Math.abs(a - b) <= eps, `${what}: ${a} vs ${b}`);

test('a GeoTIFF and an ESRI grid of the same DEM put its samples in the same place', async () => {
  const tiff = (await load('tests/fixtures/formats/jacksboro_f32_tiled_lzw.tif')).georef;
  const asc = (await load('tests/fixtures/formats/jacksboro_voids.asc')).georef;
  assert.equal(tiff.crs.label, 'EPSG:4326');
  assert.equal(tiff.crs.geographic, true);
  for (const key of ['x0', 'y0', 'dx', 'dy']) near(tiff[key], asc[key], 1e-9, key);
  assert.ok(tiff.dy < 0, 'rows go south');
  // The ASCII header gives the south-west cell's corner: the first sample's centre is half a
  // cell east of it and nrows - 1/2 cells north.
  near(asc.x0, -84.33041666666666 + 0.0008333333333333334 / 2, 1e-12, 'x0');
  near(asc.y0, 36.50791666666667 + 189.5 * 0.0008333333333333334, 1e-12, 'y0');
});

test('GeoTIFF: projected and geographic CRSs from the GeoKeys, sample centres from the tie point', async () => {
  const canyon = (await load('tests/fixtures/formats/canyon_u16_tiled_deflate.tif')).georef;
  assert.deepEqual({ ...canyon.crs, proj4: /\+proj=merc/.test(canyon.crs.proj4) },
    { epsg: 3857, label: 'EPSG:3857', name: 'WGS 84 / Pseudo-Mercator', proj4: true, geographic: false });
  assert.equal(canyon.from, 'GeoTIFF');
  near(canyon.dx, 76.437, 1e-9, 'dx'); near(canyon.dy, -76.437, 1e-9, 'dy');
  const everest = (await load('tests/fixtures/formats/everest_i16_strips.tif')).georef;
  assert.equal(everest.crs.epsg, 4326);
  assert.equal(everest.crs.geographic, true, 'from the definition, +proj=longlat');
  // Mount Everest (27.9881 N, 86.9250 E) lies inside this 200 x 200 crop of 30" cells.
  const [column, row] = crsToSample(everest, 86.925, 27.9881);
  assert.ok(column > 0 && column < 199 && row > 0 && row < 199, `Everest at sample ${column}, ${row}`);
  const [x, y] = sampleToCrs(everest, column, row);
  near(x, 86.925, 1e-9, 'back to x'); near(y, 27.9881, 1e-9, 'back to y');
});

test('a sparse GeoTIFF loaded as its data keeps the data where it was', async () => {
  const whole = (await load('tests/fixtures/formats/canyon_u16_tiled_deflate.tif')).georef;
  const part = await load('tests/fixtures/mutated/canyon_u16_tiled_deflate_sparse_8192_one_tile.tif');
  assert.deepEqual([part.cropped.column, part.cropped.row], [2816, 128]);
  near(part.georef.x0, whole.x0 + 2816 * whole.dx, 1e-6, 'x0');
  near(part.georef.y0, whole.y0 + 128 * whole.dy, 1e-6, 'y0');
});

test('SRTM: the tile name places the samples on whole arc-seconds, north-west first', async () => {
  const bytes = new Uint8Array(1201 * 1201 * 2);
  for (const [name, lon, lat] of [['N27E086.hgt', 86, 28], ['s12w077.hgt', -77, -11]]) {
    const { georef } = await loadHeightfield([{ name, bytes }]);
    assert.deepEqual([georef.crs.epsg, georef.x0, georef.y0, georef.dx, georef.dy, georef.from], [4326, lon, lat, 1 / 1200, -1 / 1200, 'tile name']);
    const [x, y] = sampleToCrs(georef, 1200, 1200);
    near(x, lon + 1, 1e-12, 'last column on the east edge'); near(y, lat - 1, 1e-12, 'last row on the south edge');
  }
  assert.equal((await loadHeightfield([{ name: 'tile.hgt', bytes }])).georef, null, 'no name, no place');
});

test('sidecars: crs and cell-edge bounds place a PNG, an f32 or a RAW file', async () => {
  const himalaya = await load('public/terrain/globe_himalaya_2048.png', 'public/terrain/globe_himalaya_2048.json');
  const g = himalaya.georef;
  assert.equal(g.crs.label, 'EPSG:4326');
  assert.equal(g.from, 'sidecar');
  near(g.dx, 1 / 120, 1e-12, 'dx: 30 arc-seconds');
  near(g.x0, 72.93333333333334 + 1 / 240, 1e-9, 'x0: half a cell inside the west edge');
  near(g.y0, 37.916666666666664 - 1 / 240, 1e-9, 'y0: half a cell inside the north edge');
  const canyon = (await load('tests/fixtures/grandcanyon_512.png', 'tests/fixtures/grandcanyon_512.json')).georef;
  assert.equal(canyon.crs.epsg, 3857);
  near(canyon.dx, (-12562578.47 - -12601714.23) / 512, 1e-6, 'dx');
  // Without bounds, nothing is placed.
  assert.equal((await load('tests/fixtures/formats/everest_16bit.png')).georef, null);
});

test('a sidecar whose bounds make no sense is refused, naming the field', async () => {
  const png = { name: 'v.png', bytes: read('tests/fixtures/formats/everest_16bit.png') };
  const sidecar = (json) => ({ name: 'v.json', bytes: new TextEncoder().encode(JSON.stringify(json)) });
  for (const [json, problem] of [
    [{ crs: 'EPSG:4326', bounds_deg: { west: 10, east: 9, south: 0, north: 1 } }, /bounds_deg: east must lie east of west/],
    [{ bounds: { west: 0, east: 1, south: 0 } }, /bounds\.north must be a finite number \(got undefined\)/],
    [{ bounds: { west: 0, east: 1, south: 0, north: 1 }, bounds_deg: { west: 0, east: 1, south: 0, north: 1 } }, /several bounds given/],
    [{ crs: 'EPSG:32611', bounds_epsg3857: { west: 0, east: 1, south: 0, north: 1 } }, /bounds_epsg3857 is not in the crs/],
  ]) {
    await assert.rejects(loadHeightfield([png, sidecar(json)]), (e) => e instanceof HeightfieldError && e.message.startsWith('v.json: ') && problem.test(e.message));
  }
});

test('CRSs compare as the same, different, or assumed when one is unknown', () => {
  assert.deepEqual([parseEpsg('EPSG:4326 (lat/lon)'), parseEpsg('urn:ogc:def:crs:EPSG::32611'), parseEpsg(3857), parseEpsg('WGS 84')], [4326, 32611, 3857, null]);
  assert.equal(compareCrs(crsOfEpsg(4326), crsOfEpsg(4326)), 'same');
  assert.equal(compareCrs(crsOfEpsg(4326), crsOfEpsg(3857)), 'different');
  assert.equal(compareCrs(UNKNOWN_CRS, crsOfEpsg(3857)), 'assumed');
  // Without a code, a CRS is its definition: one WKT is the same as itself, not as another or an unknown one.
  const custom = (proj4) => ({ epsg: null, label: 'custom (x from the WKT)', name: 'x', proj4, geographic: false });
  const a = custom('+proj=tmerc +lon_0=9 +ellps=bessel'), b = custom('+proj=tmerc +lon_0=10 +ellps=bessel');
  assert.deepEqual([sameCrs(a, { ...a }), sameCrs(a, b), sameCrs(UNKNOWN_CRS, UNKNOWN_CRS), sameCrs(a, crsOfEpsg(31467))], [true, false, false, false]);
  assert.deepEqual([compareCrs(a, { ...a }), compareCrs(a, b), compareCrs(a, UNKNOWN_CRS), compareCrs(a, crsOfEpsg(31467))],
    ['same', 'different', 'assumed', 'different']);
});
