// The contour overlay: the levels (web/measure/contour_levels.js) of the interval the user set,
// the exact height texture the terrain's shader draws the lines from (height_texture.js), and
// the labels of the major lines (labels.js), drawn in GL after the terrain. Made only while
// contours are on. `info` is what the page shows and tests read, updated in place.
//
// A streamed (tiled) terrain has no whole field in memory: its lines follow the mesh's
// interpolated height, which is the field's only where the mesh is at full resolution, and it
// has no labels; `info.message` says so.
import labelVertex from '../../../shaders/contour_label.vert?raw';
import labelFragment from '../../../shaders/contour_label.frag?raw';
import { contourLevels } from '../../measure/contour_levels.js';
import { ContourHeights, heightTexturePlan, MAX_TEXELS, TEXTURE_UNIT_CONTOUR_HEIGHTS } from './height_texture.js';
import { makeGlyphAtlas, drawTextQuads, GLYPHS, CELL_W, CELL_H } from './glyph_atlas.js';
import { LabelPlacer, LABEL_PX } from './labels.js';
import { linkProgram, uniformLocations } from '../gl_program.js';

export const TEXTURE_UNIT_GLYPHS = 6;
/** Contour lines drawn at most: a finer interval is widened (it would be a grey smear). */
export const MAX_LINES = 500;
/** Width of a minor line in CSS pixels (a major one is twice that). */
const LINE_PX = 1.2;
export const CONTOUR_UNIFORMS = ['uContourHeights', 'uContourTexel', 'uContourTexels', 'uContourStep', 'uContourTiles',
  'uContourKind', 'uContourScale', 'uContour', 'uContourSource'];

export class ContourOverlay {
  /** @param {WebGL2RenderingContext} gl */
  constructor(gl) {
    this.gl = gl;
    this.heights = new ContourHeights(gl);
    this.labels = new LabelPlacer();
    this.terrain = null;
    this.field = null;
    this.levelsKey = [null, NaN, NaN]; // interval setting, low, high
    this.anchorsKey = [null, null, NaN]; // terrain, field, major
    /** What the page shows and tests read. */
    this.info = { on: false, interval: 0, major: 0, widened: false, stride: 1, source: 'field', labels: 0,
      textureBytes: 0, textureMs: 0, message: '' };
    this.forgetGl();
  }

  /** The context was lost (or is new): GL objects are made again when next needed. */
  forgetGl() {
    this.heights.forgetGl();
    this.labelProgram = null;
  }

  /** A new field, or new spacing (the texture's texels move with it; the samples do not). */
  setField(terrain, field) {
    if (terrain !== this.terrain || field !== this.field) this.heights.release();
    this.terrain = terrain;
    this.field = field;
    this.anchorsKey[0] = null;
  }

  /**
   * The levels for this view and height range (true metres); recomputed only when they change.
   * Returns the page's message ('' when there is nothing to say).
   */
  update(view, low, high) {
    const key = this.levelsKey, info = this.info;
    info.on = view.contours === true;
    if (key[0] !== view.contourInterval || key[1] !== low || key[2] !== high) {
      const levels = contourLevels(view.contourInterval, low, high, MAX_LINES);
      key[0] = view.contourInterval; key[1] = low; key[2] = high;
      info.interval = levels.interval;
      info.major = levels.major;
      info.widened = levels.widened;
      info.levelsMessage = levels.message;
      this.noteChanged = true;
    }
    if (this.noteChanged || this.noteTerrain !== this.terrain) this.writeMessage();
    return info.message;
  }

  writeMessage() {
    const info = this.info, t = this.terrain, gl = this.gl;
    const notes = [];
    if (info.levelsMessage) notes.push(info.levelsMessage);
    info.source = t?.tiled ? 'mesh' : 'field';
    info.stride = 1;
    if (t?.tiled) notes.push('contours of a streamed terrain follow the drawn mesh (no whole field in memory) and have no labels');
    else if (t && t.handle !== 0) {
      info.stride = heightTexturePlan(t.width, t.height, gl.getParameter(gl.MAX_TEXTURE_SIZE)).stride;
      if (info.stride > 1) {
        const nth = { 2: '2nd', 3: '3rd' }[info.stride] ?? `${info.stride}th`;
        notes.push(`contours use every ${nth} sample: the field has more than ${Math.round(Math.sqrt(MAX_TEXELS))}² samples`);
      }
    }
    const text = notes.join('; ');
    info.message = text && text[0].toUpperCase() + text.slice(1);
    this.noteChanged = false;
    this.noteTerrain = t;
  }

