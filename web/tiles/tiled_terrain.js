// A terrain read tile by tile from a Cloud-Optimized GeoTIFF: the core's tiled terrain (hexlod_terrain_
// create_tiled) fed tile by tile. At open, the coarsest level is read whole, so the first frame
// draws from the overviews; then, once per frame, the tiles the core asks for (most needed
// first) are fetched, a few at a time, and handed to the core between frames. The core owns the
// tiles it holds: it lets them go itself past the cap given here (lod/tile_residency.h). Runs in
// the browser (tiles decoded in workers) and in Node (decoded in the main thread).
import { TileFetcher } from './tile_fetcher.js';
import { TileError } from './tile_error.js';
import { MAKE_COG } from './cog_source.js';
import { guessSpacing } from '../loaders/terrain_source.js';
import { resolveGeoref } from '../geo/index.js';

const BYTES = { u8: 1, u16: 2, i16: 2, f32: 4 };
const MB = 2 ** 20;
/** The default cap of the samples held in tiles past the coarsest level: 512 MiB. */
export const DEFAULT_CAP_BYTES = 512 * MB;

/**
 * Bytes of samples of every tile of one level.
 * @param {import('./cog_source.js').CogLevel} level
 */
export function levelBytes(level, sampleType) {
  return level.tilesAcross * level.tilesDown * level.tileWidth * level.tileHeight * BYTES[sampleType];
}

/**
 * Opens a tiled terrain: the core's tiled terrain over `source`'s levels, with the coarsest
 * level in, scaled and prepared (no mesh yet: the caller makes it, as for any terrain).
 * @param {import('../core/core.js').HexlodCore} core
 * @param {import('./cog_source.js').CogSource | import('./worker_tile_reader.js').WorkerTileReader} source
 * @param {{ capBytes?: number, concurrency?: number, signal?: AbortSignal, spacing?: {x: number, y: number},
 *   guessSpacing?: boolean, onProgress?: (fraction: number, phase: string) => void }} [options]
 *   capBytes: most bytes of samples the core holds in tiles past the coarsest level (default
 *   512 MiB); spacing: metres between
 *   columns and rows instead of the file's; guessSpacing: as loadTerrain (terrain_source.js)
 * @returns {Promise<{terrain: import('../core/core.js').Terrain, field: object, missing: number,
 *   loadMs: number, tiles: TiledTerrain}>} the shape loadTerrain returns, plus the tiles
 * @throws {TileError} 'too-big' when even the coarsest level does not fit the cap (a TIFF
 *   without overviews: the message says how to make them), or the reader's kinds
 */
