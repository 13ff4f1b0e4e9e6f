// Near and far planes that follow the camera's altitude and the data's extent, so a 2 m lidar
// tile seen from eye height and a continent seen from orbit both keep depth precision.
import { mat4 } from 'gl-matrix';

export const FOV_Y = (50 * Math.PI) / 180;
// A 24-bit depth buffer keeps terrain apart up to about this far / near ratio.
export const MAX_DEPTH_RATIO = 1e6;

/**
 * The world the cameras move in (drawn metres: heights times the exaggeration). `ground(x, z)`
 * is the full-resolution field's height around a point, `floor(x, z)` the highest of it and the
 * surface drawn now (web/cameras/ground.js), `spacing` the smallest sample spacing.
 */
export function emptyWorld() {
  return { extentX: 1000, extentZ: 1000, low: 0, high: 100, spacing: 1, ground: () => 0, floor: () => 0 };
}

/** Height of the eye above the ground, or above the data's top when outside the field. */
export function clearanceOf(eye, world) {
  const inside = eye[0] >= 0 && eye[2] >= 0 && eye[0] <= world.extentX && eye[2] <= world.extentZ;
  return eye[1] - (inside ? world.ground(eye[0], eye[2]) : world.high);
}

/**
 * Sets camera.near, far and fogDistance, then the projection and view-projection matrices
 * (camera.view must be up to date). Far reaches the farthest corner of the data's box; near is
 * a fraction of `clearance`, the height above the ground, and never closer than
 * far / MAX_DEPTH_RATIO.
 */
export function finishMatrices(camera, aspect, world, lookDistance, clearance) {
  const x = camera.position[0], y = camera.position[1], z = camera.position[2];
  let far = 0;
  for (let corner = 0; corner < 8; corner++) { // the box's corners, as bits: x, z, y (no arrays per frame)
    const cx = corner & 4 ? world.extentX : 0, cz = corner & 2 ? world.extentZ : 0, cy = corner & 1 ? world.high : world.low;
    far = Math.max(far, Math.hypot(cx - x, cy - y, cz - z));
  }
  far = far * 1.05 + 1;
  // What near would be with depth to spare: on the curved Earth the horizon may bring far in
  // (web/cameras/on_the_earth.js), and near with it.
  camera.nearWanted = Math.min(0.3 * Math.max(clearance, 0), 0.5 * lookDistance);
  camera.dataTop = world.high;
  camera.near = Math.max(far / MAX_DEPTH_RATIO, camera.nearWanted);
  camera.far = Math.max(far, camera.near * 10);
  camera.fogDistance = Math.max(8 * lookDistance, 0.25 * Math.hypot(world.extentX, world.extentZ));
  camera.aspect = aspect;
  mat4.perspective(camera.projection, camera.fovY, aspect, camera.near, camera.far);
  mat4.multiply(camera.viewProjection, camera.projection, camera.view);
}
