// Real GDAL-made DEMs in CRSs other than WGS 84 and UTM (tests/fixtures/crs/, made by
// scripts/make_crs_fixtures.js): each opens with its EPSG code (or its own WKT), its name, and
// GDAL's coordinates and latitudes and longitudes (expected.json, gdaltransform), whether the
// CRS comes from its GeoKeys, a WKT in its GeoKeys citation, an .aux.xml or a .prj; in the
// loaders and in `hexlod info` and `hexlod profile --crs`. A sidecar that cannot be read is a
// note, never the end of the file. Tolerance for latitude and longitude: 1e-7 degrees (all these
// CRSs are on NAD83, which GDAL and our definitions both take as WGS 84: no shift to differ).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { copyFileSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadHeightfield } from '../../web/loaders/index.js';
import { geoCoordinates, sampleToCrs } from '../../web/geo/index.js';
import { useNodeCrsDefinitions } from '../../lib/crs_definitions.js';

useNodeCrsDefinitions();

const DIR = new URL('../fixtures/crs/', import.meta.url);
const path = (name) => fileURLToPath(new URL(name, DIR));
const file = (name, as = name) => ({ name: as, bytes: new Uint8Array(readFileSync(new URL(name, DIR))) });
const EXPECTED = JSON.parse(readFileSync(new URL('expected.json', DIR), 'utf8')).dems;
const DEG = 1e-7;
const near = (a, b, eps, what) => assert.ok(Math.abs(a - b) <= eps, `${what}: ${a} vs ${b}`);
const cli = fileURLToPath(new URL('../../bin/hexlod.js', import.meta.url));
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 60000 });

/** The field's samples at GDAL's CRS coordinates and latitudes and longitudes. */
function assertPlaces(field, name) {
  const { width, height, samples } = EXPECTED[name];
  assert.deepEqual([field.width, field.height], [width, height], name);
  for (const { column, row, x, y, lon, lat } of samples) {
    const [cx, cy] = sampleToCrs(field.georef, column, row);
    near(cx, x, 1e-6, `${name} x of (${column}, ${row})`), near(cy, y, 1e-6, `${name} y of (${column}, ${row})`);
    const c = geoCoordinates(field.georef, column * field.spacingX, row * field.spacingY, field.spacingX, field.spacingY);
    near(c.lon, lon, DEG, `${name} lon of (${column}, ${row})`), near(c.lat, lat, DEG, `${name} lat of (${column}, ${row})`);
  }
}

test('a GDAL GeoTIFF in NAD83 / Conus Albers: EPSG:5070 by its GeoKeys, named, with GDAL\'s latitudes and longitudes', async () => {
  const field = await loadHeightfield([file('jacksboro_5070.tif')]);
  const { crs } = field.georef;
  assert.deepEqual([crs.epsg, crs.label, crs.name, crs.geographic], [5070, 'EPSG:5070', 'NAD83 / Conus Albers', false]);
  assert.deepEqual([field.spacingX, field.spacingY, field.notes], [100, 100, []]);
  assertPlaces(field, 'jacksboro_5070.tif');
});

test('a user-defined GeoTIFF CRS with ESRI\'s WKT in its citation is that WKT\'s CRS', async () => {
  const field = await loadHeightfield([file('jacksboro_custom_esri.tif')]);
  const { crs } = field.georef;
  assert.deepEqual([crs.epsg, crs.label], [null, 'custom (unknown from the WKT)']);
  assert.match(crs.proj4, /^PROJCS\["unknown",.*PROJECTION\["Transverse_Mercator"\].*"Central_Meridian",-84\.0\]/);
  assertPlaces(field, 'jacksboro_custom_esri.tif');
});

test('a PNG with GDAL\'s .aux.xml: placed by its geotransform, in its SRS\'s CRS, spaced by its steps', async () => {
  const field = await loadHeightfield([file('jacksboro_5070_png.png'), file('jacksboro_5070_png.png.aux.xml')]);
  assert.deepEqual([field.georef.crs.epsg, field.georef.from, field.spacingX, field.spacingY, field.spacingFromFile], [5070, '.aux.xml', 100, 100, true]);
  assertPlaces(field, 'jacksboro_5070_png.png');
  // x.aux.xml beside x.png is GDAL's other name for it.
  const short = await loadHeightfield([file('jacksboro_5070_png.png'), file('jacksboro_5070_png.png.aux.xml', 'jacksboro_5070_png.aux.xml')]);
  assert.equal(short.georef.crs.epsg, 5070);
});

test('an ESRI ASCII grid with its .prj (ESRI WKT, no code): a custom CRS, GDAL\'s latitudes and longitudes', async () => {
  const field = await loadHeightfield([file('jacksboro_5070_asc.asc'), file('jacksboro_5070_asc.prj')]);
  const { crs } = field.georef;
  assert.deepEqual([crs.epsg, crs.label, crs.name], [null, 'custom (NAD_1983_Contiguous_USA_Albers from the WKT)', 'NAD_1983_Contiguous_USA_Albers']);
  assert.deepEqual([field.spacingX, field.spacingY], [200, 200]);
  assertPlaces(field, 'jacksboro_5070_asc.asc');
  // Without its .prj the grid names no CRS.
  const bare = await loadHeightfield([file('jacksboro_5070_asc.asc')]);
  assert.deepEqual([bare.georef.crs.label, bare.georef.crs.proj4], ['unknown', null]);
});

