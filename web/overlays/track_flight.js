// The camera path of a flight along a track: keyframes (the flight files' convention, web/app/
// deterministic/flight.js: metres, x east, z south, y the height unexaggerated) along the
// track's length every few hundred metres, the eye `height` above the highest ground around it
// (so it never cuts through a ridge it passes), looking at the track `lookAhead` metres ahead
// on the ground; times at a speed, or the track's own. Shared by the page's "Fly along"
// (cameras/track_follow.js) and by regression flights with a "track": only + - * / and sqrt
// enter it, so the page and Node compute the same numbers.

/** Most keyframes a path gets: a longer track has them farther apart. */
export const MAX_TRACK_KEYFRAMES = 4000;
const DEFAULTS = { height: 300, lookAhead: 600, speed: 50, fov: 50 };

/**
 * @param {{x: ArrayLike<number>, z: ArrayLike<number>}} placed the track, local metres
 * @param {{t: Float64Array|null}} source the file's path (its times, ms)
 * @param {(x: number, z: number) => number} heightAt the ground, true metres (NaN off the field)
 * @param {{height?: number, lookAhead?: number, speed?: number|null, fov?: number, extentX?: number, extentZ?: number}} [options]
 *   speed: metres a second; null: by the track's times (an Error without them); extentX/Z: the
 *   field's, to look heights up on it where the track leaves it
 * @returns {Array<{time: number, position: number[], target: number[], fov: number}>}
 */
export function trackKeyframes(placed, source, heightAt, options = {}) {
  const { height, lookAhead, fov } = { ...DEFAULTS, ...options };
  const speed = options.speed === undefined ? DEFAULTS.speed : options.speed;
  const n = placed.x.length;
  if (n < 2) throw new Error('a track needs at least 2 points to fly along');
  if (speed === null && !source.t) throw new Error('the track has no times to fly by; give a speed');
  if (speed !== null && !(speed > 0)) throw new Error(`the speed must be positive, got ${speed}`);
  const along = new Float64Array(n);
  for (let k = 1; k < n; k++) {
    const dx = placed.x[k] - placed.x[k - 1], dz = placed.z[k] - placed.z[k - 1];
    along[k] = along[k - 1] + Math.sqrt(dx * dx + dz * dz);
  }
  const total = along[n - 1];
  if (!(total > 0)) throw new Error('the track has no length to fly along');
  const spacing = Math.max(lookAhead / 4, total / (MAX_TRACK_KEYFRAMES - 1), 1e-3);
  const count = Math.floor(total / spacing) + 1 + (total % spacing > 0 ? 1 : 0);
  const xMax = options.extentX ?? Infinity, zMax = options.extentZ ?? Infinity;
  const ground = (x, z) => {
    const h = heightAt(Math.min(Math.max(x, 0), xMax), Math.min(Math.max(z, 0), zMax));
    return h === h ? h : 0; // NaN (no height) as sea level
  };
  let k = 0;
  const point = (d) => { // the track at distance d; beyond its ends, along its first or last segment
    while (k > 0 && along[k] > d) k--;
    while (k + 2 < n && along[k + 1] < d) k++;
    const a = Math.min(k, n - 2), b = a + 1, span = along[b] - along[a];
    const s = span > 0 ? (d - along[a]) / span : 0;
    return [placed.x[a] + (placed.x[b] - placed.x[a]) * s, placed.z[a] + (placed.z[b] - placed.z[a]) * s, a, s];
  };
  const keyframes = [];
  const window = lookAhead / 2, probes = 8;
  let lastTime = -Infinity;
  for (let i = 0; i < count; i++) {
    const d = Math.min(i * spacing, total);
    let highest = -Infinity;
    for (let p = 0; p <= probes; p++) {
      const [px, pz] = point(Math.min(Math.max(d - window + (2 * window * p) / probes, 0), total));
      highest = Math.max(highest, ground(px, pz));
    }
    const [x, z, a, s] = point(d);
    const [tx, tz] = point(d + lookAhead);
    let time;
    if (speed !== null) time = d / speed;
    else {
      const t0 = source.t[0], ta = source.t[a], tb = source.t[a + 1];
      time = (ta + (tb - ta) * s - t0) / 1000;
      if (!(time === time)) time = lastTime + spacing / DEFAULTS.speed; // a fix without a time
    }
    if (!(time > lastTime)) time = lastTime + 1e-3; // strictly later, even where the logger stood still
    lastTime = time;
    keyframes.push({ time, position: [x, highest + height, z], target: [tx, ground(tx, tz), tz], fov });
    k = Math.min(k, a);
  }
  return keyframes;
}
