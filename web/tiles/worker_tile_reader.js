// Tiles read and decoded by a pool of Web Workers, behind the same readTile as a CogSource, so
// the fetcher works with either. Each worker opens the COG itself (a URL, or a Blob or File,
// which is posted without copying its bytes) and sends decoded samples back by transfer. A read
// goes to the worker with the fewest reads outstanding; an abort is forwarded to the worker, and
// its errors come back as the same TileError kinds as a CogSource's.

import { TileError, checkAborted } from './tile_error.js';
import { errorFromMessage } from './tile_service.js';

/** A module worker of tile_worker.js; Vite bundles it through the URL. */
export function createTileWorker() {
  return new Worker(new URL('./tile_worker.js', import.meta.url), { type: 'module' });
}

/** Workers for a pool when not told: one per spare core, 1 to 4. */
export function defaultWorkerCount() {
  const cores = globalThis.navigator?.hardwareConcurrency ?? 4;
  return Math.max(1, Math.min(4, cores - 1));
}

/**
 * Opens a COG in a pool of workers.
 * @param {string|URL|Blob} input a URL (read with Range requests) or a Blob or File
 * @param {{ workers?: number, retries?: number, backoffMs?: number, name?: string,
 *   signal?: AbortSignal, createWorker?: () => Worker }} [options] workers: pool size (default
 *   defaultWorkerCount()); retries, backoffMs: the workers' readers', see range_reader.js
 *   urlReader; createWorker: makes one worker (default createTileWorker; anything with
 *   postMessage, onmessage, onerror and terminate will do)
 * @returns {Promise<WorkerTileReader>} once every worker has opened the file
 * @throws {TileError} as openCog: kinds 'http', 'network', 'no-range', 'not-cog', 'bad-tiff',
 *   'aborted'; an Error if a worker does not start
 */
export async function openWorkerPool(input, options = {}) {
  const { workers = defaultWorkerCount(), signal, createWorker = createTileWorker } = options;
  if (!(Number.isInteger(workers) && workers >= 1)) throw new RangeError(`a worker pool needs a whole number >= 1 of workers, not ${workers}`);
  const name = options.name ?? (input instanceof Blob ? input.name ?? 'blob' : String(input));
  checkAborted(signal, name);
  const openOptions = { name };
  if (options.retries !== undefined) openOptions.retries = options.retries;
  if (options.backoffMs !== undefined) openOptions.backoffMs = options.backoffMs;
  const pool = [];
  for (let i = 0; i < workers; i++) pool.push(createWorker());

  const stop = () => pool.forEach((worker) => worker.terminate());
  let onAbort;
  try {
    const aborted = new Promise((_, reject) => {
      onAbort = () => reject(new TileError('aborted', `${name}: aborted`, { cause: signal.reason }));
      signal?.addEventListener('abort', onAbort, { once: true });
    });
    const infos = await Promise.race([aborted, Promise.all(pool.map((worker) => opened(worker, input, openOptions)))]);
    return new WorkerTileReader(pool, infos);
  } catch (e) {
    stop();
    throw e;
  } finally {
    signal?.removeEventListener('abort', onAbort);
  }
}

/** One worker's answer to the open message. */
function opened(worker, input, options) {
  return new Promise((resolve, reject) => {
    worker.onmessage = ({ data }) => {
      if (data.type === 'opened') resolve(data.info);
      else if (data.type === 'open-failed') reject(errorFromMessage(data.error));
    };
    worker.onerror = (event) => {
      event?.preventDefault?.();
      reject(new Error(`a tile worker did not start: ${event?.message ?? 'unknown error'}`));
    };
    worker.postMessage({ type: 'open', input, options });
  });
}

/** An open COG read by workers: the fields of a CogSource, and its readTile. */
export class WorkerTileReader {
  constructor(workers, infos) {
    const info = infos[0];
    this.name = info.name;
    /** full-resolution samples */
    this.width = info.width;
    this.height = info.height;
    /** 'i16', 'u16', 'u8' or 'f32' */
    this.sampleType = info.sampleType;
    /** raw value of a missing sample, or null */
    this.nodata = info.nodata;
    /** @type {import('../geo/georef.js').Georef|null} */
    this.georef = info.georef;
    this.statistics = info.statistics ?? null;
    /** metres = raw x heightScale + heightOffset */
    this.heightScale = info.heightScale ?? 1;
    this.heightOffset = info.heightOffset ?? 0;
    /** metres between columns and rows, or nulls */
    this.spacingX = info.spacingX;
    this.spacingY = info.spacingY;
    /** tile size of the full resolution, in samples */
    this.tileWidth = info.tileWidth;
    this.tileHeight = info.tileHeight;
    /** @type {import('./cog_source.js').CogLevel[]} full resolution first, coarser each time */
    this.levels = info.levels;
    this.hasOverviews = info.hasOverviews;
    /** file length in bytes, as the first worker learnt it at open (null if unknown) */
    this.size = info.size;
    /** requests made and body bytes received by all the workers (each opened the file), as of their last answers */
    this.stats = { requests: 0, bytes: 0 };
    this._workers = workers.map((worker, i) => ({ worker, index: i, load: 0, alive: true, stats: infos[i].stats }));
    this._pending = new Map(); // id -> { resolve, reject, signal, onAbort }
    this._nextId = 1;
    this._turn = 0;
    this._closed = false;
    for (const slot of this._workers) {
      slot.worker.onmessage = ({ data }) => this._answer(slot, data);
      slot.worker.onerror = (event) => {
        event?.preventDefault?.();
        this._lost(slot, event?.message ?? 'unknown error');
      };
    }
    this._sumStats();
  }

