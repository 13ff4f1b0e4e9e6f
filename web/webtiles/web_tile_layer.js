// One web map tile layer draped on the terrain, for the page: its template (tile_template.js),
// which tiles the view needs (tile_selection.js), their requests (tile_requests.js) and their
// place on the GPU (web/render/shading/web_tile_textures.js).
//
// The frame loop calls update(camera, viewport) every frame: it returns at once while the view
// and the terrain's heights are as they were, and chooses tiles at most every selectEveryMs
// (a view still moving when that time is up is chosen for then, and onChange asks for that
// frame). Each tile that arrives calls onChange, so the page draws it.
import { TileSelection } from './tile_selection.js';
import { TileRequests, decodeTileImage } from './tile_requests.js';
import { parseTileSpec } from './tile_template.js';
import { tableRange, terrainBounds } from './table_range.js';
import { tileKey } from './tile_key.js';
import { WebTileTextures, DEFAULT_MEMORY_BYTES, DEFAULT_TILE_SIZE } from '../render/shading/web_tile_textures.js';

const SELECT_EVERY_MS = 100;

/** Resizes a decoded tile to size² texels in the page (a service whose tiles are not all one size). */
const resizeTileImage = async (image, size) => {
  const resized = await createImageBitmap(image, { resizeWidth: size, resizeHeight: size, resizeQuality: 'high', premultiplyAlpha: 'none' });
  image.close?.();
  return resized;
};

/**
 * @typedef {object} WebTileLayerOptions
 * @property {(x: number, z: number) => ArrayLike<number>} toMercator ground metres of the terrain
 *   (x east of the first column, z south of the first row) -> Web Mercator world [x, y], 0..1, y down
 * @property {{ extentX: number, extentZ: number, low: number, high: number }} terrain the terrain in
 *   drawn metres (the cameras' world: heights times the exaggeration), read at every update
 * @property {() => void} [onChange] asks the page for a frame (a tile arrived, a selection is due)
 * @property {(message: string, fault: import('./tile_requests.js').TileFault) => void} [onMessage]
 *   the first fault of each kind, for the status line
 * @property {typeof fetch} [fetch]
 * @property {(blob: Blob) => Promise<ImageBitmap>} [decode]
 * @property {(image: ImageBitmap, size: number) => Promise<ImageBitmap>} [resize]
 * @property {number} [memoryBytes] GPU memory cap of the tiles, mipmaps included (64 MB)
 * @property {number} [concurrency] requests in flight at most (6)
 * @property {number} [selectEveryMs] least time between two selections (100)
 * @property {((x0: number, z0: number, x1: number, z1: number, out: number[]) => number[])|null} [heightRange]
 *   drawn heights [low, high] over a ground rectangle (tile_selection.js): tighter culling
 * @property {() => number} [now] milliseconds
 */

