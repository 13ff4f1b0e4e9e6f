// Areas and lengths (web/measure/polygon_area.js): exact on a level and a tilted plane (the
// surface is the map area / cos(tilt)) for convex and concave polygons, additive on rough
// ground (so the clipping of cells along the edges loses nothing), strided past the cell cap,
// and clear refusals of polygons that cannot be measured.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { samplerOfArray } from '../../web/measure/field_sampler.js';
import { measurePolygon, measurePath, MAX_AREA_CELLS } from '../../web/measure/polygon_area.js';

const near = (a, b, eps, what) => assert.ok(Math.abs(a - b) <= eps * Math.max(1, Math.abs(b)), `${what}: ${a} vs ${b}`);

/** A plane h = h0 + gx * x + gz * z sampled on a width x height grid. */
function plane(width, height, sx, sy, gx, gz, h0 = 100) {
  const a = new Float64Array(width * height);
  for (let j = 0; j < height; j++) for (let i = 0; i < width; i++) a[j * width + i] = h0 + gx * i * sx + gz * j * sy;
  return samplerOfArray(a, width, height, sx, sy);
}

// An L: a 1487 x 983 m box less a notch, corners off the sample grid.
const L = [[13, 17], [1500, 22], [1500, 900], [800, 900], [800, 300], [300, 300], [300, 1000], [13, 1000]];
const shoelace = (p) => Math.abs(p.reduce((s, a, k) => s + a[0] * p[(k + 1) % p.length][1] - p[(k + 1) % p.length][0] * a[1], 0)) / 2;
const perimeterOf = (p) => p.reduce((s, a, k) => s + Math.hypot(p[(k + 1) % p.length][0] - a[0], p[(k + 1) % p.length][1] - a[1]), 0);

test('on a level plane the surface is the map area, for a square and a concave polygon', () => {
  const sampler = plane(201, 151, 10, 7, 0, 0);
  const square = measurePolygon([[100, 100], [600, 100], [600, 600], [100, 600]], sampler);
  assert.deepEqual([square.planimetric, square.perimeter, square.clipped, square.note], [250000, 2000, null, null]);
  near(square.surface, 250000, 1e-12, 'square surface');
  near(square.perimeter3d, 2000, 1e-12, 'square perimeter along the ground');
  const l = measurePolygon(L, sampler);
  near(l.planimetric, shoelace(L), 1e-12, 'L map area');
  near(l.surface, shoelace(L), 1e-12, 'L surface');
  near(l.perimeter, perimeterOf(L), 1e-12, 'L perimeter');
  const reversed = measurePolygon([...L].reverse(), sampler);
  near(reversed.surface, l.surface, 1e-12, 'either winding');
});

test('on a tilted plane the surface is the map area / cos(tilt), convex or concave', () => {
  const gx = 0.3, gz = -0.2, secant = Math.sqrt(1 + gx * gx + gz * gz); // 1 / cos(tilt)
  const sampler = plane(201, 151, 10, 7, gx, gz);
  for (const [name, polygon] of [['L', L], ['triangle', [[5.5, 3.2], [1800.1, 400.7], [900.3, 1040]]],
    ['star', star(1000, 500, 450, 180, 7)]]) {
    const m = measurePolygon(polygon, sampler);
    near(m.planimetric, shoelace(polygon), 1e-12, `${name} map area`);
    near(m.surface, shoelace(polygon) * secant, 1e-12, `${name} surface = map area / cos(tilt)`);
    assert.ok(m.perimeter3d > m.perimeter, `${name}: the ground perimeter climbs`);
  }
  // A path along x climbs gx per metre.
  const path = measurePath([[0, 0], [100, 0], [100, 50]], sampler);
  near(path.straight, 150, 1e-12, 'straight length');
  near(path.ground, 100 * Math.hypot(1, gx) + 50 * Math.hypot(1, gz), 1e-12, 'ground length');
  assert.equal(path.clipped, null);
});

/** A concave star of `points` tips around (cx, cz). */
function star(cx, cz, outer, inner, points) {
  return Array.from({ length: 2 * points }, (_, k) => {
    const r = k % 2 ? inner : outer, a = (Math.PI * k) / points;
    return [cx + r * Math.cos(a), cz + r * Math.sin(a)];
  });
}

