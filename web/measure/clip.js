// Clipping in the plane, for measurements that must leave out what lies off the field: a
// segment against a rectangle (Liang–Barsky: the parameter range of the segment inside), and a
// polygon against a half-plane (Sutherland–Hodgman). Clipping a polygon, concave or not, by the
// half-planes of a convex shape one after another gives the part inside: it may keep zero-width
// bridges along the clip edges, which add nothing to its area.

/**
 * The part of segment a -> b inside [0, xMax] x [0, zMax], as parameters along it.
 * @returns {[number, number]|null} t0 <= t1 in 0..1, or null when no part (not even a point) is inside
 */
export function clipSegment(ax, az, bx, bz, xMax, zMax) {
  let t0 = 0, t1 = 1;
  const dx = bx - ax, dz = bz - az;
  // Each side: p * t <= q keeps the inside.
  for (const [p, q] of [[-dx, ax], [dx, xMax - ax], [-dz, az], [dz, zMax - az]]) {
    if (p === 0) {
      if (q < 0) return null;
    } else {
      const t = q / p;
      if (p < 0) t0 = Math.max(t0, t);
      else t1 = Math.min(t1, t);
    }
  }
  return t0 <= t1 ? [t0, t1] : null;
}

/**
 * The part of a polygon where a * x + b * z <= c.
 * @param {number[][]} polygon [[x, z], ...], not closed (the last vertex is not the first again)
 * @returns {number[][]} the clipped polygon (possibly empty)
 */
export function clipHalfPlane(polygon, a, b, c) {
  const out = [];
  const n = polygon.length;
  for (let k = 0; k < n; k++) {
    const p = polygon[k], q = polygon[(k + 1) % n];
    const sp = a * p[0] + b * p[1] - c, sq = a * q[0] + b * q[1] - c;
    if (sp <= 0) out.push(p);
    if ((sp < 0 && sq > 0) || (sp > 0 && sq < 0)) {
      const t = sp / (sp - sq);
      out.push([p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t]);
    }
  }
  return out;
}

/** The part of a polygon inside the rectangle [x0, x1] x [z0, z1]. */
export function clipRectangle(polygon, x0, z0, x1, z1) {
  let p = clipHalfPlane(polygon, -1, 0, -x0);
  p = clipHalfPlane(p, 1, 0, x1);
  p = clipHalfPlane(p, 0, -1, -z0);
  return clipHalfPlane(p, 0, 1, z1);
}

/** Signed area by the shoelace formula (positive when the vertices turn from +x to +z). */
export function signedArea(polygon) {
  let twice = 0;
  for (let k = 0, n = polygon.length; k < n; k++) {
    const p = polygon[k], q = polygon[(k + 1) % n];
    twice += p[0] * q[1] - q[0] * p[1];
  }
  return twice / 2;
}
