// The opening view of a terrain (default, dropped, picked, ?src=, and R): the whole field, or on
// a large field the region of greatest relief, fitted into the view from above its surface, at
// any base height, size, aspect, spacing and exaggeration.
//
// The region's surface, sampled on a grid (heights exaggerated), is fitted into the frustum by
// distance, in closed form per point; the pitch then rises until the eye is clear of the ground
// under it and nothing stands between the eye and the target.
import { EARTH_FLAT, drawnPoint, drawnUp } from '../geo/index.js';

const FOCUS_GRID = 96;        // coarse samples per side of the relief search
const FOCUS_WINDOW = 4;       // half-width, in coarse samples, of the neighbourhood whose relief counts
const LARGE_FIELD = 1500;     // samples on the longer side above which a region, not the whole field, opens
const STRIP_ASPECT = 4;       // a field this many times longer than wide is seen broadside
const HEIGHT_GRID = 48;       // samples per side of the region's height range
const FILL = 0.92;            // the region fills this share of the half field of view
const SIGHT_STEPS = 256;      // samples along the line of sight checked for ground in the way
const PITCH_STEP = 0.08;      // radians added while the eye is blocked
const MAX_PITCH = 1.45;       // radians: close to straight down
const CENTRING_PASSES = 3;    // moves of the target that centre the region on screen
const FULL_VIEW = { centreX: 0, centreY: 0, halfWidth: 1, halfHeight: 1 };
const LEANING = 0.08;         // a mean slope above which the surface is seen from downhill

/**
 * The point of greatest local relief: a high point above a deep valley (on the default terrain
 * the Himalaya's front range rising from the Ganges plain).
 * @param {{heightAt: (x: number, z: number) => number}} terrain heights in metres, unscaled
 * @returns {{x: number, z: number, extent: number}} metres: the point and the size of the region
 */
export function reliefFocus(terrain, extentX, extentZ) {
  const n = FOCUS_GRID;
  const heights = new Float64Array(n * n);
  for (let i = 0; i < n; ++i) {
    for (let j = 0; j < n; ++j) heights[i * n + j] = terrain.heightAt((j / (n - 1)) * extentX, (i / (n - 1)) * extentZ);
  }
  let best = { score: -Infinity, i: 0, j: 0 };
  for (let i = 0; i < n; ++i) {
    for (let j = 0; j < n; ++j) {
      let low = Infinity, high = -Infinity;
      for (let a = Math.max(0, i - FOCUS_WINDOW); a <= Math.min(n - 1, i + FOCUS_WINDOW); ++a) {
        for (let b = Math.max(0, j - FOCUS_WINDOW); b <= Math.min(n - 1, j + FOCUS_WINDOW); ++b) {
          low = Math.min(low, heights[a * n + b]);
          high = Math.max(high, heights[a * n + b]);
        }
      }
      const score = (high - low) + (heights[i * n + j] - low); // relief around it, and standing high in it
      if (score > best.score) best = { score, i, j };
    }
  }
  return { x: (best.j / (n - 1)) * extentX, z: (best.i / (n - 1)) * extentZ,
    extent: (2 * FOCUS_WINDOW + 1) * Math.hypot(extentX, extentZ) / n };
}

/**
 * The ground region that opens in view: the whole field, or around the relief focus of a large,
 * not too elongated field.
 * @returns {{x0: number, x1: number, z0: number, z1: number}} metres
 */
export function openingRegion(terrain, extentX, extentZ) {
  const whole = { x0: 0, x1: extentX, z0: 0, z1: extentZ };
  const longSide = Math.max(terrain.width, terrain.height), shortSide = Math.min(terrain.width, terrain.height);
  if (longSide <= LARGE_FIELD || longSide > STRIP_ASPECT * shortSide) return whole;
  const focus = reliefFocus(terrain, extentX, extentZ);
  const half = 0.3 * focus.extent; // close enough that the peaks stand up
  const clampRange = (centre, size) => {
    const lo = Math.min(Math.max(centre - half, 0), Math.max(size - 2 * half, 0));
    return [lo, Math.min(lo + 2 * half, size)];
  };
  const [x0, x1] = clampRange(focus.x, extentX), [z0, z1] = clampRange(focus.z, extentZ);
  return { x0, x1, z0, z1 };
}

/**
 * Lowest and highest drawn height (metres times `scale`) over a region, the height at its centre,
 * and the surface points sampled ([x, drawn height, z], a HEIGHT_GRID² grid over the region).
 */
