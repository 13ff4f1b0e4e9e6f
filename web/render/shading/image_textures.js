// The GPU side of one draped image (shaders/image_drape.glsl): its tiles as layers of an RGBA8
// texture array (web/imagery/image_tiling.js lays them out), mipmapped, with anisotropic
// filtering where the extension exists, and for a tiled image an overview of the whole image
// as the array's last layer, for coarse views.
// Filled from an ImageBitmap (PNG, JPEG, WebP: the browser decodes, one upload a tile) or from
// bands of rows (GeoTIFF: each band goes to the tiles it touches, and into the overview, a row
// at a time). Each image layer has textures of its own: a failed opening (abort()) leaves
// every layer on screen as it was, and after a lost context the page opens the image again
// into new ones.
// The imageTile setting (?imagetile=N) forces tiles of at most N texels (tests of the tiling on any GPU).
import { tileSource, arrayLayers } from '../../imagery/image_tiling.js';
import { OverviewRows } from '../../imagery/overview_rows.js';
import { TEXTURE_UNIT_UPLOAD } from './drape_layers.js';

const MAX_ANISOTROPY = 8;


export class ImageTextures {
  /**
   * @param {WebGL2RenderingContext} gl
   * @param {() => number} forcedTile texels a side the tiles may not exceed, read at each upload (0: none)
   */
  constructor(gl, forcedTile = () => 0) {
    this.gl = gl;
    this.forcedTile = forcedTile;
    this.pages = null;   // the texture array: tiles, then the overview
    this.tiling = null;
    this.ready = false;  // true once the whole image is on the GPU
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

  /**
   * Reserves the textures of an image laid out by `tiling`.
   * @param {import('../../imagery/image_tiling.js').ImageTiling} tiling
   */
  begin(tiling) {
    const gl = this.gl;
    this.remove();
    this.tiling = tiling;
    this.pages = gl.createTexture();
    this.bindPages();
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, levelsOf(tiling.tileWidth, tiling.tileHeight), gl.RGBA8, tiling.tileWidth, tiling.tileHeight, arrayLayers(tiling));
    if (tiling.overview) {
      const { width, height } = tiling.overview, layer = tiling.tilesX * tiling.tilesY;
      this.overviewRows = new OverviewRows(tiling.width, tiling.height, width, height, (row, rgba) => {
        this.bindPages();
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
        gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, row, layer, width, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
        resetUnpack(gl);
      });
    }
  }

  bindPages() {
    const gl = this.gl;
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_UPLOAD);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.pages);
  }

  /** Every tile from a decoded image (its overview made by the browser's resampler). */
  async uploadBitmap(bitmap) {
    const gl = this.gl, t = this.tiling;
    this.bindPages();
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
      this.bindPages();
      gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, t.tilesX * t.tilesY, t.overview.width, t.overview.height, 1, gl.RGBA, gl.UNSIGNED_BYTE, small);
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
    this.bindPages();
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
    this.bindPages();
    gl.generateMipmap(gl.TEXTURE_2D_ARRAY);
    setFiltering(gl, gl.TEXTURE_2D_ARRAY);
    this.ready = true;
  }

  /** The image being filled goes (it failed). */
  abort() {
    this.remove();
  }

  /** The textures go. */
  remove() {
    if (this.pages) this.gl.deleteTexture(this.pages);
    this.pages = null;
    this.ready = false;
    this.overviewRows = null;
  }
}

/** Trilinear, clamped and (where the GPU has it) anisotropic filtering of the bound texture. */
export function setFiltering(gl, target) {
  gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
  gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  gl.texParameteri(target, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(target, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  const anisotropic = gl.getExtension('EXT_texture_filter_anisotropic');
  if (anisotropic) {
    const most = gl.getParameter(anisotropic.MAX_TEXTURE_MAX_ANISOTROPY_EXT);
    gl.texParameterf(target, anisotropic.TEXTURE_MAX_ANISOTROPY_EXT, Math.min(MAX_ANISOTROPY, most));
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
