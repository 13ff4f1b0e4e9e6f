// Fetches the tiles a view needs, most needed first, a few at a time. The frame loop says once
// per frame which tiles it wants; tiles it no longer wants leave the queue, and their requests
// in flight are aborted. Arrived tiles wait for the frame loop to take them, so the core sees
// new tiles only between frames. A tile that fails (after the reader's own retries) is reported
// once and not asked for again until retryFailed(). The fetcher holds no tile once taken: the
// core owns the tiles it holds and lets them go itself (lod/tile_residency.h), and it wants
// only tiles it does not hold.
//
// Each frame:
//   for (const tile of fetcher.takeArrived()) core takes tile.samples
//   fetcher.want(tiles the core wants, with their screen errors)
//   for (const failure of fetcher.takeFailures()) tell the user

const AXIS = 2 ** 21; // tile columns and rows below 2^21, levels below 2^11: keys stay exact doubles

/** One number for a tile, so per-frame lookups make no strings. */
export function tileKey(level, tx, ty) {
  return (level * AXIS + ty) * AXIS + tx;
}

/** @typedef {Int16Array|Uint16Array|Uint8Array|Float32Array} TileSamples */

/**
 * @typedef {object} TileReader what reads tiles: a CogSource (cog_source.js) or a worker pool
 *   (worker_tile_reader.js)
 * @property {(level: number, tx: number, ty: number, signal?: AbortSignal) =>
 *   Promise<TileSamples>} readTile
 * @property {{ requests: number, bytes: number }} [stats] requests made and bytes received
 */

/**
 * @typedef {object} WantedTile
 * @property {number} level
 * @property {number} tx
 * @property {number} ty
 * @property {number} priority how much the view needs it: its screen error in pixels, larger first
 */

/**
 * @typedef {object} ArrivedTile
 * @property {number} level
 * @property {number} tx
 * @property {number} ty
 * @property {number} key tileKey(level, tx, ty)
 * @property {TileSamples} samples tileWidth x tileHeight, row by row
 */

/**
 * @typedef {object} TileFailure
 * @property {number} level
 * @property {number} tx
 * @property {number} ty
 * @property {number} key tileKey(level, tx, ty)
 * @property {string} kind a TileError kind ('http', 'network', 'truncated', 'decode', ...),
 *   'invalid' for a tile the file does not have, 'internal' for anything else
 * @property {string} message for the user
 * @property {unknown} error what the reader threw
 */

const byPriority = (a, b) => b.priority - a.priority;

export class TileFetcher {
  /**
   * @param {TileReader} reader
   * @param {{ concurrency?: number, onError?: (failure: TileFailure) => void, graceFrames?: number }} [options]
   *   concurrency: most requests in flight, aborted ones counted until they end; onError: called once per failed
   *   tile, as it fails (the same records also wait in takeFailures); graceFrames: a request in
   *   flight is aborted once its tile was left out of this many want() calls in a row (0: at
   *   once). The list follows the mesh, which changes as tiles arrive: a tile may leave it for a
   *   few frames and come back, and its bytes would be fetched twice.
   */
  constructor(reader, { concurrency = 6, onError = null, graceFrames = 30 } = {}) {
    if (!(Number.isInteger(concurrency) && concurrency >= 1)) throw new RangeError(`concurrency must be a whole number >= 1, not ${concurrency}`);
    this.reader = reader;
    this.concurrency = concurrency;
    this.onError = onError;
    this.graceFrames = graceFrames;
    this._wanted = new Set(); // keys of the last want()
    this._queue = []; // records of the wanted tiles to fetch, most needed first; reused
    this._pool = []; // queue records, reused across frames
    this._next = 0; // queue[_next..] not yet started
    this._inFlight = new Map(); // key -> job
    this._aborting = 0; // aborted requests not yet ended
    this._failed = new Set();
    this._arrived = []; // arrived and not yet taken
    this._arrivedKeys = new Set(); // their keys
    this._arrivedOut = [];
    this._failures = [];
    this._failuresOut = [];
    this._failedWanted = 0;
    this._closed = false;
    /** tiles delivered so far */
    this.tilesArrived = 0;
    /** sample bytes of the tiles delivered so far */
    this.bytesArrived = 0;
  }

  /**
   * The tiles the view needs now, replacing the last list. Queues those neither arrived, in
   * flight nor failed; drops from the queue and aborts in flight those no longer listed; starts
   * requests up to the concurrency.
   * @param {ArrayLike<WantedTile>} list read during the call only (the caller may reuse it)
   */
  want(list) {
    if (this._closed) return;
    const wanted = this._wanted;
    wanted.clear();
    let queued = 0, failedWanted = 0;
    for (let i = 0; i < list.length; i++) {
      const { level, tx, ty, priority } = list[i];
      const key = tileKey(level, tx, ty);
      if (wanted.has(key)) continue;
      wanted.add(key);
      if (this._arrivedKeys.has(key)) continue;
      if (this._failed.has(key)) { failedWanted++; continue; }
      if (this._inFlight.has(key)) continue;
      let record = this._pool[queued];
      if (!record) record = this._pool[queued] = { key: 0, level: 0, tx: 0, ty: 0, priority: 0 };
      record.key = key; record.level = level; record.tx = tx; record.ty = ty; record.priority = priority;
      queued++;
    }
    this._failedWanted = failedWanted;
    const queue = this._queue;
    queue.length = queued;
    for (let i = 0; i < queued; i++) queue[i] = this._pool[i];
    queue.sort(byPriority);
    this._next = 0;
    for (const [key, job] of this._inFlight) {
      if (wanted.has(key)) job.unwanted = 0;
      else if (++job.unwanted > this.graceFrames) this._abort(key, job);
    }
    this._pump();
  }

