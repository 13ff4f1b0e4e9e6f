// SRTM .hgt tiles made from the project's real GLOBE DEM (public/terrain/globe_himalaya_2048.png,
// 30" samples of the Himalaya, integer metres): the mosaic tests need adjacent tiles of full
// size (1201 x 1201), and no real SRTM tiles ship in a package we can use. The samples are
// written as they are, not resampled, so the tiles hold 30" data under 3" tile names; what the
// tests check is the stitching. The DEM has 2048 x 2048 samples and a 2 x 2 block of tiles
// 2401 x 2401: the samples beyond it are voids (-32768), as SRTM marks them.
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';

const SIDE = 1201;
const VOID = -32768;
/** The four tiles, north-west first, their names in mixed case as people's files come. */
export const TILE_NAMES = { nw: 'N27E086.hgt', ne: 'n27e087.hgt', sw: 'N26E086.HGT', se: 'N26e087.hgt' };

/**
 * @returns {{ side: number, heights: Int16Array, tiles: Record<'nw'|'ne'|'sw'|'se', { name: string, bytes: Uint8Array }> }}
 *   heights: the 2401 x 2401 field the tiles are cut from (row 0 north), voids included; the
 *   tiles share their edge rows and columns (row and column 1200), as adjacent SRTM tiles do
 */
export function globeHgtTiles() {
  const url = new URL('../public/terrain/globe_himalaya_2048.', import.meta.url);
  const meta = JSON.parse(readFileSync(new URL(`${url.href}json`), 'utf8'));
  const png = decode(readFileSync(new URL(`${url.href}png`)));
  const side = 2 * SIDE - 1;
  const heights = new Int16Array(side * side).fill(VOID);
  for (let y = 0; y < png.height; y++) {
    for (let x = 0; x < png.width; x++) {
      // The PNG's quantum (0.13 m) is below half a metre: rounding gives back GLOBE's integers.
      heights[y * side + x] = Math.round(meta.min + (png.data[y * png.width + x] / 65535) * (meta.max - meta.min));
    }
  }
  const tile = (row0, column0) => {
    const bytes = new Uint8Array(SIDE * SIDE * 2);
    const view = new DataView(bytes.buffer);
    for (let y = 0; y < SIDE; y++) {
      for (let x = 0; x < SIDE; x++) view.setInt16((y * SIDE + x) * 2, heights[(row0 + y) * side + column0 + x], false); // big-endian
    }
    return bytes;
  };
  const edge = SIDE - 1;
  const tiles = {};
  for (const [key, [row0, column0]] of Object.entries({ nw: [0, 0], ne: [0, edge], sw: [edge, 0], se: [edge, edge] })) {
    tiles[key] = { name: TILE_NAMES[key], bytes: tile(row0, column0) };
  }
  return { side, heights, tiles };
}
