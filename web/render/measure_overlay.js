// The measured polyline drawn on the ground: the line sampled at the field's spacing with the
// full-resolution heights (the mesh is coarser, so the line follows the true surface, not the
// triangles), as quads a constant number of pixels wide (WebGL2 draws 1 px lines), with a disc
// on every clicked point and one more for the point the profile chart hovers.
//
// Two passes: a faint one with no depth test, so the parts behind a ridge still show where the
// line goes, then a solid one with the depth test. The solid pass pulls every vertex a little
// towards the eye (screen position unchanged), so the line is not lost under a mesh that lies
// up to its screen error above the true surface. Heights go to the GPU unscaled: the
// exaggeration is a uniform, so changing it rebuilds nothing. Buffers are rebuilt only when the
// line changes; draw() allocates nothing.
import { linkProgram, uniformLocations } from './gl_program.js';

const VERTEX = `#version 300 es
layout(location = 0) in vec2 aCorner;   // (along 0..1, side -1..1)
layout(location = 1) in vec3 aFrom;     // segment start (or the disc's centre), metres, height unscaled
layout(location = 2) in vec3 aTo;       // segment end (the centre again for a disc)
uniform mat4 uViewProjection;
uniform vec3 uCameraPosition;
uniform vec2 uViewport;                 // pixels
uniform float uVerticalScale;
uniform float uHalfWidth;               // pixels
uniform float uTowardEye;               // share of the eye distance the vertex moves towards the eye
uniform float uDisc;                    // 1: square discs around aFrom
out vec2 vCorner;
vec4 project(vec3 p) {
  vec3 world = vec3(p.x, p.y * uVerticalScale, p.z);
  world = mix(world, uCameraPosition, uTowardEye);
  return uViewProjection * vec4(world, 1.0);
}
void main() {
  vec4 a = project(aFrom), b = project(aTo);
  vec4 here = aCorner.x < 0.5 ? a : b;
  vec2 offset;
  if (uDisc > 0.5) {
    offset = vec2(aCorner.x * 2.0 - 1.0, aCorner.y);
    vCorner = offset;
  } else {
    // Perpendicular to the segment on screen (points behind the eye: no direction, no quad).
    vec2 sa = a.xy / max(a.w, 1e-6) * uViewport, sb = b.xy / max(b.w, 1e-6) * uViewport;
    vec2 d = sb - sa;
    float len = length(d);
    vec2 n = len > 1e-6 ? vec2(-d.y, d.x) / len : vec2(0.0);
    offset = n * aCorner.y;
    vCorner = vec2(0.0, aCorner.y);
  }
  here.xy += offset * uHalfWidth * 2.0 / uViewport * here.w;
  gl_Position = here;
}`;

const FRAGMENT = `#version 300 es
precision highp float;
in vec2 vCorner;
uniform vec4 uColor;
uniform float uDisc;
out vec4 color;
void main() {
  float r = uDisc > 0.5 ? length(vCorner) : abs(vCorner.y);
  if (r > 1.0) discard;
  // A dark rim around a light core reads on snow and on shadow alike.
  float rim = smoothstep(0.55, 0.7, r);
  color = vec4(mix(uColor.rgb, vec3(0.05, 0.05, 0.08), rim), uColor.a);
}`;

const LOCATIONS = { corner: 0, from: 1, to: 2 };
const UNIFORMS = ['uViewProjection', 'uCameraPosition', 'uViewport', 'uVerticalScale', 'uHalfWidth', 'uTowardEye', 'uDisc', 'uColor'];
// Pixels (CSS) of half the line's width and of a disc's radius.
const LINE_HALF_WIDTH = 2.5, POINT_RADIUS = 5.5, HOVER_RADIUS = 7;
const TOWARD_EYE = 0.01;
const LINE_COLOR = [1.0, 0.82, 0.18], HOVER_COLOR = [0.2, 0.85, 1.0];
/** Most vertices of the drawn line: a longer one is drawn from every k-th sample. */
export const MAX_LINE_SAMPLES = 40000;

export class MeasureOverlay {
  /** @param {WebGL2RenderingContext} gl */
  constructor(gl) {
    this.gl = gl;
    this.segments = null; // Float32Array [from xyz, to xyz] per segment, kept for a lost context
    this.points = null;   // Float32Array xyz per clicked point
    this.hover = new Float32Array(6);
    this.hoverOn = false;
    this.createGlObjects();
  }

