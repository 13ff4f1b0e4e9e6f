// The surface a terrain is drawn on: the plane, or the curved Earth (the core's
// src/lod/earth_shape.h, the shaders' shaders/earth.glsl, the same shapes and numbers). A
// georeferenced field is drawn on the Earth: a geographic grid (columns of longitude, rows of
// latitude) on the WGS 84 ellipsoid, each row at its latitude's true east-west spacing; a
// projected grid wrapped onto a sphere of the Earth's radius there, distances and directions
// from the field's centre kept. The frame is fixed: east, up and south metres of the tangent
// frame at the field's centre, where heights are metres above the surface's zero.
//
// The cameras keep working in flat metres (x east, height, z south); drawnPoint() places their
// eye and target, and flatPoint() brings a drawn point back (for picking).
import { geoCoordinates } from './coordinates.js';

const A = 6378137; // WGS 84 semi-major axis, metres
const F = 1 / 298.257223563;
const E2 = F * (2 - F);
const RAD = Math.PI / 180;

export const EARTH_FLAT = 0, EARTH_SPHERE = 1, EARTH_GEOGRAPHIC = 2;

/** The plane: what a field without a georeference, or with the Earth flattened, is drawn on. */
export const FLAT_EARTH = Object.freeze({ kind: EARTH_FLAT, originX: 0, originZ: 0, radius: 6371008.8, latitude0: 0,
  metresPerRadianX: 1, metresPerRadianZ: 1, stretch: 1 });

/**
 * The Earth under a terrain: geographic grids on the ellipsoid, projected ones on a sphere of the
 * mean radius at their centre, flat without a georeference (or a centre with no latitude known).
 * `stretch`: the most drawn metres per flat metre anywhere on the field (a geographic grid's
 * rows nearer the equator than its centre are wider), for the cameras' far plane.
 * @param {import('./georef.js').Georef|null} georef
 * @param {{width: number, height: number, spacingX: number, spacingY: number}} terrain
 */
export function earthShapeOf(georef, terrain) {
  if (!georef) return FLAT_EARTH;
  const originX = 0.5 * (terrain.width - 1) * terrain.spacingX, originZ = 0.5 * (terrain.height - 1) * terrain.spacingY;
  const centre = geoCoordinates(georef, originX, originZ, terrain.spacingX, terrain.spacingY);
  if (!centre || !Number.isFinite(centre.lat) || Math.abs(centre.lat) > 90) return FLAT_EARTH;
  const latitude0 = centre.lat * RAD;
  if (georef.crs.geographic) {
    const metresPerRadianX = terrain.spacingX / (Math.abs(georef.dx) * RAD);
    // The widest row's drawn metres per flat metre east: the row nearest the equator.
    const north = geoCoordinates(georef, originX, 0, terrain.spacingX, terrain.spacingY).lat * RAD;
    const south = geoCoordinates(georef, originX, 2 * originZ, terrain.spacingX, terrain.spacingY).lat * RAD;
    const widest = north * south <= 0 ? 0 : Math.min(Math.abs(north), Math.abs(south));
    return Object.freeze({ kind: EARTH_GEOGRAPHIC, originX, originZ, radius: meanRadius(latitude0), latitude0, metresPerRadianX,
      metresPerRadianZ: terrain.spacingY / (Math.abs(georef.dy) * RAD),
      stretch: Math.max(1, (A / Math.sqrt(1 - E2 * Math.sin(widest) ** 2)) * Math.cos(widest) / metresPerRadianX) });
  }
  return Object.freeze({ kind: EARTH_SPHERE, originX, originZ, radius: meanRadius(latitude0), latitude0, metresPerRadianX: 1,
    metresPerRadianZ: 1, stretch: 1 });
}

/** The Gaussian mean radius of the ellipsoid at a latitude (radians): sqrt(M N). */
export function meanRadius(latitude) {
  const w2 = 1 - E2 * Math.sin(latitude) ** 2;
  return (A * Math.sqrt(1 - E2)) / w2;
}

/**
 * Where the flat point (x, y, z) is drawn (y: height times the exaggeration), into `out`.
 * @returns {number[]|Float32Array|Float64Array} out
 */
export function drawnPoint(earth, x, y, z, out = [0, 0, 0]) {
  if (earth.kind === EARTH_SPHERE) {
    const dx = x - earth.originX, dz = z - earth.originZ, d = Math.hypot(dx, dz), R = earth.radius;
    const along = d > 1e-9 * R ? ((R + y) * Math.sin(d / R)) / d : (R + y) / R;
    out[0] = along * dx, out[1] = y - 2 * (R + y) * Math.sin(d / (2 * R)) ** 2, out[2] = along * dz;
    return out;
  }
  if (earth.kind === EARTH_GEOGRAPHIC) {
    const phi = earth.latitude0 - (z - earth.originZ) / earth.metresPerRadianZ, dLambda = (x - earth.originX) / earth.metresPerRadianX;
    const s = Math.sin(phi), c = Math.cos(phi), s0 = Math.sin(earth.latitude0), c0 = Math.cos(earth.latitude0);
    const n = A / Math.sqrt(1 - E2 * s * s), n0 = A / Math.sqrt(1 - E2 * s0 * s0);
    const X = (n + y) * c * Math.cos(dLambda) - n0 * c0, Y = (n + y) * c * Math.sin(dLambda);
    const Z = (n * (1 - E2) + y) * s - n0 * (1 - E2) * s0;
    out[0] = Y, out[1] = c0 * X + s0 * Z, out[2] = s0 * X - c0 * Z;
    return out;
  }
  out[0] = x, out[1] = y, out[2] = z;
  return out;
}

