// web/geo/earth_shape.js: the page's twin of the core's curved Earth (src/lod/earth_shape.h).
// Its points against WGS 84 by web/geo/earth_frame.js (geodetic to Earth-centred, then the
// origin's east-up-south frame), flatPoint() undoing drawnPoint(), and the shape a terrain gets
// from its georeference.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { EARTH_FLAT, EARTH_GEOGRAPHIC, EARTH_SPHERE, drawnAxes, drawnPoint, drawnUp, earthShapeOf, flatPoint, meanRadius }
  from '../../web/geo/earth_shape.js';
import { eastUpSouthAt } from '../../web/geo/earth_frame.js';
import { crsOfEpsg } from '../../web/geo/georef.js';

const DEG = Math.PI / 180;

// A geographic grid of 0.01 degree cells, 2001 x 1001 samples, its first sample at 20 W, 60 N.
const geographicGrid = { width: 2001, height: 1001, spacingX: 0.01 * DEG * 6378137 * Math.cos(55 * DEG), spacingY: 0.01 * DEG * 6367000 };
const geographicRef = { crs: { ...crsOfEpsg(4326, true), geographic: true }, x0: -20, y0: 60, dx: 0.01, dy: -0.01, from: 'test' };

test('a geographic grid is drawn where WGS 84 puts each sample, rows at their own latitude', () => {
  const earth = earthShapeOf(geographicRef, geographicGrid);
  assert.equal(earth.kind, EARTH_GEOGRAPHIC);
  assert.ok(Math.abs(earth.latitude0 / DEG - 55) < 1e-9, 'the origin is the grid centre, 55 N');
  const frame = eastUpSouthAt(-10, 55);
  for (const [column, row, height] of [[0, 0, 0], [2000, 1000, 8000], [1000, 500, -400], [1733, 91, 1200], [5, 999, 30]]) {
    const x = column * geographicGrid.spacingX, z = row * geographicGrid.spacingY;
    const lon = -20 + 0.01 * column, lat = 60 - 0.01 * row;
    const expected = frame(lon, lat, height);
    const got = drawnPoint(earth, x, height, z);
    for (let k = 0; k < 3; k++) assert.ok(Math.abs(got[k] - expected[k]) < 1e-4, `sample ${column},${row}: ${got} against ${expected}`);
    // Back to the same flat point.
    const back = flatPoint(earth, got);
    assert.ok(Math.abs(back[0] - x) < 1e-4 && Math.abs(back[1] - height) < 1e-4 && Math.abs(back[2] - z) < 1e-4, `${back}`);
    // Up: where a metre of height moves the point.
    const above = drawnPoint(earth, x, height + 1, z), up = drawnUp(earth, x, z);
    for (let k = 0; k < 3; k++) assert.ok(Math.abs(above[k] - got[k] - up[k]) < 1e-6);
  }
  // A row's east-west spacing follows its latitude: cos(60) / cos(50) of the south edge's.
  const width = (row) => Math.hypot(...drawnPoint(earth, 2000 * geographicGrid.spacingX, 0, row * geographicGrid.spacingY)
    .map((v, k) => v - drawnPoint(earth, 0, 0, row * geographicGrid.spacingY)[k]));
  const ratio = width(0) / width(1000);
  assert.ok(Math.abs(ratio - Math.cos(60 * DEG) / Math.cos(50 * DEG)) < 0.01, `north edge / south edge ${ratio}`);
});

