// Placing an image on the terrain (web/imagery/): world files, and the map from field samples to
// texture coordinates, checked on known points, on half-overlapping images and on bad input.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseWorldFile, worldFileNames, isWorldFileName } from '../../web/geo/world_file.js';
import { placeImage } from '../../web/imagery/placement.js';
import { ImageError } from '../../web/imagery/image_error.js';
import { crsOfEpsg, makeGeoref, UNKNOWN_CRS } from '../../web/geo/georef.js';
import { resolveCrs } from '../../web/geo/index.js';
import { useNodeCrsDefinitions } from '../../lib/crs_definitions.js';

useNodeCrsDefinitions(); // CRSs as the loaders give them: with their definitions

const text = (s) => new TextEncoder().encode(s);
// A world file's problems as the image reader reports them (image_location.js).
const failAs = (name) => (problem) => { throw new ImageError(name, problem); };
const near = (a, b, what, eps = 1e-9) => assert.ok(Math.abs(a - b) <= eps, `${what}: ${a} vs ${b}`);
const uv = (p, column, row) => p.uvAt(column, row);

// A field of 101 x 51 samples 10 m apart in UTM 11N, north-west sample centre at (500000, 4000000).
const UTM = await resolveCrs(crsOfEpsg(32611));
const field = { width: 101, height: 51, georef: makeGeoref(UTM, 500000, 4000000, 10, -10, 'GeoTIFF') };

test('world files: six numbers, north-up, named after their image', () => {
  const g = parseWorldFile(text('2.5\n0\n0\n-2.5\n500001.25\n3999998.75\n'), failAs('o.pgw'));
  assert.deepEqual([g.dx, g.dy, g.x0, g.y0, g.crs, g.from], [2.5, -2.5, 500001.25, 3999998.75, UNKNOWN_CRS, 'world file']);
  assert.deepEqual(worldFileNames('Ortho.PNG'), ['ortho.pgw', 'ortho.pngw', 'ortho.wld']);
  assert.deepEqual(worldFileNames('scan.tiff'), ['scan.tfw', 'scan.tiffw', 'scan.wld']);
  assert.ok(isWorldFileName('a.jgw') && isWorldFileName('a.wld') && !isWorldFileName('a.raw') && !isWorldFileName('a.png'));
  for (const [body, problem] of [
    ['1\n0\n0\n-1\n0\n', /six numbers, one a line; this one has 5 lines/],
    ['1\n0\n0\n-1\n0\nabc\n', /line 6: "abc" is not a number/],
    ['1\n0.1\n0\n-1\n0\n0\n', /rotated or sheared/],
    ['0\n0\n0\n-1\n0\n0\n', /line 1: the pixel width 0 must be positive/],
    ['1\n0\n0\n0\n0\n0\n', /line 4: the pixel height is 0/],
    ['1e999\n0\n0\n-1\n0\n0\n', /line 1: "1e999" is not a number/],
  ]) {
    assert.throws(() => parseWorldFile(text(body), failAs('w.pgw')), (e) => e instanceof ImageError && e.message.startsWith('w.pgw: ') && problem.test(e.message));
  }
});

test('an image on the field\'s own grid maps each sample to its pixel centre', () => {
  const image = { name: 'same.png', width: 101, height: 51, georef: makeGeoref(UTM, 500000, 4000000, 10, -10, 'GeoTIFF') };
  const p = placeImage(field, image);
  assert.equal(p.how, 'georeferenced');
  assert.equal(p.note, null);
  for (const [c, r] of [[0, 0], [100, 50], [37, 12]]) {
    const [u, v] = uv(p, c, r);
    near(u, (c + 0.5) / 101, `u at column ${c}`); near(v, (r + 0.5) / 51, `v at row ${r}`);
  }
  near(p.coverage, 1, 'coverage');
});

test('a finer image placed by a world file over the west half covers half the field', () => {
  // 2.5 m pixels: 4 per field cell. The image spans x 500000..500500 (the field spans 500000..501000).
  const georef = parseWorldFile(text('2.5\n0\n0\n-2.5\n500001.25\n4000000\n'), failAs('west.pgw'));
  const image = { name: 'west.png', width: 200, height: 201, georef };
  const p = placeImage(field, image);
  assert.match(p.note, /the image names no CRS: taken to be in EPSG:32611/);
  near(p.coverage, 0.5, 'half the field', 1e-3);
  // The field sample at x = 500250 (column 25), y = 3999800 (row 20) is the image's pixel
  // (250 - 1.25) / 2.5 = 99.5 -> between pixels 99 and 100; its texture u is (99.5 + 0.5) / 200.
  const [u, v] = uv(p, 25, 20);
  near(u, 100 / 200, 'u'); near(v, (200 / 2.5 + 0.5) / 201, 'v');
  // Column 60 lies east of the image.
  assert.ok(uv(p, 60, 20)[0] > 1);
});

test('bad placements are refused with a message naming the image', async () => {
  const wgs = { name: 'wgs.tif', width: 100, height: 100, georef: makeGeoref(await resolveCrs(crsOfEpsg(4326)), -117, 36, 0.001, -0.001, 'GeoTIFF') };
  assert.throws(() => placeImage(field, wgs), (e) => e instanceof ImageError &&
    /^wgs\.tif: it lies outside the terrain \(the image spans x -117\.0005\.\.-116\.9005, y 35\.9005\.\.36\.0005, the terrain x 499995\.\.501005/.test(e.message),
  'another CRS is reprojected: this one lies elsewhere');
  const custom = { name: 'lcc.tif', width: 100, height: 100, georef: makeGeoref(await resolveCrs(crsOfEpsg(999999)), 0, 0, 1, -1, 'GeoTIFF') };
  assert.throws(() => placeImage(field, custom), (e) => e instanceof ImageError &&
    /^lcc\.tif: it is in EPSG:999999 and the terrain in EPSG:32611, and EPSG:999999 has no definition to reproject with/.test(e.message));
  const away = { name: 'away.png', width: 100, height: 100, georef: makeGeoref(UNKNOWN_CRS, 900000, 4000000, 1, -1, 'world file') };
  assert.throws(() => placeImage(field, away), (e) => e instanceof ImageError &&
    /^away\.png: it lies outside the terrain \(the image spans x 899999\.5\.\.900099\.5, .* the terrain x 499995\.\.501005, y 3999495\.\.4000005, taking the image to be in EPSG:32611\)$/.test(e.message));
});

test('without a georeference on either side the image is stretched over the field, and says so', () => {
  const plain = { name: 'map.jpg', width: 640, height: 480, georef: null };
  const p = placeImage(field, plain);
  assert.equal(p.how, 'stretched');
  assert.match(p.note, /the image has no georeference: stretched over the whole field/);
  assert.deepEqual(uv(p, 0, 0), [0, 0]);
  assert.deepEqual(uv(p, 100, 50), [1, 1]);
  const q = placeImage({ ...field, georef: null }, { ...plain, georef: field.georef });
  assert.match(q.note, /the terrain has no georeference/);
});
