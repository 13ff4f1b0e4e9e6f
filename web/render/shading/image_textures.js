// The GPU side of a draped image (shaders/image_drape.glsl): its tiles as layers of an RGBA8
// texture array (web/imagery/image_tiling.js lays them out), mipmapped, with anisotropic
// filtering where the extension exists, and an overview of the whole image for coarse views.
// Filled from an ImageBitmap (PNG, JPEG, WebP: the browser decodes, one upload a tile) or from
// bands of rows (GeoTIFF: each band goes to the tiles it touches, and into the overview, a row at a time).
// A new image is filled into textures of its own while the one shown stays on screen: it takes
// the old one's place at finish(), and abort() (a band that does not decode) leaves the old one.
// The imageTile setting (?imagetile=N) forces tiles of at most N texels (tests of the tiling on any GPU).
import { tileSource } from '../../imagery/image_tiling.js';
import { OverviewRows } from '../../imagery/overview_rows.js';

export const TEXTURE_UNIT_IMAGE_TILES = 3;
export const TEXTURE_UNIT_IMAGE_OVERVIEW = 4;
const MAX_ANISOTROPY = 8;

export class ImageTextures {
  /**
   * @param {WebGL2RenderingContext} gl
   * @param {() => number} forcedTile texels a side the tiles may not exceed, read at each upload (0: none)
   */
  constructor(gl, forcedTile = () => 0) {
    this.gl = gl;
    this.forcedTile = forcedTile;
    this.shown = null;   // { tiles, overview, tiling } of the image on screen
    this.filling = null; // the same of the image being filled
    this.overviewRows = null; // the overview made from bands as they arrive
  }

  /** The GPU's limits an image is tiled by. */
  limits() {
    const gl = this.gl;
    return {
      maxTextureSize: Math.min(gl.getParameter(gl.MAX_TEXTURE_SIZE), this.forcedTile() || Infinity),
      maxLayers: gl.getParameter(gl.MAX_ARRAY_TEXTURE_LAYERS),
    };
  }

  /** The context was lost: the textures are gone (the page drapes the image again). */
  forgetGl() {
    this.shown = this.filling = null;
    this.overviewRows = null;
  }

  /** True while a whole image is on the GPU. */
  get ready() {
    return this.shown !== null;
  }

  /** The layout of the image on screen (image_tiling.js), or null. */
  get tiling() {
    return this.shown?.tiling ?? null;
  }

  /**
   * Reserves the textures of an image laid out by `tiling`; the image on screen stays until finish().
   * @param {import('../../imagery/image_tiling.js').ImageTiling} tiling
   */
  begin(tiling) {
    const gl = this.gl;
    this.abort();
    const layers = tiling.tilesX * tiling.tilesY;
    const set = this.filling = { tiles: gl.createTexture(), overview: null, tiling };
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_TILES);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, set.tiles);
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, levelsOf(tiling.tileWidth, tiling.tileHeight), gl.RGBA8, tiling.tileWidth, tiling.tileHeight, layers);
    if (tiling.overview) {
      const { width, height } = tiling.overview;
      set.overview = gl.createTexture();
      gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_OVERVIEW);
      gl.bindTexture(gl.TEXTURE_2D, set.overview);
      gl.texStorage2D(gl.TEXTURE_2D, levelsOf(width, height), gl.RGBA8, width, height);
      this.overviewRows = new OverviewRows(tiling.width, tiling.height, width, height, (row, rgba) => {
        gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_OVERVIEW);
        gl.bindTexture(gl.TEXTURE_2D, set.overview);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
        gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, row, width, 1, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
        resetUnpack(gl);
      });
    }
  }

  /** Every tile from a decoded image (its overview made by the browser's resampler). */
  async uploadBitmap(bitmap) {
    const gl = this.gl, set = this.filling, t = set.tiling;
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_TILES);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, set.tiles);
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
      gl.bindTexture(gl.TEXTURE_2D, set.overview);
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
    const gl = this.gl, set = this.filling, t = set.tiling;
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_TILES);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, set.tiles);
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

  /**
   * After the last band (or the bitmap): the overview's last row, then mipmaps and filtering;
   * the new image takes the shown one's place.
   */
  finish() {
    const gl = this.gl, set = this.filling;
    this.overviewRows?.finish();
    this.overviewRows = null;
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
    filter(gl.TEXTURE_2D_ARRAY, set.tiles, TEXTURE_UNIT_IMAGE_TILES);
    if (set.overview) filter(gl.TEXTURE_2D, set.overview, TEXTURE_UNIT_IMAGE_OVERVIEW);
    this.release(this.shown);
    this.shown = set;
    this.filling = null;
  }

  /** The image being filled goes (it failed); the one on screen stays. */
  abort() {
    this.release(this.filling);
    this.filling = null;
    this.overviewRows = null;
  }

  /** Every image goes. */
  remove() {
    this.abort();
    this.release(this.shown);
    this.shown = null;
  }

  release(set) {
    if (!set) return;
    this.gl.deleteTexture(set.tiles);
    if (set.overview) this.gl.deleteTexture(set.overview);
  }

  /**
   * Binds the textures and sets the uniforms of shaders/image_drape.glsl.
   * @param {object} u uniform locations
   * @param {import('../../imagery/placement.js').Placement|null} placement
   * @param {{ spacingX: number, spacingY: number }} terrain metres between samples
   */
  setUniforms(u, placement, terrain) {
    const gl = this.gl, set = this.shown, t = set?.tiling;
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_TILES);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, set?.tiles ?? null);
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_IMAGE_OVERVIEW);
    gl.bindTexture(gl.TEXTURE_2D, set?.overview ?? null);
    const on = set !== null && placement !== null;
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
