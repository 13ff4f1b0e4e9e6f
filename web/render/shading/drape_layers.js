// The image layers on the terrain, as the drape shader (shaders/image_drape.glsl) reads them:
// up to MAX_DRAPES visible layers, bottom first, each with its control grid (one layer of a
// shared RG32F texture array), its texture array of pages (image tiles or web map tiles) and,
// for web map tiles, its table of which tile covers where. Called each frame with the layer
// list's drapes; uploads a control grid only when it changed, allocates nothing.

export const MAX_DRAPES = 4;
export const TEXTURE_UNIT_DRAPE_WARPS = 3;
const TEXTURE_UNIT_PAGES = [7, 8, 9, 10];
const TEXTURE_UNIT_TABLES = [11, 12, 13, 14];
// The unit the image layers' textures are bound to while they are filled (image_textures.js,
// web_tile_textures.js): one no program samples from, so an upload never disturbs what a draw bound.
export const TEXTURE_UNIT_UPLOAD = 15;
const KIND = { image: 1, tiles: 2 };
const PAGES_UNIFORMS = ['uDrapePages0', 'uDrapePages1', 'uDrapePages2', 'uDrapePages3'];
const TABLE_UNIFORMS = ['uDrapeTable0', 'uDrapeTable1', 'uDrapeTable2', 'uDrapeTable3'];

export const DRAPE_UNIFORMS = ['uDrapeWarps', ...PAGES_UNIFORMS, ...TABLE_UNIFORMS, 'uDrapeKind', 'uDrapeOpacity', 'uDrapeWarp',
  'uDrapeSize', 'uDrapeTiling', 'uDrapeTile', 'uDrapeTable'];

/**
 * @typedef {object} Drape one visible layer, as the renderer draws it
 * @property {'image'|'tiles'} kind
 * @property {import('../../geo/warp_grid.js').WarpGrid} warp ground (field samples) -> the layer's coordinates
 * @property {number} opacity 0..1
 * @property {object} textures image: ImageTextures (pages, tiling); tiles: WebTileTextures (pages, table, range)
 */

export class DrapeLayers {
  /** @param {WebGL2RenderingContext} gl */
  constructor(gl) {
    this.gl = gl;
    this.kind = new Int32Array(MAX_DRAPES);
    this.opacity = new Float32Array(MAX_DRAPES);
    this.warpMap = new Float32Array(4 * MAX_DRAPES);
    this.size = new Float32Array(2 * MAX_DRAPES);
    this.tiling = new Float32Array(4 * MAX_DRAPES);
    this.tile = new Float32Array(3 * MAX_DRAPES);
    this.table = new Int32Array(3 * MAX_DRAPES);
    this.forgetGl();
  }

  /** The context was lost (or is new): the control grids are uploaded again. */
  forgetGl() {
    this.warps = null;          // the RG32F texture array of control grids
    this.warpCapacity = [0, 0]; // its nodes across and down
    this.uploaded = new Array(MAX_DRAPES).fill(null); // the grid each of its layers holds
  }

  /**
   * Binds the textures and sets the uniforms of shaders/image_drape.glsl.
   * @param {object} u uniform locations
   * @param {Drape[]} drapes visible layers, bottom first (those past MAX_DRAPES are not drawn)
   * @param {{ spacingX: number, spacingY: number }} terrain metres between samples
   */
  setUniforms(u, drapes, terrain) {
    const gl = this.gl;
    const count = Math.min(drapes.length, MAX_DRAPES);
    if (count > 0) this.uploadWarps(drapes, count);
    gl.uniform1i(u.uDrapeWarps, TEXTURE_UNIT_DRAPE_WARPS);
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_DRAPE_WARPS);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.warps);
    for (let slot = 0; slot < MAX_DRAPES; slot++) {
      const drape = slot < count ? drapes[slot] : null;
      const textures = drape?.textures;
      const ready = drape !== null && textures.ready;
      this.kind[slot] = ready ? KIND[drape.kind] : 0;
      gl.uniform1i(u[PAGES_UNIFORMS[slot]], TEXTURE_UNIT_PAGES[slot]);
      gl.uniform1i(u[TABLE_UNIFORMS[slot]], TEXTURE_UNIT_TABLES[slot]);
      if (ready && drape.kind === 'tiles') {
        textures.bind(TEXTURE_UNIT_PAGES[slot], TEXTURE_UNIT_TABLES[slot]);
      } else {
        gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_PAGES[slot]);
        gl.bindTexture(gl.TEXTURE_2D_ARRAY, ready ? textures.pages : null);
        // An unsigned sampler's unit must not hold a texture of another kind: empty unless tiles.
        gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_TABLES[slot]);
        gl.bindTexture(gl.TEXTURE_2D, null);
      }
      if (!ready) continue;
      const w = drape.warp;
      this.opacity[slot] = drape.opacity;
      this.warpMap[4 * slot] = 1 / (terrain.spacingX * w.columnsPerCell);
      this.warpMap[4 * slot + 1] = 1 / (terrain.spacingY * w.rowsPerCell);
      this.warpMap[4 * slot + 2] = w.nodesX;
      this.warpMap[4 * slot + 3] = w.nodesY;
      if (drape.kind === 'image') {
        const t = textures.tiling;
        this.size[2 * slot] = t.width; this.size[2 * slot + 1] = t.height;
        this.tiling[4 * slot] = t.strideX; this.tiling[4 * slot + 1] = t.strideY;
        this.tiling[4 * slot + 2] = t.tilesX; this.tiling[4 * slot + 3] = t.tilesY;
        this.tile[3 * slot] = t.tileWidth; this.tile[3 * slot + 1] = t.tileHeight; this.tile[3 * slot + 2] = t.apron;
      } else {
        const r = textures.range;
        this.table[3 * slot] = r.x0; this.table[3 * slot + 1] = r.y0; this.table[3 * slot + 2] = r.zoom;
      }
    }
    gl.uniform1iv(u.uDrapeKind, this.kind);
    gl.uniform1fv(u.uDrapeOpacity, this.opacity);
    gl.uniform4fv(u.uDrapeWarp, this.warpMap);
    gl.uniform2fv(u.uDrapeSize, this.size);
    gl.uniform4fv(u.uDrapeTiling, this.tiling);
    gl.uniform3fv(u.uDrapeTile, this.tile);
    gl.uniform3iv(u.uDrapeTable, this.table);
  }

  /** Puts each visible layer's control grid in its layer of the grid texture, when it changed. */
  uploadWarps(drapes, count) {
    const gl = this.gl;
    // By index: destructuring an array makes an iterator, garbage in every frame.
    const capacityX = this.warpCapacity[0], capacityY = this.warpCapacity[1];
    let needX = capacityX, needY = capacityY;
    for (let slot = 0; slot < count; slot++) {
      needX = Math.max(needX, drapes[slot].warp.nodesX);
      needY = Math.max(needY, drapes[slot].warp.nodesY);
    }
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_DRAPE_WARPS);
    if (!this.warps || needX > capacityX || needY > capacityY) {
      if (this.warps) gl.deleteTexture(this.warps);
      this.warps = gl.createTexture();
      gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.warps);
      gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, gl.RG32F, needX, needY, MAX_DRAPES);
      gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      this.warpCapacity = [needX, needY];
      this.uploaded.fill(null);
    }
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.warps);
    for (let slot = 0; slot < count; slot++) {
      const w = drapes[slot].warp;
      if (this.uploaded[slot] === w) continue;
      gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, slot, w.nodesX, w.nodesY, 1, gl.RG, gl.FLOAT, w.values);
      this.uploaded[slot] = w;
    }
  }
}