  /** Program and buffers; again after a lost context came back (the data is uploaded anew). */
  createGlObjects() {
    const gl = this.gl;
    this.program = linkProgram(gl, VERTEX, FRAGMENT, 'measure overlay');
    this.uniforms = uniformLocations(gl, this.program, UNIFORMS);
    // A quad as two triangles: (along, side).
    this.cornerBuffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, this.cornerBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([0, -1, 1, -1, 1, 1, 0, -1, 1, 1, 0, 1]), gl.STATIC_DRAW);
    this.lineVao = this.makeVao((this.lineBuffer = gl.createBuffer()), 24, 12);
    this.pointVao = this.makeVao((this.pointBuffer = gl.createBuffer()), 12, 0);
    this.hoverVao = this.makeVao((this.hoverBuffer = gl.createBuffer()), 12, 0);
    this.upload();
  }

  /** Instanced attributes: from at offset 0, to at `toOffset`, `stride` bytes an instance. */
  makeVao(buffer, stride, toOffset) {
    const gl = this.gl, vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.cornerBuffer);
    gl.enableVertexAttribArray(LOCATIONS.corner);
    gl.vertexAttribPointer(LOCATIONS.corner, 2, gl.FLOAT, false, 0, 0);
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    for (const [location, offset] of [[LOCATIONS.from, 0], [LOCATIONS.to, toOffset]]) {
      gl.enableVertexAttribArray(location);
      gl.vertexAttribPointer(location, 3, gl.FLOAT, false, stride, offset);
      gl.vertexAttribDivisor(location, 1);
    }
    gl.bindVertexArray(null);
    return vao;
  }

  /**
   * The line to draw: samples along it (x, z local metres, heights unscaled metres; `runStart`
   * 1 where a run begins after a part off the field), and the clicked points with their heights.
   * Null clears.
   * @param {{x: ArrayLike<number>, z: ArrayLike<number>, height: ArrayLike<number>, runStart?: ArrayLike<number>}|null} samples
   * @param {number[][]} points [[x, height, z], ...]
   */
  setLine(samples, points = []) {
    if (!samples || samples.x.length < 2) this.segments = null;
    else {
      const n = samples.x.length, every = Math.max(1, Math.ceil(n / MAX_LINE_SAMPLES));
      const segments = new Float32Array(Math.ceil(n / every) * 6);
      let count = 0, previous = -1;
      for (let k = 0; k < n; k = k + every >= n && k < n - 1 ? n - 1 : k + every) {
        const breaks = samples.runStart?.[k] === 1 || !Number.isFinite(samples.height[k]);
        if (previous >= 0 && !breaks && Number.isFinite(samples.height[previous])) {
          segments.set([samples.x[previous], samples.height[previous], samples.z[previous],
            samples.x[k], samples.height[k], samples.z[k]], count * 6);
          count++;
        }
        previous = k;
      }
      this.segments = segments.subarray(0, count * 6);
    }
    this.points = points.length ? new Float32Array(points.flat()) : null;
    this.upload();
  }

  /** The chart's hovered point [x, height, z] (height unscaled), or null. */
  setHover(point) {
    this.hoverOn = point !== null;
    if (point) this.hover.set([point[0], point[1], point[2], point[0], point[1], point[2]]);
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
    const gl = this.gl, u = this.uniforms;
    // Drawing-buffer pixels per CSS pixel: 2 in a 2x screenshot or on a retina screen.
    const scale = Math.max(1, height / Math.max(1, gl.canvas.clientHeight || height));
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(u.uViewProjection, false, camera.viewProjection);
    gl.uniform3fv(u.uCameraPosition, camera.position);
    gl.uniform2f(u.uViewport, width, height);
    gl.uniform1f(u.uVerticalScale, verticalScale);
    gl.disable(gl.CULL_FACE);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    gl.depthMask(false);
    // Hidden parts, faint; then what is in view, solid.
    gl.disable(gl.DEPTH_TEST);
    this.drawAll(0.35, 0, scale, 0.7);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LEQUAL);
    this.drawAll(1, TOWARD_EYE, scale, 1);
    gl.depthMask(true);
    gl.disable(gl.BLEND);
    gl.bindVertexArray(null);
  }

  drawAll(alpha, towardEye, scale, widthShare) {
    const gl = this.gl, u = this.uniforms;
    gl.uniform1f(u.uTowardEye, towardEye);
    if (this.segments) {
      gl.uniform1f(u.uDisc, 0);
      gl.uniform1f(u.uHalfWidth, LINE_HALF_WIDTH * scale * widthShare);
      gl.uniform4f(u.uColor, LINE_COLOR[0], LINE_COLOR[1], LINE_COLOR[2], alpha);
      gl.bindVertexArray(this.lineVao);
      gl.drawArraysInstanced(gl.TRIANGLES, 0, 6, this.segments.length / 6);
    }
    gl.uniform1f(u.uDisc, 1);
    if (this.points) {
      gl.uniform1f(u.uHalfWidth, POINT_RADIUS * scale);
      gl.uniform4f(u.uColor, 1, 1, 1, alpha);
      gl.bindVertexArray(this.pointVao);
      gl.drawArraysInstanced(gl.TRIANGLES, 0, 6, this.points.length / 3);
    }
    if (this.hoverOn) {
      gl.uniform1f(u.uHalfWidth, HOVER_RADIUS * scale);
      gl.uniform4f(u.uColor, HOVER_COLOR[0], HOVER_COLOR[1], HOVER_COLOR[2], alpha);
      gl.bindVertexArray(this.hoverVao);
      gl.drawArraysInstanced(gl.TRIANGLES, 0, 6, 1);
    }
  }
}
