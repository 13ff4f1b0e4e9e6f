// Streaming tiles the way the frame loop will (web/tiles/tile_fetcher.js): the view's wanted
// tiles are given once a frame against the range server of lib/range_server.js with latency,
// and the fetcher must ask for the most needed first, a few at a time, abort what the view no
// longer needs, fetch nothing twice, hold no tile once it is handed over (the core owns them),
// and report a tile that cannot be had once while the others arrive.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { fromArrayBuffer } from 'geotiff';
import { openCog } from '../../web/tiles/cog_source.js';
import { TileFetcher, tileKey } from '../../web/tiles/tile_fetcher.js';
import { startRangeServer } from '../../lib/range_server.js';

const fixtures = fileURLToPath(new URL('../fixtures/cog/', import.meta.url));
const HIMALAYA = 'himalaya_1024_i16.tif'; // 1024^2 int16, 256^2 tiles; levels of 4x4, 2x2 and 1 tiles
const TILE_BYTES = 256 * 256 * 2;
const FAST_RETRIES = { retries: 2, backoffMs: 5 };
const bytes = new Uint8Array(readFileSync(fixtures + HIMALAYA));
let server, reference, offsets, counts;

before(async () => {
  server = await startRangeServer(fixtures, { latencyMs: 20 });
  reference = await openCog(new Blob([bytes]), { name: HIMALAYA });
  const directory = (await (await fromArrayBuffer(bytes.slice().buffer)).getImage(0)).fileDirectory;
  offsets = Array.from(await directory.loadValue('TileOffsets'));
  counts = Array.from(await directory.loadValue('TileByteCounts'));
});
after(() => server.close());

const url = () => `${server.url}/${HIMALAYA}`;
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
const key = ({ level, tx, ty }) => tileKey(level, tx, ty);
const name = ({ level, tx, ty }) => `${level}:${tx},${ty}`;

/** A reader around a CogSource that records each call, its signal, and how many overlap. */
function watched(source) {
  const reader = {
    stats: source.stats, active: 0, most: 0, started: [], signals: new Map(), outcomes: new Map(),
    async readTile(level, tx, ty, signal) {
      const tile = name({ level, tx, ty });
      reader.started.push(tile);
      reader.signals.set(tile, signal);
      reader.most = Math.max(reader.most, ++reader.active);
      try {
        const samples = await source.readTile(level, tx, ty, signal);
        reader.outcomes.set(tile, 'read');
        return samples;
      } catch (e) {
        reader.outcomes.set(tile, e.kind);
        throw e;
      } finally {
        reader.active--;
      }
    },
  };
  return reader;
}

/**
 * Frames of the frame loop, every 4 ms, until done(arrived, failures) or the time is up: take
 * the arrived tiles (the core now holds them) and the failures, then want what of the list the
 * core does not hold, as the core's wants do.
 */
async function frames(fetcher, list, done, { ms = 3000 } = {}) {
  const arrived = [], failures = [], held = new Set();
  for (const start = Date.now(); ;) {
    fetcher.want(list.filter((tile) => !held.has(key(tile))));
    for (const tile of fetcher.takeArrived()) arrived.push({ ...tile }), held.add(tile.key);
    for (const failure of fetcher.takeFailures()) failures.push({ ...failure });
    if (done(arrived, failures)) return { arrived, failures };
    if (Date.now() - start > ms) assert.fail(`not done after ${ms} ms: ${arrived.length} arrived, ${failures.length} failed`);
    await sleep(4);
  }
}

test('tiles are asked for most needed first, never more than the concurrency at once, and equal the COG\'s own', async () => {
  const reader = watched(await openCog(url()));
  const fetcher = new TileFetcher(reader, { concurrency: 3 });
  // All 16 full-resolution tiles, their priorities in a scrambled order.
  const list = [];
  for (let i = 0; i < 16; i++) list.push({ level: 0, tx: i % 4, ty: i >> 2, priority: (i * 7) % 16 + 0.5 });
  const byNeed = [...list].sort((a, b) => b.priority - a.priority).map(name);
  const before = server.stats(`/${HIMALAYA}`).requests;

  fetcher.want(list);
  assert.equal(fetcher.inFlight, 3);
  assert.equal(fetcher.queued, 13);
  assert.equal(fetcher.waiting, 16);
  const { arrived } = await frames(fetcher, list, (got) => got.length === 16);

  assert.deepEqual(reader.started, byNeed, 'started in order of need, each once though wanted every frame');
  assert.equal(reader.most, 3);
  assert.ok(byNeed.slice(0, 3).includes(name(arrived[0])), `${name(arrived[0])} arrived first`);
  assert.equal(server.stats(`/${HIMALAYA}`).requests - before, 16, 'one request a tile at the server');
  assert.equal(fetcher.waiting, 0);
  assert.equal(fetcher.tilesArrived, 16);
  assert.equal(fetcher.bytesArrived, 16 * TILE_BYTES);
  assert.equal(fetcher.bytesFetched, reader.stats.bytes);
  for (const tile of arrived) {
    assert.ok(tile.samples instanceof Int16Array);
    assert.deepEqual(tile.samples, await reference.readTile(tile.level, tile.tx, tile.ty), `samples of ${name(tile)}`);
  }

  // Wanted again once handed over (the core let it go): the fetcher kept nothing, it asks again.
  const requests = reader.started.length;
  await frames(fetcher, [list[0]], (got) => got.length === 1);
  assert.equal(reader.started.length, requests + 1);
  assert.equal(fetcher.waiting, 0);
});

