// Area and perimeter of a polygon drawn on the field, on the map and along the ground, and the
// length of an open path both ways. On a geographic grid "the map" is the WGS 84 ellipsoid
// (ground_metric.js).
//
// The ground is taken as the field's triangles: each sample cell split along its diagonal from
// (column, row) to (column + 1, row + 1) into two planar triangles. A triangle's surface is its
// map area times 1 / cos(its tilt), so the part of it inside the polygon (clipped exactly) adds
// that part's map area times the same factor: exact for a plane, whatever the polygon's shape.
// Cells wholly inside the polygon (most of a large one) take both triangles without clipping;
// only cells an edge passes through are clipped. Rows of cells are classified by the crossings
// of the polygon's edges with the row's centre line (even-odd), after marking the cells the
// edges pass through.
//
// A polygon whose bounding box covers more than MAX_AREA_CELLS cells is measured on a coarser
// grid: every s-th sample in both directions (the field's own samples, not averages), and
// `note` says so.
import { clipHalfPlane, clipRectangle, signedArea } from './clip.js';
import { checkPoints } from './points.js';
import { computeProfile } from './profile.js';
import { formatArea } from './units.js';
import { ellipsoidArea, groundMetric } from './ground_metric.js';

/** Pieces a path's segment is summed over on the ellipsoid (a metre in 10,000 km at 256). */
const STRAIGHT_PIECES = 256;

/** Most cells (of the polygon's bounding box) a surface area visits before it strides. */
export const MAX_AREA_CELLS = 1_000_000;

/**
 * @param {number[][]} points [[x, z], ...] local metres, the polygon's corners in order (at
 *   least 3; the first need not be repeated at the end), not self-intersecting
 * @param {import('./field_sampler.js').FieldSampler} sampler
 * @returns {{planimetric: number, surface: number, perimeter: number, perimeter3d: number,
 *   clipped: string|null, note: string|null}} square metres on the map and on the ground,
 *   metres around on the map and along the ground; all of the part on the field (clipped says
 *   how much lay outside), note when the surface was measured on a coarser grid
 * @throws {Error} fewer than 3 points, coordinates that are not finite numbers, edges that
 *   cross, no area, or a polygon entirely off the field
 */
export function measurePolygon(points, sampler) {
  checkPoints(points, 3, 'an area');
  const ring = openRing(points);
  if (ring.length < 3) throw new Error(`an area needs at least 3 distinct points, got ${ring.length}`);
  checkSimple(ring);
  const whole = Math.abs(signedArea(ring));
  if (!(whole > 0)) throw new Error('an area needs points that enclose some ground: these lie on one line');
  const onField = clipRectangle(ring, 0, 0, sampler.extentX, sampler.extentZ);
  // On a geographic grid, square metres of the WGS 84 ellipsoid (ground_metric.js).
  const metric = groundMetric(sampler);
  const mapArea = (polygon) => (metric ? ellipsoidArea(polygon, metric) : Math.abs(signedArea(polygon)));
  const planimetric = onField.length >= 3 ? mapArea(onField) : 0;
  if (!(planimetric > 0)) {
    throw new Error(`the area lies entirely outside the field (x 0..${sampler.extentX.toFixed(1)} m, z 0..${sampler.extentZ.toFixed(1)} m)`);
  }
  const { surface, stride } = surfaceArea(onField, sampler, metric);
  const around = computeProfile([...ring, ring[0]], sampler);
  const cut = (metric ? ellipsoidArea(ring, metric) : whole) - planimetric;
  const clipped = cut > 1e-6 * whole ? `${formatArea(cut)} of ${formatArea(whole)} lay outside the field and was left out` : null;
  const note = stride > 1 ? `surface from every ${ordinal(stride)} sample: the area spans more than ${MAX_AREA_CELLS} cells` : null;
  return { planimetric, surface, perimeter: around.summary.length, perimeter3d: around.summary.length3d, clipped, note };
}

/**
 * The length of an open path on the map and along the ground.
 * @param {number[][]} points [[x, z], ...] local metres, at least 2
 * @param {import('./field_sampler.js').FieldSampler} sampler
 * @returns {{straight: number, ground: number, clipped: string|null}} straight: metres, the sum
 *   of the segments' map lengths (the whole path); ground: metres along the surface of the part
 *   on the field (the profile's length3d); clipped: how much lay off the field, or null
 * @throws {Error} as computeProfile
 */
export function measurePath(points, sampler) {
  const profile = computeProfile(points, sampler);
  const metric = groundMetric(sampler), stretch = [1, 1];
  let straight = 0;
  for (let k = 1; k < points.length; k++) {
    const [ax, az] = points[k - 1], [bx, bz] = points[k];
    if (!metric) {
      straight += Math.hypot(bx - ax, bz - az);
      continue;
    }
    // On the ellipsoid the stretch changes along a segment: summed over short pieces of it.
    for (let i = 0; i < STRAIGHT_PIECES; i++) {
      metric.stretch(az + (bz - az) * (i + 0.5) / STRAIGHT_PIECES, stretch);
      straight += Math.hypot((bx - ax) * stretch[0], (bz - az) * stretch[1]) / STRAIGHT_PIECES;
    }
  }
  return { straight, ground: profile.summary.length3d, clipped: profile.clipped };
}

