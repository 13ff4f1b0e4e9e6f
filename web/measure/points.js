// The checks every measurement makes on the points it is given, so that a bad click list or
// URL says what is wrong instead of measuring NaN.

/**
 * Throws an Error with a clear message unless points is an array of at least `min` [x, z]
 * pairs of finite numbers.
 * @param {unknown} points
 * @param {number} min fewest points the measurement needs
 * @param {string} what the measurement, for the message ('a profile', 'an area')
 */
export function checkPoints(points, min, what) {
  if (!Array.isArray(points) || points.length < min) {
    const count = Array.isArray(points) ? points.length : 0;
    throw new Error(`${what} needs at least ${min} points, got ${count}`);
  }
  points.forEach((p, k) => {
    if (!Array.isArray(p) && !ArrayBuffer.isView(p)) throw new Error(`${what}: point ${k + 1} is not an [x, z] pair`);
    if (!Number.isFinite(p[0]) || !Number.isFinite(p[1])) {
      throw new Error(`${what}: point ${k + 1} has no finite coordinates (${p[0]}, ${p[1]})`);
    }
  });
}
