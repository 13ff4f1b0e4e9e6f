// Where a terrain lies in the tile pyramid: its bounds in Web Mercator world coordinates, and
// the tile table the drape shader reads (web/render/shading/web_tile_textures.js): the tiles of
// one zoom Z over those bounds, as fine as a table of at most MAX_TABLE_SIDE² entries allows.
import { MAX_ZOOM } from './web_mercator.js';

/** Entries a side of the tile table: 1024² entries of 4 bytes are 4 MB, and tiles of 1/1024 of the terrain are finer than any view of it needs. */
export const MAX_TABLE_SIDE = 1024;

/**
 * The Web Mercator bounds of a terrain: toMercator along its four edges (a map into Web
 * Mercator bends straight edges, so corners alone can miss the outermost point).
 * @param {number} extentX ground metres east of the first column
 * @param {number} extentZ ground metres south of the first row
 * @param {(x: number, z: number) => number[]} toMercator ground metres -> world [x, y] (0..1, y down)
 * @param {number} [steps] points an edge, minus one
 * @returns {number[]} [west, north, east, south] in world coordinates (west < east, north < south)
 */
export function terrainBounds(extentX, extentZ, toMercator, steps = 16) {
  let west = Infinity, east = -Infinity, north = Infinity, south = -Infinity;
  const add = (x, z) => {
    const m = toMercator(x, z);
    if (!(Number.isFinite(m[0]) && Number.isFinite(m[1]))) return;
    west = Math.min(west, m[0]); east = Math.max(east, m[0]);
    north = Math.min(north, m[1]); south = Math.max(south, m[1]);
  };
  for (let i = 0; i <= steps; i++) {
    const f = i / steps;
    add(f * extentX, 0); add(f * extentX, extentZ); add(0, f * extentZ); add(extentX, f * extentZ);
  }
  if (!(west <= east && north <= south)) throw new RangeError('the terrain has no place in Web Mercator (toMercator gave no finite point)');
  return [Math.max(0, west), Math.max(0, north), Math.min(1, east), Math.min(1, south)];
}

/**
 * The tiles of zoom z over world bounds: columns x0..x0+width-1, rows y0..y0+height-1.
 * @param {number[]} bounds [west, north, east, south], world coordinates
 */
export function tileRangeAt(bounds, z) {
  const n = 2 ** z;
  const x0 = Math.min(n - 1, Math.floor(bounds[0] * n)), y0 = Math.min(n - 1, Math.floor(bounds[1] * n));
  const x1 = Math.max(x0, Math.min(n - 1, Math.ceil(bounds[2] * n) - 1)), y1 = Math.max(y0, Math.min(n - 1, Math.ceil(bounds[3] * n) - 1));
  return { zoom: z, x0, y0, width: x1 - x0 + 1, height: y1 - y0 + 1 };
}

/**
 * The tile table of a terrain: the finest zoom Z <= maxZoom whose tiles over the bounds are at
 * most MAX_TABLE_SIDE a side.
 * @param {number[]} bounds [west, north, east, south], world coordinates
 * @param {number} maxZoom the layer's finest zoom
 * @returns {{ zoom: number, x0: number, y0: number, width: number, height: number }}
 */
export function tableRange(bounds, maxZoom, maxSide = MAX_TABLE_SIDE) {
  let best = tileRangeAt(bounds, 0);
  for (let z = 1; z <= Math.min(maxZoom, MAX_ZOOM); z++) {
    const range = tileRangeAt(bounds, z);
    if (range.width > maxSide || range.height > maxSide) break;
    best = range;
  }
  return best;
}
