// The GPU side of one web map tile layer (web/webtiles/): the tiles that arrived, as layers
// ("pages") of one mipmapped RGBA8 texture array, and a table that tells the drape shader which
// page holds the finest tile over each place of the terrain.
//
//   pages  TEXTURE_2D_ARRAY RGBA8, tileSize² texels × capacity layers, mipmapped
//          (LINEAR_MIPMAP_LINEAR, CLAMP_TO_EDGE, anisotropic where the extension exists).
//          Row 0 of a page is the tile's top (north) row. Capacity: what the memory cap holds.
//   table  TEXTURE_2D RG16UI (NEAREST), width × height entries: entry (i, j) stands for tile
//          (x0 + i, y0 + j) of zoom Z (setRange) and holds (page + 1, z) of the finest tile
//          that covers it, which may be a coarser ancestor (z < Z) while finer ones load;
//          (0, 0) where none is there.
//
// The shader, for a ground point whose tile coordinates at zoom Z are Z-tile units t relative
// to (x0, y0) (the warp grid's value: t = world · 2^Z − (x0, y0)):
//   uvec2 e = texelFetch(table, ivec2(floor(t)), 0).rg;    // nothing where e.r == 0u
//   int k = Z − int(e.g);                                    // zooms between the table and the tile
//   ivec2 tile = ((ivec2(floor(t)) + origin) >> k);          // the tile's column and row at zoom e.g
//   vec2 uv = (t − vec2((tile << k) − origin)) / exp2(k);     // 0..1 across the tile, v down
//   textureGrad(pages, vec3(uv, float(e.r − 1u)), dFdx(t) / exp2(k), dFdy(t) / exp2(k));
// with origin = (x0, y0) as integers (exact; float t stays small, so the texels keep their place
// even at zoom 20, where x0 is about a million).
//
// A tile's arrival or eviction rewrites only the entries of its square and uploads that
// rectangle. Eviction is least recently used under the cap, never a tile of the current wanted
// set (markWanted) or of the base level, and the tiles that stand in for wanted tiles not yet
// there go last; an evicted tile's entries fall back to its finest loaded ancestor, and the
// entries of its loaded descendants stay theirs.
import { tileKey } from '../../webtiles/tile_key.js';
import { TEXTURE_UNIT_UPLOAD } from './drape_layers.js';
import { setFiltering } from './image_textures.js';

/** GPU memory the pages may take, mipmaps included (a constructor option). */
export const DEFAULT_MEMORY_BYTES = 64 * 1024 * 1024;
export const DEFAULT_TILE_SIZE = 256;
const MIN_CAPACITY = 16;
// Pin levels of a page: evicted in this order, NEEDED never.
const FREE = 0, STANDS_IN = 1, NEEDED = 2;

export class WebTileTextures {
  /**
   * @param {WebGL2RenderingContext} gl
   * @param {{ memoryBytes?: number, tileSize?: number }} [options] memoryBytes: cap of the pages
   *   (mipmaps included); tileSize: texels a tile side (default: the first tile's width)
   */
  constructor(gl, { memoryBytes = DEFAULT_MEMORY_BYTES, tileSize = 0 } = {}) {
    this.gl = gl;
    this.memoryBytes = memoryBytes;
    this.tileSize = tileSize;
    this.range = null;        // { zoom, x0, y0, width, height } of the table
    this.entries = null;      // the table's CPU copy: Uint16Array of (page + 1, z) pairs
    this.resident = new Map(); // tile key -> page
    this.capacity = 0;
    this.figures = { resident: 0, bytes: 0, residentBytes: 0, evictions: 0, puts: 0, refused: 0 };
    this.clock = 0;
    this.forgetGl();
  }

  /**
   * The context was lost and is back (or is new): the GL objects and every tile in them are
   * gone; the table's range stays, its entries emptied, and both textures are made again at
   * the next put() or bind().
   */
  forgetGl() {
    this.pages = null;
    this.table = null;
    this.readBuffer = this.drawBuffer = null;
    this.blitMips = null; // whether a page's mipmaps are made by blits (found out at the first put)
    this.pin = this.base = null; // per page: its pin level, and whether it is a base tile
    this.resident.clear();
    this.free = [];
    this.capacity = 0;
    if (this.entries) this.entries.fill(0);
    this.figures.resident = this.figures.residentBytes = 0;
    this.figures.bytes = this.range ? 4 * this.range.width * this.range.height : 0;
  }

  /** True once the pages exist (the first tile was put). */
  get ready() {
    return this.pages !== null;
  }

  /** Whether a tile is on the GPU. */
  has(key) {
    return this.resident.has(key);
  }

