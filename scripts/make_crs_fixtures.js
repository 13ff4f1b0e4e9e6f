#!/usr/bin/env node
// Writes tests/fixtures/crs/ with GDAL (run once by a developer; the tests read only the
// committed files and need no GDAL: apt-get install -y gdal-bin):
//   node scripts/make_crs_fixtures.js
// - lonlat_gdal.json: latitudes and longitudes of points in national grids, UTM and Web
//   Mercator from gdaltransform, twice: with the EPSG code (the transformation PROJ picks from
//   its database, grids included where installed) and with the PROJ string hexlod's definitions
//   give (lib/crs_definitions.js: the same datum shift, so PROJ and proj4 do the same sums);
// - jacksboro_5070.tif: the real USGS NED Jacksboro fault DEM of
//   tests/fixtures/formats/jacksboro_f32_tiled_lzw.tif (EPSG:4326) warped by GDAL to NAD83 /
//   Conus Albers (EPSG:5070), 100 m, bilinear, Int16: a GeoTIFF whose GeoKeys name its code;
// - jacksboro_custom_esri.tif: the same DEM in a transverse Mercator of no EPSG code (central
//   meridian 84° W on NAD83), written with ESRI's GeoKeys flavour, whose citation holds the WKT;
// - jacksboro_5070_png.png + .png.aux.xml: the 5070 DEM as a 16-bit PNG, which holds no
//   georeference: GDAL writes its CRS and geotransform into the .aux.xml;
// - jacksboro_5070_asc.asc + .prj: as an ESRI ASCII grid (200 m), whose CRS GDAL writes into
//   the .prj as ESRI WKT (no EPSG code in it);
// - prj/: 2056, 27700 and 28992 as gdalsrsinfo writes them: ESRI WKT, OGC WKT1 and WKT2;
// - expected.json: for each DEM, its sample centres' CRS coordinates and GDAL's latitudes and
//   longitudes at a few samples.
import { execFileSync } from 'node:child_process';
import { mkdirSync, rmSync, writeFileSync, readFileSync, existsSync } from 'node:fs';
import { crsDefinition } from '../lib/crs_definitions.js';

const root = new URL('../', import.meta.url).pathname;
const out = `${root}tests/fixtures/crs/`;
const run = (program, args, input) => execFileSync(program, args, { input, encoding: 'utf8', stdio: ['pipe', 'pipe', 'pipe'] });

/** [lon, lat] of each [x, y] by gdaltransform from `source` (an EPSG:N or a PROJ string) to WGS 84. */
function lonLat(source, points) {
  const text = run('gdaltransform', ['-s_srs', source, '-t_srs', 'EPSG:4326', '-output_xy'], points.map((p) => p.join(' ')).join('\n') + '\n');
  return text.trim().split('\n').map((line) => line.trim().split(/\s+/).map(Number));
}

// Points inside each CRS's area (cities and corners of the country), in its own coordinates.
const POINTS = {
  2056: [[2600000, 1200000], [2683000, 1248000], [2624500, 1096000]], // Bern, Zürich, Zermatt
  27700: [[530000, 180000], [325000, 673000], [134000, 25000]], // London, Edinburgh, Land's End
  28992: [[155000, 463000], [121000, 487000], [233000, 582000]], // Amersfoort, Amsterdam, Groningen
  3035: [[4321000, 3210000], [3160000, 2030000], [5250000, 4200000]], // the centre, Madrid, Stockholm
  5070: [[0, 2000000], [1100000, 1500000], [-2000000, 2500000]], // Nebraska, Tennessee, California
  2193: [[1757000, 5920000], [1570000, 5180000], [1749000, 5428000]], // Auckland, Christchurch, Wellington
  32633: [[500000, 5000000], [400000, 5800000], [600000, 4200000]],
  3857: [[1000000, 6000000], [-8237000, 4970000], [15000000, -4000000]],
};

rmSync(out, { recursive: true, force: true });
mkdirSync(`${out}prj`, { recursive: true });
// projinfo without arguments prints PROJ's release first, and its usage, on stderr.
const projRelease = execFileSync('sh', ['-c', 'projinfo 2>&1 | head -1'], { encoding: 'utf8' }).trim();
const versions = { gdal: run('gdalinfo', ['--version']).trim(), proj: projRelease };

