// The GPU side of web/render/shading/field_shading.js: the textures the terrain's fragment stage
// reads by ground position (shaders/field_textures.glsl), made from the full-resolution field
// when the next frame needs them, and again only when what they depend on changes:
//   gradients   once per field: normals (the exaggeration is applied in the shader) and heights
//   occlusion   per field and exaggeration
//   sun         per field, exaggeration and sun direction
// The normal texture is an array of tiles no larger than MAX_TEXTURE_SIZE a side (many GPUs
// stop at 16384, one short of a 16385² field). The normalTile setting
// (?normaltile=N) forces smaller tiles (tests).
import { fieldOf, downsampleField, gradientTiles, halveImage, sunVisibility, ambientOcclusion } from './field_shading.js';
import { EARTH_FLAT, FLAT_EARTH } from '../../geo/index.js';

export const TEXTURE_UNIT_GRADIENTS = 0;
export const TEXTURE_UNIT_SUN = 1;
export const TEXTURE_UNIT_OCCLUSION = 2;
/** Largest side of the ambient-occlusion texture (paper §7: a low-resolution texture). */
export const OCCLUSION_MAX_SIDE = 512;
/** Largest side of the sun-visibility texture. */
export const SUN_MAX_SIDE = 2048;
/** Texels of the field texture at most (RGBA16F, 8 bytes each: 128 MB); larger fields keep every n-th sample. */
export const GRADIENT_MAX_TEXELS = 1 << 24;

export class FieldTextures {
  /**
   * @param {WebGL2RenderingContext} gl
   * @param {() => number} forcedTile texels a side the tiles may not exceed, read at each upload (0: none)
   */
  constructor(gl, forcedTile = () => 0) {
    this.gl = gl;
    this.forcedTile = forcedTile;
    this.terrain = null;
    this.field = null;
    this.times = { gradientsMs: 0, occlusionMs: 0, sunMs: 0 }; // the last computation of each, ms
    this.forgetGl();
  }

  /** The context was lost (or is new): every texture is made again when next needed. */
  forgetGl() {
    this.gradients = this.sun = this.occlusion = null;
    this.ready = false;
    this.occlusionScale = NaN;
    this.sunKey = [NaN, NaN, NaN, NaN];
    this.sunGrid = this.occlusionGrid = null;
    this.sunData = null; // sized for the old grid: kept, a bigger field's texImage2D failed (INVALID_OPERATION)
  }

  /** A new field (or new spacing): everything is made again. */
  setField(terrain, field) {
    const gl = this.gl;
    for (const texture of [this.gradients, this.sun, this.occlusion]) if (texture) gl.deleteTexture(texture);
    this.terrain = terrain;
    this.field = field;
    this.spacing = terrain.spacingX; // the page calls again when the cell size changes
    this.forgetGl();
  }

  /** The field as metres over its raw samples (a fresh view: WASM memory may have grown). */
  view() {
    const t = this.terrain, mask = this.field.missingMask;
    // A one-row file is widened to two rows in the core: its mask no longer fits, and is left out.
    const missing = mask && mask.length === Math.ceil((t.width * t.height) / 8) ? mask : null;
    return fieldOf(t.samples(), t.width, t.height, t.spacingX, t.spacingY, this.field.heightScale ?? 1, this.field.heightOffset ?? 0, missing);
  }

  /** Makes what is out of date (all three, so every sampler has a texture). Allocates only when something changed. */
  prepare(verticalScale, sunDirection, earth = FLAT_EARTH) {
    // A tiled terrain (a tiled COG) has no whole field to make them from: never ready, so
    // the renderer shades with the mesh's normals.
    if (!this.terrain || this.terrain.handle === 0 || this.terrain.tiled) return;
    if (!this.gradients) this.makeGradients();
    if (this.occlusionScale !== verticalScale) this.makeOcclusion(verticalScale);
    const key = this.sunKey;
    if ((key[0] !== sunDirection[0] || key[1] !== sunDirection[1] || key[2] !== sunDirection[2]
      || key[3] !== verticalScale) || this.sunEarth !== earth) {
      this.makeSun(verticalScale, sunDirection, earth);
    }
  }

