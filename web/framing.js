// The opening view of a terrain (default, dropped, picked, ?src=, and R): the whole field, or on
// a large field the region of greatest relief, fitted into the view from above its surface, at
// any base height, size, aspect, spacing and exaggeration.
//
// The region's surface, sampled on a grid (heights exaggerated), is fitted into the frustum by
// distance, in closed form per point; the pitch then rises until the eye is clear of the ground
// under it and nothing stands between the eye and the target.
const FOCUS_GRID = 96;        // coarse samples per side of the relief search
const FOCUS_WINDOW = 4;       // half-width, in coarse samples, of the neighbourhood whose relief counts
const LARGE_FIELD = 1500;     // samples on the longer side above which a region, not the whole field, opens
const STRIP_ASPECT = 4;       // a field this many times longer than wide is seen broadside
const HEIGHT_GRID = 48;       // samples per side of the region's height range
const FILL = 0.92;            // the region fills this share of the half field of view
const SIGHT_STEPS = 256;      // samples along the line of sight checked for ground in the way
const PITCH_STEP = 0.08;      // radians added while the eye is blocked
const MAX_PITCH = 1.45;       // radians: close to straight down

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

/**
 * The orbit distance at which every point ([x, y, z] metres) lies inside the view, for a camera
 * looking at `target` from yaw and pitch (orbit.js conventions: yaw 0 looks north, from +z).
 * Closed form per point: its offsets across and up the view over its depth stay within the
 * half field of view.
 */
export function fitDistance(points, target, yaw, pitch, fovY, aspect) {
  const cp = Math.cos(pitch), sp = Math.sin(pitch), sy = Math.sin(yaw), cy = Math.cos(yaw);
  const forward = [-cp * sy, -sp, -cp * cy];
  const right = [cy, 0, -sy];
  const up = [right[1] * forward[2] - right[2] * forward[1], right[2] * forward[0] - right[0] * forward[2],
    right[0] * forward[1] - right[1] * forward[0]];
  const tanY = Math.tan(0.5 * fovY) * FILL, tanX = tanY * aspect;
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
 * Puts the orbit camera where a terrain opens: its region in view, the eye above the surface.
 * @param {{width: number, height: number, heightAt: (x: number, z: number) => number}} terrain
 * @param {{extentX: number, extentZ: number, ground: (x: number, z: number) => number}} world drawn metres
 * @param {import('./cameras/orbit.js').OrbitCamera} orbit
 * @param {number} scale the vertical exaggeration
 * @param {number} aspect viewport width / height
 */
export function frameTerrain(terrain, world, orbit, scale, aspect) {
  const region = openingRegion(terrain, world.extentX, world.extentZ);
  const heights = regionHeights(terrain, region, scale);
  const sizeX = region.x1 - region.x0, sizeZ = region.z1 - region.z0;
  const target = [0.5 * (region.x0 + region.x1), heights.centre, 0.5 * (region.z0 + region.z1)];
  // Broadside to a long strip (it runs across the screen); else from the south, a little west
  // (the lit side under the renderer's sun): a whole field nearly square to the screen, which it
  // then fills, a region within a larger field more obliquely.
  const whole = sizeX === world.extentX && sizeZ === world.extentZ;
  const yaw = sizeZ > STRIP_ASPECT * sizeX ? Math.PI / 2 : whole ? 0.15 : 0.4;
  // Steeper over flat ground, where a low view shows little; lower where relief stands up.
  const relief = (heights.high - heights.low) / Math.max(Math.hypot(sizeX, sizeZ), 1e-9);
  const basePitch = relief > 0.05 ? 0.42 : 0.6;
  let pitch = basePitch;
  let distance = fitDistance(heights.points, target, yaw, pitch, orbit.fovY, aspect);
  while (!eyeIsClear(terrain, world, scale, target, yaw, pitch, distance)) {
    if (pitch >= MAX_PITCH) {
      // Needles steeper than any view from above: orbit a point over the highest ground
      // instead, which nothing can hide.
      target[1] = heights.high;
      pitch = basePitch;
      distance = fitDistance(heights.points, target, yaw, pitch, orbit.fovY, aspect);
      break;
    }
    pitch = Math.min(MAX_PITCH, pitch + PITCH_STEP);
    distance = fitDistance(heights.points, target, yaw, pitch, orbit.fovY, aspect);
  }
  orbit.target[0] = target[0];
  orbit.target[1] = target[1];
  orbit.target[2] = target[2];
  orbit.yaw = yaw;
  orbit.pitch = pitch;
  orbit.distance = Math.max(distance, 1e-2);
}