  /** The terrain program's contour uniforms, and the texture made when first needed. */
  setUniforms(u, view, low, high, pxScale) {
    const gl = this.gl;
    if (!view.contours || !this.terrain || this.terrain.handle === 0) {
      gl.uniform4f(u.uContour, 0, 0, 0, 0);
      gl.uniform1i(u.uContourHeights, TEXTURE_UNIT_CONTOUR_HEIGHTS); // its own unit: never a float sampler's
      return;
    }
    this.update(view, low, high);
    const exact = this.heights.prepare(this.terrain, this.field);
    const info = this.info;
    if (exact) {
      this.heights.setUniforms(u, this.terrain);
      info.textureBytes = this.heights.bytes;
      info.textureMs = this.heights.ms;
    }
    gl.uniform1i(u.uContourHeights, TEXTURE_UNIT_CONTOUR_HEIGHTS);
    gl.uniform1i(u.uContourSource, exact ? 0 : 1);
    gl.uniform4f(u.uContour, info.interval, info.major, LINE_PX * pxScale, 1);
  }

  /** The labels of the major lines, over what is drawn (after the terrain and the sky). */
  drawLabels(camera, width, height, view, pxScale) {
    const t = this.terrain, info = this.info;
    info.labels = 0;
    if (!view.contours || !t || t.handle === 0 || t.tiled) return;
    const gl = this.gl, labels = this.labels, key = this.anchorsKey;
    if (key[0] !== t || key[1] !== this.field || key[2] !== info.major) {
      const f = this.field ?? {};
      labels.findAnchors(t.samples(), t.width, t.height, t.spacingX, t.spacingY, f.heightScale ?? 1, f.heightOffset ?? 0, info.major);
      key[0] = t; key[1] = this.field; key[2] = info.major;
    }
    const glyphs = labels.place(camera, width, height, pxScale, view.verticalScale ?? 1, t);
    info.labels = labels.labelsShown;
    if (glyphs === 0) return;
    if (!this.labelProgram) this.makeLabelGl();
    gl.useProgram(this.labelProgram);
    gl.bindVertexArray(this.labelVao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.labelBuffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, 0, labels.instances, 0, glyphs * 5);
    const u = this.labelUniforms;
    gl.uniform2f(u.uViewport, width, height);
    const glyphH = LABEL_PX * pxScale;
    gl.uniform2f(u.uGlyphSize, glyphH * CELL_W / CELL_H, glyphH);
    gl.uniform1f(u.uGlyphs, GLYPHS.length);
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_GLYPHS);
    gl.bindTexture(gl.TEXTURE_2D, this.atlas);
    gl.uniform1i(u.uAtlas, TEXTURE_UNIT_GLYPHS);
    drawTextQuads(gl, glyphs);
  }

  makeLabelGl() {
    const gl = this.gl;
    this.labelProgram = linkProgram(gl, labelVertex, labelFragment, 'contour label');
    this.labelUniforms = uniformLocations(gl, this.labelProgram, ['uViewport', 'uGlyphSize', 'uGlyphs', 'uAtlas']);
    this.atlas = makeGlyphAtlas(gl, TEXTURE_UNIT_GLYPHS);
    this.labelVao = gl.createVertexArray();
    gl.bindVertexArray(this.labelVao);
    this.labelBuffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, this.labelBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, this.labels.instances.byteLength, gl.DYNAMIC_DRAW);
    const stride = 20;
    for (const [location, size, offset] of [[0, 2, 0], [1, 2, 8], [2, 1, 16]]) {
      gl.enableVertexAttribArray(location);
      gl.vertexAttribPointer(location, size, gl.FLOAT, false, stride, offset);
      gl.vertexAttribDivisor(location, 1);
    }
    gl.bindVertexArray(null);
  }
}
