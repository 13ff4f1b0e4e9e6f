// The profile along a track of an overlay (GPX, KML, GeoJSON): the terrain's heights at full
// resolution along it, every vertex of the track a sample (measure/profile.js), and beside them
// what the file recorded: its elevations (GPS) and times, linear by distance between vertices
// and exact at them; with its climb by those elevations (past a hysteresis against the GPS's
// noise), its duration, its mean speed and its speed while moving.
import { computeProfile } from './profile.js';

/** Slower than this between two fixes is a stop, left out of the moving speed (metres a second). */
export const STOP_SPEED = 0.5;
/**
 * Metres a recorded elevation must move from the last one counted before it counts as climb:
 * a GPS's elevations wander by metres from fix to fix, and summing every wobble would report
 * many times the real climb.
 */
export const CLIMB_HYSTERESIS = 5;

/**
 * @param {{x: ArrayLike<number>, z: ArrayLike<number>}} placed the track in local metres (overlays/place_overlay.js)
 * @param {{z: Float64Array|null, t: Float64Array|null}} source the file's path: elevations (m) and times (ms)
 * @param {import('./field_sampler.js').FieldSampler} sampler
 * @param {{step?: number}} [options]
 * @returns {import('./profile.js').Profile & {samples: {gpsElevation: Float64Array, time: Float64Array, vertex: Int32Array}}}
 *   summary adds gpsGain and gpsLoss (metres, NaN without elevations), duration (s), averageSpeed
 *   and movingSpeed (m/s; null without times)
 * @throws {Error} fewer than 2 vertices, or a track entirely off the field
 */
export function computeTrackProfile(placed, source, sampler, { step } = {}) {
  const n = placed.x.length;
  const points = Array.from({ length: n }, (_, k) => [placed.x[k], placed.z[k]]);
  const profile = computeProfile(points, sampler, { step });
  // Each vertex's distance along the line, summed as profile.js sums them (the same numbers).
  const along = new Float64Array(n);
  for (let k = 1; k < n; k++) along[k] = along[k - 1] + Math.hypot(placed.x[k] - placed.x[k - 1], placed.z[k] - placed.z[k - 1]);
  const { distance } = profile.samples, count = distance.length;
  const gpsElevation = new Float64Array(count).fill(NaN), time = new Float64Array(count).fill(NaN), vertex = new Int32Array(count).fill(-1);
  let k = 0;
  for (let i = 0; i < count; i++) {
    const d = distance[i];
    while (k + 1 < n && along[k + 1] < d) k++;
    // The sample lies between vertices k and k + 1 (or on one of them).
    const next = Math.min(k + 1, n - 1);
    if (d === along[k]) vertex[i] = k;
    else if (d === along[next]) vertex[i] = next;
    const s = along[next] > along[k] ? (d - along[k]) / (along[next] - along[k]) : 0;
    if (source.z) gpsElevation[i] = lerp(source.z[k], source.z[next], s);
    if (source.t) time[i] = lerp(source.t[k], source.t[next], s);
  }
  Object.assign(profile.samples, { gpsElevation, time, vertex });
  Object.assign(profile.summary, recordedSummary(profile.samples, profile.summary.length3d));
  return profile;
}

function lerp(a, b, s) {
  if (!Number.isFinite(a)) return s === 1 ? b : NaN;
  if (!Number.isFinite(b)) return s === 0 ? a : NaN;
  return a + (b - a) * s;
}

/** Climb by the recorded elevations, and time and speeds, over the vertices on the field. */
function recordedSummary({ distance, height, gpsElevation, time, vertex, runStart }, length3d) {
  let gpsGain = 0, gpsLoss = 0, hasElevation = false, first = NaN, last = NaN, counted = NaN;
  let movingMetres = 0, movingSeconds = 0, previous = -1;
  for (let i = 0; i < vertex.length; i++) {
    if (vertex[i] < 0) continue;
    if (Number.isFinite(time[i])) {
      if (!Number.isFinite(first)) first = time[i];
      last = time[i];
    }
    if (Number.isFinite(gpsElevation[i])) {
      hasElevation = true;
      const rise = gpsElevation[i] - counted;
      if (!Number.isFinite(counted) || runStart[i] === 1) counted = gpsElevation[i];
      else if (Math.abs(rise) >= CLIMB_HYSTERESIS) {
        if (rise > 0) gpsGain += rise; else gpsLoss -= rise;
        counted = gpsElevation[i];
      }
    }
    if (previous >= 0 && runStart[i] !== 1) {
      const seconds = (time[i] - time[previous]) / 1000;
      const dh = Number.isFinite(height[i] - height[previous]) ? height[i] - height[previous] : 0;
      const metres = Math.sqrt((distance[i] - distance[previous]) ** 2 + dh * dh);
      if (seconds > 0 && metres / seconds >= STOP_SPEED) {
        movingMetres += metres;
        movingSeconds += seconds;
      }
    }
    previous = i;
  }
  const duration = Number.isFinite(first) && last > first ? (last - first) / 1000 : null;
  return {
    gpsGain: hasElevation ? gpsGain : NaN,
    gpsLoss: hasElevation ? gpsLoss : NaN,
    duration,
    averageSpeed: duration ? length3d / duration : null,
    movingSpeed: movingSeconds > 0 ? movingMetres / movingSeconds : null,
  };
}
