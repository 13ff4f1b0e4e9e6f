// Whether a point is in sight of the eye: the ground (the core's bilinear heights of the
// full-resolution field) stays below the line between them. Labels on the terrain (contour
// labels, overlay markers' names) are drawn only where it is, as a label hidden by a ridge
// would float over it otherwise.

/** Steps of the test from the eye to the point. */
const SIGHT_STEPS = 24;

/**
 * @param {ArrayLike<number>} eye drawn metres (heights exaggerated)
 * @param {number} x @param {number} y @param {number} z the point, drawn metres
 * @param {{heightAt(x: number, z: number): number}} terrain true metres
 */
export function inSight(eye, x, y, z, verticalScale, terrain) {
  const dx = x - eye[0], dy = y - eye[1], dz = z - eye[2];
  const slack = 0.002 * Math.hypot(dx, dy, dz); // the mesh is not the field; the label sits on a slope
  for (let s = 1; s < SIGHT_STEPS; ++s) {
    const t = s / SIGHT_STEPS * 0.97;
    const ground = terrain.heightAt(eye[0] + dx * t, eye[2] + dz * t) * verticalScale;
    if (ground > eye[1] + dy * t + slack) return false;
  }
  return true;
}