test('a projected grid is wrapped on a sphere of the mean radius there, distances from its centre kept', () => {
  const utm = { crs: { ...crsOfEpsg(32633), proj4: '+proj=utm +zone=33 +datum=WGS84 +units=m +no_defs' }, x0: 300000,
    y0: 5200000, dx: 100, dy: -100, from: 'test' };
  const grid = { width: 4001, height: 4001, spacingX: 100, spacingY: 100 };
  const earth = earthShapeOf(utm, grid);
  assert.equal(earth.kind, EARTH_SPHERE);
  assert.ok(Math.abs(earth.radius - meanRadius(earth.latitude0)) < 1e-6);
  assert.ok(earth.latitude0 / DEG > 44 && earth.latitude0 / DEG < 47, `centre latitude ${earth.latitude0 / DEG}`);
  const centre = [0, -earth.radius, 0];
  for (const [x, h, z] of [[0, 0, 0], [400000, 3000, 0], [123456, -50, 398765]]) {
    const p = drawnPoint(earth, x, h, z);
    assert.ok(Math.abs(Math.hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]) - (earth.radius + h)) < 1e-6);
    const angle = Math.acos((p[1] - centre[1]) / (earth.radius + h));
    assert.ok(Math.abs(angle * earth.radius - Math.hypot(x - earth.originX, z - earth.originZ)) < 1e-3);
    const back = flatPoint(earth, p);
    assert.ok(Math.abs(back[0] - x) < 1e-5 && Math.abs(back[1] - h) < 1e-5 && Math.abs(back[2] - z) < 1e-5, `${back}`);
  }
});

test('without a georeference, or with a centre off the Earth, a terrain stays flat', () => {
  assert.equal(earthShapeOf(null, geographicGrid).kind, EARTH_FLAT);
  const offEarth = { ...geographicRef, y0: 200 };
  assert.equal(earthShapeOf(offEarth, geographicGrid).kind, EARTH_FLAT);
  const p = drawnPoint(earthShapeOf(null, geographicGrid), 1, 2, 3);
  assert.deepEqual([...p], [1, 2, 3]);
});

// The terrain's vertex shader draws each vertex from an anchor near the eye (shaders/terrain.vert,
// web/render/shading/eye_anchor.js): in the anchor's own tangent frame, as a shape whose origin
// is the anchor, then turned by the anchor's axes and moved to the anchor's place. That is the
// same point as from the field's centre: the ellipsoid is the same whatever meridian is first.
test('a geographic grid drawn from an anchor: its axes turn the anchor frame\'s points onto the centre frame\'s', () => {
  const earth = earthShapeOf(geographicRef, geographicGrid);
  const axes = new Float64Array(9), anchorPoint = [0, 0, 0];
  for (const [ax, az] of [[0, 0], [1900 * geographicGrid.spacingX, 37 * geographicGrid.spacingY], [700 * geographicGrid.spacingX, 990 * geographicGrid.spacingY]]) {
    const anchored = { ...earth, originX: ax, originZ: az, latitude0: earth.latitude0 - (az - earth.originZ) / earth.metresPerRadianZ };
    drawnAxes(earth, ax, az, axes);
    drawnPoint(earth, ax, 0, az, anchorPoint);
    // Orthonormal, and up is the surface's up.
    const column = (c) => [axes[3 * c], axes[3 * c + 1], axes[3 * c + 2]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    for (let a = 0; a < 3; a++) for (let b = 0; b < 3; b++) assert.ok(Math.abs(dot(column(a), column(b)) - (a === b ? 1 : 0)) < 1e-12);
    const up = drawnUp(earth, ax, az);
    for (let k = 0; k < 3; k++) assert.ok(Math.abs(column(1)[k] - up[k]) < 1e-12, 'the anchor\'s up');
    for (const [dx, dz, h] of [[0, 0, 100], [3000, -2000, 5000], [-25000, 40000, -300], [400 * geographicGrid.spacingX, 0, 0]]) {
      const x = ax + dx, z = az + dz, local = drawnPoint(anchored, x, h, z), expected = drawnPoint(earth, x, h, z);
      for (let k = 0; k < 3; k++) {
        const got = anchorPoint[k] + axes[k] * local[0] + axes[3 + k] * local[1] + axes[6 + k] * local[2];
        assert.ok(Math.abs(got - expected[k]) < 1e-6, `anchor (${ax}, ${az}), point (${x}, ${h}, ${z}): ${got} against ${expected[k]}`);
      }
    }
  }
  // The plane and the sphere: their own axes.
  assert.deepEqual([...drawnAxes(earthShapeOf(null, geographicGrid), 5, 7, axes)], [1, 0, 0, 0, 1, 0, 0, 0, 1]);
});