test('a tile the view stops wanting is aborted in flight (after its grace), or dropped from the queue, and never delivered', async () => {
  const reader = watched(await openCog(url()));
  const fetcher = new TileFetcher(reader, { concurrency: 2, graceFrames: 1 });
  const a = { level: 0, tx: 0, ty: 0, priority: 10 }, b = { level: 0, tx: 1, ty: 0, priority: 9 };
  const c = { level: 0, tx: 2, ty: 0, priority: 5 }, d = { level: 0, tx: 3, ty: 0, priority: 1 };
  fetcher.want([a, b, c, d]);
  assert.deepEqual(reader.started, [name(a), name(b)]);
  assert.equal(fetcher.queued, 2);

  // The view moves on: a and c are no longer needed. c leaves the queue at once; a, in flight,
  // gets one frame's grace (the list may come back to it) and is aborted at the next.
  fetcher.want([b, d]);
  assert.equal(reader.signals.get(name(a)).aborted, false);
  assert.equal(fetcher.queued, 1);
  fetcher.want([b, d]);
  assert.equal(reader.signals.get(name(a)).aborted, true);
  assert.equal(reader.signals.get(name(b)).aborted, false);
  assert.equal(fetcher.inFlight, 1);
  assert.equal(fetcher.queued, 1);
  assert.equal(fetcher.waiting, 2);
  const { arrived, failures } = await frames(fetcher, [b, d], (got) => got.length === 2);
  await sleep(50);
  arrived.push(...fetcher.takeArrived());

  assert.deepEqual(arrived.map(name).sort(), [name(b), name(d)]);
  assert.deepEqual(failures, [], 'an abort is not a failure');
  assert.deepEqual(fetcher.takeFailures(), []);
  assert.equal(reader.outcomes.get(name(a)), 'aborted');
  assert.ok(!reader.started.includes(name(c)), 'the queued tile was never asked for');
  assert.ok(reader.most <= 2, `${reader.most} at once: an aborted request holds its place until it ends`);

  // Wanted again later, it is fetched afresh.
  const again = await frames(fetcher, [a], (got) => got.length === 1);
  assert.deepEqual(again.arrived.map(name), [name(a)]);
});

test('a tile answered 404 is reported once with its kind and status, not asked for again until retryFailed, while the others arrive', async () => {
  const broken = { level: 0, tx: 1, ty: 1 };
  const brokenOffset = offsets[5];
  // Only that tile's range goes to a path the server does not have.
  const fetchOne = (target, init) => fetch(init.headers.Range.startsWith(`bytes=${brokenOffset}-`) ? `${server.url}/missing.tif` : target, init);
  const reader = watched(await openCog(url(), { ...FAST_RETRIES, fetch: fetchOne }));
  const fetcher = new TileFetcher(reader, { concurrency: 2 });
  const list = [{ ...broken, priority: 9 }, { level: 0, tx: 0, ty: 0, priority: 8 },
    { level: 0, tx: 2, ty: 1, priority: 7 }, { level: 1, tx: 0, ty: 0, priority: 6 }];

  const { arrived, failures } = await frames(fetcher, list, (got, failed) => got.length === 3 && failed.length === 1);
  assert.deepEqual(arrived.map(name).sort(), ['0:0,0', '0:2,1', '1:0,0']);
  assert.equal(failures[0].kind, 'http');
  assert.equal(failures[0].error.status, 404);
  assert.equal(failures[0].key, key(broken));
  assert.match(failures[0].message, /HTTP 404.*3 tries/);
  assert.equal(server.stats('/missing.tif').requests, 3, 'the reader\'s own retries, no more');

  // Still wanted frame after frame (the core holds the others now): neither asked for nor reported again.
  const later = await frames(fetcher, list.filter((tile) => key(tile) === key(broken)), () => false, { ms: 60 }).catch(() => null);
  assert.equal(later, null);
  assert.deepEqual(fetcher.takeFailures(), []);
  assert.equal(server.stats('/missing.tif').requests, 3);
  assert.equal(fetcher.failedWanted, 1);
  assert.equal(fetcher.waiting, 0);

  fetcher.retryFailed();
  const retried = await frames(fetcher, list, (got, failed) => failed.length === 1);
  assert.equal(retried.failures[0].kind, 'http');
  assert.equal(server.stats('/missing.tif').requests, 6);
  server.reset();
});