  /**
   * Chooses the table: tiles x0..x0+width-1, y0..y0+height-1 of zoom `zoom`
   * (web/webtiles/table_range.js tableRange). The tiles on the GPU stay and fill it again.
   */
  setRange({ zoom, x0, y0, width, height }) {
    const gl = this.gl;
    if (!(width >= 1 && height >= 1 && width <= 4096 && height <= 4096)) throw new RangeError(`a tile table of ${width} × ${height} entries`);
    if (this.table) gl.deleteTexture(this.table);
    this.table = null;
    this.range = { zoom, x0, y0, width, height };
    this.entries = new Uint16Array(2 * width * height);
    this.figures.bytes = this.pagesBytes() + 4 * width * height;
    // The tiles already there, coarse first so finer ones win.
    const tiles = [...this.resident].map(([key, page]) => ({ key, page, z: this.tileZ[page], x: this.tileX[page], y: this.tileY[page] }));
    tiles.sort((a, b) => a.z - b.z);
    for (const t of tiles) this.fill(t.z, t.x, t.y, t.page);
    if (this.base) this.base.fill(0);
    this.ensureTable();
  }

  /**
   * Puts a decoded tile (tileSize² texels: the layer resizes others) on the GPU.
   * @param {ImageBitmap|ImageData|HTMLCanvasElement|OffscreenCanvas|{ width: number, height: number, data: Uint8Array }} image
   *   RGBA, row 0 the north edge
   * @returns {boolean} false when it was not kept: finer than the table, off its range, or every page is needed
   */
  put(z, x, y, image) {
    if (!this.range) throw new Error('WebTileTextures.put before setRange');
    if (!this.tileSize) this.tileSize = image.width === image.height ? image.width : DEFAULT_TILE_SIZE;
    if (image.width !== this.tileSize || image.height !== this.tileSize) {
      throw new RangeError(`a tile of ${image.width} × ${image.height} texels, the pages take ${this.tileSize}²: resize it first`);
    }
    if (this.gl.isContextLost()) return false; // the pages died with the context: the tile is fetched again after forgetGl()
    if (z > this.range.zoom || !this.rectOf(z, x, y)) {
      this.figures.refused++;
      return false;
    }
    if (!this.pages) this.createPages();
    const key = tileKey(z, x, y);
    let page = this.resident.get(key);
    if (page === undefined) {
      page = this.free.length > 0 ? this.free.pop() : this.evictOne();
      if (page < 0) {
        this.figures.refused++;
        return false;
      }
    }
    this.upload(page, image);
    this.resident.set(key, page);
    this.tileZ[page] = z; this.tileX[page] = x; this.tileY[page] = y; this.keys[page] = key;
    this.used[page] = ++this.clock;
    this.fill(z, x, y, page);
    this.figures.puts++;
    this.count();
    return true;
  }

  /**
   * The tiles the view wants now (web/webtiles/tile_selection.js: base tiles flagged `base`):
   * none of them is evicted until the next call, and the loaded tiles that stand in for those
   * not yet there are evicted last.
   * @param {ArrayLike<{ z: number, x: number, y: number, key: number, base?: boolean }>} tiles
   */
  markWanted(tiles) {
    if (!this.pin) return;
    this.pin.fill(FREE);
    const clock = ++this.clock;
    for (let i = 0; i < tiles.length; i++) {
      const t = tiles[i];
      const page = this.resident.get(t.key);
      if (page !== undefined) {
        this.pin[page] = NEEDED;
        this.used[page] = clock;
        if (t.base) this.base[page] = 1;
        continue;
      }
      // The finest loaded ancestor shows meanwhile.
      for (let z = t.z - 1; z >= 0; z--) {
        const above = this.resident.get(tileKey(z, t.x >> (t.z - z), t.y >> (t.z - z)));
        if (above !== undefined) {
          if (this.pin[above] === FREE) this.pin[above] = STANDS_IN;
          this.used[above] = clock;
          break;
        }
      }
    }
  }

