// The GPU side of a draped image (shaders/image_drape.glsl): its tiles as layers of an RGBA8
// texture array (web/imagery/image_tiling.js lays them out), mipmapped, with anisotropic
// filtering where the extension exists, and an overview of the whole image for coarse views.
// Filled from an ImageBitmap (PNG, JPEG, WebP: the browser decodes, one upload a tile) or from
// bands of rows (GeoTIFF: each band goes to the tiles it touches, and into the overview, a row at a time).
// ?imagetile=N forces tiles of at most N texels (tests of the tiling on any GPU).
import { tileSource } from '../../imagery/image_tiling.js';
import { OverviewRows } from '../../imagery/overview_rows.js';

export const TEXTURE_UNIT_IMAGE_TILES = 3;
export const TEXTURE_UNIT_IMAGE_OVERVIEW = 4;
const MAX_ANISOTROPY = 8;

function forcedTileSize() {
  const value = Number(new URLSearchParams(globalThis.location?.search ?? '').get('imagetile'));
  return Number.isInteger(value) && value >= 64 ? value : Infinity;
}

export class ImageTextures {
  /** @param {WebGL2RenderingContext} gl */
  constructor(gl) {
    this.gl = gl;
    this.tiles = this.overview = null;
    this.tiling = null;
    this.overviewRows = null; // the overview made from bands as they arrive
    this.filling = false;
  }

  /** The GPU's limits an image is tiled by. */
  limits() {
    const gl = this.gl;
    return {
      maxTextureSize: Math.min(gl.getParameter(gl.MAX_TEXTURE_SIZE), forcedTileSize()),
      maxLayers: gl.getParameter(gl.MAX_ARRAY_TEXTURE_LAYERS),
    };
  }

  /** The context was lost: the textures are gone (the page drapes the image again). */
  forgetGl() {
    this.tiles = this.overview = null;
    this.tiling = null;
    this.overviewRows = null;
    this.filling = false;
  }

  /** True while a whole image is on the GPU. */
  get ready() {
    return this.tiling !== null && !this.filling;
  }