  makeGradients() {
    const gl = this.gl, start = performance.now();
    const field = this.view();
    const maxTile = Math.min(gl.getParameter(gl.MAX_TEXTURE_SIZE), this.forcedTile() || Infinity);
    const stride = Math.max(1, Math.ceil(Math.sqrt((field.width * field.height) / GRADIENT_MAX_TEXELS)));
    const tiles = gradientTiles(field, maxTile, stride);
    const layers = tiles.tilesX * tiles.tilesZ;
    const texture = this.gradients = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_GRADIENTS);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
    const levels = 1 + Math.floor(Math.log2(Math.max(tiles.tileX, tiles.tileZ)));
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, levels, gl.RGBA16F, tiles.tileX, tiles.tileZ, layers);
    const scratch = new Float32Array(4 * tiles.tileX * tiles.tileZ);
    const halves = [new Float32Array(scratch.length / 2), new Float32Array(scratch.length / 2)];
    for (let tz = 0; tz < tiles.tilesZ; ++tz) {
      for (let tx = 0; tx < tiles.tilesX; ++tx) {
        // Level 0 from the field, then each level the mean of the one above (RGBA16F cannot generateMipmap).
        let image = tiles.fill(tx, tz, scratch), w = tiles.tileX, h = tiles.tileZ;
        for (let level = 0; level < levels; ++level) {
          gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, level, 0, 0, tz * tiles.tilesX + tx, w, h, 1, gl.RGBA, gl.FLOAT, image);
          if (level + 1 < levels) {
            image = halveImage(image, w, h, 4, halves[level % 2]);
            w = Math.max(1, w >> 1);
            h = Math.max(1, h >> 1);
          }
        }
      }
    }
    // Bilinear within the nearest mip level: half the fetches of trilinear, no visible difference
    // on normals and heights.
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_NEAREST);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    this.tiles = tiles;
    this.ready = true;
    this.times.gradientsMs = performance.now() - start;
  }

  /** An 8-bit single-channel texture with linear filtering. */
  makeR8(unit, texture, grid, data) {
    const gl = this.gl;
    gl.activeTexture(gl.TEXTURE0 + unit);
    const result = texture ?? gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, result);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.R8, grid.width, grid.height, 0, gl.RED, gl.UNSIGNED_BYTE, data);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    return result;
  }

  makeOcclusion(verticalScale) {
    const start = performance.now();
    this.occlusionGrid = this.occlusionGrid ?? downsampleField(this.view(), OCCLUSION_MAX_SIDE);
    const data = ambientOcclusion(this.occlusionGrid, verticalScale);
    this.occlusion = this.makeR8(TEXTURE_UNIT_OCCLUSION, this.occlusion, this.occlusionGrid, data);
    this.occlusionScale = verticalScale;
    this.times.occlusionMs = performance.now() - start;
  }

  makeSun(verticalScale, sunDirection, earth) {
    const start = performance.now();
    const grid = this.sunGrid = this.sunGrid ?? downsampleField(this.view(), SUN_MAX_SIDE);
    if (this.sunData?.length !== grid.width * grid.height) this.sunData = new Uint8Array(grid.width * grid.height);
    // On the curved Earth the sun stands at another elevation over each part of the field.
    sunVisibility(grid, sunDirection, verticalScale, this.sunData, earth.kind === EARTH_FLAT ? null : earth);
    this.sunEarth = earth;
    this.sun = this.makeR8(TEXTURE_UNIT_SUN, this.sun, this.sunGrid, this.sunData);
    this.sunKey[0] = sunDirection[0]; this.sunKey[1] = sunDirection[1]; this.sunKey[2] = sunDirection[2];
    this.sunKey[3] = verticalScale;
    this.times.sunMs = performance.now() - start;
  }

  /** Binds the textures and sets the uniforms of shaders/field_textures.glsl. */
  setUniforms(u) {
    const gl = this.gl;
    if (!this.ready) return;
    const t = this.tiles;
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_GRADIENTS);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.gradients);
    gl.uniform2f(u.uGradientTexel, t.texelX, t.texelZ);
    gl.uniform2f(u.uGradientStep, t.tileX - 1, t.tileZ - 1);
    gl.uniform2f(u.uGradientTile, t.tileX, t.tileZ);
    gl.uniform2f(u.uGradientTiles, t.tilesX, t.tilesZ);
    this.bindGrid(u.uSunVisibilityMap, TEXTURE_UNIT_SUN, this.sun, this.sunGrid);
    this.bindGrid(u.uOcclusionMap, TEXTURE_UNIT_OCCLUSION, this.occlusion, this.occlusionGrid);
  }

  /** uv = xz * scale + bias for a downsampled grid whose texel j is the mean of samples [j*stride, (j+1)*stride). */
  bindGrid(location, unit, texture, grid) {
    const gl = this.gl;
    gl.activeTexture(gl.TEXTURE0 + unit);
    gl.bindTexture(gl.TEXTURE_2D, texture);
    if (!grid) return;
    const sx = this.terrain.spacingX, sz = this.terrain.spacingY, k = grid.stride;
    // Sample column c sits at x = c * sx; texel j's centre at sample (j*k + (k-1)/2).
    gl.uniform4f(location, 1 / (sx * k * grid.width), 1 / (sz * k * grid.height),
      (0.5 - (k - 1) / (2 * k)) / grid.width, (0.5 - (k - 1) / (2 * k)) / grid.height);
  }
}
