// The height profile along a polyline drawn on the field: heights of the full-resolution
// samples (bilinear between them) every `step` metres and at every vertex, and what a walker
// would want to know of it: length on the map and along the ground, climb and descent, lowest
// and highest point, mean and steepest slope.
//
// Parts of the line off the field are left out (there are no heights there), and the result
// says how much. Distances stay those along the drawn line, so a line that leaves the field and
// comes back has a jump in distance where it was outside.
import { clipSegment } from './clip.js';
import { checkPoints } from './points.js';
import { formatLength } from './units.js';
import { groundMetric } from './ground_metric.js';

/** Most samples one profile takes; a finer step is widened to this, and `note` says so. */
export const MAX_PROFILE_SAMPLES = 1_000_000;

/**
 * @typedef {object} ProfileSummary
 * @property {number} length metres on the map (2D) of the parts on the field (on a geographic
 *   grid, on the WGS 84 ellipsoid: ground_metric.js)
 * @property {number} length3d metres along the ground (height changes included; a step to or
 *   from a no-data sample counts as flat)
 * @property {number} gain metres climbed: sum of the rises between consecutive samples (>= 0)
 * @property {number} loss metres descended: sum of the drops between consecutive samples (>= 0)
 * @property {number} min lowest height, metres
 * @property {number} max highest height, metres
 * @property {number} meanSlope degrees: atan((gain + loss) / length), the slope of the climbing
 *   and descending averaged over the length
 * @property {number} steepestSlope degrees: the steepest slope between two consecutive samples
 * @property {number} meanSlopeDeg the same as meanSlope (the unit in the name)
 * @property {number} steepestSlopeDeg the same as steepestSlope
 */

/**
 * @typedef {object} Profile
 * @property {{distance: Float64Array, x: Float64Array, z: Float64Array, height: Float64Array, runStart: Uint8Array}} samples
 *   one entry per sample: metres along the drawn line from its first point, position (local
 *   metres), height (metres; NaN on no-data), and 1 where a run on the field begins (the
 *   first sample, and the first after a part off the field: a chart breaks its line there)
 * @property {ProfileSummary} summary
 * @property {string|null} clipped how much of the line lay off the field, or null
 * @property {string|null} note anything else the caller should tell (a widened step), or null
 * @property {number} step metres between samples along each segment (at most)
 * @property {number} spacingX metres between columns of the field
 * @property {number} spacingY metres between rows
 */

/**
 * @param {number[][]} points [[x, z], ...] local metres, at least 2
 * @param {import('./field_sampler.js').FieldSampler} sampler
 * @param {{step?: number}} [options] step: metres between samples (default: the field's finer spacing)
 * @returns {Profile}
 * @throws {Error} fewer than 2 points, a coordinate that is not a finite number, a step that is
 *   not positive, or a line entirely off the field
 */
export function computeProfile(points, sampler, { step } = {}) {
  checkPoints(points, 2, 'a profile');
  if (step !== undefined && !(Number.isFinite(step) && step > 0)) {
    throw new Error(`the profile step must be a positive number of metres, got ${step}`);
  }
  let note = null;
  const pieces = piecesOnField(points, sampler.extentX, sampler.extentZ);
  if (pieces.inside === 0 && pieces.parts.length === 0) {
    throw new Error(`the line lies entirely outside the field (x 0..${round(sampler.extentX)} m, z 0..${round(sampler.extentZ)} m)`);
  }
  step ??= sampler.spacing;
  if (pieces.inside / step + pieces.vertices > MAX_PROFILE_SAMPLES) {
    const wanted = step;
    step = pieces.inside / (MAX_PROFILE_SAMPLES - pieces.vertices);
    note = `sampled every ${formatLength(step)} instead of ${formatLength(wanted)}: at most ${MAX_PROFILE_SAMPLES} samples`;
  }
  const samples = sampleParts(pieces.parts, step, sampler);
  // On a geographic grid, lengths are the ellipsoid's (ground_metric.js), sample to sample.
  const metric = groundMetric(sampler);
  if (metric) measureOnTheGround(samples, metric);
  // Else the 2D length from the segments themselves: a sum over thousands of samples drifts.
  const summary = metric ? summarize(samples, metric) : { ...summarize(samples), length: pieces.inside };
  const cut = pieces.total - pieces.inside;
  // Below a millimetre is rounding at the field's edge, not a part left out.
  const clipped = cut > 1e-3 ? `${formatLength(cut)} of ${formatLength(pieces.total)} lay outside the field and was left out` : null;
  return { samples, summary, clipped, note, step, spacingX: sampler.spacingX, spacingY: sampler.spacingY };
}

/**
 * The runs of the polyline on the field: each a list of [x, z, distance] vertices (entry and
 * exit points included), with the lengths drawn and inside.
 */
