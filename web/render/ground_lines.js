// Lines and discs drawn on the terrain at a constant pixel width (WebGL2 draws 1 px lines), for
// every kind of line the page lays over the ground: the measured path (measure_overlay.js) and
// the vector overlays' tracks, outlines and markers (render/overlays/). Each segment is one
// instance of a quad, from its start to its end (metres, heights unscaled: the exaggeration is
// a uniform, so changing it rebuilds nothing); a disc is a quad around one point.
//
// Two passes: a faint one with no depth test, so the parts behind a ridge still show where the
// line goes, then a solid one with the depth test. The solid pass pulls every vertex a little
// towards the eye (screen position unchanged), so a line at the full-resolution heights is not
// lost under a mesh that lies up to its screen error above the true surface.
// On the curved Earth the points are placed on it as the terrain's vertices are (earth.glsl).
import { linkProgram, uniformLocations } from './gl_program.js';
import { resolveIncludes } from './shading/includes.js';
import { EARTH_UNIFORMS, EarthUniforms } from './shading/earth_uniforms.js';

const VERTEX = `#version 300 es
#include "earth.glsl"
layout(location = 0) in vec2 aCorner;   // (along 0..1, side -1..1)
layout(location = 1) in vec3 aFrom;     // segment start (or the disc's centre), metres, height unscaled
layout(location = 2) in vec3 aTo;       // segment end (the centre again for a disc)
uniform mat4 uViewProjection;
uniform vec3 uCameraPosition;           // drawn metres
uniform vec2 uViewport;                 // pixels
uniform float uVerticalScale;
uniform float uHalfWidth;               // pixels
uniform float uTowardEye;               // share of the eye distance the vertex moves towards the eye
uniform float uDisc;                    // 1: square discs around aFrom
out vec2 vCorner;
vec4 project(vec3 p) {
  vec3 world = earthPosition(vec3(p.x, p.y * uVerticalScale, p.z));
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
// earth.glsl's entry point for a page without the shaders (Node): points stay on the plane.
const FLAT_EARTH_GLSL = 'vec3 earthPosition(vec3 p) { return p; }';
const UNIFORMS = ['uViewProjection', ...EARTH_UNIFORMS, 'uViewport', 'uVerticalScale', 'uHalfWidth', 'uTowardEye', 'uDisc', 'uColor'];

const TOWARD_EYE = 0.01;
/** The two passes: what lies behind the relief (faint, thinner), then what is in view. */
export const GROUND_PASSES = Object.freeze([
  Object.freeze({ hidden: true, alpha: 0.35, widthShare: 0.7 }),
  Object.freeze({ hidden: false, alpha: 1, widthShare: 1 }),
]);
/** Bytes of a segment instance (from xyz, to xyz) and of a disc instance (xyz). */
export const SEGMENT_BYTES = 24, DISC_BYTES = 12;

export class GroundLines {
  /** @param {WebGL2RenderingContext} gl */
  /**
   * @param {EarthUniforms} [earth] the renderer's: the surface the terrain is drawn on
   * @param {{'earth.glsl': string}} [includes] the shaders/ files its programs include (the
   *   renderer's; the default places points on the plane)
   */
  constructor(gl, earth = new EarthUniforms(), includes = { 'earth.glsl': FLAT_EARTH_GLSL }) {
    this.gl = gl;
    this.earth = earth;
    this.includes = includes;
    this.scale = 1;
    this.createGlObjects();
  }

  /** GLSL of a program that places points on the ground, the curved Earth's functions included. */
  compose(source) {
    return resolveIncludes(source, this.includes);
  }

  /** The program and the quad's corners; again after a lost context (users make their VAOs again). */
  createGlObjects() {
    const gl = this.gl;
    this.program = linkProgram(gl, this.compose(VERTEX), FRAGMENT, 'ground lines');
    this.uniforms = uniformLocations(gl, this.program, UNIFORMS);
    // A quad as two triangles: (along, side).
    this.cornerBuffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, this.cornerBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([0, -1, 1, -1, 1, 1, 0, -1, 1, 1, 0, 1]), gl.STATIC_DRAW);
  }

  /** A VAO reading instances from `buffer`: segments (from, to) or discs (a centre each). */
  makeVao(buffer, kind) {
    const gl = this.gl, vao = gl.createVertexArray();
    const [stride, toOffset] = kind === 'disc' ? [DISC_BYTES, 0] : [SEGMENT_BYTES, 12];
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
   * Sets the camera and the blending for the lines drawn next.
   * @param {{viewProjection: Float32Array, position: Float32Array}} camera
   * @param {number} width @param {number} height drawing buffer pixels
   */
  begin(camera, width, height, verticalScale) {
    const gl = this.gl, u = this.uniforms;
    // Drawing-buffer pixels per CSS pixel: 2 in a 2x screenshot or on a retina screen.
    this.scale = Math.max(1, height / Math.max(1, gl.canvas.clientHeight || height));
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(u.uViewProjection, false, camera.viewProjection);
    this.earth.apply(gl, u, camera, verticalScale);
    gl.uniform2f(u.uViewport, width, height);
    gl.uniform1f(u.uVerticalScale, verticalScale);
    gl.disable(gl.CULL_FACE);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    gl.depthMask(false);
  }

  /** One of GROUND_PASSES: the hidden parts with no depth test, the rest with it. */
  pass(pass) {
    const gl = this.gl;
    gl.useProgram(this.program);
    if (pass.hidden) gl.disable(gl.DEPTH_TEST);
    else {
      gl.enable(gl.DEPTH_TEST);
      gl.depthFunc(gl.LEQUAL);
    }
    gl.uniform1f(this.uniforms.uTowardEye, pass.hidden ? 0 : TOWARD_EYE);
  }

  /** `count` segments of `vao`, `halfWidth` CSS pixels either side. */
  segments(vao, count, halfWidth, rgb, alpha) {
    this.instances(vao, count, 0, halfWidth, rgb, alpha);
  }

  /** `count` discs of `vao`, `radius` CSS pixels. */
  discs(vao, count, radius, rgb, alpha) {
    this.instances(vao, count, 1, radius, rgb, alpha);
  }

  instances(vao, count, disc, size, rgb, alpha) {
    if (count <= 0) return;
    const gl = this.gl, u = this.uniforms;
    gl.useProgram(this.program); // a pass may draw curtains or labels between two calls
    gl.uniform1f(u.uDisc, disc);
    gl.uniform1f(u.uHalfWidth, size * this.scale);
    gl.uniform4f(u.uColor, rgb[0], rgb[1], rgb[2], alpha);
    gl.bindVertexArray(vao);
    gl.drawArraysInstanced(gl.TRIANGLES, 0, 6, count);
  }

  /** Back to the state the terrain's drawing expects. */
  end() {
    const gl = this.gl;
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LEQUAL);
    gl.depthMask(true);
    gl.disable(gl.BLEND);
    gl.bindVertexArray(null);
  }
}

/**
 * The segments between consecutive samples of a line on the ground, as instances (from xyz, to
 * xyz): none across a break (`runStart` 1: a part off the field lies before) or a sample without
 * a height. A line of more than `maxSamples` samples is drawn from every k-th one (and its last).
 * @param {{x: ArrayLike<number>, z: ArrayLike<number>, height: ArrayLike<number>, runStart?: ArrayLike<number>}} samples
 * @returns {Float32Array}
 */
export function segmentsOf(samples, maxSamples) {
  const n = samples.x.length, every = Math.max(1, Math.ceil(n / maxSamples));
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
  return segments.subarray(0, count * 6);
}
