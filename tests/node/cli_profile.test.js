// hexlod profile, run as a user runs it: the summary, the CSV read back, lines in the file's
// CRS, and one clear line with exit code 2 for every mistake in the command line.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const cli = fileURLToPath(new URL('../../bin/hexlod.js', import.meta.url));
const fixture = (name) => fileURLToPath(new URL(`../fixtures/${name}`, import.meta.url));
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 60000 });

/** The CSV's comment lines as {key: value} and its rows as objects of numbers. */
function readCsv(text) {
  const lines = text.trimEnd().split('\n');
  const comments = {}, rows = [];
  let header = null;
  for (const line of lines) {
    if (line.startsWith('# ')) {
      const [key, ...rest] = line.slice(2).split(' ');
      comments[key] = rest.join(' ');
    } else if (!header) {
      header = line.split(',');
    } else {
      const cells = line.split(',').map(Number);
      rows.push(Object.fromEntries(header.map((name, k) => [name, cells[k]])));
    }
  }
  return { comments, header, rows };
}

test('hexlod profile prints the summary and writes the samples as CSV', () => {
  const out = join(mkdtempSync(join(tmpdir(), 'hexlod-profile-')), 'profile.csv');
  // The Maungawhau volcano: 87 x 61 samples 10 m apart, 94 .. 195 m; a line over its crater rim.
  const r = run('profile', fixture('volcano_maungawhau.png'), '--line', '50,300,430,300,430,100', '--csv', out);
  assert.equal(r.status, 0, r.stderr);
  assert.equal(r.stderr, '');
  assert.match(r.stdout, /^file\s+volcano_maungawhau\.png \(87 x 61 samples, 10 x 10 m\)$/m);
  assert.match(r.stdout, /^length\s+580 m on the map, [\d.]+ m along the ground$/m);
  assert.match(r.stdout, /^climb\s+gain [\d.]+ m, loss [\d.]+ m$/m);
  assert.match(r.stdout, /^heights\s+[\d.]+ \.\. [\d.]+ m$/m);
  assert.match(r.stdout, /^slope\s+mean [\d.]+°, steepest [\d.]+°/m);
  assert.match(r.stdout, /^samples\s+59, every 10 m at most$/m);
  assert.match(r.stdout, /^csv\s+.*profile\.csv \(59 rows\)$/m);
  assert.doesNotMatch(r.stdout, /clipped/);

  const { comments, header, rows } = readCsv(readFileSync(out, 'utf8'));
  assert.deepEqual(header, ['distance_m', 'x_m', 'z_m', 'height_m'], 'no CRS: local metres only');
  assert.equal(rows.length, 59);
  assert.equal(comments.length_m, '580');
  assert.equal(comments.crs, 'none (local metres)');
  assert.deepEqual(rows[0], { distance_m: 0, x_m: 50, z_m: 300, height_m: rows[0].height_m });
  assert.deepEqual([rows[38].distance_m, rows[38].x_m, rows[38].z_m], [380, 430, 300], 'the corner vertex');
  assert.deepEqual([rows[58].distance_m, rows[58].x_m, rows[58].z_m], [580, 430, 100]);
  // The printed heights and the CSV agree.
  const heights = rows.map((row) => row.height_m);
  const [, low, high] = /heights\s+([\d.]+) \.\. ([\d.]+) m/.exec(r.stdout);
  assert.equal(Math.min(...heights).toFixed(1), low);
  assert.equal(Math.max(...heights).toFixed(1), high);
  assert.ok(Math.min(...heights) >= 94 && Math.max(...heights) <= 195);
  let gain = 0;
  for (let k = 1; k < heights.length; k++) gain += Math.max(0, heights[k] - heights[k - 1]);
  assert.ok(Math.abs(gain - Number(comments.gain_m)) < 0.05, `gain from the rows ${gain} vs ${comments.gain_m}`);
});