  /** Binds the pages and the table to texture units (the shader's samplers: sampler2DArray, usampler2D). */
  bind(pagesUnit, tableUnit) {
    const gl = this.gl;
    if (this.range && !this.table) this.ensureTable();
    gl.activeTexture(gl.TEXTURE0 + pagesUnit);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.pages);
    gl.activeTexture(gl.TEXTURE0 + tableUnit);
    gl.bindTexture(gl.TEXTURE_2D, this.table);
  }

  /** The entry (page + 1, z) of table cell (i, j), from the CPU copy; [0, 0] when none. */
  entry(i, j) {
    const k = 2 * (j * this.range.width + i);
    return [this.entries[k], this.entries[k + 1]];
  }

  /** Every GL object goes. */
  dispose() {
    const gl = this.gl;
    if (this.pages) gl.deleteTexture(this.pages);
    if (this.table) gl.deleteTexture(this.table);
    if (this.readBuffer) gl.deleteFramebuffer(this.readBuffer);
    if (this.drawBuffer) gl.deleteFramebuffer(this.drawBuffer);
    this.range = null;
    this.entries = null;
    this.forgetGl();
  }

  // --- inside ---

  pagesBytes() {
    return this.capacity * layerBytes(this.tileSize);
  }

  createPages() {
    const gl = this.gl, size = this.tileSize;
    this.capacity = Math.min(gl.getParameter(gl.MAX_ARRAY_TEXTURE_LAYERS), 65535,
      Math.max(MIN_CAPACITY, Math.floor(this.memoryBytes / layerBytes(size))));
    this.levels = 1 + Math.floor(Math.log2(size));
    this.pages = gl.createTexture();
    this.withUnit(gl.TEXTURE_2D_ARRAY, this.pages, () => {
      gl.texStorage3D(gl.TEXTURE_2D_ARRAY, this.levels, gl.RGBA8, size, size, this.capacity);
      setFiltering(gl, gl.TEXTURE_2D_ARRAY); // as an image layer's pages
    });
    this.readBuffer = gl.createFramebuffer();
    this.drawBuffer = gl.createFramebuffer();
    const n = this.capacity;
    this.free = [];
    for (let page = n - 1; page >= 0; page--) this.free.push(page);
    this.tileZ = new Uint8Array(n); this.tileX = new Uint32Array(n); this.tileY = new Uint32Array(n);
    this.keys = new Float64Array(n);
    this.used = new Float64Array(n);
    this.pin = new Uint8Array(n);
    this.base = new Uint8Array(n);
    this.figures.bytes = this.pagesBytes() + (this.range ? 4 * this.range.width * this.range.height : 0);
  }

  ensureTable() {
    const gl = this.gl, { width, height } = this.range;
    this.table = gl.createTexture();
    this.withUnit(gl.TEXTURE_2D, this.table, () => {
      gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RG16UI, width, height);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    });
    this.uploadEntries(0, 0, width, height);
  }

  /** The least recently used page that no wanted tile needs, emptied; -1 when every page is needed. */
  evictOne() {
    let best = -1;
    for (let page = 0; page < this.capacity; page++) {
      if (this.pin[page] === NEEDED || this.base[page]) continue;
      if (best < 0 || this.pin[page] < this.pin[best] || (this.pin[page] === this.pin[best] && this.used[page] < this.used[best])) best = page;
    }
    if (best < 0) return -1;
    const z = this.tileZ[best], x = this.tileX[best], y = this.tileY[best];
    this.resident.delete(this.keys[best]);
    // Its entries fall back to its finest loaded ancestor (or none).
    let above = -1, aboveZ = 0;
    for (let up = z - 1; up >= 0 && above < 0; up--) {
      const page = this.resident.get(tileKey(up, x >> (z - up), y >> (z - up)));
      if (page !== undefined) { above = page; aboveZ = up; }
    }
    this.replace(z, x, y, best + 1, above + 1, above < 0 ? 0 : aboveZ);
    this.pin[best] = FREE;
    this.figures.evictions++;
    return best;
  }

  /** Entries under tile (z, x, y) showing a coarser tile (or none) now show page `page`. */
  fill(z, x, y, page) {
    const e = this.entries, rect = this.rectOf(z, x, y);
    if (!rect) return;
    const [i0, j0, i1, j1] = rect, width = this.range.width;
    for (let j = j0; j < j1; j++) {
      for (let k = 2 * (j * width + i0), end = 2 * (j * width + i1); k < end; k += 2) {
        if (e[k] === 0 || e[k + 1] <= z) { e[k] = page + 1; e[k + 1] = z; }
      }
    }
    this.uploadEntries(i0, j0, i1 - i0, j1 - j0);
  }

  /** Entries under tile (z, x, y) that hold `from` get (to, toZ). */
  replace(z, x, y, from, to, toZ) {
    const e = this.entries, rect = this.rectOf(z, x, y);
    if (!rect) return;
    const [i0, j0, i1, j1] = rect, width = this.range.width;
    for (let j = j0; j < j1; j++) {
      for (let k = 2 * (j * width + i0), end = 2 * (j * width + i1); k < end; k += 2) {
        if (e[k] === from) { e[k] = to; e[k + 1] = toZ; }
      }
    }
    this.uploadEntries(i0, j0, i1 - i0, j1 - j0);
  }

  /** The table cells [i0, i1) × [j0, j1) under tile (z, x, y), or null off the table. */
  rectOf(z, x, y) {
    const { zoom, x0, y0, width, height } = this.range;
    if (z > zoom) return null;
    const n = 2 ** (zoom - z);
    const i0 = Math.max(0, x * n - x0), i1 = Math.min(width, (x + 1) * n - x0);
    const j0 = Math.max(0, y * n - y0), j1 = Math.min(height, (y + 1) * n - y0);
    return i0 < i1 && j0 < j1 ? [i0, j0, i1, j1] : null;
  }

  uploadEntries(i, j, w, h) {
    const gl = this.gl;
    if (!this.table || w <= 0 || h <= 0) return;
    this.withUnit(gl.TEXTURE_2D, this.table, () => {
      gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
      gl.pixelStorei(gl.UNPACK_ROW_LENGTH, this.range.width);
      gl.pixelStorei(gl.UNPACK_SKIP_PIXELS, i);
      gl.pixelStorei(gl.UNPACK_SKIP_ROWS, j);
      gl.texSubImage2D(gl.TEXTURE_2D, 0, i, j, w, h, gl.RG_INTEGER, gl.UNSIGNED_SHORT, this.entries);
      resetUnpack(gl);
    });
  }

  upload(page, image) {
    const gl = this.gl, size = this.tileSize;
    this.withUnit(gl.TEXTURE_2D_ARRAY, this.pages, () => {
      resetUnpack(gl);
      if (image.data && !(typeof ImageData !== 'undefined' && image instanceof ImageData)) {
        gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, page, size, size, 1, gl.RGBA, gl.UNSIGNED_BYTE, image.data);
      } else {
        gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, page, size, size, 1, gl.RGBA, gl.UNSIGNED_BYTE, image);
      }
      this.makeMipmaps(page);
    });
  }

  /**
   * The page's mipmap levels, each the 2 × 2 mean of the one above, by framebuffer blits of
   * that one layer: generateMipmap would remake every page of the array for each tile.
   */
  makeMipmaps(page) {
    const gl = this.gl;
    if (this.blitMips === false) { gl.generateMipmap(gl.TEXTURE_2D_ARRAY); return; }
    const read = gl.getParameter(gl.READ_FRAMEBUFFER_BINDING), draw = gl.getParameter(gl.DRAW_FRAMEBUFFER_BINDING);
    const scissor = gl.isEnabled(gl.SCISSOR_TEST);
    if (scissor) gl.disable(gl.SCISSOR_TEST);
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.readBuffer);
    gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, this.drawBuffer);
    let size = this.tileSize;
    for (let level = 1; level < this.levels; level++) {
      gl.framebufferTextureLayer(gl.READ_FRAMEBUFFER, gl.COLOR_ATTACHMENT0, this.pages, level - 1, page);
      gl.framebufferTextureLayer(gl.DRAW_FRAMEBUFFER, gl.COLOR_ATTACHMENT0, this.pages, level, page);
      if (this.blitMips === null) {
        this.blitMips = gl.checkFramebufferStatus(gl.READ_FRAMEBUFFER) === gl.FRAMEBUFFER_COMPLETE &&
          gl.checkFramebufferStatus(gl.DRAW_FRAMEBUFFER) === gl.FRAMEBUFFER_COMPLETE;
        if (!this.blitMips) break;
      }
      const next = Math.max(1, size >> 1);
      gl.blitFramebuffer(0, 0, size, size, 0, 0, next, next, gl.COLOR_BUFFER_BIT, gl.LINEAR);
      size = next;
    }
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, read);
    gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, draw);
    if (scissor) gl.enable(gl.SCISSOR_TEST);
    if (this.blitMips === false) gl.generateMipmap(gl.TEXTURE_2D_ARRAY);
  }

  /** Runs `work` with `texture` bound on the upload unit, which no draw samples from. */
  withUnit(target, texture, work) {
    const gl = this.gl;
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNIT_UPLOAD);
    gl.bindTexture(target, texture);
    work();
  }

  count() {
    this.figures.resident = this.resident.size;
    this.figures.residentBytes = this.resident.size * layerBytes(this.tileSize);
  }
}

/** GPU bytes of one page: RGBA8 and its mipmaps (a third more). */
function layerBytes(size) {
  let bytes = 0;
  for (let s = size; s >= 1; s >>= 1) bytes += 4 * s * s;
  return bytes;
}

function resetUnpack(gl) {
  gl.pixelStorei(gl.UNPACK_SKIP_PIXELS, 0);
  gl.pixelStorei(gl.UNPACK_SKIP_ROWS, 0);
  gl.pixelStorei(gl.UNPACK_ROW_LENGTH, 0);
  gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
}
