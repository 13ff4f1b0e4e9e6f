// What lies under the pointer: the ray through a pixel meets the field's surface (bilinear,
// heights times the exaggeration); the readout gives x, z, the height and the slope there. On
// the curved Earth the ray runs in the drawn frame and each point of it is brought back to flat
// metres (web/geo/earth_shape.js) to be compared with the ground under it.
import { mat4, vec4 } from 'gl-matrix';
import { FLAT_EARTH, flatPoint } from '../geo/index.js';

const inverse = mat4.create();
const near = vec4.create(), far = vec4.create();
const drawn = [0, 0, 0], flat = [0, 0, 0];

/**
 * The ground point under pixel (px, py) of a width x height viewport (CSS pixels from the top
 * left), or null when the ray misses the field.
 * @param {{viewProjection: mat4, position: Float32Array, far: number}} camera matrices up to date
 * @param {{heightAt(x: number, z: number): number}} terrain
 * @param {{extentX: number, extentZ: number, spacing: number, high: number, earth?: object}} world (earth:
 *   the surface drawn, web/geo/earth_shape.js; the plane without)
 * @param {number} verticalScale the exaggeration
 * @returns {{x: number, z: number, height: number, slopeDeg: number} | null} metres (height
 *   unscaled, as in the file), slope in degrees of the true surface
 */
export function pickGround(camera, px, py, width, height, terrain, world, verticalScale) {
  const ndcX = (2 * px) / width - 1, ndcY = 1 - (2 * py) / height;
  mat4.invert(inverse, camera.viewProjection);
  vec4.transformMat4(near, [ndcX, ndcY, -1, 1], inverse);
  vec4.transformMat4(far, [ndcX, ndcY, 1, 1], inverse);
  const o = [near[0] / near[3], near[1] / near[3], near[2] / near[3]];
  const e = [far[0] / far[3], far[1] / far[3], far[2] / far[3]];
  const length = Math.hypot(e[0] - o[0], e[1] - o[1], e[2] - o[2]);
  const d = [(e[0] - o[0]) / length, (e[1] - o[1]) / length, (e[2] - o[2]) / length];
  const inside = (x, z) => x >= 0 && z >= 0 && x <= world.extentX && z <= world.extentZ;
  const earth = world.earth ?? FLAT_EARTH;
  // The flat point (x, drawn height, z) at t along the ray.
  const at = (t) => {
    drawn[0] = o[0] + d[0] * t, drawn[1] = o[1] + d[1] * t, drawn[2] = o[2] + d[2] * t;
    return flatPoint(earth, drawn, flat);
  };
  // Above the ground at t? Outside the field there is no ground.
  const above = (t) => {
    const [x, y, z] = at(t);
    return !inside(x, z) || y > terrain.heightAt(x, z) * verticalScale;
  };
  // March in steps of half a sample near the eye, growing with distance (a sub-pixel step on
  // screen), then bisect the crossing.
  let t0 = 0;
  for (let t = 0, k = 0; t <= length && k < 100000; ++k) {
    const step = Math.max(world.spacing * 0.5, t * 0.001);
    const t1 = t + step;
    if (!above(t1)) {
      const [x1, , z1] = at(t1);
      if (inside(x1, z1)) {
        t0 = t;
        let lo = t0, hi = t1;
        for (let i = 0; i < 40; ++i) {
          const mid = 0.5 * (lo + hi);
          if (above(mid)) lo = mid; else hi = mid;
        }
        const [x, , z] = at(hi);
        return { x, z, height: terrain.heightAt(x, z), slopeDeg: slopeAt(terrain, x, z, world) };
      }
    }
    t = t1;
  }
  return null;
}

/** Slope of the true surface in degrees, from central differences one sample apart. */
function slopeAt(terrain, x, z, world) {
  const h = world.spacing;
  const dx = (terrain.heightAt(x + h, z) - terrain.heightAt(x - h, z)) / (2 * h);
  const dz = (terrain.heightAt(x, z + h) - terrain.heightAt(x, z - h)) / (2 * h);
  return (Math.atan(Math.hypot(dx, dz)) * 180) / Math.PI;
}