export class WebTileLayer {
  /**
   * @param {WebGL2RenderingContext} gl
   * @param {string|import('./tile_template.js').TileLayerSpec} spec the page's `tiles=` value, or a parsed layer
   * @param {WebTileLayerOptions} options
   * @throws {import('./tile_template.js').TileSpecError} for a spec that cannot be used
   */
  constructor(gl, spec, { toMercator, terrain, onChange = () => {}, onMessage = () => {}, fetch, decode = decodeTileImage,
    resize = resizeTileImage, memoryBytes = DEFAULT_MEMORY_BYTES, concurrency = 6, selectEveryMs = SELECT_EVERY_MS,
    heightRange = null, now = () => performance.now() } = {}) {
    this.gl = gl;
    this.spec = typeof spec === 'string' ? parseTileSpec(spec) : spec;
    this.onChange = onChange;
    this.now = now;
    this.selectEveryMs = selectEveryMs;
    this.resize = resize;
    this.textures = new WebTileTextures(gl, { memoryBytes });
    // Until the first tile tells the tile size, the wanted tiles are limited for 256² tiles.
    const guess = Math.floor(memoryBytes / ((DEFAULT_TILE_SIZE * DEFAULT_TILE_SIZE * 4 * 4) / 3));
    this.selection = new TileSelection({ maxTiles: Math.max(8, guess - 2) });
    this.requests = new TileRequests(this.spec, {
      onTile: (z, x, y, image) => this.arrive(z, x, y, image),
      onMessage: (fault) => onMessage(fault.message, fault),
      fetch, decode, concurrency, now,
    });
    this.lastMatrix = new Float64Array(16).fill(NaN);
    this.lastKey = new Float64Array(4); // viewport height, the terrain's low and high, fov
    this.lastSelect = -Infinity;
    this.dirty = true;
    this.timer = null;
    this.wanted = [];      // the last wanted list: the selection with failed tiles replaced by their ancestors
    this.wantedPool = [];
    this.wantedKeys = new Set();
    this.refused = new Set(); // tiles the GPU did not keep (every page needed): not asked for again until the next selection
    this.isThere = (k) => this.textures.has(k) || this.refused.has(k);
    this.shownFigures = { resident: 0, bytes: 0, residentBytes: 0, evictions: 0, fetched: 0, bytesFetched: 0, failed: 0, aborted: 0,
      inFlight: 0, wanted: 0, baseZoom: -1, tableZoom: -1 };
    this.view = { heightRange, position: null, viewProjection: null, viewportHeight: 0, fovY: 0, terrain: null, toMercator: null,
      bounds: null, tileSize: DEFAULT_TILE_SIZE, minZoom: 0, maxZoom: 0 };
    this.setTerrain(terrain, toMercator);
  }

  /** The credit to show while the layer is drawn ('' when the spec gives none). */
  get attribution() {
    return this.spec.attribution;
  }

  /** The tile table the shader reads: { zoom, x0, y0, width, height } (see web_tile_textures.js). */
  get table() {
    return this.textures.range;
  }

  /** True once a tile is on the GPU. */
  get ready() {
    return this.textures.ready;
  }

  /**
   * A new terrain (or a new placement of it): the tile table follows its extent; the tiles
   * already on the GPU stay where they still apply.
   */
  setTerrain(terrain, toMercator) {
    this.terrain = terrain;
    this.toMercator = toMercator;
    this.bounds = terrainBounds(terrain.extentX, terrain.extentZ, toMercator);
    this.textures.setRange(tableRange(this.bounds, this.spec.maxZoom));
    this.dirty = true;
  }

  /**
   * Called every frame. Cheap when nothing changed; chooses the tiles the view needs (at most
   * every selectEveryMs) and asks for those missing.
   * @param {{ position: ArrayLike<number>, viewProjection: ArrayLike<number>, fovY: number }} camera drawn metres
   * @param {{ height: number }} viewport device pixels
   * @returns {boolean} whether it chose tiles
   */
  update(camera, viewport) {
    // The flat camera's matrix (on_the_earth.js): the tiles are chosen over the flat field.
    const m = camera.flatViewProjection ?? camera.viewProjection, last = this.lastMatrix, key = this.lastKey;
    let changed = this.dirty || key[0] !== viewport.height || key[1] !== this.terrain.low || key[2] !== this.terrain.high || key[3] !== camera.fovY;
    for (let i = 0; i < 16 && !changed; i++) changed = last[i] !== m[i];
    if (!changed) return false;
    const now = this.now(), wait = this.lastSelect + this.selectEveryMs - now;
    if (wait > 0) {
      this.dirty = true;
      if (this.timer === null) {
        this.timer = setTimeout(() => { this.timer = null; this.onChange(); }, wait + 1);
        this.timer.unref?.();
      }
      return false;
    }
    for (let i = 0; i < 16; i++) last[i] = m[i];
    key[0] = viewport.height; key[1] = this.terrain.low; key[2] = this.terrain.high; key[3] = camera.fovY;
    this.lastSelect = now;
    this.dirty = false;
    this.select(camera, viewport);
    return true;
  }

