// The measured polyline drawn on the ground: the line sampled at the field's spacing with the
// full-resolution heights (the mesh is coarser, so the line follows the true surface, not the
// triangles), a constant number of pixels wide, with a disc on every clicked point and one more
// for the point the profile chart hovers. Drawn by the page's ground lines (ground_lines.js),
// as the overlays' tracks are. Buffers are rebuilt only when the line changes; draw()
// allocates nothing.
import { GROUND_PASSES, segmentsOf } from './ground_lines.js';

// Pixels (CSS) of half the line's width and of a disc's radius.
const LINE_HALF_WIDTH = 2.5, POINT_RADIUS = 5.5, HOVER_RADIUS = 7;
const LINE_COLOR = [1.0, 0.82, 0.18], POINT_COLOR = [1, 1, 1], HOVER_COLOR = [0.2, 0.85, 1.0];
/** Most vertices of the drawn line: a longer one is drawn from every k-th sample. */
export const MAX_LINE_SAMPLES = 40000;

export class MeasureOverlay {
  /** @param {import('./ground_lines.js').GroundLines} lines */
  constructor(lines) {
    this.lines = lines;
    this.gl = lines.gl;
    this.segments = null; // Float32Array [from xyz, to xyz] per segment, kept for a lost context
    this.points = null;   // Float32Array xyz per clicked point
    this.hover = new Float32Array(3);
    this.hoverOn = false;
    this.createGlObjects();
  }

  /** Buffers; again after a lost context came back (the data is uploaded anew). */
  createGlObjects() {
    const gl = this.gl, lines = this.lines;
    this.lineVao = lines.makeVao((this.lineBuffer = gl.createBuffer()), 'segment');
    this.pointVao = lines.makeVao((this.pointBuffer = gl.createBuffer()), 'disc');
    this.hoverVao = lines.makeVao((this.hoverBuffer = gl.createBuffer()), 'disc');
    this.upload();
  }

  /**
   * The line to draw: samples along it (x, z local metres, heights unscaled metres; `runStart`
   * 1 where a run begins after a part off the field), and the clicked points with their heights.
   * Null clears.
   * @param {{x: ArrayLike<number>, z: ArrayLike<number>, height: ArrayLike<number>, runStart?: ArrayLike<number>}|null} samples
   * @param {number[][]} points [[x, height, z], ...]
   */
  setLine(samples, points = []) {
    this.segments = !samples || samples.x.length < 2 ? null : segmentsOf(samples, MAX_LINE_SAMPLES);
    this.points = points.length ? new Float32Array(points.flat()) : null;
    this.upload();
  }

  /** The chart's hovered point [x, height, z] (height unscaled), or null. */
  setHover(point) {
    this.hoverOn = point !== null;
    if (point) this.hover.set(point);
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.hoverBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, this.hover, gl.DYNAMIC_DRAW);
  }

  upload() {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.lineBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, this.segments ?? new Float32Array(6), gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.pointBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, this.points ?? new Float32Array(3), gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.hoverBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, this.hover, gl.DYNAMIC_DRAW);
  }

  /** Whether there is anything to draw. */
  get empty() {
    return !this.segments && !this.points && !this.hoverOn;
  }

  /**
   * Draws over the terrain just drawn (its depth buffer still there).
   * @param {{viewProjection: Float32Array, position: Float32Array}} camera
   * @param {number} width @param {number} height drawing buffer pixels
   * @param {number} verticalScale the exaggeration
   */
  draw(camera, width, height, verticalScale) {
    if (this.empty) return;
    const lines = this.lines;
    lines.begin(camera, width, height, verticalScale);
    for (let k = 0; k < GROUND_PASSES.length; k++) { // indexed: an iterator would be garbage each frame
      const pass = GROUND_PASSES[k];
      lines.pass(pass);
      if (this.segments) lines.segments(this.lineVao, this.segments.length / 6, LINE_HALF_WIDTH * pass.widthShare, LINE_COLOR, pass.alpha);
      if (this.points) lines.discs(this.pointVao, this.points.length / 3, POINT_RADIUS, POINT_COLOR, pass.alpha);
      if (this.hoverOn) lines.discs(this.hoverVao, 1, HOVER_RADIUS, HOVER_COLOR, pass.alpha);
    }
    lines.end();
  }
}
