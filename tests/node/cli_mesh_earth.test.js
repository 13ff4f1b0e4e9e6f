// hexlod mesh --earth curved: a georeferenced field's mesh on the WGS 84 ellipsoid, in the
// east-up-south frame at the field's centre. A zero-height geographic grid 60° wide and 40°
// tall (an ESRI grid with a WGS 84 .prj) must put every vertex within a metre of the ellipsoid,
// checked with the WGS 84 formulas written here, not the code's own; the vertices must span the
// field from corner to corner; a field without a georeference is refused by name.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync, readFileSync, rmSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const cli = fileURLToPath(new URL('../../bin/hexlod.js', import.meta.url));
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 120000 });
const WGS84_PRJ = 'GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["Degree",0.0174532925199433]]';
let dir;

before(() => {
  dir = mkdtempSync(join(tmpdir(), 'hexlod-earth-'));
  // 121 x 81 samples of 0.5°: sample centres from 29.75° W to 30.25° E and 10.25° N to 50.25° N.
  const row = Array(121).fill('0').join(' ');
  writeFileSync(join(dir, 'zero.asc'), `ncols 121\nnrows 81\nxllcorner -30\nyllcorner 10\ncellsize 0.5\n${Array(81).fill(row).join('\n')}\n`);
  writeFileSync(join(dir, 'zero.prj'), WGS84_PRJ);
});
after(() => rmSync(dir, { recursive: true, force: true }));

// WGS 84, from its definition.
const a = 6378137, f = 1 / 298.257223563, e2 = f * (2 - f), b = a * (1 - f), ep2 = (a * a - b * b) / (b * b);
const rad = Math.PI / 180;
function ecef(lonDeg, latDeg, h) {
  const phi = latDeg * rad, lam = lonDeg * rad, n = a / Math.sqrt(1 - e2 * Math.sin(phi) ** 2);
  return [(n + h) * Math.cos(phi) * Math.cos(lam), (n + h) * Math.cos(phi) * Math.sin(lam), (n * (1 - e2) + h) * Math.sin(phi)];
}
/** Longitude, latitude (degrees) and ellipsoidal height of an Earth-centred point (Bowring's method, iterated). */
function geodetic([x, y, z]) {
  const p = Math.hypot(x, y);
  let phi = Math.atan2(z, p * (1 - e2));
  for (let k = 0; k < 5; k++) {
    const beta = Math.atan2((1 - f) * Math.sin(phi), Math.cos(phi));
    phi = Math.atan2(z + ep2 * b * Math.sin(beta) ** 3, p - e2 * a * Math.cos(beta) ** 3);
  }
  const n = a / Math.sqrt(1 - e2 * Math.sin(phi) ** 2);
  return [Math.atan2(y, x) / rad, phi / rad, p / Math.cos(phi) - n];
}
/** East, up, south metres at the origin (lon0, lat0) back to Earth-centred metres. */
function fromEastUpSouth([east, up, south], lon0, lat0) {
  const o = ecef(lon0, lat0, 0), phi = lat0 * rad, lam = lon0 * rad, north = -south;
  return [
    o[0] - Math.sin(lam) * east - Math.sin(phi) * Math.cos(lam) * north + Math.cos(phi) * Math.cos(lam) * up,
    o[1] + Math.cos(lam) * east - Math.sin(phi) * Math.sin(lam) * north + Math.cos(phi) * Math.sin(lam) * up,
    o[2] + Math.cos(phi) * north + Math.sin(phi) * up,
  ];
}

test('a zero-height field 60° x 40° exported on the curved Earth: every vertex within 1 m of the ellipsoid, corner to corner', () => {
  const obj = join(dir, 'zero.obj'), json = join(dir, 'zero.json');
  const result = run('mesh', join(dir, 'zero.asc'), '--max-error', '1', '--earth', 'curved', '--obj', obj, '--json', json);
  assert.equal(result.status, 0, result.stderr);
  const text = readFileSync(obj, 'utf8');
  assert.match(text, /# metres on the WGS 84 ellipsoid: x east, y up, z south of 30\.25000° N 0\.25000° E/);
  const vertices = text.split('\n').filter((l) => l.startsWith('v ')).map((l) => l.slice(2).split(' ').map(Number));
  assert.ok(vertices.length >= 4, `${vertices.length} vertices`);
  // The field's centre sample: column 60, row 40.
  const places = vertices.map((v) => geodetic(fromEastUpSouth(v, 0.25, 30.25)));
  const worst = Math.max(...places.map(([, , h]) => Math.abs(h)));
  assert.ok(worst <= 1, `every vertex within 1 m of the ellipsoid (worst ${worst.toFixed(3)} m)`);
  const lons = places.map(([lon]) => lon), lats = places.map(([, lat]) => lat);
  const near = (got, want) => Math.abs(got - want) < 1e-6;
  assert.ok(near(Math.min(...lons), -29.75) && near(Math.max(...lons), 30.25), `longitudes ${Math.min(...lons)} to ${Math.max(...lons)}`);
  assert.ok(near(Math.min(...lats), 10.25) && near(Math.max(...lats), 50.25), `latitudes ${Math.min(...lats)} to ${Math.max(...lats)}`);
  // Curved, not flat: the corners lie hundreds of kilometres below the centre's tangent plane.
  const lowest = Math.min(...vertices.map((v) => v[1]));
  assert.ok(lowest < -500e3, `the corners drop below the tangent plane (${(lowest / 1000).toFixed(0)} km)`);
  assert.equal(JSON.parse(readFileSync(json, 'utf8')).settings.earth, 'curved');
});

test('the default is as the page draws: curved with a georeference, flat without; --earth flat flattens it, a bad --earth is refused', () => {
  const byDefault = join(dir, 'default.json');
  const curved = run('mesh', join(dir, 'zero.asc'), '--max-error', '1', '--json', byDefault);
  assert.equal(curved.status, 0, curved.stderr);
  assert.equal(JSON.parse(readFileSync(byDefault, 'utf8')).settings.earth, 'curved');
  const obj = join(dir, 'flat.obj'), json = join(dir, 'flat.json');
  const flat = run('mesh', join(dir, 'zero.asc'), '--max-error', '1', '--earth', 'flat', '--obj', obj, '--json', json);
  assert.equal(flat.status, 0, flat.stderr);
  assert.equal(JSON.parse(readFileSync(json, 'utf8')).settings.earth, 'flat');
  const ys = readFileSync(obj, 'utf8').split('\n').filter((l) => l.startsWith('v ')).map((l) => Number(l.split(' ')[2]));
  assert.ok(ys.every((y) => y === 0), 'flat: every height 0');

  const volcano = fileURLToPath(new URL('../fixtures/volcano_maungawhau.png', import.meta.url));
  const volcanoJson = join(dir, 'volcano.json');
  const plain = run('mesh', volcano, '--max-error', '1', '--json', volcanoJson);
  assert.equal(plain.status, 0, plain.stderr);
  assert.equal(JSON.parse(readFileSync(volcanoJson, 'utf8')).settings.earth, 'flat', 'no georeference: flat by default');
  const bare = run('mesh', volcano, '--max-error', '1', '--earth', 'curved', '--obj', join(dir, 'v.obj'));
  assert.equal(bare.status, 1);
  assert.match(bare.stderr, /^hexlod: volcano_maungawhau\.png: --earth curved needs a georeferenced field/);
  const bad = run('mesh', join(dir, 'zero.asc'), '--max-error', '1', '--earth', 'round');
  assert.equal(bad.status, 2);
  assert.match(bad.stderr, /--earth is flat or curved, not 'round'/);
});
