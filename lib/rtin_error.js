// Error of a mesh on the sample grid (such as @mapbox/martini's RTIN meshes, whose vertices are
// grid points of a padded (2^k + 1)^2 grid) against the original samples: every sample of the
// W x H field is interpolated linearly inside the triangle that contains it, and the error is
// the vertical distance. A sample on an edge shared by two triangles keeps the larger error.

/**
 * @param {{vertices: Uint16Array|Uint32Array, triangles: Uint32Array}} mesh vertices as
 *   (column, row) pairs of the grid, triangles 3 vertex indices each, any winding
 * @param {Float32Array} gridHeights heights of the grid the mesh was built on, row-major
 * @param {number} gridSize columns of that grid
 * @param {Float32Array} samples heights of the original field, row-major, width x height
 * @param {number} width
 * @param {number} height
 * @param {{quantiles?: boolean}} [options] quantiles: also compute p99 and the mean (sorts)
 * @returns {{max: number, p99: number, mean: number, evaluated: number, uncovered: number}}
 */
export function gridMeshError({ vertices, triangles }, gridHeights, gridSize, samples, width, height, options = {}) {
  const error = new Float32Array(width * height).fill(-1);
  let max = 0;
  for (let t = 0; t < triangles.length; t += 3) {
    const a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    let ax = vertices[2 * a], ay = vertices[2 * a + 1];
    let bx = vertices[2 * b], by = vertices[2 * b + 1];
    const cx = vertices[2 * c], cy = vertices[2 * c + 1];
    let ha = gridHeights[ay * gridSize + ax], hb = gridHeights[by * gridSize + bx];
    const hc = gridHeights[cy * gridSize + cx];
    let area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    if (area === 0) continue;
    if (area < 0) { // make it counter-clockwise in (column, row) so the edge functions are >= 0 inside
      [ax, bx] = [bx, ax];
      [ay, by] = [by, ay];
      [ha, hb] = [hb, ha];
      area = -area;
    }
    const x0 = Math.max(0, Math.min(ax, bx, cx)), x1 = Math.min(width - 1, Math.max(ax, bx, cx));
    const y0 = Math.max(0, Math.min(ay, by, cy)), y1 = Math.min(height - 1, Math.max(ay, by, cy));
    for (let y = y0; y <= y1; y++) {
      for (let x = x0; x <= x1; x++) {
        // Barycentric weights times the area: integers, exact.
        const wa = (bx - x) * (cy - y) - (by - y) * (cx - x);
        if (wa < 0) continue;
        const wb = (cx - x) * (ay - y) - (cy - y) * (ax - x);
        if (wb < 0) continue;
        const wc = area - wa - wb;
        if (wc < 0) continue;
        const h = (wa * ha + wb * hb + wc * hc) / area;
        const k = y * width + x;
        const e = Math.abs(h - samples[k]);
        if (e > error[k]) {
          error[k] = e;
          if (e > max) max = e;
        }
      }
    }
  }
  let evaluated = 0, sum = 0;
  for (let k = 0; k < error.length; k++) {
    if (error[k] >= 0) {
      evaluated += 1;
      sum += error[k];
    }
  }
  const result = { max, p99: NaN, mean: evaluated ? sum / evaluated : NaN, evaluated, uncovered: error.length - evaluated };
  if (options.quantiles) {
    const covered = error.filter((e) => e >= 0).sort();
    result.p99 = covered.length ? covered[Math.max(0, Math.ceil(0.99 * covered.length) - 1)] : NaN;
  }
  return result;
}

/**
 * The field padded to (2^k + 1)^2 as martini requires, the last column and row replicated.
 * @returns {{size: number, heights: Float32Array}}
 */
export function padToPowerOfTwoPlusOne(samples, width, height) {
  let size = 2;
  while (size + 1 < Math.max(width, height)) size *= 2;
  size += 1;
  const heights = new Float32Array(size * size);
  for (let y = 0; y < size; y++) {
    const row = Math.min(y, height - 1) * width;
    const out = y * size;
    heights.set(samples.subarray(row, row + width), out);
    heights.fill(samples[row + width - 1], out + width, out + size);
  }
  return { size, heights };
}
