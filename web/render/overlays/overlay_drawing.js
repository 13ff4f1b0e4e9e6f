// One overlay on the terrain, as the renderer draws it each frame from the layer list
// (app/layers.js overlays): its lines on the ground or aloft, their curtains, its markers and
// their names, in its colour and width. The geometry (overlay_geometry.js) is uploaded when it
// changes; draw() allocates nothing.
import { GROUND_PASSES } from '../ground_lines.js';
import { linkProgram, uniformLocations } from '../gl_program.js';
import { EARTH_UNIFORMS } from '../shading/earth_uniforms.js';
import { MarkerLabels } from './marker_labels.js';

const CURTAIN_VERTEX = `#version 300 es
#include "earth.glsl"
layout(location = 0) in vec3 aPosition;  // metres, height unscaled
uniform mat4 uViewProjection;
uniform float uVerticalScale;
void main() { gl_Position = uViewProjection * vec4(earthPosition(vec3(aPosition.x, aPosition.y * uVerticalScale, aPosition.z)), 1.0); }`;
const CURTAIN_FRAGMENT = `#version 300 es
precision mediump float;
uniform vec4 uColor;
out vec4 color;
void main() { color = uColor; }`;
const CURTAIN_ALPHA = 0.28;
const MARKER_RADIUS = 6;

export class OverlayDrawing {
  /**
   * @param {import('../ground_lines.js').GroundLines} lines the renderer's
   * @param {() => ({heightAt(x: number, z: number): number}|null)} terrain the core's heights, for the names' sight test
   */
  constructor(lines, terrain) {
    this.lines = lines;
    this.terrain = terrain;
    this.geometry = null;
    this.style = { color: [1, 0.3, 0.6], halfWidth: 2, visible: true };
    this.labels = null;
    this.createGlObjects(lines.gl);
  }

  createGlObjects(gl) {
    this.gl = gl;
    this.segmentVao = this.lines.makeVao((this.segmentBuffer = gl.createBuffer()), 'segment');
    this.markerVao = this.lines.makeVao((this.markerBuffer = gl.createBuffer()), 'disc');
    this.curtainProgram = linkProgram(gl, this.lines.compose(CURTAIN_VERTEX), CURTAIN_FRAGMENT, 'overlay curtain');
    this.curtainUniforms = uniformLocations(gl, this.curtainProgram, ['uViewProjection', 'uVerticalScale', 'uColor', ...EARTH_UNIFORMS]);
    this.curtainVao = gl.createVertexArray();
    gl.bindVertexArray(this.curtainVao);
    this.curtainBuffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, this.curtainBuffer);
    gl.enableVertexAttribArray(0);
    gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 12, 0);
    gl.bindVertexArray(null);
    this.labels?.createGlObjects(gl);
    if (this.geometry) this.upload();
  }

  /** @param {import('./overlay_geometry.js').OverlayGeometry} geometry */
  setGeometry(geometry) {
    this.geometry = geometry;
    this.labels?.dispose();
    this.labels = geometry.markerNames.some((name) => name) ? new MarkerLabels(this.gl, geometry.markerNames) : null;
    this.upload();
  }

  upload() {
    const gl = this.gl, g = this.geometry;
    for (const [buffer, data] of [[this.segmentBuffer, g.segments], [this.markerBuffer, g.markers], [this.curtainBuffer, g.curtain]]) {
      gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
      gl.bufferData(gl.ARRAY_BUFFER, data.length ? data : new Float32Array(6), gl.STATIC_DRAW);
    }
  }

  /** @param {{color?: number[], halfWidth?: number, visible?: boolean}} style colour 0..1, CSS pixels either side */
  setStyle(style) {
    Object.assign(this.style, style);
  }

  draw(gl, camera, width, height, verticalScale) {
    const g = this.geometry, style = this.style;
    if (!g || !style.visible) return;
    const lines = this.lines;
    lines.begin(camera, width, height, verticalScale);
    for (let k = 0; k < GROUND_PASSES.length; k++) { // indexed: an iterator would be garbage each frame
      const pass = GROUND_PASSES[k];
      lines.pass(pass);
      if (!pass.hidden && g.curtain.length) this.drawCurtain(camera, verticalScale);
      lines.segments(this.segmentVao, g.segments.length / 6, style.halfWidth * pass.widthShare, style.color, pass.alpha);
      lines.discs(this.markerVao, g.markers.length / 3, MARKER_RADIUS, style.color, pass.alpha);
    }
    lines.end();
    this.labels?.draw(camera, width, height, verticalScale, g.markers, this.terrain(), lines.scale);
  }

  /** The curtain: see-through, depth-tested, both faces. */
  drawCurtain(camera, verticalScale) {
    const gl = this.gl, u = this.curtainUniforms, c = this.style.color;
    gl.useProgram(this.curtainProgram);
    gl.uniformMatrix4fv(u.uViewProjection, false, camera.viewProjection);
    this.lines.earth.apply(gl, u, camera, verticalScale);
    gl.uniform1f(u.uVerticalScale, verticalScale);
    gl.uniform4f(u.uColor, c[0], c[1], c[2], CURTAIN_ALPHA);
    gl.bindVertexArray(this.curtainVao);
    gl.drawArrays(gl.TRIANGLES, 0, this.geometry.curtain.length / 3);
  }

  dispose() {
    const gl = this.gl;
    for (const buffer of [this.segmentBuffer, this.markerBuffer, this.curtainBuffer]) gl.deleteBuffer(buffer);
    this.labels?.dispose();
  }
}
