// A track of a user's file on the real Everest DEM, read as a person reads it: `hexlod profile
// --track` writes every vertex of the track to the CSV with its lon/lat, the DEM's height there
// (checked against a bilinear interpolation of the GeoTIFF's own samples, read here with the
// geotiff package and projected with proj4, not through the product's loaders or geo module)
// and the recorded elevation and time; the camera path of a flight along it follows it, above the
// ground; a regression flight takes its keyframes from the track.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { fromArrayBuffer } from 'geotiff';
import proj4 from 'proj4';
import { trackKeyframes } from '../../web/overlays/track_flight.js';
import { samplerOfArray } from '../../web/measure/field_sampler.js';
import { computeTrackProfile } from '../../web/measure/track_profile.js';

const cli = fileURLToPath(new URL('../../bin/hexlod.js', import.meta.url));
const fixture = (name) => fileURLToPath(new URL(`../fixtures/${name}`, import.meta.url));
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });
const expected = JSON.parse(readFileSync(fixture('overlays/expected.json'), 'utf8'));
const trackXml = readFileSync(fixture('overlays/everest_trek.gpx'), 'utf8');
const trkpts = [...trackXml.matchAll(/<trkpt lat="([^"]+)" lon="([^"]+)"><ele>([^<]+)<\/ele><time>([^<]+)<\/time>/g)]
  .map((m) => ({ lat: Number(m[1]), lon: Number(m[2]), ele: Number(m[3]), time: m[4] }));

function readCsv(text) {
  const lines = text.trimEnd().split('\n').filter((l) => !l.startsWith('#'));
  const header = lines[0].split(',');
  return lines.slice(1).map((line) => Object.fromEntries(line.split(',').map((v, k) => [header[k], v])));
}

test('hexlod profile --track: every vertex in the CSV, heights bilinear at its lon/lat, recorded elevations and times beside them', async () => {
  const out = join(mkdtempSync(join(tmpdir(), 'hexlod-track-')), 'trek.csv');
  const r = run('profile', fixture('measure/everest_utm45.tif'), '--track', fixture('overlays/everest_trek.gpx'), '--csv', out);
  assert.equal(r.status, 0, r.stderr);
  assert.match(r.stdout, /^track\s+everest_trek\.gpx \(GPX\), line 1 of 2: Everest Base Camp trek, 400 points$/m);
  assert.match(r.stdout, /^ {2}\* 1 {2}Everest Base Camp trek \(track, 400 points\)$/m);
  assert.match(r.stdout, /recorded gain \d+\.\d m, loss \d+\.\d m/);
  assert.match(r.stdout, /^time\s+10\.14 h; mean speed \d\.\d\d km\/h, moving \d\.\d\d km\/h$/m, '399 fixes 90 s apart and a 10 min stop');
  const rows = readCsv(readFileSync(out, 'utf8'));
  const vertexRows = rows.filter((row) => row.vertex !== '');
  assert.equal(vertexRows.length, trkpts.length, 'every vertex of the track is a row');
  vertexRows.forEach((row, k) => {
    assert.equal(Number(row.vertex), k);
    assert.ok(Math.abs(Number(row.lon) - trkpts[k].lon) < 1e-7 && Math.abs(Number(row.lat) - trkpts[k].lat) < 1e-7, `vertex ${k}'s lon/lat`);
    assert.equal(Number(row.gps_elevation_m), trkpts[k].ele);
    assert.equal(row.time, new Date(trkpts[k].time).toISOString());
  });
  // The DEM's own samples, read and projected independently of the product.
  const tiff = await (await fromArrayBuffer(readFileSync(fixture('measure/everest_utm45.tif')).buffer)).getImage();
  const [samples] = await tiff.readRasters();
  const width = tiff.getWidth(), [x0, , , y0] = [expected.dem.geotransform[0], 0, 0, expected.dem.geotransform[3]];
  const toUtm = proj4('+proj=longlat +datum=WGS84 +no_defs', '+proj=utm +zone=45 +datum=WGS84 +units=m +no_defs');
  let checked = 0;
  for (const row of rows) {
    const [e, n] = toUtm.forward([Number(row.lon), Number(row.lat)]);
    const c = (e - x0) / 1000 - 0.5, r2 = (y0 - n) / 1000 - 0.5;
    const i = Math.floor(c), j = Math.floor(r2), fu = c - i, fv = r2 - j;
    const s = [samples[j * width + i], samples[j * width + i + 1], samples[(j + 1) * width + i], samples[(j + 1) * width + i + 1]];
    if (s.some((v) => v === -32768)) continue; // a void the loaders fill by interpolation
    const bilinear = (s[0] * (1 - fu) + s[1] * fu) * (1 - fv) + (s[2] * (1 - fu) + s[3] * fu) * fv;
    assert.ok(Math.abs(Number(row.height_m) - bilinear) < 0.05, `at ${row.lon}, ${row.lat}: ${row.height_m} vs ${bilinear}`);
    checked++;
  }
  assert.ok(checked > 300, `${checked} rows checked against the GeoTIFF's samples`);
});

