// WebGL2 renderer of the hexagon mesh's fan stream (paper §7). It only uploads and draws
// arrays the core filled; it computes no geometry. Attribute locations match the layout()
// qualifiers in shaders/.
//
// Uploads follow the stream's version: buffers are sized to capacity (they grow by doubling)
// and only the ranges the core marked dirty are copied, straight from WASM memory. One
// drawElements call draws every cell: TRIANGLE_FAN with primitive restart (the paper's layout),
// or TRIANGLES when the stream is in the list layout.
//
// Shading (paper §7) is composed from shaders/ by `#include "file"` lines: scattering.glsl
// (the atmosphere, per vertex and for the sky), field_textures.glsl (normals, sun shadow and
// ambient occlusion from the full-resolution field, web/render/shading/field_textures.js), ground_color.glsl
// and tonemap.glsl. The sky is a second, full-screen pass drawn behind the terrain.
import terrainVertex from '../../shaders/terrain.vert?raw';
import terrainFragment from '../../shaders/terrain.frag?raw';
import skyVertex from '../../shaders/sky.vert?raw';
import skyFragment from '../../shaders/sky.frag?raw';
import scatteringGlsl from '../../shaders/scattering.glsl?raw';
import fieldTexturesGlsl from '../../shaders/field_textures.glsl?raw';
import groundColorGlsl from '../../shaders/ground_color.glsl?raw';
import tonemapGlsl from '../../shaders/tonemap.glsl?raw';
import imageDrapeGlsl from '../../shaders/image_drape.glsl?raw';
import contoursGlsl from '../../shaders/contours.glsl?raw';
import earthGlsl from '../../shaders/earth.glsl?raw';
import { mat4 } from 'gl-matrix';
import { STREAM_VERTEX_BYTES, STREAM_NORMAL_BYTES } from '../core/core.js';
import { MeasureOverlay } from './measure_overlay.js';
import { GroundLines } from './ground_lines.js';
import { resolveIncludes } from './shading/includes.js';
import { Atmosphere, BETA_RAYLEIGH, BETA_MIE, SCALE_HEIGHTS, MIE_G, SUN_IRRADIANCE, EXPOSURE } from './shading/atmosphere.js';
import { FieldTextures, TEXTURE_UNIT_GRADIENTS, TEXTURE_UNIT_SUN, TEXTURE_UNIT_OCCLUSION } from './shading/field_textures.js';
import { ImageTextures } from './shading/image_textures.js';
import { DrapeLayers, DRAPE_UNIFORMS } from './shading/drape_layers.js';
import { ContourOverlay, CONTOUR_UNIFORMS } from './contours/contour_overlay.js';
import { EarthUniforms, EARTH_UNIFORMS } from './shading/earth_uniforms.js';
import { EyeAnchor, ANCHOR_UNIFORMS } from './shading/eye_anchor.js';
import { VertexLattice, LATTICE_BYTES } from './vertex_lattice.js';
import { linkProgram, uniformLocations } from './gl_program.js';

export const ATTRIB_POSITION = 0;
export const ATTRIB_NORMAL = 1;
export const ATTRIB_MORPH_FROM = 2;
export const ATTRIB_MORPH_KEY = 3;
export const ATTRIB_LATTICE = 4;
export const ATTRIB_SKY_CORNER = 0;
/** Shading modes (uMode in shaders/terrain.frag). */
export const SHADING_MODES = { natural: 0, hypsometric: 1, slope: 2, hillshade: 3, plain: 4 };
const SHADER_FILES = { 'scattering.glsl': scatteringGlsl, 'field_textures.glsl': fieldTexturesGlsl,
  'ground_color.glsl': groundColorGlsl, 'tonemap.glsl': tonemapGlsl, 'image_drape.glsl': imageDrapeGlsl,
  'contours.glsl': contoursGlsl, 'earth.glsl': earthGlsl };
