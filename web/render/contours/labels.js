// Labels of the major contour lines: points on them found once per field and major step (where
// sample rows and columns cross a major level; the field is linear along them, so the point is
// on the line exactly), then each frame projected to the screen, turned along the contour and
// kept upright, dropped where they would overlap a label already placed or where the ground
// between the eye and the point hides it (the core's bilinear heights along the sight line).
// A frame allocates nothing: every per-frame array is made once (or when the viewport grows).
import { FLAT_EARTH, drawnPoint } from '../../geo/index.js';
import { inSight } from '../sight_line.js';
import { labelGlyphs, CELL_W, CELL_H, ADVANCE } from './glyph_atlas.js';

/** Points kept at most (each is tested every frame while on screen). */
const MAX_ANCHORS = 4096;
/** Labels drawn at most in one frame, and glyphs per label. */
const MAX_LABELS = 96, MAX_GLYPHS = 8;
/** Label height in CSS pixels. */
export const LABEL_PX = 13;
const GRID = 8; // pixels per cell of the occupancy grid

const drawn = [0, 0, 0]; // a label's drawn point, reused

export class LabelPlacer {
  constructor() {
    this.count = 0;
    this.x = new Float64Array(MAX_ANCHORS);
    this.z = new Float64Array(MAX_ANCHORS);
    this.h = new Float64Array(MAX_ANCHORS); // true metres (the level)
    this.tx = new Float64Array(MAX_ANCHORS); // the contour's direction on the ground (unit)
    this.tz = new Float64Array(MAX_ANCHORS);
    this.glyphs = new Uint8Array(MAX_ANCHORS * MAX_GLYPHS);
    this.glyphCount = new Uint8Array(MAX_ANCHORS);
    /** Per glyph drawn: centre x, y (px), axis x, y, glyph index. */
    this.instances = new Float32Array(MAX_LABELS * MAX_GLYPHS * 5);
    this.instanceCount = 0;
    this.labelsShown = 0;
    this.occupied = new Uint8Array(0);
    this.key = null;
  }

  /**
   * Finds the label points of this field's major levels (allocates; only when the field or the
   * step changed). Rows and columns every `every` samples, one point per level per block.
   * @param {ArrayLike<number>} raw the samples; metres = raw * scale + offset
   */
  findAnchors(raw, width, height, spacingX, spacingZ, scale, offset, major) {
    this.count = 0;
    const every = Math.max(2, Math.round(Math.max(width, height) / 40));
    const taken = new Set();
    const at = (c, r) => raw[r * width + c] * scale + offset;
    const add = (c, r, level, gx, gz) => {
      const key = `${Math.floor(c / every)},${Math.floor(r / every)},${level}`;
      if (taken.has(key) || this.count >= MAX_ANCHORS) return;
      const n = Math.hypot(gx, gz);
      if (!(n > 0)) return;
      const glyphs = labelGlyphs(level);
      if (glyphs.length > MAX_GLYPHS) return;
      taken.add(key);
      const k = this.count++;
      this.x[k] = c * spacingX;
      this.z[k] = r * spacingZ;
      this.h[k] = level;
      this.tx[k] = -gz / n; // along the contour: across the gradient
      this.tz[k] = gx / n;
      this.glyphs.set(glyphs, k * MAX_GLYPHS);
      this.glyphCount[k] = glyphs.length;
    };
    const cross = (h0, h1, visit) => {
      const lo = Math.min(h0, h1), hi = Math.max(h0, h1);
      if (!(hi > lo)) return;
      // A sample on a level counts as below it, as contours.glsl draws it.
      for (let level = Math.ceil(lo / major) * major; level < hi; level += major) visit(level, (level - h0) / (h1 - h0));
    };
    // Sample rows: the height is linear between neighbouring samples along a row.
    for (let r = Math.floor(every / 2); r < height; r += every) {
      const r0 = Math.max(0, r - 1), r1 = Math.min(height - 1, r + 1);
      for (let c = 0; c + 1 < width; ++c) {
        cross(at(c, r), at(c + 1, r), (level, t) => {
          const cc = Math.round(c + t);
          add(c + t, r, level, (at(c + 1, r) - at(c, r)) / spacingX, (at(cc, r1) - at(cc, r0)) / ((r1 - r0) * spacingZ || 1));
        });
      }
    }
    // Sample columns, for contours that run along the rows.
    for (let c = Math.floor(every / 2); c < width; c += every) {
      const c0 = Math.max(0, c - 1), c1 = Math.min(width - 1, c + 1);
      for (let r = 0; r + 1 < height; ++r) {
        cross(at(c, r), at(c, r + 1), (level, t) => {
          const rr = Math.round(r + t);
          add(c, r + t, level, (at(c1, rr) - at(c0, rr)) / ((c1 - c0) * spacingX || 1), (at(c, r + 1) - at(c, r)) / spacingZ);
        });
      }
    }
  }

