// Decoded tiles of a tiled terrain, least recently used first out, within a byte cap. The
// tiles the drawn mesh still uses are pinned by the caller and never evicted; the keys evicted
// are kept until the caller takes them, so it can tell the core to drop the same tiles.

/** 512 MiB of samples. */
export const DEFAULT_CAP_BYTES = 512 * 1024 * 1024;

const AXIS = 2 ** 21; // tile columns and rows below 2^21, levels below 2^11: keys stay exact doubles

/**
 * One number for a tile, so per-frame lookups make no strings.
 * @param {number} level 0 is the full resolution
 * @param {number} tx tile column, 0..2^21-1
 * @param {number} ty tile row, 0..2^21-1
 * @returns {number} a non-negative integer, equal for equal tiles
 */
export function tileKey(level, tx, ty) {
  return (level * AXIS + ty) * AXIS + tx;
}

/** @param {number} key from tileKey @returns {number} */
export const keyLevel = (key) => Math.floor(key / (AXIS * AXIS));
/** @param {number} key from tileKey @returns {number} */
export const keyTx = (key) => key % AXIS;
/** @param {number} key from tileKey @returns {number} */
export const keyTy = (key) => Math.floor(key / AXIS) % AXIS;

/** @typedef {Int16Array|Uint16Array|Uint8Array|Float32Array} TileSamples */

export class TileCache {
  /** @param {{ capBytes?: number }} [options] capBytes: most sample bytes held (pinned tiles may exceed it) */
  constructor({ capBytes = DEFAULT_CAP_BYTES } = {}) {
    /** @type {Map<number, TileSamples>} oldest use first (a use moves a key to the end) */
    this._tiles = new Map();
    this._pinned = new Set();
    this._evicted = new Set(); // evicted since the last takeEvicted
    this._taken = [];
    this._bytes = 0;
    this._cap = checkCap(capBytes);
    /** get() calls that found their tile */
    this.hits = 0;
    /** get() calls that did not */
    this.misses = 0;
    /** tiles evicted so far */
    this.evictions = 0;
  }

  /** Sample bytes held, pinned ones included. */
  get bytes() {
    return this._bytes;
  }

  /** Tiles held. */
  get size() {
    return this._tiles.size;
  }

  /** The cap in bytes of samples; setting a smaller one evicts down to it at once (pinned tiles stay). */
  get capBytes() {
    return this._cap;
  }

  set capBytes(bytes) {
    this._cap = checkCap(bytes);
    this._evictToCap();
  }

  /**
   * Holds a tile as the most recently used, replacing one of the same key; then evicts the
   * least recently used unpinned tiles while over the cap (possibly this one, if the cap is
   * smaller than the pinned tiles and it together).
   * @param {number} level
   * @param {number} tx
   * @param {number} ty
   * @param {TileSamples} samples kept, not copied
   * @returns {number} tiles evicted by this call (their keys wait in takeEvicted)
   */
  put(level, tx, ty, samples) {
    const key = tileKey(level, tx, ty);
    const old = this._tiles.get(key);
    if (old) {
      this._bytes -= old.byteLength;
      this._tiles.delete(key);
    }
    this._evicted.delete(key); // back before the caller heard it left: nothing to drop
    this._tiles.set(key, samples);
    this._bytes += samples.byteLength;
    return this._evictToCap();
  }

  /**
   * A tile's samples, marked as just used, or undefined; counted as a hit or a miss.
   * @returns {TileSamples|undefined}
   */
  get(level, tx, ty) {
    const key = tileKey(level, tx, ty);
    const samples = this._tiles.get(key);
    if (samples === undefined) {
      this.misses++;
      return undefined;
    }
    this.hits++;
    this._tiles.delete(key);
    this._tiles.set(key, samples);
    return samples;
  }

  /** Whether a tile is held; does not mark it used nor count. */
  has(level, tx, ty) {
    return this._tiles.has(tileKey(level, tx, ty));
  }

  /** @param {number} key from tileKey @returns {boolean} */
  hasKey(key) {
    return this._tiles.has(key);
  }

  /** @param {number} key from tileKey @returns {TileSamples|undefined} without marking it used or counting */
  peekKey(key) {
    return this._tiles.get(key);
  }

  /**
   * Marks a held tile as just used without counting a hit (a tile the view wants again).
   * @param {number} key from tileKey
   * @returns {boolean} whether it is held
   */
  touchKey(key) {
    const samples = this._tiles.get(key);
    if (samples === undefined) return false;
    this._tiles.delete(key);
    this._tiles.set(key, samples);
    return true;
  }

  /**
   * The tile's samples were handed to their owner (the core copied them): the cache keeps only
   * their size, so the cap still counts them, and lets the array go. Its place in the LRU order
   * stays. False when the tile is not held.
   * @param {number} key from tileKey
   */
  handOver(key) {
    const samples = this._tiles.get(key);
    if (samples === undefined) return false;
    this._tiles.set(key, { byteLength: samples.byteLength });
    return true;
  }

  /**
   * Replaces the pinned set: the tiles the drawn mesh still uses, never evicted while pinned.
   * Tiles unpinned may be evicted at once if the cache is over its cap.
   * @param {Iterable<number>} keys from tileKey (copied; held or not)
   * @returns {number} tiles evicted by this call
   */
  setPinned(keys) {
    this._pinned.clear();
    for (const key of keys) this._pinned.add(key);
    return this._evictToCap();
  }

  /** @param {number} key from tileKey @returns {boolean} */
  isPinned(key) {
    return this._pinned.has(key);
  }

  /**
   * The keys evicted since the last call, oldest first, for the caller to drop from the core.
   * A key evicted and then put again before this call is not among them.
   * @returns {number[]} owned by the cache and reused: valid until the next call
   */
  takeEvicted() {
    const out = this._taken;
    out.length = 0;
    for (const key of this._evicted) out.push(key);
    this._evicted.clear();
    return out;
  }

  /** Removes every tile (pins stay), as evictions. @returns {number} tiles removed */
  clear() {
    const count = this._tiles.size;
    for (const key of this._tiles.keys()) this._evicted.add(key);
    this.evictions += count;
    this._tiles.clear();
    this._bytes = 0;
    return count;
  }

  _evictToCap() {
    if (this._bytes <= this._cap) return 0;
    let count = 0;
    for (const [key, samples] of this._tiles) {
      if (this._pinned.has(key)) continue;
      this._tiles.delete(key); // deleting the current entry keeps a Map iteration valid
      this._bytes -= samples.byteLength;
      this._evicted.add(key);
      count++;
      if (this._bytes <= this._cap) break;
    }
    this.evictions += count;
    return count;
  }
}

function checkCap(bytes) {
  if (!(bytes >= 0)) throw new RangeError(`a tile cache cap must be a byte count >= 0, not ${bytes}`);
  return bytes;
}
