// What the renderer draws of an overlay placed on the terrain (overlays/place_overlay.js), made
// once when the overlay, the terrain or the way it is drawn changes, never per frame:
//   - lines and polygon outlines clamped to the ground: each path simplified for drawing (within
//     a fraction of the field's spacing, so nothing a screen shows is lost), then sampled along
//     at the field's spacing with the full-resolution heights, exactly as the measured line is
//     (measure/profile.js), so they follow the true surface and never the coarser mesh;
//   - or lines at the file's own altitude, with a curtain down to the ground if asked;
//   - markers at points, with their names for the labels;
//   - the simplified paths in local metres, for hovering and clicking (overlay_picking.js).
// Parts off the field are not drawn; the placement counts the features entirely off it.
import { computeProfile } from '../../measure/profile.js';
import { simplifyForDrawing } from '../../overlays/simplify_path.js';
import { segmentsOf } from '../ground_lines.js';

/** Samples one overlay draws at most; past it the sampling step widens. */
export const MAX_OVERLAY_SAMPLES = 400000;
/** Share of the field's spacing a simplified path may stray from the file's. */
const SIMPLIFY_SHARE = 0.25;

/**
 * @typedef {object} OverlayGeometry
 * @property {Float32Array} segments clamped and aloft lines, (from xyz, to xyz) per segment, heights unscaled metres
 * @property {Float32Array} curtain triangles (xyz each vertex) from lines aloft down to the ground
 * @property {Float32Array} markers xyz of each point drawn
 * @property {string[]} markerNames the name of each marker ('' for none)
 * @property {Array<{feature: number, path: number, kind: string, x: Float64Array, z: Float64Array, closed: boolean}>} picks
 *   the drawn paths in local metres (simplified), for hover and click
 * @property {number} drawnVertices vertices of the files' paths kept for drawing
 * @property {number} fileVertices vertices of the files' paths
 */

/**
 * @param {{features: Array<{feature: object, paths: Array<{x: Float64Array, z: Float64Array, inside: Uint8Array}>}>}} placed
 * @param {import('../../measure/field_sampler.js').FieldSampler} sampler
 * @param {{altitude?: 'file'|'clamp'|'absolute', curtain?: boolean}} [options] 'file': each
 *   feature as its file says (KML altitudeMode); a line aloft needs altitudes in the file
 * @returns {OverlayGeometry}
 */
export function overlayGeometry(placed, sampler, { altitude = 'file', curtain = false } = {}) {
  const tolerance = sampler.spacing * SIMPLIFY_SHARE;
  const lines = [], markers = [], markerNames = [], picks = [];
  let fileVertices = 0, drawnVertices = 0, length = 0;
  placed.features.forEach(({ feature, paths }, index) => {
    const aloft = (altitude === 'file' ? feature.altitude : altitude) === 'absolute';
    paths.forEach((path, p) => {
      const source = feature.paths[p];
      fileVertices += path.x.length;
      if (feature.kind === 'point') {
        for (let k = 0; k < path.x.length; k++) {
          if (!path.inside[k]) continue;
          const ground = sampler.heightAt(path.x[k], path.z[k]);
          const own = source.z?.[k];
          markers.push(path.x[k], aloft && Number.isFinite(own) ? own : ground, path.z[k]);
          markerNames.push(feature.name ?? '');
          drawnVertices++;
        }
        picks.push({ feature: index, path: p, kind: 'point', x: path.x, z: path.z, closed: false });
        return;
      }
      const closed = feature.kind === 'polygon';
      const kept = simplifyForDrawing(path.x, path.z, tolerance, aloft ? source.z : null);
      drawnVertices += kept.length;
      const x = Float64Array.from(kept, (k) => path.x[k]), z = Float64Array.from(kept, (k) => path.z[k]);
      const ele = source.z ? Float64Array.from(kept, (k) => source.z[k]) : null;
      picks.push({ feature: index, path: p, kind: feature.kind, x, z, closed });
      for (let k = 1; k < x.length; k++) length += Math.hypot(x[k] - x[k - 1], z[k] - z[k - 1]);
      lines.push({ x, z, ele, aloft: aloft && ele !== null });
    });
  });
  const step = Math.max(sampler.spacing, length / MAX_OVERLAY_SAMPLES);
  const segmentParts = [], curtainParts = [];
  for (const line of lines) {
    if (line.x.length < 2) continue;
    if (line.aloft) {
      const { segments, wall } = aloftLine(line, sampler, curtain);
      segmentParts.push(segments);
      if (wall) curtainParts.push(wall);
    } else {
      const samples = clampedSamples(line, sampler, step);
      if (samples) segmentParts.push(segmentsOf(samples, Infinity));
    }
  }
  return { segments: concat(segmentParts), curtain: concat(curtainParts), markers: new Float32Array(markers), markerNames,
    picks, drawnVertices, fileVertices };
}

/** The line's samples on the field at the full-resolution heights, or null when none of it is on the field. */
function clampedSamples(line, sampler, step) {
  const points = Array.from(line.x, (x, k) => [x, line.z[k]]);
  try {
    return computeProfile(points, sampler, { step }).samples;
  } catch {
    return null; // entirely off the field: the placement counts it
  }
}

/**
 * A line at its own altitudes (a vertex without one stays on the ground), and the curtain: two
 * triangles a segment from the line down to the ground under its ends. Segments with an end off
 * the field are left out.
 */
function aloftLine(line, sampler, withCurtain) {
  const n = line.x.length;
  const segments = new Float32Array((n - 1) * 6), wall = withCurtain ? new Float32Array((n - 1) * 18) : null;
  let count = 0;
  for (let k = 1; k < n; k++) {
    const ax = line.x[k - 1], az = line.z[k - 1], bx = line.x[k], bz = line.z[k];
    const ga = sampler.heightAt(ax, az), gb = sampler.heightAt(bx, bz);
    if (!Number.isFinite(ga) || !Number.isFinite(gb)) continue;
    const ha = Number.isFinite(line.ele[k - 1]) ? line.ele[k - 1] : ga, hb = Number.isFinite(line.ele[k]) ? line.ele[k] : gb;
    segments.set([ax, ha, az, bx, hb, bz], count * 6);
    wall?.set([ax, ha, az, bx, hb, bz, bx, gb, bz, ax, ha, az, bx, gb, bz, ax, ga, az], count * 18);
    count++;
  }
  return { segments: segments.subarray(0, count * 6), wall: wall?.subarray(0, count * 18) ?? null };
}

function concat(parts) {
  const out = new Float32Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const part of parts) {
    out.set(part, at);
    at += part.length;
  }
  return out;
}
