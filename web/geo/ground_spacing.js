// Metres on the ground between the columns and rows of a geographic grid (steps in degrees).

/** Mean radius of the Earth in metres (the sphere EPSG:4326 distances are taken on here). */
export const EARTH_RADIUS_M = 6371008.8;
const METRES_PER_DEGREE = (Math.PI / 180) * EARTH_RADIUS_M;

/**
 * Ground spacing of a geographic grid (steps in degrees) at a latitude: north-south is the
 * arc of the step, east-west shrinks with cos(latitude). Accurate to ~0.5 % against the
 * ellipsoid, far below what a viewer can see.
 * @param {number} stepLonDeg degrees between columns
 * @param {number} stepLatDeg degrees between rows
 * @param {number} latitudeDeg latitude of the data's centre
 * @returns {{ spacingX: number, spacingY: number }} metres
 */
export function degreesToMetres(stepLonDeg, stepLatDeg, latitudeDeg) {
  const cos = Math.max(Math.cos((latitudeDeg * Math.PI) / 180), 1e-6);
  return { spacingX: Math.abs(stepLonDeg) * METRES_PER_DEGREE * cos, spacingY: Math.abs(stepLatDeg) * METRES_PER_DEGREE };
}
