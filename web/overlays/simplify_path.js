// A path simplified for drawing only (profiles and flights read every vertex): Douglas-Peucker
// with an explicit stack (no recursion: a 500 000-point track would overflow it), keeping every
// vertex that strays more than `tolerance` from the line between the vertices kept around it,
// on the map, or in space for a line drawn at its own altitudes.

/**
 * @param {ArrayLike<number>} x @param {ArrayLike<number>} z the path, metres
 * @param {number} tolerance metres
 * @param {ArrayLike<number>|null} [y] heights, metres, for a path drawn aloft (NaN counts as 0)
 * @returns {Uint32Array} indices of the vertices kept, first and last always, in order
 */
export function simplifyForDrawing(x, z, tolerance, y = null) {
  const h = (k) => (y && Number.isFinite(y[k]) ? y[k] : 0);
  const n = x.length;
  if (n <= 2) return Uint32Array.from({ length: n }, (_, k) => k);
  const keep = new Uint8Array(n);
  keep[0] = keep[n - 1] = 1;
  const stack = new Uint32Array(2 * n);
  let top = 0;
  stack[top++] = 0;
  stack[top++] = n - 1;
  const limit = tolerance * tolerance;
  while (top > 0) {
    const last = stack[--top], first = stack[--top];
    const ax = x[first], az = z[first], ay = h(first), ex = x[last] - ax, ez = z[last] - az, ey = h(last) - ay;
    const len2 = ex * ex + ez * ez + ey * ey;
    let far = -1, farthest = limit;
    for (let k = first + 1; k < last; k++) {
      const px = x[k] - ax, pz = z[k] - az, py = h(k) - ay;
      // Distance to the segment (to its end points beyond them): a path that turns back stays whole.
      const t = len2 > 0 ? Math.min(1, Math.max(0, (px * ex + pz * ez + py * ey) / len2)) : 0;
      const dx = px - ex * t, dz = pz - ez * t, dy = py - ey * t, d2 = dx * dx + dz * dz + dy * dy;
      if (d2 > farthest) { farthest = d2; far = k; }
    }
    if (far < 0) continue;
    keep[far] = 1;
    stack[top++] = first;
    stack[top++] = far;
    stack[top++] = far;
    stack[top++] = last;
  }
  let count = 0;
  for (let k = 0; k < n; k++) count += keep[k];
  const kept = new Uint32Array(count);
  for (let k = 0, i = 0; k < n; k++) if (keep[k]) kept[i++] = k;
  return kept;
}