test('a connection that breaks on one tile is reported once as a network error through onError, and the others arrive', async () => {
  const reader = watched(await openCog(url(), FAST_RETRIES));
  const reported = [];
  const fetcher = new TileFetcher(reader, { onError: (failure) => reported.push({ ...failure }) });
  // The answers break after 60000 bytes: of these, only tile (0, 0) (97574 bytes) is longer.
  const list = [[0, 0], [0, 2], [2, 3], [3, 3]].map(([tx, ty], i) => ({ level: 0, tx, ty, priority: 10 - i }));
  assert.ok(counts[0] > 60000 && [8, 14, 15].every((i) => counts[i] < 60000));
  server.options.dropAfterBytes = 60000;
  try {
    const { arrived, failures } = await frames(fetcher, list, (got, failed) => got.length === 3 && failed.length === 1);
    assert.deepEqual(arrived.map(name).sort(), ['0:0,2', '0:2,3', '0:3,3']);
    assert.equal(failures[0].kind, 'network');
    assert.match(failures[0].message, /connection lost.*3 tries/);
    assert.equal(reported.length, 1);
    assert.deepEqual(reported[0], failures[0]);
    assert.equal(reader.started.filter((tile) => tile === '0:0,0').length, 1);
  } finally {
    server.options.dropAfterBytes = null;
  }
});

test('a tile outside the file is reported as invalid, and a throwing onError does not stop the fetching', async () => {
  const fetcher = new TileFetcher(reference, { onError: () => { throw new Error('caller bug'); } });
  const shown = [];
  const consoleError = console.error;
  console.error = (e) => shown.push(e.message);
  try {
    const list = [{ level: 0, tx: 9, ty: 0, priority: 2 }, { level: 1, tx: 1, ty: 1, priority: 1 }, { level: 1, tx: 0, ty: 1, priority: 0 }];
    const { failures } = await frames(fetcher, list, (got, failed) => got.length === 2 && failed.length === 1);
    assert.equal(failures[0].kind, 'invalid');
    assert.deepEqual(shown, ['caller bug']);
  } finally {
    console.error = consoleError;
  }
});

test('a tile dropped in flight whose read ends well anyway (a reader that ignores the signal) is not delivered', async () => {
  const pending = new Map();
  const deaf = { readTile: (level, tx, ty) => new Promise((resolve) => pending.set(`${level}:${tx},${ty}`, resolve)) };
  const fetcher = new TileFetcher(deaf, { concurrency: 1, graceFrames: 0 });
  const a = { level: 0, tx: 0, ty: 0, priority: 2 }, b = { level: 0, tx: 1, ty: 0, priority: 1 };
  fetcher.want([a, b]);
  fetcher.want([b]);
  assert.equal(pending.has(name(b)), false, 'the aborted read holds the only place until it ends');
  pending.get(name(a))(new Int16Array(4));
  await sleep(0);
  assert.deepEqual(fetcher.takeArrived(), []);
  assert.ok(pending.has(name(b)), 'its place went to the next tile');
  pending.get(name(b))(new Int16Array(4));
  await sleep(0);
  assert.deepEqual(fetcher.takeArrived().map(name), [name(b)]);
});

test('a tile that arrived and waits to be taken is not asked for again, and once taken the fetcher holds nothing', async () => {
  const pending = new Map(), started = [];
  const manual = { readTile: (level, tx, ty) => new Promise((resolve) => (started.push(`${level}:${tx},${ty}`), pending.set(`${level}:${tx},${ty}`, resolve))) };
  const fetcher = new TileFetcher(manual);
  const a = { level: 0, tx: 0, ty: 0, priority: 2 }, b = { level: 0, tx: 1, ty: 0, priority: 1 };
  fetcher.want([a, b]);
  pending.get(name(a))(new Int16Array(4));
  await sleep(0);
  fetcher.want([a, b]); // the core has not had it yet, so still wants it
  assert.deepEqual(started, [name(a), name(b)], 'not asked for twice');
  assert.equal(fetcher.waiting, 1);
  assert.deepEqual(fetcher.takeArrived().map(name), [name(a)]);
  assert.deepEqual(fetcher.takeArrived(), [], 'handed over once');
  fetcher.want([a, b]); // wanted after it was handed over: the core let it go again
  assert.deepEqual(started, [name(a), name(b), name(a)]);
});