const SKY_COLOR = [0.62, 0.74, 0.88]; // the clear colour of the plain mode (no sky pass)
const OUTLINE_COLOR = new Float32Array([0.08, 0.09, 0.12, 0.55]);
// view.terrainMask: the terrain's pixels in one colour on black, nothing else (tests find the
// terrain's pixels by it: the plain ground past the field looks like the terrain's own lowlands).
const MASK_COLOR = new Float32Array([1, 0, 1, 1]);
const NO_LINE = new Float32Array([0, 0, 0, 0]);
const UNIFORMS = [...ANCHOR_UNIFORMS, ...EARTH_UNIFORMS, 'uSunDirection', 'uHeightRange', 'uTint', 'uTintAmount',
  'uExtent', 'uLineColor', 'uFrame', 'uMorphFrames', 'uVerticalScale', 'uBetaRayleigh', 'uBetaMie', 'uScaleHeight',
  'uMieG', 'uSunIrradiance', 'uSunAirMass', 'uSkyLight', 'uExposure', 'uMode', 'uNormalSource', 'uShadows',
  'uOcclusionOn', 'uSnowLine', 'uTreeLine', 'uNoiseScale', 'uGradients', 'uGradientTexel', 'uGradientStep',
  'uGradientTile', 'uGradientTiles', 'uSunVisibility', 'uSunVisibilityMap', 'uOcclusion', 'uOcclusionMap',
  'uImageOpacity', 'uImageUnlit', 'uHoleSource', ...DRAPE_UNIFORMS, ...CONTOUR_UNIFORMS];
const SKY_UNIFORMS = ['uInverseViewProjection', ...EARTH_UNIFORMS, 'uVerticalScale', 'uBetaRayleigh', 'uBetaMie',
  'uScaleHeight', 'uMieG', 'uSunDirection', 'uSunIrradiance', 'uSunAirMass', 'uExposure', 'uGroundLevel', 'uSkyLight',
  'uHeightRange', 'uSnowLine', 'uTreeLine', 'uNoiseScale'];
const NO_GROUND = -1e30; // uGroundLevel without a terrain: the sky alone
const GROUND_LEVEL = 5, NO_GROUND_SLOT = 6; // in Renderer.groundValues

// The terrain's and the sky's programs, their shared GLSL included.
const link = (gl, vertex, fragment, what) =>
  linkProgram(gl, resolveIncludes(vertex, SHADER_FILES), resolveIncludes(fragment, SHADER_FILES), what);
