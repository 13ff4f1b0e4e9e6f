// The tile cache (web/tiles/tile_cache.js): least recently used out first, within its byte
// cap, pinned tiles never out, and every evicted key handed to the caller once.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { TileCache, DEFAULT_CAP_BYTES, tileKey, keyLevel, keyTx, keyTy } from '../../web/tiles/tile_cache.js';

const tile = (bytes) => new Uint8Array(bytes);
const keys = (...tiles) => tiles.map(([level, tx, ty]) => tileKey(level, tx, ty));

test('tile keys are distinct per tile and give their level, column and row back', () => {
  const seen = new Set();
  for (const level of [0, 1, 7, 2047]) {
    for (const [tx, ty] of [[0, 0], [1, 0], [0, 1], [2 ** 21 - 1, 5], [3, 2 ** 21 - 1]]) {
      const key = tileKey(level, tx, ty);
      assert.ok(Number.isSafeInteger(key));
      assert.deepEqual([keyLevel(key), keyTx(key), keyTy(key)], [level, tx, ty]);
      seen.add(key);
    }
  }
  assert.equal(seen.size, 20);
});

test('the least recently used tile goes first; get marks a tile used, has does not', () => {
  const cache = new TileCache({ capBytes: 300 });
  assert.equal(cache.capBytes, 300);
  assert.equal(new TileCache().capBytes, DEFAULT_CAP_BYTES);
  cache.put(0, 0, 0, tile(100));
  cache.put(0, 1, 0, tile(100));
  cache.put(0, 2, 0, tile(100));
  assert.equal(cache.bytes, 300);
  assert.ok(cache.get(0, 0, 0)); // (0, 0) now the most recent: (1, 0) is the oldest
  assert.ok(cache.has(0, 1, 0)); // not a use
  assert.equal(cache.put(0, 3, 0, tile(100)), 1);
  assert.deepEqual(cache.takeEvicted(), keys([0, 1, 0]));
  assert.equal(cache.has(0, 1, 0), false);
  assert.equal(cache.put(0, 4, 0, tile(100)), 1);
  assert.deepEqual(cache.takeEvicted(), keys([0, 2, 0]));
  assert.equal(cache.put(0, 5, 0, tile(100)), 1);
  assert.deepEqual(cache.takeEvicted(), keys([0, 0, 0]));
  assert.deepEqual(cache.takeEvicted(), [], 'each key is handed over once');
  assert.equal(cache.get(0, 9, 9), undefined);
  assert.deepEqual([cache.hits, cache.misses, cache.evictions], [1, 1, 3]);
  assert.equal(cache.bytes, 300);
});

test('pinned tiles are never evicted, even past the cap; unpinning lets them go', () => {
  const cache = new TileCache({ capBytes: 250 });
  cache.setPinned(keys([0, 0, 0], [0, 1, 0]));
  cache.put(0, 0, 0, tile(100));
  cache.put(0, 1, 0, tile(100));
  cache.put(0, 2, 0, tile(100)); // over: the only unpinned tile, though the newest, goes
  assert.deepEqual(cache.takeEvicted(), keys([0, 2, 0]));
  cache.put(0, 3, 0, tile(100));
  cache.put(0, 4, 0, tile(20));
  assert.deepEqual(cache.takeEvicted(), keys([0, 3, 0]));
  assert.ok(cache.has(0, 0, 0) && cache.has(0, 1, 0) && cache.has(0, 4, 0));
  assert.equal(cache.bytes, 220);

  cache.setPinned(keys([0, 1, 0], [0, 4, 0]));
  cache.capBytes = 120; // a smaller cap evicts at once, the oldest unpinned first
  assert.deepEqual(cache.takeEvicted(), keys([0, 0, 0]));
  assert.equal(cache.bytes, 120);
  cache.capBytes = 0;
  assert.deepEqual(cache.takeEvicted(), [], 'all that is left is pinned');
  assert.equal(cache.bytes, 120);
  assert.equal(cache.setPinned([]), 2);
  assert.deepEqual(cache.takeEvicted(), keys([0, 1, 0], [0, 4, 0]));
  assert.equal(cache.bytes, 0);
  assert.throws(() => { cache.capBytes = -1; }, RangeError);
});

test('a tile evicted and put back before the caller took the evictions is not reported', () => {
  const cache = new TileCache({ capBytes: 100 });
  cache.put(1, 0, 0, tile(100));
  cache.put(1, 1, 0, tile(100));
  cache.put(1, 0, 0, tile(100));
  assert.deepEqual(cache.takeEvicted(), keys([1, 1, 0]));
  // Replacing a tile counts its bytes once.
  cache.put(1, 0, 0, tile(60));
  assert.equal(cache.bytes, 60);
  assert.equal(cache.size, 1);
});