  /**
   * The tiles decoded since the last call, in the order they arrived; the fetcher lets them go.
   * @returns {ArrivedTile[]} owned by the fetcher and reused: valid until the next call
   */
  takeArrived() {
    const out = this._arrivedOut;
    this._arrivedOut = this._arrived;
    this._arrived = out;
    this._arrived.length = 0;
    this._arrivedKeys.clear();
    return this._arrivedOut;
  }

  /**
   * The tiles that failed since the last call, one record each.
   * @returns {TileFailure[]} owned by the fetcher and reused: valid until the next call
   */
  takeFailures() {
    const taken = this._failures;
    this._failures = this._failuresOut;
    this._failures.length = 0;
    this._failuresOut = taken;
    return taken;
  }

  /** Forgets the failed tiles, so the next want() asks for them again. */
  retryFailed() {
    this._failed.clear();
    this._failedWanted = 0;
  }

  /** Requests in flight (not those aborted and still ending). */
  get inFlight() {
    return this._inFlight.size;
  }

  /** Wanted tiles not yet requested. */
  get queued() {
    return this._queue.length - this._next;
  }

  /** Wanted tiles still to come (queued or in flight): the HUD's "waiting for N tiles". */
  get waiting() {
    return this.queued + this._inFlight.size;
  }

  /** Wanted tiles that failed and are not asked for until retryFailed(), as of the last want(). */
  get failedWanted() {
    return this._failedWanted;
  }

  /** Tiles that failed and are remembered. */
  get failed() {
    return this._failed.size;
  }

  /** Bytes the reader received so far (headers included), or 0 if it does not count. */
  get bytesFetched() {
    return this.reader.stats?.bytes ?? 0;
  }

  /** Requests the reader made so far (retries included), or 0 if it does not count. */
  get requests() {
    return this.reader.stats?.requests ?? 0;
  }

  /** Aborts every request and forgets the queue; later calls to want() do nothing. */
  close() {
    this._closed = true;
    for (const [key, job] of this._inFlight) this._abort(key, job);
    this._queue.length = 0;
    this._next = 0;
  }

  _abort(key, job) {
    this._inFlight.delete(key);
    job.aborted = true;
    this._aborting++;
    job.controller.abort();
  }

  _pump() {
    const queue = this._queue;
    while (this._next < queue.length && this._inFlight.size + this._aborting < this.concurrency) {
      const record = queue[this._next++];
      // Arrived or started since it was queued (a tile listed twice).
      if (this._inFlight.has(record.key) || this._arrivedKeys.has(record.key) || this._failed.has(record.key)) continue;
      this._start(record);
    }
  }

  _start({ key, level, tx, ty }) {
    const job = { key, level, tx, ty, aborted: false, unwanted: 0, controller: new AbortController() };
    this._inFlight.set(key, job);
    let reading;
    try {
      reading = Promise.resolve(this.reader.readTile(level, tx, ty, job.controller.signal));
    } catch (e) {
      reading = Promise.reject(e);
    }
    reading.then((samples) => this._arrive(job, samples), (error) => this._fail(job, error));
  }

  _ended(job) {
    if (job.aborted) {
      this._aborting--;
      return false;
    }
    this._inFlight.delete(job.key);
    return true;
  }

  _arrive(job, samples) {
    if (this._ended(job)) {
      this._arrivedKeys.add(job.key);
      this._arrived.push({ level: job.level, tx: job.tx, ty: job.ty, key: job.key, samples });
      this.tilesArrived++;
      this.bytesArrived += samples.byteLength;
    }
    if (!this._closed) this._pump();
  }

  _fail(job, error) {
    if (this._ended(job)) {
      this._failed.add(job.key);
      if (this._wanted.has(job.key)) this._failedWanted++;
      const kind = error?.kind ?? (error instanceof RangeError ? 'invalid' : 'internal');
      const failure = { level: job.level, tx: job.tx, ty: job.ty, key: job.key, kind, message: String(error?.message ?? error), error };
      this._failures.push(failure);
      if (this.onError) {
        try {
          this.onError(failure);
        } catch (e) {
          // The caller's bug, not this tile's: shown, and the fetching goes on.
          if (typeof globalThis.reportError === 'function') globalThis.reportError(e);
          else console.error(e);
        }
      }
    }
    if (!this._closed) this._pump();
  }
}
