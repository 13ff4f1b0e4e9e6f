// Which terrains the page reads tile by tile, and opening one: a COG read by a pool of tile workers
// (web/tiles/worker_tile_reader.js) behind the core's tiled terrain (tiled_terrain.js).
// A URL to a TIFF is always tried this way (the page falls back to a whole load when the server
// or the file cannot stream); a dropped TIFF streams only when loading it whole would be worse:
// it has overviews, or its samples would not fit the tile cache.
import { openCog } from '../tiles/cog_source.js';
import { openWorkerPool } from '../tiles/worker_tile_reader.js';
import { openTiledTerrain, levelBytes } from '../tiles/tiled_terrain.js';
import { hasTiffSignature, readDirectory } from '../geo/index.js';
import { MAKE_COG } from '../tiles/cog_source.js';
import { formatMB } from './url_fetch.js';

const TILE_WIDTH = 322; // TIFF tag: a tiled image has it, a striped one not

/** A TIFF by its name. */
export const isTiffName = (name) => /\.tiff?$/i.test(name);

/**
 * Whether a dropped or picked file streams: a tiled TIFF with overviews, or one whose
 * full-resolution samples exceed `capBytes`. `head` is the file's first bytes (already read):
 * a striped TIFF is told from them alone, so other files pay nothing; a tiled one has its
 * directories read by slices (never the whole file).
 * @param {File} file @param {Uint8Array} head @param {number} capBytes
 */
export async function shouldOpenTiled(file, head, capBytes) {
  if (!isTiffName(file.name) || !hasTiffSignature(head)) return false;
  let tiled = null; // unknown when the first directory lies beyond the head
  try {
    tiled = readDirectory(head, (problem) => { throw new Error(problem); }).values(TILE_WIDTH) !== undefined;
  } catch { /* the whole load reports a damaged file */ }
  if (tiled === false || (tiled === null && file.size <= capBytes)) return false;
  try {
    const source = await openCog(file, { name: file.name });
    return source.hasOverviews || levelBytes(source.levels[0], source.sampleType) > capBytes;
  } catch {
    return false; // not a COG after all: loaded whole as before, which says what is wrong with it
  }
}

/**
 * What a ?src= TIFF that could not be opened tile by tile becomes: loaded whole as any URL when
 * the server ignores Range or the file is not tiled, if it fits the tile cache (a file larger
 * than that is what tiles are for); any other failure is the load's end.
 * @param {import('../tiles/tile_error.js').TileError} error why it could not be opened tile by tile
 * @param {string} name @param {number} capBytes the tile cache's cap
 * @returns {{ failed: string } | { whole: { maxBytes: number, advice: string } }} the message of a
 *   failure, or the whole load's size cap and what to say when the file passes it
 */
export function afterTilesFailed(error, name, capBytes) {
  if (error.kind !== 'no-range' && error.kind !== 'not-cog') return { failed: `${name}: cannot stream it (${error.message})` };
  const why = error.kind === 'no-range' ? 'its server ignores Range requests' : 'it is not tiled';
  const advice = `too big to load whole and it cannot stream: ${why}. Make it a Cloud-Optimized GeoTIFF ` +
    `(${MAKE_COG}) served from a host that honours Range requests, or raise the tile cache under Controls › Loading from a URL`;
  if (error.size != null && error.size > capBytes) {
    return { failed: `${name}: ${formatMB(error.size)} MB, more than the ${formatMB(capBytes)} MB tile cache, ${advice}` };
  }
  return { whole: { maxBytes: capBytes, advice } };
}

/**
 * Opens `input` (a URL or a File) as a tiled terrain: the worker pool opens the file, then
 * the coarsest level is read. The pool is closed when anything fails or the signal aborts.
 * @returns {Promise<{terrain, field, missing, loadMs, tiles}>} as openTiledTerrain
 * @throws {import('../tiles/tile_error.js').TileError} the pool's kinds, and 'too-big'
 */
export async function openTiled(core, input, { name, capBytes, signal, onProgress }) {
  const source = await openWorkerPool(input, { name, signal });
  try {
    return await openTiledTerrain(core, source, { capBytes, signal, guessSpacing: true, onProgress });
  } catch (error) {
    source.close();
    throw error;
  }
}