export function regionHeights(terrain, region, scale) {
  let low = Infinity, high = -Infinity;
  const points = [];
  for (let i = 0; i < HEIGHT_GRID; ++i) {
    for (let j = 0; j < HEIGHT_GRID; ++j) {
      const x = region.x0 + ((region.x1 - region.x0) * j) / (HEIGHT_GRID - 1);
      const z = region.z0 + ((region.z1 - region.z0) * i) / (HEIGHT_GRID - 1);
      const h = terrain.heightAt(x, z) * scale;
      low = Math.min(low, h);
      high = Math.max(high, h);
      points.push([x, h, z]);
    }
  }
  const centre = terrain.heightAt(0.5 * (region.x0 + region.x1), 0.5 * (region.z0 + region.z1)) * scale;
  return { low, high, centre, points };
}

/** The camera's forward, right and up vectors for a yaw and pitch (orbit.js conventions). */
function viewBasis(yaw, pitch) {
  const cp = Math.cos(pitch), sp = Math.sin(pitch), sy = Math.sin(yaw), cy = Math.cos(yaw);
  const forward = [-cp * sy, -sp, -cp * cy];
  const right = [cy, 0, -sy];
  const up = [right[1] * forward[2] - right[2] * forward[1], right[2] * forward[0] - right[0] * forward[2],
    right[0] * forward[1] - right[1] * forward[0]];
  return { forward, right, up };
}

/**
 * The orbit distance at which every point ([x, y, z] metres) lies inside the view, for a camera
 * looking at `target` from yaw and pitch (orbit.js conventions: yaw 0 looks north, from +z).
 * Closed form per point: its offsets across and up the view over its depth stay within the
 * half field of view.
 */
export function fitDistance(points, target, yaw, pitch, fovY, aspect, free = FULL_VIEW) {
  const { forward, right, up } = viewBasis(yaw, pitch);
  const tanY = Math.tan(0.5 * fovY) * FILL * free.halfHeight, tanX = Math.tan(0.5 * fovY) * FILL * aspect * free.halfWidth;
  let distance = 0;
  for (const [x, y, z] of points) {
    const q0 = x - target[0], q1 = y - target[1], q2 = z - target[2];
    const along = q0 * forward[0] + q1 * forward[1] + q2 * forward[2];
    const across = Math.abs(q0 * right[0] + q2 * right[2]);
    const upward = Math.abs(q0 * up[0] + q1 * up[1] + q2 * up[2]);
    distance = Math.max(distance, across / tanX - along, upward / tanY - along);
  }
  return distance;
}

/**
 * The smallest orbit distance, at most `flatDistance`, from which the drawn (curved) points all
 * lie within the view's free part, the orbit placed on the Earth as the page places it
 * (on_the_earth.js): bisection over the distance, each step the points' angles from the drawn
 * view direction against the half field of view.
 */
function fitOnTheEarth(earth, points, target, flatDistance, yaw, pitch, fovY, aspect, free) {
  const drawn = points.map(([x, y, z]) => drawnPoint(earth, x, y, z));
  const t = drawnPoint(earth, target[0], target[1], target[2]);
  const tanY = Math.tan(0.5 * fovY) * FILL * free.halfHeight, tanX = Math.tan(0.5 * fovY) * FILL * aspect * free.halfWidth;
  const fits = (d) => {
    const cp = Math.cos(pitch);
    const eye = drawnPoint(earth, target[0] + d * cp * Math.sin(yaw), target[1] + d * Math.sin(pitch), target[2] + d * cp * Math.cos(yaw));
    const f = [t[0] - eye[0], t[1] - eye[1], t[2] - eye[2]], fl = Math.hypot(...f);
    const forward = f.map((v) => v / fl);
    const upHint = drawnUp(earth, target[0], target[2]);
    let right = [forward[1] * upHint[2] - forward[2] * upHint[1], forward[2] * upHint[0] - forward[0] * upHint[2], forward[0] * upHint[1] - forward[1] * upHint[0]];
    const rl = Math.hypot(...right);
    if (!(rl > 1e-9)) return true;
    right = right.map((v) => v / rl);
    const up = [right[1] * forward[2] - right[2] * forward[1], right[2] * forward[0] - right[0] * forward[2], right[0] * forward[1] - right[1] * forward[0]];
    return drawn.every((p) => {
      const q = [p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]];
      const depth = q[0] * forward[0] + q[1] * forward[1] + q[2] * forward[2];
      if (!(depth > 0)) return false;
      const sx = (q[0] * right[0] + q[1] * right[1] + q[2] * right[2]) / depth;
      const sy = (q[0] * up[0] + q[1] * up[1] + q[2] * up[2]) / depth;
      return Math.abs(sx) <= tanX && Math.abs(sy - free.centreY * Math.tan(0.5 * fovY)) <= tanY;
    });
  };
  if (!fits(flatDistance)) return flatDistance;
  let lo = 0.01 * flatDistance, hi = flatDistance;
  for (let k = 0; k < 30; ++k) {
    const mid = 0.5 * (lo + hi);
    if (fits(mid)) hi = mid;
    else lo = mid;
  }
  return hi;
}