test('hexlod profile --track refuses clearly: no line, off the terrain, no such line, a broken file, no georeference', () => {
  const fail = (pattern, ...args) => {
    const r = run('profile', ...args);
    assert.equal(r.status, 2, r.stderr);
    assert.match(r.stderr, pattern);
  };
  const dem = fixture('measure/everest_utm45.tif');
  fail(/line 1 \(Mont Blanc\): the line lies entirely outside the field/, dem, '--track', fixture('overlays/off_terrain_alps.gpx'));
  fail(/--feature 9: .* has 3 lines/, dem, '--track', fixture('overlays/everest_places.kml'), '--feature', '9');
  fail(/a KMZ without a KML document inside/, dem, '--track', fixture('overlays/bad_no_kml.kmz'));
  fail(/takes --line or --track, not both/, dem, '--track', fixture('overlays/everest_trek.gpx'), '--line', '0,0,1,1');
  fail(/has no georeference/, fixture('volcano_maungawhau.png'), '--track', fixture('overlays/everest_trek.gpx'));
  const noLine = join(mkdtempSync(join(tmpdir(), 'hexlod-track-')), 'points.geojson');
  writeFileSync(noLine, JSON.stringify({ type: 'Point', coordinates: [86.9, 27.9] }));
  fail(/it has no line/, dem, '--track', noLine);
});

test('the profile of a track keeps every vertex and interpolates the recorded values between them', () => {
  const sampler = samplerOfArray(new Float32Array(11 * 11).map((_, k) => k % 11), 11, 11, 10, 10);
  const placed = { x: Float64Array.of(0, 35, 35), z: Float64Array.of(0, 0, 40) };
  const source = { z: Float64Array.of(100, 135, NaN), t: Float64Array.of(0, 35000, 75000) };
  const p = computeTrackProfile(placed, source, sampler);
  assert.deepEqual(Array.from(p.samples.vertex).filter((v) => v >= 0), [0, 1, 2]);
  const at = (d) => Array.from(p.samples.distance).indexOf(d);
  assert.deepEqual(Array.from(p.samples.distance), [0, 8.75, 17.5, 26.25, 35, 45, 55, 65, 75], 'equal steps of at most the spacing');
  assert.equal(p.samples.gpsElevation[at(8.75)], 108.75);
  assert.equal(p.samples.time[at(65)], 65000);
  assert.ok(Number.isNaN(p.samples.gpsElevation[at(75)]));
  assert.equal(p.summary.duration, 75);
  assert.equal(p.summary.gpsGain, 35);
  assert.ok(Math.abs(p.summary.averageSpeed - p.summary.length3d / 75) < 1e-12);
});