export async function openTiledTerrain(core, source, options = {}) {
  const start = performance.now();
  const capBytes = options.capBytes ?? DEFAULT_CAP_BYTES;
  const { levels, sampleType } = source;
  const coarsest = levels.length - 1, top = levels[coarsest];
  const topBytes = levelBytes(top, sampleType);
  if (topBytes > capBytes) {
    throw new TileError('too-big', `${source.name}: ${levels[0].width}x${levels[0].height} samples ` +
      `(${Math.round(levelBytes(levels[0], sampleType) / MB)} MB) and its coarsest level alone needs ` +
      `${Math.round(topBytes / MB)} MB, more than the ${Math.round(capBytes / MB)} MB tile cache: ` +
      `give it overviews (${MAKE_COG}) to stream it`);
  }
  const terrain = core.createTiledTerrain(levels, sampleType);
  try {
    // The coarsest level, whole: what the first frame draws.
    const overview = [];
    for (let ty = 0; ty < top.tilesDown; ty++) for (let tx = 0; tx < top.tilesAcross; tx++) overview.push([tx, ty]);
    let done = 0, next = 0;
    const worker = async () => {
      while (next < overview.length) {
        const [tx, ty] = overview[next++];
        const samples = await source.readTile(coarsest, tx, ty, options.signal);
        terrain.tileBuffer(coarsest, tx, ty).set(samples);
        terrain.commitTile(coarsest, tx, ty);
        options.onProgress?.(++done / overview.length, 'overview');
      }
    };
    await Promise.all(Array.from({ length: Math.min(options.concurrency ?? 6, overview.length) }, worker));

    const field = {
      source: source.name, format: 'cog', width: source.width, height: source.height, sampleType,
      nodata: source.nodata, heightScale: source.heightScale ?? 1, heightOffset: source.heightOffset ?? 0, georef: await resolveGeoref(source.georef), tiled: true,
      spacingX: source.spacingX ?? 1, spacingY: source.spacingY ?? 1, spacingFromFile: source.spacingX != null,
      levels: levels.length, tileWidth: source.tileWidth, tileHeight: source.tileHeight, fileBytes: source.size,
    };
    const scale = options.spacing ? { ...field, spacingX: options.spacing.x, spacingY: options.spacing.y } : field;
    terrain.setScale(scale);
    terrain.prepare();
    if (options.guessSpacing && !field.spacingFromFile && !options.spacing) guessSpacing(terrain, field);
    if (source.statistics) { // raw values: in metres through the scale, which may be negative
      const ends = [source.statistics.min, source.statistics.max].map((raw) => raw * field.heightScale + field.heightOffset);
      terrain.declareHeightRange(Math.min(...ends), Math.max(...ends));
    }
    const tiles = new TiledTerrain(terrain, source, { concurrency: options.concurrency });
    tiles.setCapBytes(capBytes);
    return { terrain, field, missing: 0, loadMs: performance.now() - start, tiles };
  } catch (error) {
    terrain.destroy();
    throw error;
  }
}

/** The per-frame exchange between the core and the fetcher, and its figures for the HUD. */
export class TiledTerrain {
  constructor(terrain, source, { concurrency }) {
    this.terrain = terrain;
    this.source = source;
    this.fetcher = new TileFetcher(source, { concurrency });
    /** tiles handed to the core so far, and the last failures (for the HUD) */
    this.tilesIn = 0;
    this.failures = [];
    this.closed = false;
  }

  /**
   * One frame's exchange, after the frame's LOD update: what arrived goes in (its heights change
   * at the end of the next frame's stream step), then what the core still asks for goes to the
   * fetcher (a tile just handed in is no longer asked for). Returns how many tiles went in.
   */
  tick() {
    if (this.closed) return 0;
    const { terrain, fetcher } = this;
    let arrived = 0;
    for (const tile of fetcher.takeArrived()) {
      terrain.tileBuffer(tile.level, tile.tx, tile.ty).set(tile.samples);
      terrain.commitTile(tile.level, tile.tx, tile.ty);
      arrived++;
    }
    fetcher.want(terrain.tileWants());
    this.tilesIn += arrived;
    const failed = fetcher.takeFailures();
    if (failed.length > 0) this.failures = failed.map(({ level, tx, ty, kind, message }) => ({ level, tx, ty, kind, message }));
    return arrived;
  }

  /** Tiles the view waits for (wanted, not in, not failed). */
  get waiting() {
    return this.fetcher.waiting;
  }

  /** Bytes fetched so far (headers and tiles), and the file's size when known. */
  get bytesFetched() {
    return this.fetcher.bytesFetched;
  }

  get fileBytes() {
    return this.source.size ?? null;
  }

  /** Bytes of samples the core holds in tiles past the coarsest level, as of the last frame. */
  get heldBytes() {
    return this.terrain.stats.tileBytes;
  }

  /** Tiles the core let go so far to stay within its cap, as of the last frame. */
  get tilesEvicted() {
    return this.terrain.stats.tilesEvicted;
  }

  /** The cap, bytes of samples in tiles past the coarsest level. */
  get capBytes() {
    return this.capBytesSet;
  }

  /** A smaller cap lets tiles go at the next frame's stream step. */
  setCapBytes(bytes) {
    this.terrain.setTileCap(bytes);
    this.capBytesSet = bytes;
  }

  /** Stops every request; the terrain stays as it is. */
  close() {
    this.closed = true;
    this.fetcher.close();
    this.source.close?.();
  }
}