/**
 * Fits the points into the view centred: the target moves across the view until the points'
 * projected extent is centred on the screen (a field seen obliquely is not centred on its middle
 * point) or on the part of it the page's bars leave free, then onto the first ground along the view ray, which leaves the view as it is.
 * @returns {{target: number[], distance: number}}
 */
function centredView(terrain, world, scale, points, start, yaw, pitch, fovY, aspect, free) {
  const { forward, right, up } = viewBasis(yaw, pitch);
  const tanY = Math.tan(0.5 * fovY), tanX = tanY * aspect;
  const target = start.slice();
  let distance = 0;
  for (let pass = 0; pass < CENTRING_PASSES; ++pass) {
    distance = fitDistance(points, target, yaw, pitch, fovY, aspect, free);
    let left = Infinity, rightmost = -Infinity, bottom = Infinity, top = -Infinity;
    for (const [x, y, z] of points) {
      const q0 = x - target[0], q1 = y - target[1], q2 = z - target[2];
      const depth = distance + q0 * forward[0] + q1 * forward[1] + q2 * forward[2];
      const sx = (q0 * right[0] + q2 * right[2]) / (depth * tanX);
      const sy = (q0 * up[0] + q1 * up[1] + q2 * up[2]) / (depth * tanY);
      left = Math.min(left, sx); rightmost = Math.max(rightmost, sx);
      bottom = Math.min(bottom, sy); top = Math.max(top, sy);
    }
    // Offsets (screen units, -1..1) from the window's centre, back to metres at the target's depth.
    const cx = (0.5 * (left + rightmost) - free.centreX) * tanX * distance;
    const cy = (0.5 * (bottom + top) - free.centreY) * tanY * distance;
    for (let k = 0; k < 3; ++k) target[k] += right[k] * cx + up[k] * cy;
  }
  distance = fitDistance(points, target, yaw, pitch, fovY, aspect, free);
  // The same view, orbiting the ground point at the screen's centre rather than a point in the air.
  const eye = [target[0] - forward[0] * distance, target[1] - forward[1] * distance, target[2] - forward[2] * distance];
  const reach = 2 * distance;
  for (let k = 1; k <= SIGHT_STEPS * 2; ++k) {
    const t = (reach * k) / (SIGHT_STEPS * 2);
    const x = eye[0] + forward[0] * t, y = eye[1] + forward[1] * t, z = eye[2] + forward[2] * t;
    if (x < 0 || z < 0 || x > world.extentX || z > world.extentZ) continue;
    if (y <= terrain.heightAt(x, z) * scale) return { target: [x, y, z], distance: t };
  }
  return { target, distance };
}

/**
 * Whether the eye is clear of the ground under it (the highest samples around it) and sees the
 * target over the field's surface (bilinear) all the way.
 */
function eyeIsClear(terrain, world, scale, target, yaw, pitch, distance) {
  const cp = Math.cos(pitch);
  const eye = [target[0] + distance * cp * Math.sin(yaw), target[1] + distance * Math.sin(pitch),
    target[2] + distance * cp * Math.cos(yaw)];
  const inside = (x, z) => x >= 0 && z >= 0 && x <= world.extentX && z <= world.extentZ;
  if (inside(eye[0], eye[2]) && eye[1] < world.ground(eye[0], eye[2]) + 0.01 * distance) return false;
  for (let k = 1; k < SIGHT_STEPS; ++k) {
    const t = k / SIGHT_STEPS; // 0 at the eye, 1 at the target, which lies on the surface
    const x = eye[0] + (target[0] - eye[0]) * t, z = eye[2] + (target[2] - eye[2]) * t;
    if (!inside(x, z)) continue;
    const y = eye[1] + (target[1] - eye[1]) * t;
    if (y < terrain.heightAt(x, z) * scale) return false;
  }
  return true;
}

/**
 * The mean slope of the region's surface: the least-squares plane through its sampled points
 * (a regular grid, so x and z are uncorrelated), as height gained per metre east and south.
 */
