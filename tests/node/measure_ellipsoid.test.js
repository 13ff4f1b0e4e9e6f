// Measuring on a geographic grid (longitude and latitude) happens on the WGS 84 ellipsoid
// (web/measure/ground_metric.js): a grid's local metres take its centre row's east-west spacing,
// which is wrong by the ratio of cosines elsewhere. Checked against arc lengths and areas
// integrated numerically here from the ellipsoid's radii of curvature, not the code's closed forms.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { computeProfile } from '../../web/measure/profile.js';
import { measurePolygon, measurePath } from '../../web/measure/polygon_area.js';
import { samplerOfArray } from '../../web/measure/field_sampler.js';

const A = 6378137, F = 1 / 298.257223563, E2 = F * (2 - F), RAD = Math.PI / 180;
const N = (phi) => A / Math.sqrt(1 - E2 * Math.sin(phi) ** 2);
const M = (phi) => (A * (1 - E2)) / (1 - E2 * Math.sin(phi) ** 2) ** 1.5;
/** Simpson's rule over [a, b] in 2000 steps. */
function integrate(f, a, b) {
  const n = 2000, h = (b - a) / n;
  let sum = f(a) + f(b);
  for (let i = 1; i < n; i++) sum += (i % 2 ? 4 : 2) * f(a + i * h);
  return (sum * h) / 3;
}

// A flat (zero-height) grid of 0.05 degree cells from 55 N to 65 N and 10 E to 20 E, whose local
// metres are those of its centre row (60 N), as the loaders give a geographic grid.
const cells = 200, step = 0.05;
const spacingX = step * RAD * N(60 * RAD) * Math.cos(60 * RAD), spacingY = step * RAD * M(60 * RAD);
const georef = { crs: { epsg: 4326, label: 'EPSG:4326', name: null, proj4: null, geographic: true }, x0: 10, y0: 65, dx: step, dy: -step, from: 'test' };
const sampler = { ...samplerOfArray(new Float64Array((cells + 1) ** 2), cells + 1, cells + 1, spacingX, spacingY), georef };
const xOf = (lon) => ((lon - 10) / step) * spacingX, zOf = (lat) => ((65 - lat) / step) * spacingY;

test('a line along a parallel and one along a meridian measure their arcs on the ellipsoid', () => {
  for (const lat of [56, 60, 64]) {
    const along = computeProfile([[xOf(11), zOf(lat)], [xOf(19), zOf(lat)]], sampler);
    const arc = 8 * RAD * N(lat * RAD) * Math.cos(lat * RAD);
    assert.ok(Math.abs(along.summary.length - arc) < 1e-6 * arc, `${lat} N: ${along.summary.length} m, the parallel's arc ${arc} m`);
    assert.ok(Math.abs(along.samples.distance.at(-1) - arc) < 1e-6 * arc, 'the chart\'s distances too');
  }
  const meridian = computeProfile([[xOf(15), zOf(56)], [xOf(15), zOf(64)]], sampler);
  const arc = integrate(M, 56 * RAD, 64 * RAD);
  assert.ok(Math.abs(meridian.summary.length - arc) < 1e-6 * arc, `${meridian.summary.length} m against ${arc} m`);
  const path = measurePath([[xOf(11), zOf(64)], [xOf(19), zOf(64)]], sampler);
  assert.ok(Math.abs(path.straight - 8 * RAD * N(64 * RAD) * Math.cos(64 * RAD)) < 1, `straight ${path.straight}`);
});

test('an area of 8 x 8 degrees is the ellipsoid\'s, not the centre row\'s metres squared', () => {
  const ring = [[xOf(11), zOf(64)], [xOf(19), zOf(64)], [xOf(19), zOf(56)], [xOf(11), zOf(56)]];
  const { planimetric, surface } = measurePolygon(ring, sampler);
  const expected = 8 * RAD * integrate((phi) => M(phi) * N(phi) * Math.cos(phi), 56 * RAD, 64 * RAD);
  assert.ok(Math.abs(planimetric - expected) < 1e-6 * expected, `${planimetric} m² against ${expected} m²`);
  // A flat field's surface is its area, cell by cell on the ellipsoid.
  assert.ok(Math.abs(surface - expected) < 1e-4 * expected, `surface ${surface} m² against ${expected} m²`);
  // South of the centre row its metres are too narrow: 56 to 60 N by them is 3.5 % short.
  const south = [[xOf(11), zOf(60)], [xOf(19), zOf(60)], [xOf(19), zOf(56)], [xOf(11), zOf(56)]];
  const band = 8 * RAD * integrate((phi) => M(phi) * N(phi) * Math.cos(phi), 56 * RAD, 60 * RAD);
  const flat = (xOf(19) - xOf(11)) * (zOf(56) - zOf(60));
  assert.ok(flat < 0.97 * band, `by the centre row's metres ${flat} m², on the ellipsoid ${band} m²`);
  assert.ok(Math.abs(measurePolygon(south, sampler).planimetric - band) < 1e-6 * band);
});

test('a projected grid is measured in its own metres', () => {
  const utm = { ...sampler, georef: { ...georef, crs: { epsg: 32633, label: 'EPSG:32633', name: null, proj4: null, geographic: false } } };
  const line = computeProfile([[0, 0], [3000, 4000]], utm);
  assert.equal(line.summary.length, 5000);
});