test('an ASCII grid in degrees by its .prj, though its numbers look like metres, is spaced in metres on the ground', async () => {
  const asc = new TextEncoder().encode('ncols 4\nnrows 3\nxllcorner 8\nyllcorner 46\ncellsize 0.5\n1 2 3 4\n5 6 7 8\n9 10 11 12\n');
  const prj = new TextEncoder().encode('GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433],AUTHORITY["EPSG","4326"]]');
  const bare = await loadHeightfield([{ name: 'alps.asc', bytes: asc }]);
  assert.equal(bare.spacingX, 0.5, 'a 0.5 cell is taken for metres without its .prj');
  const field = await loadHeightfield([{ name: 'alps.asc', bytes: asc }, { name: 'alps.prj', bytes: prj }]);
  assert.deepEqual([field.georef.crs.epsg, field.geographic], [4326, true]);
  near(field.spacingY, 55597, 1, 'half a degree of latitude in metres');
  near(field.spacingX, 55597 * Math.cos((46.75 * Math.PI) / 180), 1, 'half a degree of longitude at 46.75° N');
});

test('sidecars that cannot be read, or belong to another file, are notes: the height field still opens', async () => {
  const garbage = { name: 'jacksboro_5070_asc.prj', bytes: new TextEncoder().encode('PROJCS["My grid",PROJECTION["Nope"]]') };
  const field = await loadHeightfield([file('jacksboro_5070_asc.asc'), garbage, file('jacksboro_5070_png.png.aux.xml', 'other.aux.xml')]);
  assert.equal(field.georef.crs.label, 'unknown');
  assert.deepEqual(field.notes, [
    'other.aux.xml: belongs to no height field here (jacksboro_5070_asc.asc is not its grid); not used',
    'jacksboro_5070_asc.prj: proj4 cannot read the CRS "My grid" in it (PROJCS[...] without an EPSG code); write it with one (e.g. gdalsrsinfo -o wkt1 EPSG:NNNN); not used',
  ]);
  // A GeoTIFF that names its CRS keeps it; a sidecar naming another is a note.
  const tif = await loadHeightfield([file('jacksboro_5070.tif'), { name: 'jacksboro_5070.prj', bytes: readFileSync(new URL('prj/epsg2056_wkt1.prj', DIR)) }]);
  assert.equal(tif.georef.crs.epsg, 5070);
  assert.deepEqual(tif.notes, ['jacksboro_5070.tif names EPSG:5070 itself and its sidecar EPSG:2056: the file\'s is used']);
});

test('hexlod info and profile --crs: the code, the name, and GDAL\'s latitudes and longitudes', () => {
  const info = run('info', path('jacksboro_5070.tif'));
  assert.equal(info.status, 0, info.stderr);
  assert.match(info.stdout, /^crs {6}EPSG:5070 NAD83 \/ Conus Albers$/m);
  assert.match(info.stdout, /^centre {3}E 1 041 050 m N 1 569 100 m \(EPSG:5070\) · 36\.58\d\d° N 84\.226\d° W$/m);
  const json = JSON.parse(run('info', path('jacksboro_5070.tif'), '--json').stdout);
  assert.deepEqual([json.crs.epsg, json.crs.name, json.crs.definition, json.crs.geographic], [5070, 'NAD83 / Conus Albers', true, false]);
  // The .prj beside an ASCII grid is read with it.
  const asc = run('info', path('jacksboro_5070_asc.asc'));
  assert.match(asc.stdout, /^crs {6}custom \(NAD_1983_Contiguous_USA_Albers from the WKT\) NAD_1983_Contiguous_USA_Albers$/m);

  const { samples } = EXPECTED['jacksboro_5070.tif'];
  const [first, , last] = samples;
  const r = run('profile', path('jacksboro_5070.tif'), '--crs', '--line', `${first.x},${first.y},${last.x},${last.y}`);
  assert.equal(r.status, 0, r.stderr);
  const deg = (v, ns) => `${Math.abs(v).toFixed(4)}° ${v < 0 ? ns[1] : ns[0]}`;
  assert.match(r.stdout, new RegExp(`^from +E 1 030 750 m N 1 579 050 m \\(EPSG:5070\\) · ${deg(first.lat, 'NS')} ${deg(first.lon, 'EW')}$`, 'm'));
  assert.match(r.stdout, new RegExp(`^to +E 1 051 350 m N 1 559 150 m \\(EPSG:5070\\) · ${deg(last.lat, 'NS')} ${deg(last.lon, 'EW')}$`, 'm'));
});

test('hexlod mesh --image reads the .prj beside the image: its CRS is no longer assumed', () => {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-prj-'));
  const imagery = (name) => fileURLToPath(new URL(`../fixtures/imagery/${name}`, import.meta.url));
  for (const name of ['bmng_himalaya_4arcmin.jpg', 'bmng_himalaya_4arcmin.jgw']) copyFileSync(imagery(name), join(dir, name));
  const terrain = fileURLToPath(new URL('../../public/terrain/globe_himalaya_2048.png', import.meta.url));
  const mesh = () => run('mesh', terrain, '--max-error', '3000', '--obj', join(dir, 'm.obj'), '--json', join(dir, 'm.json'),
    '--image', join(dir, 'bmng_himalaya_4arcmin.jpg'));
  const assumed = mesh();
  assert.equal(assumed.status, 0, assumed.stderr);
  assert.match(assumed.stdout, /\(the image names no CRS: taken to be in EPSG:4326\)/);
  writeFileSync(join(dir, 'bmng_himalaya_4arcmin.prj'), 'GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,298.257223563]],' +
    'PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433],AUTHORITY["EPSG",4326]]');
  const named = mesh();
  assert.equal(named.status, 0, named.stderr);
  assert.doesNotMatch(named.stdout, /names no CRS/);
  const report = JSON.parse(readFileSync(join(dir, 'm.json'), 'utf8'));
  assert.deepEqual([report.image.prj, report.image.crs, report.image.placement], ['bmng_himalaya_4arcmin.prj', 'EPSG:4326', 'georeferenced']);
});