test('on rough ground a box\'s surface is the sum of its parts: no cell along an edge is lost or counted twice', () => {
  let seed = 7;
  const random = () => (seed = (seed * 16807) % 2147483647) / 2147483647;
  const heights = Float64Array.from({ length: 60 * 50 }, () => random() * 30);
  const sampler = samplerOfArray(heights, 60, 50, 10, 10);
  const box = measurePolygon([[13.3, 17.7], [455.5, 17.7], [455.5, 401.2], [13.3, 401.2]], sampler);
  const notch = measurePolygon([[200.1, 101.7], [300.9, 101.7], [300.9, 401.2], [200.1, 401.2]], sampler);
  const rest = measurePolygon([[13.3, 17.7], [455.5, 17.7], [455.5, 401.2], [300.9, 401.2], [300.9, 101.7], [200.1, 101.7], [200.1, 401.2], [13.3, 401.2]], sampler);
  near(notch.surface + rest.surface, box.surface, 1e-12, 'notch + L = box');
  const lower = measurePolygon([[13.3, 17.7], [455.5, 17.7], [455.5, 401.2]], sampler);
  const upper = measurePolygon([[13.3, 17.7], [455.5, 401.2], [13.3, 401.2]], sampler);
  near(lower.surface + upper.surface, box.surface, 1e-12, 'two triangles = box');
  assert.ok(box.surface > box.planimetric * 1.1, 'rough ground has more surface than map');
  // Whole cells: the box over every cell is the sum of every triangle's area.
  const all = measurePolygon([[0, 0], [590, 0], [590, 490], [0, 490]], sampler);
  let triangles = 0;
  const h = (i, j) => heights[j * 60 + i];
  const area3 = (a, b, c) => {
    const u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]], v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    return Math.hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]) / 2;
  };
  for (let j = 0; j < 49; j++) {
    for (let i = 0; i < 59; i++) {
      const a = [i * 10, h(i, j), j * 10], b = [i * 10 + 10, h(i + 1, j), j * 10];
      const c = [i * 10 + 10, h(i + 1, j + 1), j * 10 + 10], d = [i * 10, h(i, j + 1), j * 10 + 10];
      triangles += area3(a, b, c) + area3(a, c, d);
    }
  }
  near(all.surface, triangles, 1e-12, 'the whole field = the sum of its triangles (diagonal from (i, j) to (i + 1, j + 1))');
});

test('a polygon partly off the field is measured on the field; a huge one strides and says so', () => {
  const sampler = plane(101, 101, 10, 10, 0.5, 0);
  const half = measurePolygon([[-500, 0], [500, 0], [500, 500], [-500, 500]], sampler);
  assert.equal(half.planimetric, 250000);
  near(half.surface, 250000 * Math.hypot(1, 0.5), 1e-12, 'the part on the field');
  assert.equal(half.clipped, '250000 m² of 500000 m² lay outside the field and was left out');
  // 2001 x 2001 samples: 4 million cells, past the cap.
  const big = plane(2001, 2001, 1, 1, 0.5, 0.25);
  const m = measurePolygon(star(1000, 1000, 990, 400, 5), big);
  assert.ok(MAX_AREA_CELLS < 4e6);
  assert.equal(m.note, `surface from every 2nd sample: the area spans more than ${MAX_AREA_CELLS} cells`);
  near(m.surface, m.planimetric * Math.sqrt(1 + 0.25 + 0.0625), 1e-12, 'still exact on a plane');
});

test('polygons that cannot be measured are refused with a clear message', () => {
  const sampler = plane(11, 11, 10, 10, 0, 0);
  for (const [points, message] of [
    [[[0, 0], [10, 0]], /needs at least 3 points, got 2/],
    [[[0, 0], [10, 0], [0, 0]], /at least 3 distinct points, got 2/],
    [[[0, 0], [10, 10], [10, 0], [0, 10]], /edges must not cross: edge 1 and edge 3 meet/],
    [[[0, 0], [50, 0], [50, 50], [20, 50], [20, -10]], /edges must not cross/],
    [[[0, 0], [10, 0], [20, 0]], /edges must not cross|lie on one line/],
    [[[200, 200], [300, 200], [300, 300]], /entirely outside the field/],
    [[[0, 0], [10, Infinity], [5, 5]], /point 2 has no finite coordinates/],
    [null, /needs at least 3 points, got 0/],
  ]) assert.throws(() => measurePolygon(points, sampler), message, JSON.stringify(points));
  // A closed ring (first point repeated) is the same polygon.
  assert.equal(measurePolygon([[0, 0], [50, 0], [50, 50], [0, 0]], sampler).planimetric, 1250);
});

test('random polygons on a tilted plane, partly off the field and with corners on grid lines: surface = map area / cos(tilt)', () => {
  let seed = 3;
  const random = () => (seed = (seed * 16807) % 2147483647) / 2147483647;
  const gx = 0.7, gz = -0.4, secant = Math.sqrt(1 + gx * gx + gz * gz);
  const sampler = plane(61, 47, 10, 7, gx, gz, 0);
  for (let t = 0; t < 300; t++) {
    // A star-shaped polygon (simple by construction), its corners snapped to sample lines in half the cases.
    const n = 3 + Math.floor(random() * 12), cx = random() * 600, cz = random() * 322, snap = random() < 0.5;
    const points = Array.from({ length: n }, (_, k) => {
      const angle = (2 * Math.PI * (k + random() * 0.8)) / n, r = 5 + random() * 250;
      const x = cx + r * Math.cos(angle), z = cz + r * Math.sin(angle);
      return snap ? [Math.round(x / 10) * 10, Math.round(z / 7) * 7] : [x, z];
    });
    const m = measurePolygon(points, sampler);
    near(m.surface, m.planimetric * secant, 1e-12, `polygon ${t}: ${JSON.stringify(points)}`);
  }
});