test('a flight along a track follows it at its height above the ground, looking ahead, at its speed or by its times', () => {
  const sampler = samplerOfArray(new Float32Array(101 * 101).map((_, k) => 100 * Math.sin(k / 37)), 101, 101, 10, 10);
  const n = 200, x = new Float64Array(n), z = new Float64Array(n), t = new Float64Array(n);
  for (let k = 0; k < n; k++) {
    x[k] = 100 + 3 * k;
    z[k] = 500 + 200 * Math.sin(k / 30);
    t[k] = 1e12 + k * 2000 + (k > 100 ? 60000 : 0); // a minute's stop half way
  }
  const keys = trackKeyframes({ x, z }, { t }, sampler.heightAt, { height: 120, lookAhead: 80, speed: 20, extentX: 1000, extentZ: 1000 });
  for (let i = 1; i < keys.length; i++) assert.ok(keys[i].time > keys[i - 1].time);
  // The distance from a point to the track's polyline.
  const near = (p) => {
    let d = Infinity;
    for (let k = 1; k < n; k++) {
      const ex = x[k] - x[k - 1], ez = z[k] - z[k - 1], s = Math.max(0, Math.min(1, ((p[0] - x[k - 1]) * ex + (p[2] - z[k - 1]) * ez) / (ex * ex + ez * ez)));
      d = Math.min(d, Math.hypot(x[k - 1] + ex * s - p[0], z[k - 1] + ez * s - p[2]));
    }
    return d;
  };
  let total = 0;
  for (let k = 1; k < n; k++) total += Math.hypot(x[k] - x[k - 1], z[k] - z[k - 1]);
  for (const k of keys) {
    assert.ok(near(k.position) < 1e-6, 'the eye is over the track');
    assert.ok(k.position[1] >= sampler.heightAt(k.position[0], k.position[2]) + 120 - 1e-9, 'at least the height above the ground');
    if (k.time * 20 + 80 <= total) assert.ok(near(k.target) < 1e-6, 'it looks at the track ahead');
    assert.ok(Math.hypot(k.target[0] - k.position[0], k.target[2] - k.position[2]) > 10, 'ahead, not down');
  }
  assert.ok(Math.abs(keys.at(-1).time * 20 - total) < 1e-6, 'the whole track at 20 m/s');
  const byTimes = trackKeyframes({ x, z }, { t }, sampler.heightAt, { height: 120, lookAhead: 80, speed: null });
  assert.ok(Math.abs(byTimes.at(-1).time - (t[n - 1] - t[0]) / 1000) < 1e-6, 'the track\'s own duration');
  assert.throws(() => trackKeyframes({ x, z }, { t: null }, sampler.heightAt, { speed: null }), /no times to fly by/);
});

test('a regression flight takes its keyframes from a track, and refuses a missing one as bad input', () => {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-track-flight-'));
  const flight = join(dir, 'trek.flight.json');
  writeFileSync(flight, JSON.stringify({ dem: fixture('measure/everest_utm45.tif'), fps: 5, viewport: [64, 36],
    track: { file: fixture('overlays/everest_trek.gpx'), height: 500, speed: 4000, lookAhead: 3000 }, overlays: [fixture('overlays/everest_places.kml')] }));
  const update = run('regress', flight, '--node-only', '--update', '--refs', join(dir, 'refs'), '--out', join(dir, 'out'));
  assert.equal(update.status, 0, update.stdout + update.stderr);
  const stats = JSON.parse(readFileSync(join(dir, 'out', 'trek', 'stats.json'), 'utf8'));
  const keys = stats.spec.keyframes;
  assert.ok(keys.length > 10);
  assert.equal(stats.frames, Math.floor(keys.at(-1).time * 5 + 1e-9) + 1);
  // The camera starts over Lukla (GDAL's pixel of the track's first vertex), 500 m above the ground or more.
  const first = expected.track.vertices[0];
  assert.ok(Math.abs(keys[0].position[0] - first.column * 1000) < 1e-6 && Math.abs(keys[0].position[2] - first.row * 1000) < 1e-6);
  assert.ok(keys[0].position[1] > 2500 + 500);
  assert.deepEqual(stats.spec.overlays, [fixture('overlays/everest_places.kml')]);
  const again = run('regress', flight, '--node-only', '--refs', join(dir, 'refs'), '--out', join(dir, 'out'));
  assert.equal(again.status, 0, again.stdout);
  writeFileSync(flight, JSON.stringify({ dem: fixture('measure/everest_utm45.tif'), track: 'missing.gpx' }));
  const missing = run('regress', flight, '--node-only', '--update', '--refs', join(dir, 'refs'), '--out', join(dir, 'out'));
  assert.equal(missing.status, 2);
  assert.match(missing.stdout + missing.stderr, /its track .*missing\.gpx: no such file/);
});