/** The surface's up (unit, drawn frame) under flat (x, z), into `out`. */
export function drawnUp(earth, x, z, out = [0, 0, 0]) {
  if (earth.kind === EARTH_SPHERE) {
    const dx = x - earth.originX, dz = z - earth.originZ, d = Math.hypot(dx, dz), R = earth.radius;
    const along = d > 1e-9 * R ? Math.sin(d / R) / d : 1 / R;
    out[0] = along * dx, out[1] = Math.cos(d / R), out[2] = along * dz;
    return out;
  }
  if (earth.kind === EARTH_GEOGRAPHIC) {
    const phi = earth.latitude0 - (z - earth.originZ) / earth.metresPerRadianZ, dLambda = (x - earth.originX) / earth.metresPerRadianX;
    const s = Math.sin(phi), c = Math.cos(phi), s0 = Math.sin(earth.latitude0), c0 = Math.cos(earth.latitude0);
    const X = c * Math.cos(dLambda), Y = c * Math.sin(dLambda);
    out[0] = Y, out[1] = c0 * X + s0 * s, out[2] = s0 * X - c0 * s;
    return out;
  }
  out[0] = 0, out[1] = 1, out[2] = 0;
  return out;
}

/**
 * The tangent frame under a geographic grid's flat (x, z): its east, up and south (unit vectors
 * of the drawn frame), into `axes` (9 numbers, column by column as a GLSL mat3 takes them). On
 * the plane and the sphere (whose wrap is about the origin only the origin's frame is used) the
 * drawn frame's own axes.
 */
export function drawnAxes(earth, x, z, axes) {
  axes.fill(0);
  if (earth.kind !== EARTH_GEOGRAPHIC) {
    axes[0] = axes[4] = axes[8] = 1;
    return axes;
  }
  const phi = earth.latitude0 - (z - earth.originZ) / earth.metresPerRadianZ, dLambda = (x - earth.originX) / earth.metresPerRadianX;
  const s = Math.sin(phi), c = Math.cos(phi), sL = Math.sin(dLambda), cL = Math.cos(dLambda);
  const s0 = Math.sin(earth.latitude0), c0 = Math.cos(earth.latitude0);
  // Earth-centred vectors (the origin's meridian as longitude 0) turned to the origin's east,
  // up and south: (X, Y, Z) goes to (Y, c0 X + s0 Z, s0 X - c0 Z). South is minus north.
  axes[0] = cL, axes[1] = -c0 * sL, axes[2] = -s0 * sL;
  axes[3] = c * sL, axes[4] = c0 * c * cL + s0 * s, axes[5] = s0 * c * cL - c0 * s;
  axes[6] = s * sL, axes[7] = c0 * s * cL - s0 * c, axes[8] = s0 * s * cL + c0 * c;
  return axes;
}

/**
 * The flat point (x, height, z) drawn at p, into `out`: the inverse of drawnPoint (heights in the
 * same drawn units). On the ellipsoid by Bowring's method, to well under a millimetre.
 */
export function flatPoint(earth, p, out = [0, 0, 0]) {
  if (earth.kind === EARTH_SPHERE) {
    const R = earth.radius, cx = p[0], cy = p[1] + R, cz = p[2];
    const r = Math.hypot(cx, cy, cz), horizontal = Math.hypot(cx, cz);
    const d = Math.atan2(horizontal, cy) * R;
    out[0] = earth.originX + (horizontal > 0 ? (cx / horizontal) * d : 0);
    out[1] = r - R;
    out[2] = earth.originZ + (horizontal > 0 ? (cz / horizontal) * d : 0);
    return out;
  }
  if (earth.kind === EARTH_GEOGRAPHIC) {
    // Back to Earth-centred (the origin's meridian as longitude 0), then geodetic.
    const s0 = Math.sin(earth.latitude0), c0 = Math.cos(earth.latitude0);
    const n0 = A / Math.sqrt(1 - E2 * s0 * s0);
    const east = p[0], up = p[1], north = -p[2];
    const X = c0 * up - s0 * north + n0 * c0, Y = east, Z = s0 * up + c0 * north + n0 * (1 - E2) * s0;
    const lambda = Math.atan2(Y, X), rho = Math.hypot(X, Y);
    const b = A * Math.sqrt(1 - E2), ep2 = E2 / (1 - E2);
    const theta = Math.atan2(Z * A, rho * b);
    const phi = Math.atan2(Z + ep2 * b * Math.sin(theta) ** 3, rho - E2 * A * Math.cos(theta) ** 3);
    const s = Math.sin(phi), n = A / Math.sqrt(1 - E2 * s * s);
    const height = Math.abs(Math.cos(phi)) > 1e-9 ? rho / Math.cos(phi) - n : Math.abs(Z) / Math.abs(s) - n * (1 - E2);
    out[0] = earth.originX + lambda * earth.metresPerRadianX;
    out[1] = height;
    out[2] = earth.originZ - (phi - earth.latitude0) * earth.metresPerRadianZ;
    return out;
  }
  out[0] = p[0], out[1] = p[1], out[2] = p[2];
  return out;
}
