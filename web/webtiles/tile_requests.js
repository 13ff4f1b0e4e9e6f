// The fetch queue of one web tile layer: at most `concurrency` requests in flight, the most
// wanted first; each want() re-orders what waits, and a request whose tile is no longer wanted
// is aborted. A fetched tile is decoded (createImageBitmap in the page) and handed to onTile.
//
// A tile that fails leaves what is drawn as it is (coarser tiles stand in) and gives the layer's
// user ONE message per kind of fault, not one per tile:
//   http         the server answered with an error status ("HTTP 404 for https://…/7/98/55.png")
//   not-image    the answer is not an image (an HTML error page served as 200)
//   cors         the server answers but does not let this page read its tiles
//   unreachable  no answer: the server is down, or the address is wrong
// A fetch that fails without a status (a TypeError) is one of the last two; a second request
// with mode 'no-cors' tells them apart: it gets an opaque answer when the server is there.
// A failed tile is not asked for again at once: a missing tile (404, 410) or a broken image
// never in this session, others after a delay that doubles each time; after a cors or
// unreachable fault the whole layer waits likewise, so a server that is down is not asked for
// every tile of every view.
import { layerHost, tileUrl } from './tile_template.js';

export const FAULTS = ['http', 'not-image', 'cors', 'unreachable'];
const FIRST_DELAY_MS = 2000;
const MAX_DELAY_MS = 5 * 60 * 1000;

/** Decodes a fetched tile in the page: straight alpha, as the drape blends it. */
export const decodeTileImage = (blob) => createImageBitmap(blob, { premultiplyAlpha: 'none', colorSpaceConversion: 'default' });

/**
 * @typedef {object} TileFault
 * @property {'http'|'not-image'|'cors'|'unreachable'} kind
 * @property {string} message for the status line
 * @property {string} url the tile's address
 * @property {number} status the HTTP status, 0 without one
 */

export class TileRequests {
  /**
   * @param {import('./tile_template.js').TileLayerSpec} layer
   * @param {object} options
   * @param {(z: number, x: number, y: number, image: ImageBitmap) => void} options.onTile a tile arrived (it owns the image)
   * @param {(fault: TileFault) => void} [options.onMessage] the first fault of each kind
   * @param {typeof fetch} [options.fetch]
   * @param {(blob: Blob) => Promise<ImageBitmap>} [options.decode] rejects for what is not an image
   * @param {number} [options.concurrency] requests in flight at most (aborted ones count until they end)
   * @param {() => number} [options.now] milliseconds (the back-off's clock)
   * @param {number} [options.firstDelayMs] the first wait after a fault that may pass
   */
  constructor(layer, { onTile, onMessage = () => {}, fetch: fetchFn = (...a) => globalThis.fetch(...a), decode = decodeTileImage,
    concurrency = 6, now = () => performance.now(), firstDelayMs = FIRST_DELAY_MS } = {}) {
    this.layer = layer;
    this.host = layerHost(layer);
    this.onTile = onTile;
    this.onMessage = onMessage;
    this.fetch = fetchFn;
    this.decode = decode;
    this.concurrency = concurrency;
    this.now = now;
    this.firstDelayMs = firstDelayMs;
    // The wanted list, most wanted first (copied: the caller reuses its array).
    this.wanted = { count: 0, z: new Int32Array(64), x: new Int32Array(64), y: new Int32Array(64), key: new Float64Array(64) };
    this.wantedKeys = new Set();
    this.isResident = () => false;
    this.delivered = new Set();  // tiles handed to onTile since the last want(): never asked for twice in one view
    this.inFlight = new Map();   // key -> AbortController
    this.active = 0;             // requests not yet settled, aborted ones included
    this.failed = new Map();     // key -> { until, delay }: a tile not to ask for before `until` (Infinity: never)
    this.pausedUntil = 0;        // the layer waits after a cors or unreachable fault
    this.pauseMs = 0;
    this.reported = new Set();   // fault kinds already told
    this.faults = [];            // every fault told, in order
    this.timer = null;
    this.disposed = false;
    this.figures = { fetched: 0, bytes: 0, failed: 0, aborted: 0, requested: 0 };
  }

  /**
   * The tiles wanted now, most wanted first: requests start for those neither resident, in
   * flight nor backing off, and those in flight that are not in the list are aborted.
   * @param {ArrayLike<{ z: number, x: number, y: number, key: number }>} tiles
   * @param {(key: number) => boolean} isResident whether a tile is already there
   */
  want(tiles, isResident) {
    const w = this.wanted;
    if (w.key.length < tiles.length) {
      const size = Math.max(tiles.length, 2 * w.key.length);
      w.z = new Int32Array(size); w.x = new Int32Array(size); w.y = new Int32Array(size); w.key = new Float64Array(size);
    }
    this.wantedKeys.clear();
    for (let i = 0; i < tiles.length; i++) {
      const t = tiles[i];
      w.z[i] = t.z; w.x[i] = t.x; w.y[i] = t.y; w.key[i] = t.key;
      this.wantedKeys.add(t.key);
    }
    w.count = tiles.length;
    this.isResident = isResident;
    this.delivered.clear();
    for (const [key, controller] of this.inFlight) {
      if (!this.wantedKeys.has(key)) {
        controller.abort();
        this.inFlight.delete(key);
        this.figures.aborted++;
      }
    }
    this.pump();
  }