test('hexlod profile --crs takes the line in the file\'s CRS and writes its coordinates', () => {
  const out = join(mkdtempSync(join(tmpdir(), 'hexlod-profile-')), 'utm.csv');
  // everest_utm45.tif: sample centres from easting 410500, northing 3189500, 1000 m apart; a
  // line from 20 km west of the field to a point on it.
  const r = run('profile', fixture('measure/everest_utm45.tif'), '--crs', '--line', '390500,3089500,490500,3089500', '--csv', out, '--step', '500');
  assert.equal(r.status, 0, r.stderr);
  assert.match(r.stdout, /^from\s+E 410 500 m N 3 089 500 m \(EPSG:32645\) · 27\.\d{4}° N 86\.\d{4}° E$/m);
  assert.match(r.stdout, /^to\s+E 490 500 m N 3 089 500 m \(EPSG:32645\) · 27\.9304° N 86\.9034° E$/m);
  assert.match(r.stdout, /^clipped\s+20\.0 km of 100\.0 km lay outside the field and was left out$/m);
  const { comments, header, rows } = readCsv(readFileSync(out, 'utf8'));
  assert.deepEqual(header, ['distance_m', 'x_m', 'z_m', 'easting_m', 'northing_m', 'lon', 'lat', 'height_m']);
  assert.equal(comments.crs, 'EPSG:32645');
  assert.match(comments.clipped, /^20\.0 km of 100\.0 km/);
  assert.equal(rows.length, 161, '80 km every 500 m');
  assert.deepEqual([rows[0].distance_m, rows[0].easting_m, rows[0].x_m, rows[0].z_m], [20000, 410500, 0, 100000]);
  const last = rows[rows.length - 1];
  assert.deepEqual([last.easting_m, last.northing_m], [490500, 3089500]);
  // GDAL: 490500 3089500 -> 86.9034411736594 27.930434207429
  assert.ok(Math.abs(last.lon - 86.9034411736594) < 1e-8 && Math.abs(last.lat - 27.930434207429) < 1e-8);
});

test('mistakes in the command line exit 2 with one clear line; a missing file exits 1 as for every command', () => {
  const volcano = fixture('volcano_maungawhau.png');
  for (const [args, message] of [
    [[volcano, '--line', '1,2,3'], /--line needs X,Y pairs, got 3 numbers/],
    [[volcano, '--line', '1,2'], /--line needs at least 2 points \(4 numbers\), got 2/],
    [[volcano, '--line', '1,2,east,4'], /--line must be numbers X0,Y0,X1,Y1,\.\.\.: 'east' is not a number/],
    [[volcano, '--line', '1,2,,4'], /'' is not a number/],
    [[volcano, '--line', '5000,5000,6000,6000'], /--line: the line lies entirely outside the field \(x 0\.\.860 m, z 0\.\.600 m\)/],
    [[volcano, '--line', '1,2,3,4', '--crs'], /--crs: volcano_maungawhau\.png has no georeference/],
    [[volcano, '--line', '1,2,3,4', '--step', '0'], /--step must be greater than 0/],
    [[volcano, '--line', '1,2,3,4', '--step', 'fine'], /--step must be a number/],
    [[volcano], /profile needs --line/],
    [['--line', '1,2,3,4'], /profile takes exactly one height field file/],
  ]) {
    const r = run('profile', ...args);
    assert.equal(r.status, 2, `${args}: ${r.stderr}`);
    assert.match(r.stderr, message, args.join(' '));
    assert.match(r.stderr, /^hexlod: [^\n]*; usage: hexlod profile <heightfield> \(--line /);
    assert.equal(r.stderr.trim().split('\n').length, 1, `one line: ${r.stderr}`);
    assert.equal(r.stdout, '');
  }
  const missing = run('profile', join(tmpdir(), 'no-such-dem.tif'), '--line', '1,2,3,4');
  assert.equal(missing.status, 1);
  assert.match(missing.stderr, /^hexlod: .*no-such-dem\.tif: no such file\n$/);
  const help = run('profile', '--help');
  assert.equal(help.status, 0);
  assert.match(help.stdout, /--line X0,Y0,X1,Y1/);
  assert.match(run('--help').stdout, /hexlod profile <heightfield>/);
});