const crs = {};
for (const [code, points] of Object.entries(POINTS)) {
  const definition = crsDefinition(Number(code));
  const epsg = lonLat(`EPSG:${code}`, points), same = lonLat(definition.proj4, points);
  crs[code] = { name: definition.name, proj4: definition.proj4,
    points: points.map(([x, y], k) => ({ x, y, epsg: epsg[k], sameShift: same[k] })) };
}
writeFileSync(`${out}lonlat_gdal.json`, JSON.stringify({ made: 'scripts/make_crs_fixtures.js', ...versions, crs }, null, 1) + '\n');

for (const code of [2056, 27700, 28992]) {
  for (const [flavour, format] of [['esri', 'wkt_esri'], ['wkt1', 'wkt1'], ['wkt2', 'wkt2']]) {
    writeFileSync(`${out}prj/epsg${code}_${flavour}.prj`, run('gdalsrsinfo', ['-o', format, `EPSG:${code}`]).trim() + '\n');
  }
}

const source = `${root}tests/fixtures/formats/jacksboro_f32_tiled_lzw.tif`;
const tif = `${out}jacksboro_5070.tif`;
run('gdalwarp', ['-q', '-t_srs', 'EPSG:5070', '-tr', '100', '100', '-tap', '-r', 'bilinear', '-ot', 'Int16', '-dstnodata', '-32768',
  '-co', 'COMPRESS=DEFLATE', source, tif]);
const custom = `${out}jacksboro_custom_esri.tif`;
run('gdalwarp', ['-q', '-t_srs', '+proj=tmerc +lat_0=0 +lon_0=-84 +k=0.9996 +x_0=500000 +y_0=0 +datum=NAD83 +units=m +no_defs',
  '-tr', '100', '100', '-tap', '-r', 'bilinear', '-ot', 'Int16', '-dstnodata', '-32768', '-co', 'COMPRESS=DEFLATE',
  '-co', 'GEOTIFF_KEYS_FLAVOR=ESRI_PE', source, custom]);
const png = `${out}jacksboro_5070_png.png`;
run('gdal_translate', ['-q', '-of', 'PNG', '-ot', 'UInt16', '-a_nodata', 'none', tif, png]);
const asc = `${out}jacksboro_5070_asc.asc`;
run('gdalwarp', ['-q', '-tr', '200', '200', '-r', 'bilinear', '-of', 'AAIGrid', '-ot', 'Int16', tif, asc]);
for (const extra of [`${out}jacksboro_5070_asc.asc.aux.xml`, `${out}jacksboro_5070_png.png.xml`]) if (existsSync(extra)) rmSync(extra);

/** GDAL's CRS coordinates of sample centres and their latitude and longitude (EPSG pipeline). */
function expected(file, samples) {
  const xy = run('gdaltransform', [file], samples.map(([c, r]) => `${c + 0.5} ${r + 0.5}`).join('\n') + '\n')
    .trim().split('\n').map((line) => line.trim().split(/\s+/).slice(0, 2).map(Number));
  const ll = run('gdaltransform', [file, '-t_srs', 'EPSG:4326', '-output_xy'], samples.map(([c, r]) => `${c + 0.5} ${r + 0.5}`).join('\n') + '\n')
    .trim().split('\n').map((line) => line.trim().split(/\s+/).map(Number));
  return samples.map(([column, row], k) => ({ column, row, x: xy[k][0], y: xy[k][1], lon: ll[k][0], lat: ll[k][1] }));
}
const size = (file) => /Size is (\d+), (\d+)/.exec(run('gdalinfo', [file])).slice(1).map(Number);
const dems = {};
for (const file of [tif, custom, png, asc]) {
  const [width, height] = size(file);
  const name = file.slice(out.length);
  dems[name] = { width, height, samples: expected(file, [[0, 0], [Math.floor(width / 2), Math.floor(height / 2)], [width - 1, height - 1]]) };
}
writeFileSync(`${out}expected.json`, JSON.stringify({ made: 'scripts/make_crs_fixtures.js', ...versions, dems }, null, 1) + '\n');
for (const name of Object.keys(dems)) console.log(name, readFileSync(`${out}${name}`).length, 'bytes');