  /**
   * Chooses this frame's labels and writes their glyphs into `instances`.
   * @param {{viewProjection: Float32Array, position: ArrayLike<number>}} camera drawn metres
   * @param {number} pxScale device pixels per CSS pixel
   * @param {{heightAt(x: number, z: number): number}} terrain the core's bilinear heights, true metres
   */
  place(camera, width, height, pxScale, verticalScale, terrain) {
    const m = camera.viewProjection, eye = camera.position, earth = camera.earth ?? FLAT_EARTH;
    const gw = Math.ceil(width / GRID), gh = Math.ceil(height / GRID);
    if (this.occupied.length < gw * gh) this.occupied = new Uint8Array(gw * gh); // only when the viewport grows
    const occupied = this.occupied;
    occupied.fill(0, 0, gw * gh);
    const glyphH = LABEL_PX * pxScale, advance = glyphH * (CELL_W / CELL_H) * ADVANCE;
    let labels = 0, glyphs = 0;
    for (let k = 0; k < this.count && labels < MAX_LABELS; ++k) {
      const x = this.x[k], y = this.h[k] * verticalScale, z = this.z[k];
      // Where it is drawn (on the curved Earth, web/geo/earth_shape.js).
      drawnPoint(earth, x, y, z, drawn);
      const px = drawn[0], py = drawn[1], pz = drawn[2]; // not destructured: an array iterator each time
      const w = m[3] * px + m[7] * py + m[11] * pz + m[15];
      if (!(w > 0)) continue;
      const sx = ((m[0] * px + m[4] * py + m[8] * pz + m[12]) / w + 1) * 0.5 * width;
      const sy = ((m[1] * px + m[5] * py + m[9] * pz + m[13]) / w + 1) * 0.5 * height;
      const n = this.glyphCount[k], halfW = 0.5 * n * advance + 2 * pxScale;
      if (sx < halfW || sy < glyphH || sx > width - halfW || sy > height - glyphH) continue;
      // The contour's direction on the screen: a point a little along it, projected.
      const d = 0.01 * Math.hypot(x - eye[0], y - eye[1], z - eye[2]);
      drawnPoint(earth, x + this.tx[k] * d, y, z + this.tz[k] * d, drawn);
      const x2 = drawn[0], y2 = drawn[1], z2 = drawn[2];
      const w2 = m[3] * x2 + m[7] * y2 + m[11] * z2 + m[15];
      if (!(w2 > 0)) continue;
      let ax = ((m[0] * x2 + m[4] * y2 + m[8] * z2 + m[12]) / w2 + 1) * 0.5 * width - sx;
      let ay = ((m[1] * x2 + m[5] * y2 + m[9] * z2 + m[13]) / w2 + 1) * 0.5 * height - sy;
      const len = Math.hypot(ax, ay);
      if (len < 0.002 * width) continue; // the contour runs towards the eye: a label would be a sliver
      ax /= len; ay /= len;
      if (ax < 0) { ax = -ax; ay = -ay; } // upright: text reads left to right
      if (Math.abs(ay) > 0.8) continue; // too steep to read
      // The label's bounding box in grid cells: free?
      const ex = Math.abs(ax) * halfW + Math.abs(ay) * 0.5 * glyphH, ey = Math.abs(ay) * halfW + Math.abs(ax) * 0.5 * glyphH;
      const i0 = Math.max(0, Math.floor((sx - ex) / GRID) - 1), i1 = Math.min(gw - 1, Math.floor((sx + ex) / GRID) + 1);
      const j0 = Math.max(0, Math.floor((sy - ey) / GRID) - 1), j1 = Math.min(gh - 1, Math.floor((sy + ey) / GRID) + 1);
      let free = true;
      for (let j = j0; j <= j1 && free; ++j) for (let i = i0; i <= i1; ++i) if (occupied[j * gw + i]) { free = false; break; }
      if (!free || !inSight(eye, x, y, z, verticalScale, terrain)) continue;
      for (let j = j0; j <= j1; ++j) for (let i = i0; i <= i1; ++i) occupied[j * gw + i] = 1;
      for (let g = 0; g < n; ++g) {
        const offset = (g - (n - 1) / 2) * advance, q = glyphs * 5;
        this.instances[q] = sx + ax * offset;
        this.instances[q + 1] = sy + ay * offset;
        this.instances[q + 2] = ax;
        this.instances[q + 3] = ay;
        this.instances[q + 4] = this.glyphs[k * MAX_GLYPHS + g];
        glyphs += 1;
      }
      labels += 1;
    }
    this.instanceCount = glyphs;
    this.labelsShown = labels;
    return glyphs;
  }
}

