// The overlay feature under the pointer: the nearest line, outline or point within a tolerance
// of a ground point (local metres), or the polygon that holds it. Read from each overlay's drawn
// paths (render/overlays/overlay_geometry.js picks), simplified as they are drawn.

/**
 * @param {Array<{visible: boolean, geometry: {picks: Array<{feature: number, path: number, kind: string,
 *   x: ArrayLike<number>, z: ArrayLike<number>, closed: boolean}>}|null}>} overlays top last
 * @param {number} x @param {number} z the ground point, local metres
 * @param {number} tolerance metres
 * @returns {{overlay: number, feature: number, path: number, kind: string, distance: number}|null}
 *   lines and points before the polygons that hold the point; the topmost overlay wins a tie
 */
export function nearestFeature(overlays, x, z, tolerance) {
  let best = null, inside = null;
  for (let o = overlays.length - 1; o >= 0; o--) {
    const layer = overlays[o];
    if (!layer.visible || !layer.geometry) continue;
    const crossings = new Map(); // polygon feature -> ray crossings of its rings
    for (const pick of layer.geometry.picks) {
      const d = pick.kind === 'point' ? pointDistance(pick, x, z) : pathDistance(pick, x, z);
      if (d <= tolerance && (!best || d < best.distance)) best = { overlay: o, feature: pick.feature, path: pick.path, kind: pick.kind, distance: d };
      if (pick.closed) crossings.set(pick.feature, (crossings.get(pick.feature) ?? 0) + rayCrossings(pick, x, z));
    }
    if (!inside) {
      for (const [feature, count] of crossings) {
        if (count % 2 === 1) { inside = { overlay: o, feature, path: 0, kind: 'polygon', distance: 0 }; break; }
      }
    }
  }
  return best ?? inside;
}

function pointDistance({ x: px, z: pz }, x, z) {
  let d = Infinity;
  for (let k = 0; k < px.length; k++) d = Math.min(d, Math.hypot(px[k] - x, pz[k] - z));
  return d;
}

/** Distance from (x, z) to the polyline (closed back to its start for a ring). */
function pathDistance({ x: px, z: pz, closed }, x, z) {
  const n = px.length;
  if (n === 1) return Math.hypot(px[0] - x, pz[0] - z);
  let d = Infinity;
  for (let k = 1; k < n + (closed ? 1 : 0); k++) {
    const a = k - 1, b = k % n;
    const ex = px[b] - px[a], ez = pz[b] - pz[a], len2 = ex * ex + ez * ez;
    const t = len2 > 0 ? Math.min(1, Math.max(0, ((x - px[a]) * ex + (z - pz[a]) * ez) / len2)) : 0;
    d = Math.min(d, Math.hypot(px[a] + ex * t - x, pz[a] + ez * t - z));
  }
  return d;
}

/** Crossings of a ray from (x, z) towards +x with the ring's edges (even-odd: odd is inside). */
function rayCrossings({ x: px, z: pz }, x, z) {
  let count = 0;
  for (let k = 0, j = px.length - 1; k < px.length; j = k++) {
    if ((pz[k] > z) !== (pz[j] > z) && x < px[j] + ((z - pz[j]) * (px[k] - px[j])) / (pz[k] - pz[j])) count++;
  }
  return count;
}
