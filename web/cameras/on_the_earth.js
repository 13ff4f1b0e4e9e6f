// The cameras move in flat metres (x east, height above the surface's zero, z south); on the
// curved Earth their eye and target are drawn where those flat points are (web/geo/earth_shape.js),
// looking with the surface's up under the eye. So an orbit keeps its distance over the ground, a
// walk stays on it, and a camera 10 km up sees the horizon dip as it does from 10 km.
import { mat4 } from 'gl-matrix';
import { EARTH_FLAT, drawnPoint, drawnUp } from '../geo/index.js';
import { MAX_DEPTH_RATIO } from './clip_planes.js';

/**
 * Sets camera.drawnPosition, drawnTarget, drawnUp, earth and flatViewProjection (made once per
 * camera), and on the curved Earth its view and view-projection from the drawn eye, target and
 * up. Call after camera.update().
 * @param {{position: ArrayLike<number>, target: ArrayLike<number>, up: ArrayLike<number>,
 *   view: mat4, projection: mat4, viewProjection: mat4}} camera
 * @param {object} earth a shape of web/geo/earth_shape.js
 */
export function placeOnEarth(camera, earth) {
  if (!camera.drawnPosition) {
    camera.drawnPosition = new Float64Array(3);
    camera.drawnTarget = new Float64Array(3);
    camera.drawnUp = new Float64Array(3);
    camera.flatViewProjection = mat4.create();
  }
  camera.earth = earth; // what draws on the terrain places its points with it (drawnPoint)
  // The flat camera's matrix, for what chooses data by the flat view (web map tiles).
  mat4.copy(camera.flatViewProjection, camera.viewProjection);
  const p = camera.position, t = camera.target;
  if (earth.kind === EARTH_FLAT) {
    camera.drawnPosition.set(p);
    camera.drawnTarget.set(t);
    camera.drawnUp.set(camera.up);
    return;
  }
  // The far plane reaches the farthest flat corner; rows drawn wider than flat reach further.
  // But nothing lies beyond the horizon's reach: the eye's horizon distance plus that of the
  // highest data. On a world field the flat corners are 40,000 km away, and a far plane there
  // would hold near 40 m out, clipping the valley floor under an eye 2 m up.
  const reach = horizonReach(earth.radius, p[1], camera.dataTop ?? 0);
  const far = Math.min(camera.far * Math.max(1, earth.stretch), reach);
  if (far !== camera.far) {
    camera.far = Math.max(far, 10 * (camera.nearWanted ?? camera.near));
    camera.near = Math.max(camera.far / MAX_DEPTH_RATIO, Math.min(camera.nearWanted ?? camera.near, 0.1 * camera.far));
    mat4.perspective(camera.projection, camera.fovY, camera.aspect, camera.near, camera.far);
  }
  drawnPoint(earth, p[0], p[1], p[2], camera.drawnPosition);
  drawnPoint(earth, t[0], t[1], t[2], camera.drawnTarget);
  drawnUp(earth, p[0], p[2], camera.drawnUp);
  mat4.lookAt(camera.view, camera.drawnPosition, camera.drawnTarget, camera.drawnUp);
  mat4.multiply(camera.viewProjection, camera.projection, camera.view);
}

// The horizon's reach uses the mean radius; the ellipsoid's radii of curvature differ from it
// by under 1 %, so 2 % spare covers them.
const HORIZON_MARGIN = 1.02;

/** How far the horizon lies from a point `height` metres above a sphere of `radius` (0 below it). */
function horizonDistance(radius, height) {
  return Math.sqrt(Math.max(0, height * (2 * radius + height)));
}

/**
 * How far anything of the data can be seen from an eye `eyeHeight` metres above a sphere of
 * `radius`, the data reaching `dataTop`: the eye's horizon distance plus the highest data's.
 */
export function horizonReach(radius, eyeHeight, dataTop) {
  return HORIZON_MARGIN * (horizonDistance(radius, eyeHeight) + horizonDistance(radius, dataTop));
}

/**
 * A camera as the core takes it ({eye, target, up, far, ...}: flat metres) placed on the curved
 * Earth, into `out` (its eye, target and up arrays made once by the caller; the other fields
 * copied). From the same doubles, the page and `hexlod regress` in Node give the core the same
 * camera.
 */
export function lodCameraOnEarth(lod, earth, out) {
  const eye = out.eye, target = out.target, up = out.up; // made once; the frame path allocates nothing
  Object.assign(out, lod);
  out.eye = eye, out.target = target, out.up = up;
  const e = lod.eye, t = lod.target;
  if (earth.kind === EARTH_FLAT) {
    for (let k = 0; k < 3; k++) out.eye[k] = e[k], out.target[k] = t[k], out.up[k] = lod.up ? lod.up[k] : k === 1 ? 1 : 0;
    return out;
  }
  drawnPoint(earth, e[0], e[1], e[2], out.eye);
  drawnPoint(earth, t[0], t[1], t[2], out.target);
  drawnUp(earth, e[0], e[2], out.up);
  out.far = lod.far * Math.max(1, earth.stretch);
  return out;
}
