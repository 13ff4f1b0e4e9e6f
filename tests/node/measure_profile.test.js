// Height profiles (web/measure/profile.js) over the core's field (web/measure/field_sampler.js):
// the heights are the full-resolution samples, bilinear between them, at the right distances
// along the line; climb, descent and slopes add up on fields whose values are known; parts off
// the field are left out and said so.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { createNodeCore } from '../../lib/node_core.js';
import { loadFiles, readInputs } from '../../lib/cli_common.js';
import { fieldSampler, samplerOfArray } from '../../web/measure/field_sampler.js';
import { computeProfile } from '../../web/measure/profile.js';

const fixture = (name) => new URL(`../fixtures/${name}`, import.meta.url).pathname;
const near = (a, b, eps, what) => assert.ok(Math.abs(a - b) <= eps, `${what}: ${a} vs ${b}`);
const core = await createNodeCore();

/** Bilinear height of raw row-major samples at fractional (u, v) samples, written apart from the library's. */
function bilinearOfRaw(raw, width, u, v) {
  const i = Math.min(Math.floor(u), width - 2), j = Math.floor(v);
  const a = raw[j * width + i], b = raw[j * width + i + 1], c = raw[(j + 1) * width + i], d = raw[(j + 1) * width + i + 1];
  const s = u - i, t = v - j;
  return (1 - t) * ((1 - s) * a + s * b) + t * ((1 - s) * c + s * d);
}

/** A core terrain of f32 heights in metres, row-major. */
function coreTerrain(heights, width, height, spacingX, spacingY) {
  const terrain = core.createTerrain(width, height, 'f32');
  terrain.samples().set(heights);
  terrain.setScale({ spacingX, spacingY, heightScale: 1, heightOffset: 0, nodata: null });
  terrain.prepare();
  return terrain;
}

test('profile heights on a real DEM are its samples, bilinear between them, at the distances along the line', async () => {
  // USGS NED 3" around the Jacksboro Fault: 403 x 344 float32 samples, 74.4 m x 92.6 m apart.
  const { terrain, field } = await loadFiles(core, readInputs(fixture('jacksboro_fault.f32')), {});
  const raw = new Float32Array(readFileSync(fixture('jacksboro_fault.f32')).buffer.slice(0));
  const { width } = terrain, sx = terrain.spacingX, sy = terrain.spacingY;
  assert.deepEqual([width, terrain.height, sx, sy], [403, 344, 74.4, 92.6]);
  // Its local metres (its geographic grid is measured on the ellipsoid: measure_ellipsoid.test.js).
  const sampler = fieldSampler(terrain, null);
  assert.ok(field.georef?.crs.geographic, 'a geographic grid');
  const line = [[1000.3, 2000.7], [25000.1, 3000.2], [12000, 28000], [12000, 5000]];
  const profile = computeProfile(line, sampler);
  const { distance, x, z, height } = profile.samples;
  assert.equal(profile.clipped, null);
  assert.equal(profile.step, 74.4, 'the finer spacing is the default step');

  // Every vertex is a sample, at its distance along the line.
  let along = 0;
  for (let v = 0; v < line.length; v++) {
    if (v > 0) along += Math.hypot(line[v][0] - line[v - 1][0], line[v][1] - line[v - 1][1]);
    const k = Array.from(x).findIndex((value, i) => value === line[v][0] && z[i] === line[v][1]);
    assert.ok(k >= 0, `vertex ${v} is a sample`);
    near(distance[k], along, 1e-6, `distance of vertex ${v}`);
  }
  near(distance[distance.length - 1], along, 1e-6, 'the last sample ends the line');
  near(profile.summary.length, along, 1e-6, '2D length');
  for (let k = 1; k < distance.length; k++) {
    const step = distance[k] - distance[k - 1];
    assert.ok(step > 0 && step <= 74.4 + 1e-9, `samples ${k - 1}..${k} are ${step} m apart`);
    near(step, Math.hypot(x[k] - x[k - 1], z[k] - z[k - 1]), 1e-6, `distance ${k} matches the positions`);
  }
  // Heights: the raw float32 samples, bilinear (the core computes in double from the same floats).
  let worst = 0;
  for (let k = 0; k < height.length; k++) worst = Math.max(worst, Math.abs(height[k] - bilinearOfRaw(raw, width, x[k] / sx, z[k] / sy)));
  assert.ok(worst < 1e-3, `heights differ from the raw samples' bilinear by up to ${worst} m`);
  // At a sample, the sample itself.
  near(sampler.heightAt(100 * sx, 200 * sy), raw[200 * width + 100], 1e-4, 'height at sample (100, 200)');
  // The summary against the samples.
  assert.equal(profile.summary.min, Math.min(...height));
  assert.equal(profile.summary.max, Math.max(...height));
  assert.ok(profile.summary.length3d > profile.summary.length);
  assert.ok(profile.summary.gain > 0 && profile.summary.loss > 0);
  terrain.destroy();
});