/** 2 -> '2nd', 3 -> '3rd', 11 -> '11th'. */
function ordinal(n) {
  const tens = n % 100, units = n % 10;
  const suffix = tens >= 11 && tens <= 13 ? 'th' : units === 1 ? 'st' : units === 2 ? 'nd' : units === 3 ? 'rd' : 'th';
  return `${n}${suffix}`;
}

/** The polygon without a repeated closing point or repeated consecutive points. */
function openRing(points) {
  const ring = [];
  for (const p of points) {
    const last = ring[ring.length - 1];
    if (!last || last[0] !== p[0] || last[1] !== p[1]) ring.push([p[0], p[1]]);
  }
  while (ring.length > 1 && ring[0][0] === ring[ring.length - 1][0] && ring[0][1] === ring[ring.length - 1][1]) ring.pop();
  return ring;
}

/** Throws when two edges cross or touch other than at their shared corner. */
function checkSimple(ring) {
  const n = ring.length;
  for (let a = 0; a < n; a++) {
    const p = ring[a], q = ring[(a + 1) % n];
    for (let b = a + 1; b < n; b++) {
      const r = ring[b], s = ring[(b + 1) % n];
      const adjacent = b === a + 1 || (a === 0 && b === n - 1);
      if (adjacent ? foldsBack(p, q, r, s, b === a + 1) : segmentsMeet(p, q, r, s)) {
        throw new Error(`an area's edges must not cross: edge ${a + 1} and edge ${b + 1} meet`);
      }
    }
  }
}

/** Two edges that share a corner overlap (the outline doubles back along itself). */
function foldsBack(p, q, r, s, qIsShared) {
  const [corner, u, v] = qIsShared ? [q, p, s] : [p, q, r];
  const ux = u[0] - corner[0], uz = u[1] - corner[1], vx = v[0] - corner[0], vz = v[1] - corner[1];
  return ux * vz - uz * vx === 0 && ux * vx + uz * vz > 0;
}

function segmentsMeet(p, q, r, s) {
  const d1 = orient(r, s, p), d2 = orient(r, s, q), d3 = orient(p, q, r), d4 = orient(p, q, s);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 === 0 && within(r, s, p)) || (d2 === 0 && within(r, s, q)) || (d3 === 0 && within(p, q, r)) || (d4 === 0 && within(p, q, s));
}