  /** Workers in the pool, those that died included. */
  get workerCount() {
    return this._workers.length;
  }

  /** Reads outstanding at each worker, cancelled ones until the worker answers them. */
  get loads() {
    return this._workers.map((slot) => slot.load);
  }

  /**
   * One tile's samples, decoded by a worker; as CogSource.readTile.
   * @param {number} level index into levels (0 is the full resolution)
   * @param {number} tx tile column, 0 at the west
   * @param {number} ty tile row, 0 at the north
   * @param {AbortSignal} [signal] aborting rejects at once and cancels the worker's read
   * @returns {Promise<Int16Array|Uint16Array|Uint8Array|Float32Array>} tileWidth x tileHeight samples
   * @throws {TileError} kinds 'http', 'network', 'truncated', 'decode', 'aborted'; a
   *   RangeError for a tile the file does not have; an Error if the worker died
   */
  readTile(level, tx, ty, signal) {
    const where = `${this.name}: tile (${tx}, ${ty}) of level ${level}`;
    try {
      checkAborted(signal, where);
      if (this._closed) throw new TileError('aborted', `${where}: the tile reader was closed`);
    } catch (e) {
      return Promise.reject(e);
    }
    const slot = this._pick();
    if (!slot) return Promise.reject(new Error(`${where}: every tile worker has died`));
    const id = this._nextId++;
    return new Promise((resolve, reject) => {
      const entry = { resolve, reject, signal, onAbort: null, slot };
      if (signal) {
        entry.onAbort = () => {
          this._pending.delete(id);
          slot.worker.postMessage({ type: 'cancel', id });
          reject(new TileError('aborted', `${where}: aborted`, { cause: signal.reason }));
        };
        signal.addEventListener('abort', entry.onAbort, { once: true });
      }
      this._pending.set(id, entry);
      slot.load++;
      slot.worker.postMessage({ type: 'read', id, level, tx, ty });
    });
  }

  /** Ends every worker; reads still pending reject as aborted. */
  close() {
    if (this._closed) return;
    this._closed = true;
    for (const slot of this._workers) {
      slot.alive = false;
      slot.worker.terminate();
    }
    for (const [id, entry] of this._pending) this._settle(id, entry, null, new TileError('aborted', `${this.name}: the tile reader was closed`));
  }

  /** The live worker with the fewest reads outstanding, ties taken in turn. */
  _pick() {
    const count = this._workers.length;
    let best = null;
    for (let k = 0; k < count; k++) {
      const slot = this._workers[(this._turn + k) % count];
      if (slot.alive && (!best || slot.load < best.load)) best = slot;
    }
    if (best) this._turn = (best.index + 1) % count;
    return best;
  }

  _answer(slot, data) {
    if (data.type !== 'tile' && data.type !== 'failed') return;
    slot.load--;
    if (data.stats) {
      slot.stats = data.stats;
      this._sumStats();
    }
    const entry = this._pending.get(data.id);
    if (!entry) return; // cancelled: its caller has had its answer
    if (data.type === 'tile') this._settle(data.id, entry, data.samples, null);
    else this._settle(data.id, entry, null, errorFromMessage(data.error));
  }

  _settle(id, entry, samples, error) {
    this._pending.delete(id);
    if (entry.onAbort) entry.signal.removeEventListener('abort', entry.onAbort);
    if (error) entry.reject(error);
    else entry.resolve(samples);
  }

  /** A worker that died: its reads fail, and no more go to it. */
  _lost(slot, why) {
    slot.alive = false;
    slot.load = 0;
    slot.worker.terminate();
    for (const [id, entry] of this._pending) {
      if (entry.slot === slot) this._settle(id, entry, null, new Error(`${this.name}: a tile worker died (${why})`));
    }
  }

  _sumStats() {
    let requests = 0, bytes = 0;
    for (const slot of this._workers) {
      requests += slot.stats?.requests ?? 0;
      bytes += slot.stats?.bytes ?? 0;
    }
    this.stats.requests = requests;
    this.stats.bytes = bytes;
  }
}