  /** Whether a tile failed and waits (or will never be asked for again). */
  isFailed(key) {
    const failure = this.failed.get(key);
    return failure !== undefined && failure.until > this.now();
  }

  /** Requests in flight (aborted ones that have not ended included). */
  get pending() {
    return this.active;
  }

  /** Starts requests while there is room, most wanted first. */
  pump() {
    if (this.disposed) return;
    const now = this.now(), w = this.wanted;
    let wake = Infinity;
    for (let i = 0; i < w.count && this.active < this.concurrency; i++) {
      const key = w.key[i];
      if (this.inFlight.has(key) || this.delivered.has(key) || this.isResident(key)) continue;
      if (now < this.pausedUntil) { wake = this.pausedUntil; break; }
      const failure = this.failed.get(key);
      if (failure && failure.until > now) { wake = Math.min(wake, failure.until); continue; }
      this.start(w.z[i], w.x[i], w.y[i], key);
    }
    // A wait that ends while nothing else happens: come back then (Infinity: a tile never retried).
    if (wake !== Infinity && this.timer === null) {
      this.timer = setTimeout(() => { this.timer = null; this.pump(); }, Math.max(0, wake - now) + 1);
      this.timer.unref?.(); // Node: a wait never keeps a test process alive
    }
  }

  start(z, x, y, key) {
    const controller = new AbortController();
    this.inFlight.set(key, controller);
    this.active++;
    this.figures.requested++;
    const url = tileUrl(this.layer, z, x, y);
    this.request(url, z, x, y, key, controller.signal).finally(() => {
      this.active--;
      if (this.inFlight.get(key) === controller) this.inFlight.delete(key);
      this.pump();
    });
  }

  async request(url, z, x, y, key, signal) {
    let fault = null;
    try {
      const response = await this.fetch(url, { signal, mode: 'cors', credentials: 'omit' });
      if (!response.ok) {
        fault = { kind: 'http', status: response.status, url, message: `HTTP ${response.status} for ${url}` };
      } else {
        const blob = await response.blob();
        this.figures.bytes += blob.size;
        let image;
        try {
          image = await this.decode(blob);
        } catch {
          if (signal.aborted) return;
          const type = response.headers?.get?.('content-type') || blob.type || 'no content type';
          fault = { kind: 'not-image', status: response.status, url, message: `not an image (${type}, ${blob.size} bytes): ${url}` };
        }
        if (image) {
          if (signal.aborted || this.disposed) { image.close?.(); return; }
          this.figures.fetched++;
          this.pauseMs = 0;
          this.failed.delete(key);
          this.delivered.add(key);
          this.onTile(z, x, y, image);
          return;
        }
      }
    } catch (error) {
      if (signal.aborted || error?.name === 'AbortError') return;
      fault = await this.networkFault(url, signal);
      if (!fault) return;
    }
    this.fail(key, fault);
  }

  /** A fetch that failed without a status: a server that refuses cross-origin reads, or none. */
  async networkFault(url, signal) {
    let opaque = false;
    try {
      const probe = await this.fetch(url, { signal, mode: 'no-cors', credentials: 'omit' });
      opaque = probe.type === 'opaque' || probe.ok;
    } catch {
      if (signal.aborted) return null;
    }
    return opaque
      ? { kind: 'cors', status: 0, url, message: `the tile server ${this.host} answers but does not let this page read its tiles ` +
        `(no Access-Control-Allow-Origin header): ${url}` }
      : { kind: 'unreachable', status: 0, url, message: `cannot reach the tile server ${this.host} (it is down, or the address is wrong): ${url}` };
  }

  fail(key, fault) {
    this.figures.failed++;
    const now = this.now();
    const missing = fault.kind === 'not-image' || fault.status === 404 || fault.status === 410;
    const previous = this.failed.get(key);
    const delay = Math.min(MAX_DELAY_MS, previous ? previous.delay * 2 : this.firstDelayMs);
    this.failed.set(key, { until: missing ? Infinity : now + delay, delay });
    if (fault.kind === 'cors' || fault.kind === 'unreachable') {
      this.pauseMs = Math.min(MAX_DELAY_MS, this.pauseMs ? this.pauseMs * 2 : this.firstDelayMs);
      this.pausedUntil = now + this.pauseMs;
    }
    if (!this.reported.has(fault.kind)) {
      this.reported.add(fault.kind);
      this.faults.push(fault);
      this.onMessage(fault);
    }
  }

  /** Every request is aborted and none starts again. */
  dispose() {
    this.disposed = true;
    for (const controller of this.inFlight.values()) controller.abort();
    this.inFlight.clear();
    if (this.timer !== null) clearTimeout(this.timer);
    this.timer = null;
  }
}