const orient = (a, b, c) => (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
const within = (a, b, c) => Math.min(a[0], b[0]) <= c[0] && c[0] <= Math.max(a[0], b[0]) && Math.min(a[1], b[1]) <= c[1] && c[1] <= Math.max(a[1], b[1]);

/**
 * Surface area in square metres of a polygon on the field (all of it inside [0, extentX] x
 * [0, extentZ]), over the field's triangles, every `stride`-th sample.
 */
function surfaceArea(polygon, sampler, metric) {
  const stretch = [1, 1]; // ground metres per local metre east and south in the row (ground_metric.js)
  const { spacingX, spacingY, extentX, extentZ } = sampler;
  let minX = Infinity, maxX = -Infinity, minZ = Infinity, maxZ = -Infinity;
  for (const [x, z] of polygon) minX = Math.min(minX, x), maxX = Math.max(maxX, x), minZ = Math.min(minZ, z), maxZ = Math.max(maxZ, z);
  const boxCells = (Math.ceil(maxX / spacingX) - Math.floor(minX / spacingX)) * (Math.ceil(maxZ / spacingY) - Math.floor(minZ / spacingY));
  const stride = Math.max(1, Math.ceil(Math.sqrt(boxCells / MAX_AREA_CELLS)));
  // Grid lines every `stride` samples; the last column and row of cells end at the field's edge.
  const cellW = stride * spacingX, cellH = stride * spacingY;
  const lastI = Math.ceil(extentX / cellW - 1e-9) - 1, lastJ = Math.ceil(extentZ / cellH - 1e-9) - 1;
  const lineX = (i) => Math.min(i * cellW, extentX), lineZ = (j) => Math.min(j * cellH, extentZ);
  const i0 = Math.max(0, Math.floor(minX / cellW)), i1 = Math.min(lastI, Math.floor(maxX / cellW));
  const j0 = Math.max(0, Math.floor(minZ / cellH)), j1 = Math.min(lastJ, Math.floor(maxZ / cellH));
  const columns = i1 - i0 + 2;
  let above = nodeRow(sampler, j0, i0, columns, lineX, lineZ), below = null;
  const boundary = new Uint8Array(columns);
  let surface = 0;
  for (let j = j0; j <= j1; j++) {
    below = nodeRow(sampler, j + 1, i0, columns, lineX, lineZ);
    const z0 = lineZ(j), z1 = lineZ(j + 1);
    if (metric) metric.stretch(0.5 * (z0 + z1), stretch);
    const [sx, sz] = stretch, groundShare = sx * sz; // one row spans a sample's latitude: one stretch
    const strip = clipHalfPlane(clipHalfPlane(polygon, 0, -1, -z0), 0, 1, z1);
    if (strip.length < 3) {
      above = below;
      continue;
    }
    markCrossedCells(strip, boundary, i0, i1, cellW, z0, z1);
    const inside = centreCrossings(polygon, (z0 + z1) / 2);
    for (let i = i0; i <= i1; i++) {
      const x0 = lineX(i), x1 = lineX(i + 1), c = i - i0;
      // Corners: a (x0, z0), b (x1, z0), c (x1, z1), d (x0, z1); triangles a-b-c and a-c-d.
      const ha = above[c], hb = above[c + 1], hc = below[c + 1], hd = below[c];
      const lower = groundShare * slopeFactor((x1 - x0) * sx, (z1 - z0) * sz, hb - ha, hc - hb);
      const upper = groundShare * slopeFactor((x1 - x0) * sx, (z1 - z0) * sz, hc - hd, hd - ha);
      if (boundary[c]) {
        const cell = clipHalfPlane(clipHalfPlane(strip, -1, 0, -x0), 1, 0, x1);
        if (cell.length < 3) continue;
        // The diagonal a -> c: the lower triangle is on its +x side.
        const nx = z1 - z0, nz = -(x1 - x0), offset = nx * x0 + nz * z0;
        const aLower = Math.abs(signedArea(clipHalfPlane(cell, -nx, -nz, -offset)));
        const aUpper = Math.abs(signedArea(clipHalfPlane(cell, nx, nz, offset)));
        surface += aLower * lower + aUpper * upper;
      } else if (isInside(inside, (x0 + x1) / 2)) {
        const half = ((x1 - x0) * (z1 - z0)) / 2;
        surface += half * (lower + upper);
      }
    }
    boundary.fill(0);
    above = below;
  }
  return { surface, stride };
}

/** Heights at the grid nodes of row j, columns i0 .. i0 + count - 1. */
function nodeRow(sampler, j, i0, count, lineX, lineZ) {
  const row = new Float64Array(count), z = lineZ(j);
  for (let c = 0; c < count; c++) row[c] = sampler.heightAt(lineX(i0 + c), z);
  return row;
}

/**
 * Surface / map area of a triangle of a cell w x h metres: the lower one (a-b-c) rises dx along
 * its x edge (a-b) and dz along its z edge (b-c); the upper one (a-c-d) dx along d-c and dz
 * along a-d. Both are planes with gradient (dx / w, dz / h).
 */
function slopeFactor(w, h, dx, dz) {
  const gx = dx / w, gz = dz / h;
  const factor = Math.sqrt(1 + gx * gx + gz * gz);
  return Number.isFinite(factor) ? factor : 1; // no-data: counted as flat
}

/**
 * Marks the cells (columns) of a row strip that an edge of the strip's polygon passes through.
 * Edges along the strip's top or bottom line are left out: they lie on cell borders (clipping
 * made them, or the polygon has an edge there), so the cells beside them are wholly on one side.
 */
function markCrossedCells(strip, boundary, i0, i1, cellW, z0, z1) {
  const eps = 1e-9 * (z1 - z0);
  const onLine = (p, q, z) => Math.abs(p[1] - z) <= eps && Math.abs(q[1] - z) <= eps;
  for (let k = 0, n = strip.length; k < n; k++) {
    const p = strip[k], q = strip[(k + 1) % n];
    if (onLine(p, q, z0) || onLine(p, q, z1)) continue;
    const a = Math.max(i0, Math.floor(Math.min(p[0], q[0]) / cellW)), b = Math.min(i1, Math.floor(Math.max(p[0], q[0]) / cellW));
    for (let i = a; i <= b; i++) boundary[i - i0] = 1;
  }
}

/** The x of every crossing of the polygon's edges with the line z = zc, sorted. */
function centreCrossings(polygon, zc) {
  const xs = [];
  for (let k = 0, n = polygon.length; k < n; k++) {
    const p = polygon[k], q = polygon[(k + 1) % n];
    if ((p[1] <= zc) !== (q[1] <= zc)) xs.push(p[0] + ((zc - p[1]) / (q[1] - p[1])) * (q[0] - p[0]));
  }
  return xs.sort((u, v) => u - v);
}

/** Even-odd: x is inside when an odd number of crossings lie to its left. */
function isInside(crossings, x) {
  let count = 0;
  while (count < crossings.length && crossings[count] < x) count++;
  return count % 2 === 1;
}
