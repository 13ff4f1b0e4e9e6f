// Which web map tiles a view needs: the tiles whose texels are about one screen pixel where
// they fall on the terrain, only those in view, nearest first; and before them a coarse base
// level covering the whole terrain in a few tiles, so that something is always drawn.
//
// The terrain's extent is cut into a quadtree of ground patches, each a box from the lowest
// to the highest drawn height. A patch outside the view frustum is dropped. For one in view,
// the ground metres a screen pixel spans at its nearest point (Cesium's screen-space measure,
// 2·d·tan(fov/2) / viewport height) and the patch's Mercator scale give the zoom whose texel
// is that size; a patch that would need more than 2 × 2 tiles of that zoom is split, so near
// patches become small and get fine tiles, far ones stay large and coarse.
//
// Runs when the view changes (throttled by its caller), not every frame; it reuses its records
// and arrays between calls.
import { tileKey } from './tile_key.js';
import { tileRangeAt } from './table_range.js';

/** Tiles a side of a patch before it is split. */
const TILES_A_PATCH = 2;
/** Base level: the finest zoom covering the terrain in at most this many tiles. */
export const BASE_TILES = 9;
/** A base level coarser than the layer allows would need more tiles than this: none then. */
const MAX_BASE_TILES = 64;
// Safety limits of the quadtree walk (a split always halves the patch: depth 30 is far below a millimetre).
const MAX_DEPTH = 30;
const MAX_PATCHES = 20000;

/**
 * @typedef {object} WantedTile
 * @property {number} z
 * @property {number} x
 * @property {number} y
 * @property {number} key tileKey(z, x, y)
 * @property {number} distance metres from the eye to the nearest patch that wants it (0 for base tiles)
 * @property {boolean} base a tile of the base level
 */

/**
 * @typedef {object} SelectionView
 * @property {ArrayLike<number>} position the eye, drawn metres [x, y, z] (x east, y up, z south)
 * @property {ArrayLike<number>} viewProjection column-major 4×4 (gl-matrix), clip = M · [x, y, z, 1]
 * @property {number} viewportHeight pixels (device pixels: what a texel should match)
 * @property {number} fovY vertical field of view, radians
 * @property {{ extentX: number, extentZ: number, low: number, high: number }} terrain drawn metres:
 *   x in [0, extentX], z in [0, extentZ], heights (times the exaggeration) in [low, high]
 * @property {(x: number, z: number) => ArrayLike<number>} toMercator ground metres -> world [x, y] (0..1, y down)
 * @property {number[]} bounds the terrain's world bounds [west, north, east, south] (table_range.js terrainBounds)
 * @property {number} tileSize texels a tile side
 * @property {number} minZoom coarsest zoom the layer has
 * @property {number} maxZoom finest zoom wanted: the layer's, and no finer than the tile table's
 * @property {((x0: number, z0: number, x1: number, z1: number, out: number[]) => number[])|null} [heightRange]
 *   the lowest and highest drawn height over a ground rectangle, written into out (e.g. from
 *   the field's min/max pyramid): tighter boxes than the terrain's whole range cull more and
 *   measure distances truer; without it every patch spans terrain.low..terrain.high
 */

export class TileSelection {
  /** @param {{ maxTiles?: number }} [options] maxTiles: most tiles returned (base included), the farthest dropped */
  constructor({ maxTiles = 256 } = {}) {
    this.maxTiles = maxTiles;
    this.tiles = [];        // the result: records of this.pool, base first, then nearest first
    this.pool = [];
    this.count = 0;
    this.byKey = new Map(); // key -> record, during one select
    this.planes = new Float64Array(24);
    this.stack = new Float64Array(5 * 4 * (MAX_DEPTH + 2)); // x0, z0, x1, z1, depth of patches to visit
    this.baseZoom = -1;
    this.patches = 0;       // patches visited by the last select (for tests and figures)
    this.heights = [0, 0];
  }

