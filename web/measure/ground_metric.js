// Metres on the ground for a field on the Earth. A geographic grid's local metres take one
// east-west spacing, its centre row's (web/geo/ground_spacing.js), so away from that row they
// are not the ground's: on the WGS 84 ellipsoid a row at latitude phi is N(phi) cos(phi) metres
// a radian of longitude wide and M(phi) a radian of latitude tall. Lengths and areas measured
// on such a grid go through this metric; a projected grid's metres are its CRS's, as GIS
// measure them on the map.
const A = 6378137, F = 1 / 298.257223563, E2 = F * (2 - F), E = Math.sqrt(E2), B2 = A * A * (1 - E2);
const RAD = Math.PI / 180;

/**
 * The ground's metric of a sampler's field, or null when its local metres are the ground's (a
 * projected grid, or no georeference).
 * @param {import('./field_sampler.js').FieldSampler} sampler
 * @returns {{stretch: (z: number, out: number[]) => number[], areaCoordinate: (z: number) => number}|null}
 *   stretch: ground metres per local metre east and south at row z; areaCoordinate: a function
 *   of z whose shoelace with x gives square metres on the ellipsoid (the area from the equator to
 *   the row's latitude, per local metre east)
 */
export function groundMetric(sampler) {
  const g = sampler.georef;
  if (!g || !g.crs.geographic || !(Math.abs(g.dx) > 0 && Math.abs(g.dy) > 0)) return null;
  const perRadianX = sampler.spacingX / (Math.abs(g.dx) * RAD), perRadianZ = sampler.spacingY / (Math.abs(g.dy) * RAD);
  const latitudeAt = (z) => Math.max(-90, Math.min(90, g.y0 + (z / sampler.spacingY) * g.dy)) * RAD;
  return {
    stretch(z, out) {
      const phi = latitudeAt(z), w2 = 1 - E2 * Math.sin(phi) ** 2;
      out[0] = ((A / Math.sqrt(w2)) * Math.cos(phi)) / perRadianX;
      out[1] = (A * (1 - E2)) / (w2 * Math.sqrt(w2)) / perRadianZ;
      return out;
    },
    // The ellipsoid's area from the equator to latitude phi, a radian of longitude wide:
    // b^2 / 2 (sin(phi) / (1 - e^2 sin^2(phi)) + atanh(e sin(phi)) / e).
    areaCoordinate(z) {
      const s = Math.sin(latitudeAt(z));
      return ((B2 / 2) * (s / (1 - E2 * s * s) + Math.atanh(E * s) / E)) / perRadianX;
    },
  };
}

// Pieces each edge is cut into for an area on the ellipsoid: the area coordinate is not linear
// in z, so a straight edge is followed by a polyline (1e-9 of a 10 degree square at 64).
const EDGE_PIECES = 64;

/**
 * Square metres on the ellipsoid of a polygon in local metres (its edges straight on the map).
 * @param {number[][]} ring [[x, z], ...]
 * @param {NonNullable<ReturnType<typeof groundMetric>>} metric
 */
export function ellipsoidArea(ring, metric) {
  let twice = 0;
  for (let k = 0; k < ring.length; k++) {
    const [ax, az] = ring[k], [bx, bz] = ring[(k + 1) % ring.length];
    let px = ax, pa = metric.areaCoordinate(az);
    for (let i = 1; i <= EDGE_PIECES; i++) {
      const t = i / EDGE_PIECES, x = ax + (bx - ax) * t, a = metric.areaCoordinate(az + (bz - az) * t);
      twice += px * a - x * pa;
      px = x, pa = a;
    }
  }
  return Math.abs(twice) / 2;
}
