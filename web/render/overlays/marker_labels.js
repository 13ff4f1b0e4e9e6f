// The names of an overlay's markers, drawn beside them on the screen: each name drawn once into
// a texture from a 2D canvas (any script the browser's fonts have), then each frame the markers
// in view are projected, and a name is drawn where it overlaps no name already placed and the
// ground does not hide its marker (sight_line.js, as the contour labels). In GL, not the DOM,
// so screenshots carry them. A frame allocates nothing.
import { FLAT_EARTH, drawnPoint } from '../../geo/index.js';
import { linkProgram, uniformLocations } from '../gl_program.js';
import { inSight } from '../sight_line.js';
import { TEXTURE_UNIT_GLYPHS } from '../contours/contour_overlay.js';
import { textCanvas, textTexture, drawTextQuads } from '../contours/glyph_atlas.js';

/** Names drawn at most (the first ones of the file); a cell of the atlas each. */
export const MAX_MARKER_LABELS = 256;
const CELL_W = 512, CELL_H = 40, COLUMNS = 2;
/** Label height in CSS pixels. */
const LABEL_PX = 15;
const GRID = 8; // pixels per cell of the occupancy grid

const VERTEX = `#version 300 es
layout(location = 0) in vec3 aLabel;   // screen x, y (pixels, y up), atlas cell
layout(location = 1) in float aWidth;  // share of the cell's width the text takes
uniform vec2 uViewport;
uniform vec2 uCellPixels;             // a cell's size on screen
uniform float uColumns;
uniform float uRows;
out vec2 vUv;
void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
  vec2 size = uCellPixels * vec2(aWidth, 1.0);
  vec2 p = aLabel.xy + vec2(corner.x * size.x, (corner.y - 0.5) * size.y);
  gl_Position = vec4(p / uViewport * 2.0 - 1.0, 0.0, 1.0);
  float column = mod(aLabel.z, uColumns), row = floor(aLabel.z / uColumns);
  vUv = vec2((column + corner.x * aWidth) / uColumns, (row + 1.0 - corner.y) / uRows);
}`;

const FRAGMENT = `#version 300 es
precision mediump float;
in vec2 vUv;
uniform sampler2D uAtlas;
out vec4 color;
void main() { color = texture(uAtlas, vUv); }`;

const drawn = [0, 0, 0]; // a marker's drawn point, reused

export class MarkerLabels {
  /**
   * @param {WebGL2RenderingContext} gl
   * @param {string[]} names one a marker ('' for none)
   */
  constructor(gl, names) {
    this.gl = gl;
    this.cells = new Int32Array(names.length).fill(-1); // the atlas cell of each marker's name
    this.widths = new Float32Array(MAX_MARKER_LABELS);
    this.texts = [];
    for (let k = 0; k < names.length && this.texts.length < MAX_MARKER_LABELS; k++) {
      if (!names[k]) continue;
      this.cells[k] = this.texts.length;
      this.texts.push(names[k].length > 40 ? `${names[k].slice(0, 39)}…` : names[k]);
    }
    this.instances = new Float32Array(MAX_MARKER_LABELS * 4);
    this.occupied = new Uint8Array(0);
    this.shown = 0;
    this.createGlObjects(gl);
  }