  select(camera, viewport) {
    const v = this.view, table = this.textures.range;
    v.position = camera.position; v.viewProjection = camera.flatViewProjection ?? camera.viewProjection; v.fovY = camera.fovY;
    v.viewportHeight = viewport.height; v.terrain = this.terrain; v.toMercator = this.toMercator; v.bounds = this.bounds;
    v.tileSize = this.textures.tileSize || DEFAULT_TILE_SIZE;
    v.minZoom = Math.min(this.spec.minZoom, table.zoom);
    v.maxZoom = Math.min(this.spec.maxZoom, table.zoom);
    const tiles = this.selection.select(v);
    this.wantInstead(tiles, v.minZoom);
    this.textures.markWanted(this.wanted);
    this.refused.clear();
    this.requests.want(this.wanted, this.isThere);
  }

  /** this.wanted: the selection, with a tile that failed replaced by its nearest ancestor that has not. */
  wantInstead(tiles, minZoom) {
    const out = this.wanted, keys = this.wantedKeys;
    keys.clear();
    let count = 0;
    for (let i = 0; i < tiles.length; i++) {
      let { z, x, y, key } = tiles[i];
      while (this.requests.isFailed(key) && z > minZoom) {
        z--; x >>= 1; y >>= 1;
        key = tileKey(z, x, y);
      }
      if (keys.has(key)) continue;
      keys.add(key);
      if (count === this.wantedPool.length) this.wantedPool.push({ z: 0, x: 0, y: 0, key: 0, distance: 0, base: false });
      const r = this.wantedPool[count];
      r.z = z; r.x = x; r.y = y; r.key = key; r.distance = tiles[i].distance; r.base = tiles[i].base;
      out[count++] = r;
    }
    out.length = count;
  }

  arrive(z, x, y, image) {
    const textures = this.textures;
    if (this.gl.isContextLost?.()) { image.close?.(); return; } // asked for again once the context is back
    const size = textures.tileSize;
    if (size && (image.width !== size || image.height !== size)) {
      this.resize(image, size).then((resized) => this.arrive(z, x, y, resized), () => {});
      return;
    }
    const first = !textures.ready;
    const kept = textures.put(z, x, y, image);
    image.close?.();
    if (first && textures.ready) this.selection.maxTiles = Math.max(8, textures.capacity - 2);
    if (!kept) {
      this.refused.add(tileKey(z, x, y));
      return;
    }
    // The stand-ins and pins follow what is there now.
    this.textures.markWanted(this.wanted);
    this.onChange();
  }

  /**
   * Whether the tiles of the last selection are all there (on the GPU, refused by it, or
   * failed) and nothing is in flight: a deterministic flight draws a frame only then, so its
   * pixels do not depend on how fast the server answered.
   */
  get settled() {
    if (this.dirty || this.requests.pending > 0) return false;
    for (let i = 0; i < this.wanted.length; i++) {
      const key = this.wanted[i].key;
      if (!this.textures.has(key) && !this.refused.has(key) && !this.requests.isFailed(key)) return false;
    }
    return true;
  }

  /**
   * What the layer holds and has fetched: tiles and bytes on the GPU, tiles and bytes fetched,
   * evictions, requests in flight, tiles wanted and failed. The same object each call, brought
   * up to date (a HUD may read it every frame).
   */
  get figures() {
    const f = this.shownFigures, t = this.textures.figures, r = this.requests.figures;
    f.resident = t.resident; f.bytes = t.bytes; f.residentBytes = t.residentBytes; f.evictions = t.evictions;
    f.fetched = r.fetched; f.bytesFetched = r.bytes; f.failed = r.failed; f.aborted = r.aborted;
    f.inFlight = this.requests.pending; f.wanted = this.wanted.length; f.baseZoom = this.selection.baseZoom;
    f.tableZoom = this.textures.range?.zoom ?? -1;
    return f;
  }

  /** The context came back: the tiles are fetched again as the view wants them. */
  forgetGl() {
    this.textures.forgetGl();
    this.dirty = true;
  }

  /** Requests stop, GPU objects go. */
  dispose() {
    this.requests.dispose();
    this.textures.dispose();
    if (this.timer !== null) clearTimeout(this.timer);
    this.timer = null;
  }
}
