// A Cloud-Optimized GeoTIFF named on the command line, streamed instead of read whole: a local
// file is read by slices (fs.openAsBlob), an http(s) URL by Range requests. Only the header,
// the coarsest level and the tiles the refinement asks for are read (web/tiles/tiled_terrain.js).
import { openAsBlob, existsSync, statSync } from 'node:fs';
import { basename, extname } from 'node:path';
import { isUrl, urlFileName } from './dem_source.js';
import { createNodeCore } from './node_core.js';
import { openCog } from '../web/tiles/cog_source.js';
import { TileError } from '../web/tiles/tile_error.js';
import { openTiledTerrain } from '../web/tiles/tiled_terrain.js';

const TIFF = new Set(['.tif', '.tiff']);

/**
 * The COG to stream for one input, or null to read it whole as any file: a path or URL of a
 * TIFF that is tiled, with overviews (a local COG without overviews is read whole, as before).
 * An http(s) URL is always streamed when tiled; one that is not (or a server without Range)
 * fails with the reason, since a command reads URLs by Range only.
 * @param {string} input
 */
export async function openCogInput(input) {
  const url = isUrl(input);
  const name = url ? urlFileName(input) : basename(input);
  if (!TIFF.has(extname(name).toLowerCase())) return null;
  if (!url && !(existsSync(input) && statSync(input).isFile())) return null; // the whole-file path says what is wrong
  let source;
  try {
    source = await openCog(url ? input : await openAsBlob(input), { name });
  } catch (error) {
    if (!url && error instanceof TileError && error.kind === 'not-cog') return null;
    throw error;
  }
  return url || source.hasOverviews ? source : null;
}

/**
 * A tiled terrain for a command: the loadForCommand shape plus `tiles`.
 * @param {import('../web/tiles/cog_source.js').CogSource} source
 * @param {{x: number, y: number}|null} cellSize
 */
export async function tilesForCommand(source, cellSize) {
  const core = await createNodeCore();
  const loaded = await openTiledTerrain(core, source, cellSize ? { spacing: cellSize } : {});
  if (!cellSize && !loaded.field.spacingFromFile) {
    console.error(`hexlod: warning: ${loaded.field.source} has no cell size; using 1 m, set --cell-size`);
  }
  return { core, ...loaded, spacingX: loaded.terrain.spacingX, spacingY: loaded.terrain.spacingY };
}

/**
 * Frames (LOD update and stream step, so that arrived tiles change the heights) until the mesh
 * converged and no tile is awaited, or `maxUpdates`. Waits for tiles in flight between updates.
 * @returns {Promise<{updates: number, converged: boolean}>}
 */
export async function settleTiles(terrain, tiles, maxUpdates, onUpdate = () => {}) {
  let updates = 0, quiet = 0;
  while (updates < maxUpdates && quiet < 2) {
    const figures = terrain.frame(null);
    onUpdate(figures);
    updates++;
    const arrived = tiles.tick();
    const resting = figures.converged && figures.pendingMerges === 0 && tiles.waiting === 0 && arrived === 0;
    quiet = resting ? quiet + 1 : 0;
    if (tiles.waiting > 0 && arrived === 0) await new Promise((resolve) => setTimeout(resolve, 1));
  }
  return { updates, converged: quiet >= 2 };
}