// A variant of a shader: `#define name` after its #version line.
const withDefine = (source, name) => source.replace(/^(#version[^\n]*\n)/, `$1#define ${name}\n`);

// The atmosphere's constants as the uniforms take them, converted once: a plain array passed to
// uniform*fv is read element by element by the browser, which boxes every double each frame.
const ATMOSPHERE_F32 = { betaRayleigh: new Float32Array(BETA_RAYLEIGH), betaMie: new Float32Array(BETA_MIE),
  scaleHeights: new Float32Array(SCALE_HEIGHTS), sunIrradiance: new Float32Array(SUN_IRRADIANCE) };

/** A colour per level: hues far apart around the wheel, semi-hexagons (odd levels) darker. */
function levelColor(level) {
  const hue = ((level >> 1) * 137) % 360;
  const lightness = level % 2 ? 0.4 : 0.55;
  const a = 0.9 * Math.min(lightness, 1 - lightness);
  const channel = (n) => {
    const k = (n + hue / 30) % 12;
    return lightness - a * Math.max(-1, Math.min(k - 3, 9 - k, 1));
  };
  return [channel(0), channel(8), channel(4)];
}
// The colours of every level a mesh can have, made once (a frame with colour by level on
// computes none): two levels per doubling of the side, so a 65,536-sample field reaches level
// 32 and the largest tiled one (2^21 samples a side) 42.
const LEVEL_COLORS = Array.from({ length: 64 }, (_, level) => new Float32Array(levelColor(level)));

/** A GL buffer that follows an array in WASM memory: grown by doubling, filled by ranges. */
class MirroredBuffer {
  constructor(gl, target) {
    this.gl = gl;
    this.target = target;
    this.buffer = gl.createBuffer();
    this.capacity = 0; // bytes allocated on the GPU
  }

  /**
   * Makes the GPU copy equal the `byteLength` bytes at `pointer` in WASM memory (`heap`: all of
   * it as bytes) where the ranges say it changed, or everywhere when `all`. The ranges are
   * `pairs` [first, count] pairs of elements of `elementBytes`, at int32 index `rangesAt` of
   * `i32` (all of memory as int32). Copies straight from WASM memory: no view is made. Returns
   * the bytes uploaded.
   */
  update(heap, pointer, byteLength, i32, rangesAt, pairs, elementBytes, all) {
    const gl = this.gl;
    gl.bindBuffer(this.target, this.buffer);
    if (byteLength > this.capacity) {
      this.capacity = Math.max(byteLength, 2 * this.capacity, 1 << 16);
      gl.bufferData(this.target, this.capacity, gl.DYNAMIC_DRAW);
      all = true;
    }
    if (all) {
      if (byteLength > 0) gl.bufferSubData(this.target, 0, heap, pointer, byteLength);
      return byteLength;
    }
    let uploaded = 0;
    for (let k = 0; k < pairs; k++) {
      const offset = i32[rangesAt + 2 * k] * elementBytes, length = i32[rangesAt + 2 * k + 1] * elementBytes;
      gl.bufferSubData(this.target, offset, heap, pointer + offset, length);
      uploaded += length;
    }
    return uploaded;
  }
}

const NOTHING_OVER = Object.freeze({ drapes: Object.freeze([]), overlays: Object.freeze([]) });

export class TerrainRenderer {
  /**
   * @param {WebGL2RenderingContext} gl
   * @param {{ normalTile?: () => number, imageTile?: () => number }} [forcedTiles] texels a side the
   *   normal and image texture tiles may not exceed (0: the GPU's limit), read at each upload
   */
  constructor(gl, forcedTiles = {}) {
    this.gl = gl;
    this.forcedTiles = forcedTiles;
    this.earth = new EarthUniforms(); // the plane until setEarth; the lines on the ground share it
    this.createGlObjects();
    this.heightRange = [0, 1];
    /** [true low, true high, snow line, tree line, noise scale, drawn ground level, NO_GROUND] (setGroundColourUniforms) */
    this.groundValues = new Float32Array(7);
    this.groundRange = null;
    this.extent = [0, 0];
    this.atmosphere = new Atmosphere();
    this.sunDirection = this.atmosphere.sunDirection;
    this.lastUploadBytes = 0;
    this.streamBytes = 0; // bytes of the whole stream (what a full upload would copy)
    this.eyeAnchor = new EyeAnchor(); // the terrain drawn relative to the eye (shading/eye_anchor.js)
  }

  /** The surface the terrain is drawn on (web/geo/earth_shape.js), as the core refines for it. */
  setEarth(earth) {
    this.earth.set(earth);
  }

  /**
   * The program, buffers and vertex arrays. Called again after a lost context came back
   * (web/app/context_loss.js): the old objects died with it, and the next upload copies everything.
   */
  createGlObjects() {
    const gl = this.gl;
    this.program = link(gl, terrainVertex, terrainFragment, 'terrain');
    this.uniforms = uniformLocations(gl, this.program, UNIFORMS);
    this.holesProgram = null; // linked when first drawn (holesVariant): most terrains never need it
    this.skyProgram = link(gl, skyVertex, skyFragment, 'sky');
    this.skyUniforms = uniformLocations(gl, this.skyProgram, SKY_UNIFORMS);
    this.skyVao = gl.createVertexArray();
    gl.bindVertexArray(this.skyVao);
    this.skyBuffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, this.skyBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([-1, -1, 3, -1, -1, 3]), gl.STATIC_DRAW); // one triangle over the screen
    gl.enableVertexAttribArray(ATTRIB_SKY_CORNER);
    gl.vertexAttribPointer(ATTRIB_SKY_CORNER, 2, gl.FLOAT, false, 0, 0);
    gl.bindVertexArray(null);
    this.inverseViewProjection = new Float32Array(16);
    // Textures from the field: made again from the field (kept by setField) after a lost context.
    this.fieldTextures?.forgetGl();
    this.fieldTextures = this.fieldTextures ?? new FieldTextures(gl, this.forcedTiles.normalTile);
    // The image layers' textures died with the context too: the page opens them again.
    this.drapes?.forgetGl();
    this.drapes = this.drapes ?? new DrapeLayers(gl);
    this.contours?.forgetGl();
    this.contours = this.contours ?? new ContourOverlay(gl); // contour lines and labels (web/render/contours/)
    this.vertices = new MirroredBuffer(gl, gl.ARRAY_BUFFER);
    if (this.lattice) this.lattice.createGlObjects();
    else this.lattice = new VertexLattice(gl); // the vertices' exact lattice points (vertex_lattice.js)
    this.normals = new MirroredBuffer(gl, gl.ARRAY_BUFFER); // while the core keeps mesh normals
    this.hasNormals = false;
    gl.vertexAttrib4f(ATTRIB_NORMAL, 0, 1, 0, 0); // what the shader reads while there are none
    this.indices = new MirroredBuffer(gl, gl.ELEMENT_ARRAY_BUFFER);
    this.levelBuffer = gl.createBuffer();
    this.outlineBuffer = gl.createBuffer();
    this.mainVao = this.makeVao(this.indices.buffer);
    this.levelVao = this.makeVao(this.levelBuffer);
    this.outlineVao = this.makeVao(this.outlineBuffer);
    this.indexCount = 0;
    this.layout = 'fans';
    this.version = -1;      // stream version on the GPU; -1: nothing uploaded yet
    this.levelOffsets = new Int32Array(64); // the level view's offsets, grown when needed
    this.levelOffsetCount = 0;
    this.outlineCount = 0;
    // Lines on the ground (ground_lines.js), shared by the measured line and the overlays: one
    // object for the page's life, its GL objects made again after a lost context.
    if (this.groundLines) this.groundLines.createGlObjects();
    else this.groundLines = new GroundLines(gl, this.earth, SHADER_FILES);
    // The measured line on the ground (measure_overlay.js): its data outlives a lost context.
    if (this.measureOverlay) this.measureOverlay.createGlObjects();
    else this.measureOverlay = new MeasureOverlay(this.groundLines);
  }

  makeVao(indexBuffer) {
    const gl = this.gl;
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.vertices.buffer);
    const stride = STREAM_VERTEX_BYTES; // src/stream_vertex.h
    gl.enableVertexAttribArray(ATTRIB_POSITION);
    gl.vertexAttribPointer(ATTRIB_POSITION, 3, gl.FLOAT, false, stride, 0);
    gl.enableVertexAttribArray(ATTRIB_MORPH_FROM);
    gl.vertexAttribPointer(ATTRIB_MORPH_FROM, 1, gl.FLOAT, false, stride, 12);
    gl.enableVertexAttribArray(ATTRIB_MORPH_KEY);
    gl.vertexAttribPointer(ATTRIB_MORPH_KEY, 1, gl.FLOAT, false, stride, 16);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.lattice.buffer);
    gl.enableVertexAttribArray(ATTRIB_LATTICE);
    gl.vertexAttribIPointer(ATTRIB_LATTICE, 2, gl.INT, LATTICE_BYTES, 0);
    // The normals are a buffer of their own, read only while the core keeps them (setNormalsOn).
    gl.bindBuffer(gl.ARRAY_BUFFER, this.normals.buffer);
    gl.vertexAttribPointer(ATTRIB_NORMAL, 4, gl.SHORT, true, STREAM_NORMAL_BYTES, 0); // w: no-data (hexlod.h)
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, indexBuffer);
    gl.bindVertexArray(null);
    return vao;
  }

  /** A new terrain (or a lost context): the next upload copies everything. */
  invalidate() {
    this.version = -1;
  }

  /**
   * Brings the GPU copy of the terrain's stream up to date, uploading only what changed since
   * the last call, and only when the version moved. Returns the bytes uploaded.
   * @param {import('../core/core.js').Terrain} terrain
   * @param {import('../core/core.js').FrameStats} stats the figures of its last frame (stream step included)
   * @param {'fans'|'triangles'} layout the stream's index layout
   */
  upload(terrain, stats, layout) {
    const all = this.version < 0 || layout !== this.layout;
    let bytes = 0;
    if (all || stats.version !== this.version) {
      const heap = terrain.core.module.HEAPU8, i32 = terrain.scratchI32();
      bytes += this.vertices.update(heap, stats.vertexPointer, stats.vertexCount * STREAM_VERTEX_BYTES, i32,
        stats.dirtyVerticesPointer / 4, stats.dirtyVertexPairs, STREAM_VERTEX_BYTES, all);
      bytes += this.lattice.update(terrain.core.module.HEAPF32, stats.vertexPointer, stats.vertexCount, i32,
        stats.dirtyVerticesPointer / 4, stats.dirtyVertexPairs, all);
      const normals = stats.normalsPointer !== 0;
      if (normals) {
        bytes += this.normals.update(heap, stats.normalsPointer, stats.vertexCount * STREAM_NORMAL_BYTES, i32,
          stats.dirtyVerticesPointer / 4, stats.dirtyVertexPairs, STREAM_NORMAL_BYTES, all || !this.hasNormals);
      }
      this.setNormalsOn(normals);
      this.gl.bindVertexArray(null);
      bytes += this.indices.update(heap, stats.indexPointer, stats.indexCount * 4, i32,
        stats.dirtyIndicesPointer / 4, stats.dirtyIndexPairs, 4, all);
      this.version = stats.version;
      this.layout = layout;
      this.indexCount = stats.indexCount;
      this.streamBytes = stats.vertexCount * (STREAM_VERTEX_BYTES + (normals ? STREAM_NORMAL_BYTES : 0)) + stats.indexCount * 4;
      terrain.acknowledgeStream(); // after reading the figures: it clears the dirty ranges
    }
    this.lastUploadBytes = bytes;
    return bytes;
  }

  /** Whether the vertex arrays read the normals buffer (else the constant up normal). */
  setNormalsOn(on) {
    if (on === this.hasNormals) return;
    const gl = this.gl;
    for (const vao of [this.mainVao, this.levelVao, this.outlineVao]) {
      gl.bindVertexArray(vao);
      if (on) gl.enableVertexAttribArray(ATTRIB_NORMAL);
      else gl.disableVertexAttribArray(ATTRIB_NORMAL);
    }
    gl.bindVertexArray(null);
    this.hasNormals = on;
  }

  /**
   * The level-ordered view (Terrain.levelView, a LevelView) for colour by level and the
   * outlines: uploaded straight from the views on all WASM memory, so no view is made per frame.
   */
  setLevelView(levelView) {
    const gl = this.gl;
    gl.bindVertexArray(null);
    uploadRange(gl, this.levelBuffer, levelView.u32, levelView.indexStart, levelView.indexCount);
    uploadRange(gl, this.outlineBuffer, levelView.u32, levelView.outlineStart, levelView.outlineCount);
    const count = levelView.levelOffsetCount;
    if (this.levelOffsets.length < count) this.levelOffsets = new Int32Array(2 * count);
    for (let k = 0; k < count; k++) this.levelOffsets[k] = levelView.i32[levelView.levelOffsetStart + k];
    this.levelOffsetCount = count;
    this.outlineCount = levelView.outlineCount;
  }

  /**
   * @param {number} minHeight @param {number} maxHeight drawn height range, metres (exaggerated)
   * @param {number} extentX @param {number} extentZ the field's rectangle, metres
   */
  /** The terrain's lattice (the vertices are placed from their lattice points): spacing, metres, and size, samples. */
  setLattice(spacingX, spacingY, width, height) {
    const a = this.eyeAnchor;
    if (a.spacingX === spacingX && a.spacingY === spacingY && a.latticeLast[0] === 2 * (width - 1) && a.latticeLast[1] === height - 1) return;
    this.lattice.setSpacing(spacingX, spacingY);
    this.eyeAnchor.setLattice(spacingX, spacingY, width, height);
    this.invalidate(); // every lattice point anew
  }

  setShading(minHeight, maxHeight, extentX, extentZ) {
    this.heightRange = [minHeight, maxHeight];
    this.extent = [extentX, extentZ];
  }

  /**
   * The field the shading reads (normals, shadows, ambient occlusion; web/render/shading/field_textures.js).
   * Textures are made when the next frame needs them, and again only when what they depend on changes.
   * @param {import('../core/core.js').Terrain} terrain @param {{heightScale: number, heightOffset: number}} field
   */
  setField(terrain, field) {
    this.fieldTextures.setField(terrain, field);
    this.contours.setField(terrain, field);
  }

  /** The contour overlay's message for the page ('' when none) for this view: a widened interval, a coarser field. */
  contourNote(view) {
    const scale = view.verticalScale ?? 1;
    return this.contours.update(view, this.heightRange[0] / scale, this.heightRange[1] / scale);
  }

  /** Textures for one more image layer (web/imagery/open_image.js fills them). */
  newImageTextures() {
    return new ImageTextures(this.gl, this.forcedTiles.imageTile);
  }

  /** The sun: compass azimuth (0 north, 90 east) and elevation, degrees. */
  setSun(azimuthDeg, elevationDeg) {
    this.atmosphere.setSun(azimuthDeg, elevationDeg);
  }

  /**
   * One frame seen by a camera whose matrices are up to date: the terrain with the image layers
   * of the layer list (app/layers.js) draped on it, the measured line, the layer list's
   * overlays, bottom first, then the sky.
   * @param {{colorByLevel?: boolean, outline?: boolean, frame?: number, morphFrames?: number,
   *   verticalScale?: number, hideTerrain?: boolean, terrainMask?: boolean}} view frame and
   *   morphFrames drive the geomorph blend; hideTerrain draws the background alone; terrainMask
   *   the terrain's pixels alone in magenta on black (tests find the terrain's pixels by it)
   * @param {{ drapes: import('./shading/drape_layers.js').Drape[], overlays: ArrayLike<{ draw: Function,
   *   createGlObjects: Function }> }} [shown] the layer list: its visible image layers (drapes),
   *   bottom first, and its overlays, each drawn with draw(gl, camera, width, height,
   *   verticalScale); createGlObjects(gl) is the page's to call after a lost context came back.
   *   A new kind of layer drawn over the terrain needs nothing of this file.
   */
  draw(camera, width, height, view = {}, shown = NOTHING_OVER) {
    const overlays = shown.overlays;
    const gl = this.gl;
    this.drawPixelScale = this.pixelScale(height); // the contours' line width and labels
    const mode = SHADING_MODES[view.shading ?? 'natural'] ?? 0;
    const verticalScale = view.verticalScale ?? 1;
    gl.viewport(0, 0, width, height);
    if (view.terrainMask) gl.clearColor(0, 0, 0, 1);
    else gl.clearColor(SKY_COLOR[0], SKY_COLOR[1], SKY_COLOR[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LEQUAL);
    if (view.terrainMask) {
      if (this.indexCount > 0) this.drawTerrain(camera, view, mode, verticalScale, shown.drapes);
      gl.bindVertexArray(null);
      return;
    }
    if (this.indexCount > 0 && !view.hideTerrain) this.drawTerrain(camera, view, mode, verticalScale, shown.drapes);
    // The measured line: over the terrain, its hidden parts faint (the sky covers none of it).
    if (!view.hideTerrain) this.measureOverlay.draw(camera, width, height, verticalScale);
    for (let k = 0; k < overlays.length && !view.hideTerrain; k++) overlays[k].draw(gl, camera, width, height, verticalScale);
    // The sky where no terrain was drawn: after the terrain, so the depth test skips covered pixels.
    // Past the field's edges, plain ground at its lowest height goes on to the horizon.
    if (mode !== SHADING_MODES.plain) this.drawSky(camera, verticalScale, this.indexCount > 0);
    // Tests judge the lines alone with view.contourLabels = false.
    if (view.contours && view.contourLabels !== false && this.indexCount > 0 && !view.hideTerrain) this.contours.drawLabels(camera, width, height, view, this.drawPixelScale);
    gl.bindVertexArray(null);
  }

  /** Device pixels per CSS pixel of a drawing `height` pixels tall (a 2x screenshot: twice the screen's). */
  pixelScale(height) {
    const css = this.gl.canvas.clientHeight;
    return css > 0 ? Math.max(1, height / css) : 1;
  }

  /**
   * The procedural ground's uniforms (ground_color.glsl), which the terrain and the plain ground
   * beyond it share. Their values are worked out again only when the height range, the
   * exaggeration or the spacing changed, and passed from a typed array: the frame path makes no
   * new numbers (frame_allocations test).
   */
  setGroundColourUniforms(u, verticalScale) {
    const gl = this.gl, g = this.groundValues;
    const spacing = this.fieldTextures.spacing ?? 1;
    if (this.groundRange !== this.heightRange || this.groundScale !== verticalScale || this.groundSpacing !== spacing) {
      const low = this.heightRange[0] / verticalScale, high = this.heightRange[1] / verticalScale;
      // Snow on the upper part of real mountains only (never on a hill of a few hundred metres);
      // trees give way to bare soil below it.
      const snowLine = high > 3000 ? Math.max(3000, low + 0.65 * (high - low)) : 1e9;
      g.set([low, high, snowLine, Math.min(3500, snowLine - 1000), spacing, this.heightRange[0], NO_GROUND]);
      this.groundRange = this.heightRange;
      this.groundScale = verticalScale;
      this.groundSpacing = spacing;
    }
    gl.uniform2fv(u.uHeightRange, g, 0, 2);
    gl.uniform1fv(u.uSnowLine, g, 2, 1);
    gl.uniform1fv(u.uTreeLine, g, 3, 1);
    gl.uniform1fv(u.uNoiseScale, g, 4, 1);
  }

  /** Uniforms the terrain and the sky share: the atmosphere and the tone curve. */
  setAtmosphereUniforms(u) {
    const gl = this.gl, a = this.atmosphere;
    gl.uniform3fv(u.uBetaRayleigh, ATMOSPHERE_F32.betaRayleigh);
    gl.uniform3fv(u.uBetaMie, ATMOSPHERE_F32.betaMie);
    gl.uniform2fv(u.uScaleHeight, ATMOSPHERE_F32.scaleHeights);
    gl.uniform1f(u.uMieG, MIE_G);
    gl.uniform3fv(u.uSunDirection, a.sunDirection);
    gl.uniform3fv(u.uSunIrradiance, ATMOSPHERE_F32.sunIrradiance);
    gl.uniform1f(u.uSunAirMass, a.sunAirMass);
    gl.uniform1f(u.uExposure, EXPOSURE);
  }

  drawSky(camera, verticalScale, ground) {
    const gl = this.gl, u = this.skyUniforms;
    gl.useProgram(this.skyProgram);
    this.setGroundColourUniforms(u, verticalScale);
    gl.uniform1fv(u.uGroundLevel, this.groundValues, ground ? GROUND_LEVEL : NO_GROUND_SLOT, 1);
    gl.uniform3fv(u.uSkyLight, this.atmosphere.skyLight);
    mat4.invert(this.inverseViewProjection, camera.viewProjection); // no allocation
    gl.uniformMatrix4fv(u.uInverseViewProjection, false, this.inverseViewProjection);
    this.earth.apply(gl, u, camera, verticalScale);
    gl.uniform1f(u.uVerticalScale, verticalScale);
    this.setAtmosphereUniforms(u);
    gl.depthMask(false);
    gl.bindVertexArray(this.skyVao);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.depthMask(true);
  }

  /**
   * Whether drawing `view` reads the mesh's vertex normals (paper §7): the plain mode, the mesh
   * as the normals' source, and any mode until the field's textures are ready. The page keeps
   * the core's stream normals on only then (32 bytes a vertex saved).
   */
  usesMeshNormals(view) {
    const plain = (SHADING_MODES[view.shading ?? 'natural'] ?? 0) === SHADING_MODES.plain;
    return plain || view.normals === 'mesh' || !this.fieldTextures.ready;
  }

  /**
   * Whether no-data is drawn as holes now: when asked, and the field has any (a field held whole
   * says which samples; a tiled field's stream marks them as its tiles come).
   */
  drawsHoles(view) {
    const textures = this.fieldTextures;
    return view.nodata === 'holes' && (textures.terrain?.tiled === true || !!textures.field?.missingMask);
  }

  /** No-data as holes: a variant of the terrain program whose fragments may discard (shaders/terrain.frag). */
  holesVariant() {
    if (this.holesProgram) return;
    this.holesProgram = link(this.gl, terrainVertex, withDefine(terrainFragment, 'NODATA_HOLES'), 'terrain with holes');
    this.holesUniforms = uniformLocations(this.gl, this.holesProgram, UNIFORMS);
  }

  drawTerrain(camera, view, mode, verticalScale, drapes) {
    const gl = this.gl;
    const plain = mode === SHADING_MODES.plain;
    const holes = this.drawsHoles(view);
    // Field textures follow the exaggeration and the sun (shadows); the plain mode needs none,
    // unless it draws holes (the field's presence is in them).
    if (!plain || holes) this.fieldTextures.prepare(verticalScale, this.atmosphere.sunDirection, this.earth.earth);
    gl.enable(gl.CULL_FACE);
    if (holes) this.holesVariant();
    gl.useProgram(holes ? this.holesProgram : this.program);
    const u = holes ? this.holesUniforms : this.uniforms;
    if (holes) gl.uniform1i(u.uHoleSource, this.fieldTextures.ready ? 0 : 1);
    this.eyeAnchor.apply(gl, u, camera, this.earth.earth);
    this.earth.apply(gl, u, camera, verticalScale);
    this.setGroundColourUniforms(u, verticalScale);
    const low = this.heightRange[0] / verticalScale, high = this.heightRange[1] / verticalScale;
    gl.uniform2f(u.uExtent, this.extent[0], this.extent[1]);
    gl.uniform4fv(u.uLineColor, view.terrainMask ? MASK_COLOR : NO_LINE);
    gl.uniform1f(u.uFrame, view.frame ?? 0);
    gl.uniform1f(u.uMorphFrames, view.morphFrames ?? 0);
    gl.uniform1f(u.uVerticalScale, verticalScale);
    this.setAtmosphereUniforms(u);
    gl.uniform3fv(u.uSkyLight, this.atmosphere.skyLight);
    gl.uniform1i(u.uMode, mode);
    const ready = !plain && this.fieldTextures.ready;
    gl.uniform1i(u.uNormalSource, view.normals === 'mesh' || !ready ? 1 : 0);
    gl.uniform1f(u.uShadows, view.shadows === false || !ready ? 0 : 1);
    gl.uniform1f(u.uOcclusionOn, view.occlusion === false || !ready ? 0 : 1);
    gl.uniform1i(u.uGradients, TEXTURE_UNIT_GRADIENTS);
    gl.uniform1i(u.uSunVisibility, TEXTURE_UNIT_SUN);
    gl.uniform1i(u.uOcclusion, TEXTURE_UNIT_OCCLUSION);
    this.fieldTextures.setUniforms(u);
    this.drapes.setUniforms(u, drapes, this.fieldTextures.terrain ?? { spacingX: 1, spacingY: 1 });
    gl.uniform1f(u.uImageOpacity, view.imageOpacity ?? 1);
    gl.uniform1f(u.uImageUnlit, view.imageUnlit ? 1 : 0);
    this.contours.setUniforms(u, view, low, high, this.drawPixelScale);
    // Push the surface back a little so the outlines on it are not lost in the depth test.
    gl.enable(gl.POLYGON_OFFSET_FILL);
    gl.polygonOffset(1, 1);
    if (view.colorByLevel && this.levelOffsetCount > 1) {
      // One range per level, each in its own colour (the level-ordered view's fans).
      gl.bindVertexArray(this.levelVao);
      gl.uniform1f(u.uTintAmount, 0.45);
      for (let level = 0; level + 1 < this.levelOffsetCount; ++level) {
        const first = this.levelOffsets[level], count = this.levelOffsets[level + 1] - first;
        if (count === 0) continue;
        gl.uniform3fv(u.uTint, LEVEL_COLORS[Math.min(level, LEVEL_COLORS.length - 1)]);
        gl.drawElements(gl.TRIANGLE_FAN, count, gl.UNSIGNED_INT, first * 4);
      }
    } else {
      // WebGL2 always restarts primitives at index 0xFFFFFFFF: every cell in one call.
      gl.bindVertexArray(this.mainVao);
      gl.uniform1f(u.uTintAmount, 0);
      gl.drawElements(this.layout === 'fans' ? gl.TRIANGLE_FAN : gl.TRIANGLES, this.indexCount, gl.UNSIGNED_INT, 0);
    }
    gl.disable(gl.POLYGON_OFFSET_FILL);
    if (view.outline && this.outlineCount > 0 && !view.terrainMask) {
      gl.enable(gl.BLEND);
      gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
      gl.uniform4fv(u.uLineColor, OUTLINE_COLOR);
      gl.bindVertexArray(this.outlineVao);
      gl.drawElements(gl.LINES, this.outlineCount, gl.UNSIGNED_INT, 0);
      gl.disable(gl.BLEND);
    }
  }
}

/**
 * Replaces an element buffer's data with `count` elements of `heap` from `first` (element
 * indices): no view is made. A count of 0 empties the buffer (bufferData's length 0 would mean
 * "to the end of the source", all of memory).
 */
function uploadRange(gl, buffer, heap, first, count) {
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, buffer);
  if (count > 0) gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, heap, gl.DYNAMIC_DRAW, first, count);
  else gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, 0, gl.DYNAMIC_DRAW);
}

export { SKY_COLOR, levelColor };