function piecesOnField(points, xMax, zMax) {
  const parts = [];
  let current = null, total = 0, inside = 0, vertices = 0;
  for (let k = 0; k + 1 < points.length; k++) {
    const [ax, az] = points[k], [bx, bz] = points[k + 1];
    const length = Math.hypot(bx - ax, bz - az);
    const span = clipSegment(ax, az, bx, bz, xMax, zMax);
    if (span) {
      const [t0, t1] = span;
      // Clamped: an entry or exit point computed from t may land an ulp off the field.
      const at = (t) => [clamp(ax + (bx - ax) * t, xMax), clamp(az + (bz - az) * t, zMax), total + length * t];
      // A run goes on only where the segment starts on the field where the last one ended.
      if (!current || t0 > 0) parts.push((current = [at(t0)])), vertices++;
      if (t1 > t0) current.push(at(t1)), vertices++;
      inside += length * (t1 - t0);
      if (t1 < 1) current = null;
    } else {
      current = null;
    }
    total += length;
  }
  return { parts, total, inside, vertices };
}

/** Samples along every run: each vertex, and points at most `step` apart between them. */
function sampleParts(parts, step, sampler) {
  let count = 0;
  for (const part of parts) {
    count++;
    for (let k = 1; k < part.length; k++) count += intervals(part[k - 1], part[k], step);
  }
  const distance = new Float64Array(count), x = new Float64Array(count), z = new Float64Array(count);
  const height = new Float64Array(count), runStart = new Uint8Array(count);
  let n = 0;
  const put = (px, pz, d) => {
    x[n] = px, z[n] = pz, distance[n] = d, height[n] = sampler.heightAt(px, pz);
    n++;
  };
  for (const part of parts) {
    runStart[n] = 1;
    put(part[0][0], part[0][1], part[0][2]);
    for (let k = 1; k < part.length; k++) {
      const [ax, az, ad] = part[k - 1], [bx, bz, bd] = part[k];
      const m = intervals(part[k - 1], part[k], step);
      for (let i = 1; i < m; i++) {
        const t = i / m;
        put(ax + (bx - ax) * t, az + (bz - az) * t, ad + (bd - ad) * t);
      }
      put(bx, bz, bd); // the vertex itself, not a sum of steps
    }
  }
  return { distance, x, z, height, runStart };
}

/** How many equal intervals of at most `step` metres a segment takes (at least 1). */
function intervals(a, b, step) {
  return Math.max(1, Math.ceil(Math.hypot(b[0] - a[0], b[1] - a[1]) / step - 1e-9));
}

const stretch = [1, 1]; // ground metres per local metre east and south, reused

/** Map metres between samples k - 1 and k: the ground metric's at their middle row, if any. */
function runLength(x, z, k, metric) {
  const dx = x[k] - x[k - 1], dz = z[k] - z[k - 1];
  if (!metric) return Math.hypot(dx, dz);
  metric.stretch(0.5 * (z[k] + z[k - 1]), stretch);
  return Math.hypot(dx * stretch[0], dz * stretch[1]);
}

/**
 * The samples' distances along the line as the ground metric measures them. Across a part off
 * the field (a new run) the line's own map length there, scaled as the straight step is.
 */
function measureOnTheGround({ distance, x, z, runStart }, metric) {
  let before = distance[0]; // the map distance of the sample before, as sampled
  for (let k = 1; k < distance.length; k++) {
    const mapStep = distance[k] - before, flat = Math.hypot(x[k] - x[k - 1], z[k] - z[k - 1]);
    before = distance[k];
    const ground = runLength(x, z, k, metric);
    distance[k] = distance[k - 1] + (!runStart[k] ? ground : flat > 0 ? mapStep * (ground / flat) : mapStep);
  }
}

/** Lengths, climb, heights and slopes over the samples, never across a gap between runs. */
function summarize({ x, z, height, runStart }, metric = null) {
  let length = 0, length3d = 0, gain = 0, loss = 0, min = Infinity, max = -Infinity, steepest = 0;
  for (let k = 0; k < height.length; k++) {
    const h = height[k];
    if (h < min) min = h;
    if (h > max) max = h;
    if (runStart[k]) continue;
    const run = runLength(x, z, k, metric);
    const rise = h - height[k - 1];
    length += run;
    if (!Number.isFinite(rise)) { // a no-data sample: no climb is known there, taken as flat
      length3d += run;
      continue;
    }
    length3d += Math.hypot(run, rise);
    if (rise > 0) gain += rise;
    else loss -= rise;
    if (run > 0) steepest = Math.max(steepest, Math.abs(rise) / run);
  }
  const degrees = (ratio) => (Math.atan(ratio) * 180) / Math.PI;
  const meanSlope = length > 0 ? degrees((gain + loss) / length) : 0;
  const steepestSlope = degrees(steepest);
  if (min > max) min = max = NaN; // every sample was no-data
  return { length, length3d, gain, loss, min, max, meanSlope, steepestSlope, meanSlopeDeg: meanSlope, steepestSlopeDeg: steepestSlope };
}

const round = (v) => Number(v.toFixed(1));
const clamp = (v, max) => Math.min(Math.max(v, 0), max);