  /**
   * Reserves the textures of an image laid out by `tiling` (the previous image goes).
   * @param {import('../../imagery/image_tiling.js').ImageTiling} tiling
   */
  begin(tiling) {
    const gl = this.gl;
    this.remove();
    this.tiling = tiling;
    const layers = tiling.tilesX * tiling.tilesY;
    this.tiles = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_TILES);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.tiles);
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, levelsOf(tiling.tileWidth, tiling.tileHeight), gl.RGBA8, tiling.tileWidth, tiling.tileHeight, layers);
    if (tiling.overview) {
      const { width, height } = tiling.overview;
      this.overview = gl.createTexture();
      gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_OVERVIEW);
      gl.bindTexture(gl.TEXTURE_2D, this.overview);
      gl.texStorage2D(gl.TEXTURE_2D, levelsOf(width, height), gl.RGBA8, width, height);
      this.overviewRows = new OverviewRows(tiling.width, tiling.height, width, height, (row, rgba) => {
        gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_OVERVIEW);
        gl.bindTexture(gl.TEXTURE_2D, this.overview);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
        gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, row, width, 1, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
        resetUnpack(gl);
      });
    }
    this.filling = true;
  }

  /** Every tile from a decoded image (its overview made by the browser's resampler). */
  async uploadBitmap(bitmap) {
    const gl = this.gl, t = this.tiling;
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_TILES);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.tiles);
    for (let ty = 0; ty < t.tilesY; ty++) {
      for (let tx = 0; tx < t.tilesX; tx++) {
        const [x0, y0, x1, y1] = tileSource(t, tx, ty);
        gl.pixelStorei(gl.UNPACK_SKIP_PIXELS, x0);
        gl.pixelStorei(gl.UNPACK_SKIP_ROWS, y0);
        gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, x0 - (tx * t.strideX - t.apron), y0 - (ty * t.strideY - t.apron),
          ty * t.tilesX + tx, x1 - x0, y1 - y0, 1, gl.RGBA, gl.UNSIGNED_BYTE, bitmap);
      }
    }
    resetUnpack(gl);
    if (t.overview) {
      const small = await createImageBitmap(bitmap, { resizeWidth: t.overview.width, resizeHeight: t.overview.height, resizeQuality: 'high' });
      gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_OVERVIEW);
      gl.bindTexture(gl.TEXTURE_2D, this.overview);
      gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, t.overview.width, t.overview.height, gl.RGBA, gl.UNSIGNED_BYTE, small);
      small.close();
      this.overviewRows = null;
    }
    this.finish();
  }

  /**
   * Rows y..y+rows-1 of the image, RGBA (width * rows * 4 bytes): into every tile they touch
   * (aprons included), and into the overview.
   */
  uploadBand(y, rows, rgba) {
    const gl = this.gl, t = this.tiling;
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_TILES);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.tiles);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.pixelStorei(gl.UNPACK_ROW_LENGTH, t.width);
    for (let ty = 0; ty < t.tilesY; ty++) {
      for (let tx = 0; tx < t.tilesX; tx++) {
        const [x0, y0, x1, y1] = tileSource(t, tx, ty);
        const top = Math.max(y0, y), bottom = Math.min(y1, y + rows);
        if (top >= bottom) continue;
        gl.pixelStorei(gl.UNPACK_SKIP_PIXELS, x0);
        gl.pixelStorei(gl.UNPACK_SKIP_ROWS, top - y);
        gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, x0 - (tx * t.strideX - t.apron), top - (ty * t.strideY - t.apron),
          ty * t.tilesX + tx, x1 - x0, bottom - top, 1, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
      }
    }
    resetUnpack(gl);
    this.overviewRows?.add(y, rows, rgba);
  }

  /** After the last band (or the bitmap): the overview's last row, then mipmaps and filtering. */
  finish() {
    const gl = this.gl;
    this.overviewRows?.finish();
    this.overviewRows = null;
    this.filling = false;
    const anisotropic = gl.getExtension('EXT_texture_filter_anisotropic');
    const filter = (target, texture, unit) => {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(target, texture);
      gl.generateMipmap(target);
      gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
      gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
      gl.texParameteri(target, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
      gl.texParameteri(target, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
      if (anisotropic) {
        const most = gl.getParameter(anisotropic.MAX_TEXTURE_MAX_ANISOTROPY_EXT);
        gl.texParameterf(target, anisotropic.TEXTURE_MAX_ANISOTROPY_EXT, Math.min(MAX_ANISOTROPY, most));
      }
    };
    filter(gl.TEXTURE_2D_ARRAY, this.tiles, TEXTURE_UNIT_IMAGE_TILES);
    if (this.overview) filter(gl.TEXTURE_2D, this.overview, TEXTURE_UNIT_IMAGE_OVERVIEW);
  }

  /** The image goes. */
  remove() {
    const gl = this.gl;
    if (this.tiles) gl.deleteTexture(this.tiles);
    if (this.overview) gl.deleteTexture(this.overview);
    this.forgetGl();
  }

  /**
   * Binds the textures and sets the uniforms of shaders/image_drape.glsl.
   * @param {object} u uniform locations
   * @param {import('../../imagery/placement.js').Placement|null} placement
   * @param {{ spacingX: number, spacingY: number }} terrain metres between samples
   */
  setUniforms(u, placement, terrain) {
    const gl = this.gl, t = this.tiling;
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_TILES);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.ready ? this.tiles : null);
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_OVERVIEW);
    gl.bindTexture(gl.TEXTURE_2D, this.ready ? this.overview : null);
    const on = this.ready && placement !== null;
    gl.uniform1f(u.uImageOn, on ? 1 : 0);
    if (!on) return;
    // Ground metres -> field samples (x / spacing) -> texture uv (the placement's scale and offset).
    gl.uniform4f(u.uImageMap, placement.scaleU / terrain.spacingX, placement.scaleV / terrain.spacingY, placement.offsetU, placement.offsetV);
    gl.uniform2f(u.uImageSize, t.width, t.height);
    gl.uniform4f(u.uImageTiling, t.strideX, t.strideY, t.tilesX, t.tilesY);
    gl.uniform3f(u.uImageTile, t.tileWidth, t.tileHeight, t.apron);
  }
}

function levelsOf(width, height) {
  return 1 + Math.floor(Math.log2(Math.max(width, height)));
}

function resetUnpack(gl) {
  gl.pixelStorei(gl.UNPACK_SKIP_PIXELS, 0);
  gl.pixelStorei(gl.UNPACK_SKIP_ROWS, 0);
  gl.pixelStorei(gl.UNPACK_ROW_LENGTH, 0);
  gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
}