  /**
   * The tiles `view` needs.
   * @param {SelectionView} view
   * @returns {WantedTile[]} this.tiles (the same array each call, rewritten)
   */
  select(view) {
    this.count = 0;
    this.byKey.clear();
    this.patches = 0;
    const { terrain, minZoom } = view;
    const maxZoom = Math.max(minZoom, view.maxZoom);
    this.addBase(view.bounds, minZoom, maxZoom);
    const base = this.count;
    frustumPlanes(view.viewProjection, this.planes);
    // Metres a pixel spans per metre of distance.
    const pixelPerMetre = (2 * Math.tan(view.fovY / 2)) / view.viewportHeight;
    const ex = view.position[0], ey = view.position[1], ez = view.position[2];
    const stack = this.stack;
    let top = 0;
    const push = (x0, z0, x1, z1, depth) => {
      stack[top++] = x0; stack[top++] = z0; stack[top++] = x1; stack[top++] = z1; stack[top++] = depth;
    };
    push(0, 0, terrain.extentX, terrain.extentZ, 0);
    while (top > 0 && this.patches < MAX_PATCHES) {
      const depth = stack[--top], z1 = stack[--top], x1 = stack[--top], z0 = stack[--top], x0 = stack[--top];
      this.patches++;
      let low = terrain.low, high = terrain.high;
      if (view.heightRange) {
        const h = view.heightRange(x0, z0, x1, z1, this.heights);
        low = h[0]; high = h[1];
      }
      if (!boxInFrustum(this.planes, x0, low, z0, x1, high, z1)) continue;
      // The patch's Mercator box (corners and centre: a patch is small enough for its edges to be straight).
      let west = Infinity, east = -Infinity, north = Infinity, south = -Infinity;
      for (let k = 0; k < 5; k++) {
        const m = view.toMercator(k === 4 ? (x0 + x1) / 2 : k & 1 ? x1 : x0, k === 4 ? (z0 + z1) / 2 : k & 2 ? z1 : z0);
        const mx = m[0], my = m[1];
        if (mx < west) west = mx;
        if (mx > east) east = mx;
        if (my < north) north = my;
        if (my > south) south = my;
      }
      if (!(west <= east && north <= south)) continue; // off the map's domain
      const dx = Math.max(x0 - ex, 0, ex - x1), dy = Math.max(low - ey, 0, ey - high), dz = Math.max(z0 - ez, 0, ez - z1);
      const distance = Math.hypot(dx, dy, dz);
      // World units a ground metre, on this patch (a conformal map: the larger axis).
      const scale = Math.max((east - west) / Math.max(x1 - x0, 1e-9), (south - north) / Math.max(z1 - z0, 1e-9));
      const pixelMetres = distance * pixelPerMetre;
      let z = pixelMetres > 0 && scale > 0 ? Math.round(Math.log2(1 / (scale * view.tileSize * pixelMetres))) : maxZoom;
      z = Math.min(maxZoom, Math.max(minZoom, z));
      const n = 2 ** z;
      // A patch ending on a tile edge does not reach into the tile beyond it.
      const tx0 = Math.min(n - 1, Math.max(0, Math.floor(west * n))), tx1 = Math.max(tx0, Math.min(n - 1, Math.ceil(east * n) - 1));
      const ty0 = Math.min(n - 1, Math.max(0, Math.floor(north * n))), ty1 = Math.max(ty0, Math.min(n - 1, Math.ceil(south * n) - 1));
      if ((tx1 - tx0 >= TILES_A_PATCH || ty1 - ty0 >= TILES_A_PATCH) && depth < MAX_DEPTH) {
        const mx = (x0 + x1) / 2, mz = (z0 + z1) / 2;
        push(x0, z0, mx, mz, depth + 1); push(mx, z0, x1, mz, depth + 1);
        push(x0, mz, mx, z1, depth + 1); push(mx, mz, x1, z1, depth + 1);
        continue;
      }
      for (let ty = ty0; ty <= ty1; ty++) for (let tx = tx0; tx <= tx1; tx++) this.add(z, tx, ty, distance, false);
    }
    const tiles = this.tiles;
    tiles.length = this.count;
    for (let k = 0; k < this.count; k++) tiles[k] = this.pool[k];
    tiles.sort(byNeed);
    if (tiles.length > this.maxTiles) tiles.length = Math.max(this.maxTiles, base);
    this.count = tiles.length;
    return tiles;
  }

  /** The base level: the finest zoom that covers the bounds in at most BASE_TILES tiles. */
  addBase(bounds, minZoom, maxZoom) {
    let zoom = minZoom;
    for (let z = minZoom + 1; z <= maxZoom; z++) {
      const r = tileRangeAt(bounds, z);
      if (r.width * r.height > BASE_TILES) break;
      zoom = z;
    }
    const r = tileRangeAt(bounds, zoom);
    this.baseZoom = r.width * r.height <= MAX_BASE_TILES ? zoom : -1;
    if (this.baseZoom < 0) return;
    for (let y = r.y0; y < r.y0 + r.height; y++) for (let x = r.x0; x < r.x0 + r.width; x++) this.add(zoom, x, y, 0, true);
  }

  add(z, x, y, distance, base) {
    const key = tileKey(z, x, y);
    const known = this.byKey.get(key);
    if (known) {
      if (distance < known.distance && !known.base) known.distance = distance;
      return;
    }
    if (this.count === this.pool.length) this.pool.push({ z: 0, x: 0, y: 0, key: 0, distance: 0, base: false });
    const record = this.pool[this.count++];
    record.z = z; record.x = x; record.y = y; record.key = key; record.distance = distance; record.base = base;
    this.byKey.set(key, record);
  }
}

/** The base level first, then nearest first, finer first at the same distance. */
function byNeed(a, b) {
  if (a.base !== b.base) return a.base ? -1 : 1;
  return a.distance - b.distance || b.z - a.z;
}

/**
 * The six planes (a, b, c, d; inside where a·x + b·y + c·z + d >= 0) of a view-projection
 * matrix's frustum (Gribb and Hartmann's extraction; WebGL's clip z from -w to w).
 */
export function frustumPlanes(m, out) {
  for (let p = 0; p < 6; p++) {
    const row = p >> 1, sign = p & 1 ? -1 : 1;
    for (let c = 0; c < 4; c++) out[4 * p + c] = m[4 * c + 3] + sign * m[4 * c + row];
  }
  return out;
}

/** Whether an axis-aligned box reaches inside every plane (its corner farthest along each plane's normal). */
export function boxInFrustum(planes, x0, y0, z0, x1, y1, z1) {
  for (let p = 0; p < 24; p += 4) {
    const a = planes[p], b = planes[p + 1], c = planes[p + 2];
    if (a * (a > 0 ? x1 : x0) + b * (b > 0 ? y1 : y0) + c * (c > 0 ? z1 : z0) + planes[p + 3] < 0) return false;
  }
  return true;
}
