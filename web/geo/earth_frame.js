// Points of a georeferenced field on the WGS 84 ellipsoid, in a local east-north-up frame at a
// chosen origin: the field drawn on the curved Earth instead of a plane. A sample's longitude
// and latitude (from its CRS) and height become Earth-centred coordinates (ECEF), then metres
// east, up and south of the origin (x east, y up, z south, as the flat field's axes run).
// Heights are taken as above the ellipsoid (a DEM's geoid heights differ by under 110 m).

const A = 6378137; // WGS 84 semi-major axis, metres
const F = 1 / 298.257223563;
const E2 = F * (2 - F); // first eccentricity squared
const RAD = Math.PI / 180;

/** Earth-centred, Earth-fixed metres of a longitude, latitude (degrees) and ellipsoidal height. */
export function geodeticToEcef(lon, lat, height, out = [0, 0, 0]) {
  const phi = lat * RAD, lambda = lon * RAD;
  const sinPhi = Math.sin(phi), cosPhi = Math.cos(phi);
  const n = A / Math.sqrt(1 - E2 * sinPhi * sinPhi); // prime vertical radius of curvature
  out[0] = (n + height) * cosPhi * Math.cos(lambda);
  out[1] = (n + height) * cosPhi * Math.sin(lambda);
  out[2] = (n * (1 - E2) + height) * sinPhi;
  return out;
}

/**
 * The local frame at an origin on the ellipsoid: a function from longitude, latitude and height
 * to [x east, y up, z south] metres of that origin's tangent frame.
 * @param {number} lon0 degrees
 * @param {number} lat0 degrees
 * @returns {(lon: number, lat: number, height: number, out?: number[]) => number[]}
 */
export function eastUpSouthAt(lon0, lat0) {
  const origin = geodeticToEcef(lon0, lat0, 0);
  const sinPhi = Math.sin(lat0 * RAD), cosPhi = Math.cos(lat0 * RAD);
  const sinLambda = Math.sin(lon0 * RAD), cosLambda = Math.cos(lon0 * RAD);
  const p = [0, 0, 0];
  return (lon, lat, height, out = [0, 0, 0]) => {
    geodeticToEcef(lon, lat, height, p);
    const dx = p[0] - origin[0], dy = p[1] - origin[1], dz = p[2] - origin[2];
    const east = -sinLambda * dx + cosLambda * dy;
    const north = -sinPhi * cosLambda * dx - sinPhi * sinLambda * dy + cosPhi * dz;
    const up = cosPhi * cosLambda * dx + cosPhi * sinLambda * dy + sinPhi * dz;
    out[0] = east;
    out[1] = up;
    out[2] = -north;
    return out;
  };
}