  createGlObjects(gl) {
    this.gl = gl;
    this.program = null;
    if (this.texts.length === 0) return;
    this.program = linkProgram(gl, VERTEX, FRAGMENT, 'marker label');
    this.uniforms = uniformLocations(gl, this.program, ['uViewport', 'uCellPixels', 'uColumns', 'uRows', 'uAtlas']);
    this.rows = Math.ceil(this.texts.length / COLUMNS);
    this.atlas = this.drawAtlas();
    this.vao = gl.createVertexArray();
    gl.bindVertexArray(this.vao);
    this.buffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buffer);
    gl.bufferData(gl.ARRAY_BUFFER, this.instances.byteLength, gl.DYNAMIC_DRAW);
    gl.enableVertexAttribArray(0);
    gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 16, 0);
    gl.vertexAttribDivisor(0, 1);
    gl.enableVertexAttribArray(1);
    gl.vertexAttribPointer(1, 1, gl.FLOAT, false, 16, 12);
    gl.vertexAttribDivisor(1, 1);
    gl.bindVertexArray(null);
  }

  /** The names, dark on a light halo, one a cell; each one's width as a share of its cell. */
  drawAtlas() {
    const gl = this.gl, g = textCanvas(CELL_W * COLUMNS, CELL_H * this.rows, Math.round(CELL_H * 0.6));
    this.texts.forEach((text, k) => {
      const x = (k % COLUMNS) * CELL_W + 8, y = Math.floor(k / COLUMNS) * CELL_H + CELL_H * 0.54;
      g.strokeStyle = 'rgba(255, 255, 255, 0.92)';
      g.lineWidth = 7;
      g.strokeText(text, x, y, CELL_W - 16);
      g.fillStyle = 'rgb(20, 20, 30)';
      g.fillText(text, x, y, CELL_W - 16);
      this.widths[k] = Math.min(CELL_W, g.measureText(text).width + 16) / CELL_W;
    });
    return textTexture(gl, TEXTURE_UNIT_GLYPHS, g.canvas);
  }

  /**
   * Places and draws this frame's names.
   * @param {Float32Array} markers xyz of each marker, heights unscaled metres
   * @param {{heightAt(x: number, z: number): number}} terrain
   */
  draw(camera, width, height, verticalScale, markers, terrain, pxScale) {
    this.shown = 0;
    if (!this.program || !terrain) return;
    const m = camera.viewProjection, eye = camera.position, earth = camera.earth ?? FLAT_EARTH;
    const gw = Math.ceil(width / GRID), gh = Math.ceil(height / GRID);
    if (this.occupied.length < gw * gh) this.occupied = new Uint8Array(gw * gh); // only when the viewport grows
    this.occupied.fill(0, 0, gw * gh);
    const cellH = LABEL_PX * pxScale, cellW = cellH * CELL_W / CELL_H, gap = 9 * pxScale;
    let count = 0;
    for (let k = 0; k < this.cells.length && count < MAX_MARKER_LABELS; k++) {
      const cell = this.cells[k];
      if (cell < 0) continue;
      const x = markers[3 * k], y = markers[3 * k + 1] * verticalScale, z = markers[3 * k + 2];
      // Where it is drawn (on the curved Earth, web/geo/earth_shape.js).
      drawnPoint(earth, x, y, z, drawn);
      const dx = drawn[0], dy = drawn[1], dz = drawn[2]; // not destructured: an array iterator each time
      const w = m[3] * dx + m[7] * dy + m[11] * dz + m[15];
      if (!(w > 0)) continue;
      const sx = ((m[0] * dx + m[4] * dy + m[8] * dz + m[12]) / w + 1) * 0.5 * width + gap;
      const sy = ((m[1] * dx + m[5] * dy + m[9] * dz + m[13]) / w + 1) * 0.5 * height;
      const labelW = this.widths[cell] * cellW;
      if (sx < 0 || sy < cellH / 2 || sx + labelW > width || sy > height - cellH / 2) continue;
      const i0 = Math.floor(sx / GRID), i1 = Math.min(gw - 1, Math.floor((sx + labelW) / GRID));
      const j0 = Math.max(0, Math.floor((sy - cellH / 2) / GRID)), j1 = Math.min(gh - 1, Math.floor((sy + cellH / 2) / GRID));
      if (this.overlaps(i0, i1, j0, j1, gw) || !inSight(eye, x, y, z, verticalScale, terrain)) continue;
      for (let j = j0; j <= j1; j++) this.occupied.fill(1, j * gw + i0, j * gw + i1 + 1);
      this.instances[4 * count] = sx;
      this.instances[4 * count + 1] = sy;
      this.instances[4 * count + 2] = cell;
      this.instances[4 * count + 3] = this.widths[cell];
      count++;
    }
    this.shown = count;
    if (count === 0) return;
    const gl = this.gl, u = this.uniforms;
    gl.useProgram(this.program);
    gl.bindVertexArray(this.vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, 0, this.instances, 0, count * 4);
    gl.uniform2f(u.uViewport, width, height);
    gl.uniform2f(u.uCellPixels, cellW, cellH);
    gl.uniform1f(u.uColumns, COLUMNS);
    gl.uniform1f(u.uRows, this.rows);
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_GLYPHS);
    gl.bindTexture(gl.TEXTURE_2D, this.atlas);
    gl.uniform1i(u.uAtlas, TEXTURE_UNIT_GLYPHS);
    drawTextQuads(gl, count);
  }

  overlaps(i0, i1, j0, j1, gw) {
    for (let j = j0; j <= j1; j++) for (let i = i0; i <= i1; i++) if (this.occupied[j * gw + i]) return true;
    return false;
  }

  dispose() {
    if (this.atlas) this.gl.deleteTexture(this.atlas);
    this.atlas = null;
  }
}