export function meanSlope(points) {
  let sx = 0, sz = 0, sh = 0;
  for (const [x, h, z] of points) { sx += x; sz += z; sh += h; }
  const n = points.length, mx = sx / n, mz = sz / n, mh = sh / n;
  let xh = 0, xx = 0, zh = 0, zz = 0;
  for (const [x, h, z] of points) {
    xh += (x - mx) * (h - mh); xx += (x - mx) ** 2;
    zh += (z - mz) * (h - mh); zz += (z - mz) ** 2;
  }
  return { east: xx > 0 ? xh / xx : 0, south: zz > 0 ? zh / zz : 0 };
}

/**
 * Puts the orbit camera where a terrain opens: its region in view, the eye above the surface.
 * @param {{width: number, height: number, heightAt: (x: number, z: number) => number}} terrain
 * @param {{extentX: number, extentZ: number, ground: (x: number, z: number) => number}} world drawn metres
 * @param {import('./orbit.js').OrbitCamera} orbit
 * @param {number} scale the vertical exaggeration
 * @param {number} aspect viewport width / height
 * @param {{top: number, bottom: number}} [covered] shares of the view's height covered by the
 *   page's bars at its top and bottom: the region is fitted between them
 */
export function frameTerrain(terrain, world, orbit, scale, aspect, covered = { top: 0, bottom: 0 }) {
  // The part of the screen left free, in screen units (-1 bottom .. 1 top).
  const free = { centreX: 0, centreY: covered.bottom - covered.top, halfWidth: 1, halfHeight: 1 - covered.top - covered.bottom };
  const region = openingRegion(terrain, world.extentX, world.extentZ);
  const heights = regionHeights(terrain, region, scale);
  const sizeX = region.x1 - region.x0, sizeZ = region.z1 - region.z0;
  const target = [0.5 * (region.x0 + region.x1), heights.centre, 0.5 * (region.z0 + region.z1)];
  // Broadside to a long strip (it runs across the screen); else from the south, a little west
  // (the lit side under the renderer's sun): a whole field nearly square to the screen, which it
  // then fills, a region within a larger field more obliquely.
  // A surface that leans as a whole (a tilted plane) is seen from downhill, facing the camera,
  // not edge-on from behind.
  const whole = sizeX === world.extentX && sizeZ === world.extentZ;
  const slope = meanSlope(heights.points);
  let yaw = sizeZ > STRIP_ASPECT * sizeX ? Math.PI / 2 : whole ? 0.15 : 0.4;
  if (Math.hypot(slope.east, slope.south) > LEANING) yaw = Math.atan2(-slope.east, -slope.south);
  // Steeper over flat ground, where a low view shows little; lower where relief stands up.
  const relief = (heights.high - heights.low) / Math.max(Math.hypot(sizeX, sizeZ), 1e-9);
  // A region the curved Earth bends by more than a few degrees (over 1,600 km) is seen from
  // high above: from the side its far part curves away out of sight.
  const curved = world.earth && world.earth.kind !== EARTH_FLAT;
  const wide = curved && Math.hypot(sizeX, sizeZ) > 0.25 * world.earth.radius;
  const basePitch = wide ? 1.2 : relief > 0.05 ? 0.42 : 0.6;
  let pitch = basePitch;
  const fit = (at, pitchNow) => centredView(terrain, world, scale, heights.points, at, yaw, pitchNow, orbit.fovY, aspect, free);
  let view = fit(target, pitch);
  while (!eyeIsClear(terrain, world, scale, view.target, yaw, pitch, view.distance)) {
    if (pitch >= MAX_PITCH) {
      // Needles steeper than any view from above: orbit a point over the highest ground
      // instead, which nothing can hide.
      target[1] = heights.high;
      pitch = basePitch;
      const distance = fitDistance(heights.points, target, yaw, pitch, orbit.fovY, aspect, free);
      view = { target, distance };
      break;
    }
    pitch = Math.min(MAX_PITCH, pitch + PITCH_STEP);
    view = fit(target, pitch);
  }
  // On the curved Earth the region is drawn smaller than flat (a whole-world field is a globe):
  // the nearest distance at which its drawn points fit the view instead, if nearer.
  const earth = world.earth;
  const distance = earth && earth.kind !== EARTH_FLAT
    ? fitOnTheEarth(earth, heights.points, view.target, view.distance, yaw, pitch, orbit.fovY, aspect, free) : view.distance;
  target.splice(0, 3, ...view.target);
  orbit.target[0] = target[0];
  orbit.target[1] = target[1];
  orbit.target[2] = target[2];
  orbit.yaw = yaw;
  orbit.pitch = pitch;
  orbit.distance = Math.max(distance, 1e-2);
}