test('gain, loss, lowest, highest and slopes of a field whose heights are known', () => {
  // One row climbs 0 -> 10, drops to 5, climbs to 20, stays, drops to 0: gain 25, loss 25.
  const row = [0, 10, 5, 20, 20, 0];
  const heights = new Float32Array([...row, ...row]);
  for (const [name, sampler, destroy] of [
    ['array', samplerOfArray(heights, 6, 2, 10, 10), () => {}],
    ['core', ...(() => { const t = coreTerrain(heights, 6, 2, 10, 10); return [fieldSampler(t), () => t.destroy()]; })()],
  ]) {
    const p = computeProfile([[0, 5], [50, 5]], sampler);
    assert.deepEqual(Array.from(p.samples.height), row, `${name}: heights at every sample`);
    assert.deepEqual(Array.from(p.samples.distance), [0, 10, 20, 30, 40, 50], `${name}: distances`);
    const s = p.summary;
    assert.equal(s.gain, 25, `${name} gain`);
    assert.equal(s.loss, 25, `${name} loss`);
    assert.equal(s.min, 0);
    assert.equal(s.max, 20);
    assert.equal(s.length, 50);
    near(s.length3d, Math.hypot(10, 10) + Math.hypot(10, 5) + Math.hypot(10, 15) + 10 + Math.hypot(10, 20), 1e-9, `${name} length3d`);
    near(s.meanSlope, (Math.atan(50 / 50) * 180) / Math.PI, 1e-9, `${name} mean slope, degrees`);
    near(s.steepestSlope, (Math.atan(2) * 180) / Math.PI, 1e-9, `${name} steepest slope, degrees`);
    assert.equal(s.meanSlopeDeg, s.meanSlope);
    // Half steps: bilinear heights between the samples.
    const half = computeProfile([[0, 5], [50, 5]], sampler, { step: 5 });
    assert.deepEqual(Array.from(half.samples.height), [0, 5, 10, 7.5, 5, 12.5, 20, 20, 20, 10, 0], `${name}: half steps`);
    destroy();
  }
});

test('parts of the line off the field are left out, and the note says how much', () => {
  const heights = new Float32Array(11 * 11).map((_, k) => k % 11); // rises 1 m per column
  const sampler = samplerOfArray(heights, 11, 11, 100, 100); // 1 km square
  // 4.5 km drawn: from 1 km west of the field across it, 1 km on east of it, and back 1.5 km
  // (1 km off the field, 0.5 km on it).
  const p = computeProfile([[-1000, 500], [1000, 500], [2000, 500], [500, 500]], sampler);
  assert.equal(p.clipped, '3.00 km of 4.50 km lay outside the field and was left out');
  near(p.summary.length, 1500, 1e-9, 'only the 1.5 km on the field');
  assert.equal(p.samples.distance[0], 1000, 'distances stay those along the drawn line');
  assert.equal(p.samples.runStart[0], 1);
  const back = p.samples.distance.indexOf(4000);
  assert.ok(back > 0 && p.samples.runStart[back] === 1, 'the run back onto the field starts anew');
  assert.equal(p.summary.gain, 10, 'no climb is counted across the gap');
  assert.equal(p.summary.loss, 5);
  for (const [points, message] of [
    [[[2000, 2000], [3000, 3000]], /entirely outside the field \(x 0\.\.1000 m, z 0\.\.1000 m\)/],
    [[[0, 0]], /needs at least 2 points, got 1/],
    [[], /needs at least 2 points, got 0/],
    ['0,0,1,1', /needs at least 2 points/],
    [[[0, 0], [NaN, 5]], /point 2 has no finite coordinates/],
    [[[0, 0], [5]], /point 2 has no finite coordinates/],
  ]) assert.throws(() => computeProfile(points, sampler), message);
  assert.throws(() => computeProfile([[0, 0], [1, 1]], sampler, { step: 0 }), /step must be a positive number/);
});

test('the core sampler has no heights off the field, and an array marks no-data as NaN', () => {
  const terrain = coreTerrain(new Float32Array(16).fill(7), 4, 4, 2, 2);
  const sampler = fieldSampler(terrain);
  assert.deepEqual([sampler.extentX, sampler.extentZ, sampler.spacing, sampler.georef], [6, 6, 2, null]);
  assert.equal(sampler.heightAt(6, 6), 7);
  assert.ok(Number.isNaN(sampler.heightAt(-0.1, 3)) && Number.isNaN(sampler.heightAt(3, 6.1)));
  terrain.destroy();
  const holes = samplerOfArray([1, 2, NaN, 4, 5, 6], 3, 2, 1, 1);
  assert.equal(holes.heightAt(0.5, 0.5), 3);
  assert.ok(Number.isNaN(holes.heightAt(1.5, 0.5)), 'a cell with a missing sample has no height');
});

test('lines crossing the field\'s edges get heights at their entry and exit points, never NaN', () => {
  // Awkward spacings: an entry point computed along the segment may land an ulp off the field.
  const sampler = samplerOfArray(new Float64Array(7 * 5).fill(3), 7, 5, 0.1, 0.3);
  let seed = 5, profiles = 0;
  const random = () => (seed = (seed * 16807) % 2147483647) / 2147483647;
  for (let t = 0; t < 5000; t++) {
    const line = [[random() * 2 - 0.5, random() * 2 - 0.5], [random() * 2 - 0.5, random() * 2 - 0.5]];
    let p;
    try { p = computeProfile(line, sampler); } catch { continue; } // entirely off the field
    profiles++;
    assert.ok(p.samples.height.every((h) => Math.abs(h - 3) < 1e-12), `line ${JSON.stringify(line)}: ${p.samples.height}`);
  }
  assert.ok(profiles > 1000);
});
