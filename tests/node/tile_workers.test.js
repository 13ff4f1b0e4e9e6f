// Tiles decoded in workers (web/tiles/worker_tile_reader.js, tile_service.js, tile_worker.js):
// the pool routes each read to its least busy worker, forwards aborts, turns the workers' errors
// back into TileErrors of the same kind, and its tiles equal the COG's own. Workers are
// scripted fakes (to steer routing exactly), the real service over a MessageChannel, and the
// real worker script in a Node thread.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { Worker as NodeWorker } from 'node:worker_threads';
import { openCog } from '../../web/tiles/cog_source.js';
import { TileError } from '../../web/tiles/tile_error.js';
import { serveTiles } from '../../web/tiles/tile_service.js';
import { openWorkerPool } from '../../web/tiles/worker_tile_reader.js';
import { TileFetcher } from '../../web/tiles/tile_fetcher.js';
import { startRangeServer } from '../../lib/range_server.js';

const fixtures = fileURLToPath(new URL('../fixtures/cog/', import.meta.url));
const HIMALAYA = 'himalaya_1024_i16.tif';
const FAST_RETRIES = { retries: 2, backoffMs: 5 };
const bytes = new Uint8Array(readFileSync(fixtures + HIMALAYA));
const ALL_TILES = [[0, 4], [1, 2], [2, 1]].flatMap(([level, across]) =>
  Array.from({ length: across * across }, (_, i) => [level, i % across, Math.floor(i / across)]));
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
let server, reference;
const referenceTiles = new Map(); // 'level:tx,ty' -> the COG's own samples
const expected = (level, tx, ty) => referenceTiles.get(`${level}:${tx},${ty}`);

before(async () => {
  server = await startRangeServer(fixtures, { latencyMs: 10 });
  reference = await openCog(new Blob([bytes]), { name: HIMALAYA });
  for (const [level, tx, ty] of ALL_TILES) referenceTiles.set(`${level}:${tx},${ty}`, await reference.readTile(level, tx, ty));
});
after(() => server.close());
const url = () => `${server.url}/${HIMALAYA}`;

/** A worker that answers its open at once and its reads only when the test says. */
class ScriptedWorker {
  constructor(made) {
    this.reads = [];
    this.cancels = [];
    this.terminated = false;
    made.push(this);
  }
  postMessage(message) {
    if (message.type === 'open') {
      queueMicrotask(() => this.onmessage({ data: { type: 'opened', info: { name: 'scripted', levels: reference.levels, stats: { requests: 1, bytes: 100 } } } }));
    } else if (message.type === 'read') {
      this.reads.push(message);
    } else if (message.type === 'cancel') {
      this.cancels.push(message.id);
    }
  }
  answer(index, data) {
    const { id } = this.reads[index];
    this.onmessage({ data: { id, stats: { requests: 2, bytes: 300 }, ...data } });
  }
  terminate() {
    this.terminated = true;
  }
}

/** A worker in this thread: the real service at the other end of a MessageChannel. */
class ChannelWorker {
  constructor(made) {
    const { port1, port2 } = new MessageChannel();
    serveTiles(port2);
    this.port = port1;
    this.sent = [];
    this.received = [];
    port1.onmessage = (event) => {
      this.received.push(event.data);
      this.onmessage?.(event);
    };
    made?.push(this);
  }
  postMessage(message, transfer) {
    this.sent.push(message);
    this.port.postMessage(message, transfer);
  }
  terminate() {
    this.port.close();
    this.terminated = true;
  }
}

test('reads go to the least busy worker, ties in turn, and the pool sums the workers\' figures', async () => {
  const made = [];
  const pool = await openWorkerPool('scripted.tif', { workers: 3, createWorker: () => new ScriptedWorker(made) });
  assert.equal(pool.workerCount, 3);
  assert.deepEqual(pool.stats, { requests: 3, bytes: 300 });
  assert.equal(pool.levels, reference.levels);
  const a = pool.readTile(0, 0, 0), b = pool.readTile(0, 1, 0), c = pool.readTile(0, 2, 0);
  assert.deepEqual(made.map((w) => w.reads.length), [1, 1, 1]);
  assert.deepEqual(pool.loads, [1, 1, 1]);
  made[1].answer(0, { type: 'tile', samples: new Int16Array([1]) });
  made[2].answer(0, { type: 'tile', samples: new Int16Array([2]) });
  assert.deepEqual(await b, new Int16Array([1]));
  assert.deepEqual(await c, new Int16Array([2]));
  assert.deepEqual(pool.stats, { requests: 1 + 2 + 2, bytes: 100 + 300 + 300 });
  // Worker 0 is still busy: turn order would give it the next read; the least busy take it.
  const d = pool.readTile(0, 3, 0), e = pool.readTile(0, 0, 1);
  assert.deepEqual(made.map((w) => w.reads.length), [1, 2, 2]);
  assert.deepEqual(made[1].reads[1], { type: 'read', id: made[1].reads[1].id, level: 0, tx: 3, ty: 0 });
  assert.deepEqual(pool.loads, [1, 1, 1]);
  made[0].answer(0, { type: 'tile', samples: new Int16Array([0]) });
  made[1].answer(1, { type: 'tile', samples: new Int16Array([3]) });
  made[2].answer(1, { type: 'tile', samples: new Int16Array([4]) });
  assert.deepEqual(await Promise.all([a, d, e]), [new Int16Array([0]), new Int16Array([3]), new Int16Array([4])]);
  pool.close();
  assert.ok(made.every((w) => w.terminated));
});

test('an abort rejects at once and is forwarded; the worker stays busy until it answers, and its late answer is dropped', async () => {
  const made = [];
  const pool = await openWorkerPool('scripted.tif', { workers: 2, createWorker: () => new ScriptedWorker(made) });
  const controller = new AbortController();
  const reading = pool.readTile(0, 1, 1, controller.signal);
  controller.abort();
  await assert.rejects(reading, (e) => e instanceof TileError && e.kind === 'aborted');
  assert.deepEqual(made[0].cancels, [made[0].reads[0].id]);
  assert.deepEqual(pool.loads, [1, 0]);
  const next = pool.readTile(0, 2, 2);
  assert.equal(made[1].reads.length, 1, 'the next read goes to the idle worker');
  made[0].answer(0, { type: 'failed', error: { name: 'TileError', kind: 'aborted', message: 'aborted' } });
  assert.deepEqual(pool.loads, [0, 1]);
  made[1].answer(0, { type: 'tile', samples: new Int16Array([7]) });
  assert.deepEqual(await next, new Int16Array([7]));
  // Aborted before it starts: no message at all.
  await assert.rejects(pool.readTile(0, 0, 0, AbortSignal.abort()), { kind: 'aborted' });
  assert.equal(made[0].reads.length + made[1].reads.length, 2);
  pool.close();
});

test('the workers\' errors come back as TileErrors of the same kind, RangeErrors as RangeErrors, and a dead worker takes no more reads', async () => {
  const made = [];
  const pool = await openWorkerPool('scripted.tif', { workers: 2, createWorker: () => new ScriptedWorker(made) });
  const notFound = pool.readTile(0, 0, 0), outside = pool.readTile(0, 9, 0);
  made[0].answer(0, { type: 'failed', error: { name: 'TileError', kind: 'http', status: 404, message: 'x: HTTP 404 (3 tries)' } });
  made[1].answer(0, { type: 'failed', error: { name: 'RangeError', message: 'tile (9, 0) is outside' } });
  await assert.rejects(notFound, (e) => e instanceof TileError && e.kind === 'http' && e.status === 404 && /HTTP 404/.test(e.message));
  await assert.rejects(outside, (e) => e instanceof RangeError && /outside/.test(e.message));
  const truncated = pool.readTile(0, 1, 0);
  made[0].answer(1, { type: 'failed', error: { name: 'TileError', kind: 'truncated', size: 1234, message: 'cut' } });
  await assert.rejects(truncated, { kind: 'truncated', size: 1234 });

  const lost = pool.readTile(0, 2, 0);
  assert.equal(made[1].reads.length, 2);
  made[1].onerror({ message: 'out of memory' });
  await assert.rejects(lost, /a tile worker died \(out of memory\)/);
  const waiting = [pool.readTile(0, 3, 0), pool.readTile(0, 3, 1)];
  assert.deepEqual(made.map((w) => w.reads.length), [4, 2], 'only the live worker is asked');
  pool.close();
  for (const read of waiting) await assert.rejects(read, { kind: 'aborted', message: /closed/ });
});

test('a pool over the real service reads every tile of every level equal to the COG\'s own, from a URL and from a Blob', async () => {
  for (const input of [url(), new Blob([bytes])]) {
    const made = [];
    const before = server.stats(`/${HIMALAYA}`);
    const pool = await openWorkerPool(input, { workers: 3, name: HIMALAYA, createWorker: () => new ChannelWorker(made) });
    assert.equal(pool.sampleType, 'i16');
    assert.equal(pool.nodata, -32768);
    assert.deepEqual(pool.levels, reference.levels);
    assert.deepEqual(pool.georef, reference.georef);
    const tiles = await Promise.all(ALL_TILES.map(([level, tx, ty]) => pool.readTile(level, tx, ty)));
    for (let i = 0; i < ALL_TILES.length; i++) {
      assert.ok(tiles[i] instanceof Int16Array);
      assert.deepEqual(tiles[i], expected(...ALL_TILES[i]), `tile ${ALL_TILES[i]}`);
    }
    assert.deepEqual(made.map((w) => w.sent.filter((m) => m.type === 'read').length), [7, 7, 7]);
    if (typeof input === 'string') {
      const after = server.stats(`/${HIMALAYA}`);
      assert.deepEqual(pool.stats, { requests: after.requests - before.requests, bytes: after.bytes - before.bytes });
    }
    pool.close();
  }
});

test('over the real service, an abort cancels the worker\'s fetch, and a 404, a broken connection or a bad tile keep their kind', async () => {
  const made = [];
  const pool = await openWorkerPool(url(), { workers: 2, ...FAST_RETRIES, createWorker: () => new ChannelWorker(made) });
  const controller = new AbortController();
  server.options.latencyMs = 300; // the read is surely still at the server when aborted
  const reading = pool.readTile(0, 0, 0, controller.signal);
  await sleep(20);
  controller.abort();
  server.options.latencyMs = 10;
  await assert.rejects(reading, { kind: 'aborted' });
  assert.ok(made[0].sent.some((m) => m.type === 'cancel'));
  for (let i = 0; i < 100 && pool.loads[0] > 0; i++) await sleep(2);
  assert.deepEqual(pool.loads, [0, 0], 'the worker answered its cancelled read');
  const cancelled = made[0].sent.find((m) => m.type === 'cancel').id;
  const answer = made[0].received.find((m) => m.id === cancelled);
  assert.equal(answer.type, 'failed', 'the worker stopped the read');
  assert.equal(answer.error.kind, 'aborted');

  server.options.dropAfterBytes = 1000;
  try {
    await assert.rejects(pool.readTile(0, 1, 0), (e) => e instanceof TileError && e.kind === 'network' && /3 tries/.test(e.message));
  } finally {
    server.options.dropAfterBytes = null;
  }
  server.options.failPaths = [`/${HIMALAYA}`];
  try {
    await assert.rejects(pool.readTile(0, 1, 1), (e) => e instanceof TileError && e.kind === 'http' && e.status === 404);
  } finally {
    server.options.failPaths = {};
  }
  assert.deepEqual(await pool.readTile(0, 1, 1), expected(0, 1, 1), 'the pool goes on after failures');
  pool.close();

  const corrupt = bytes.slice();
  const at = corrupt.length - 40000; // inside the last tile stored
  corrupt.fill(0xff, at, at + 20000);
  const blobPool = await openWorkerPool(new Blob([corrupt]), { workers: 1, name: 'corrupt.tif', createWorker: () => new ChannelWorker() });
  const kinds = await Promise.all(ALL_TILES.map(([level, tx, ty]) => blobPool.readTile(level, tx, ty).then(() => 'read', (e) => e.kind)));
  assert.ok(kinds.includes('decode'), kinds.join(' '));
  blobPool.close();
});

test('opening fails as openCog does, and every worker is ended', async () => {
  const made = [];
  await assert.rejects(openWorkerPool(`${server.url}/missing.tif`, { workers: 2, ...FAST_RETRIES, createWorker: () => new ChannelWorker(made) }),
    (e) => e instanceof TileError && e.kind === 'http' && e.status === 404);
  assert.equal(made.length, 2);
  assert.ok(made.every((w) => w.terminated));
  await assert.rejects(openWorkerPool(new Blob(['{"width": 2}']), { workers: 1, createWorker: () => new ChannelWorker(made) }), { kind: 'bad-tiff' });
});

test('the fetcher takes a worker pool in place of a CogSource', async () => {
  const pool = await openWorkerPool(url(), { workers: 2, createWorker: () => new ChannelWorker() });
  const fetcher = new TileFetcher(pool, { concurrency: 4 });
  const list = ALL_TILES.map(([level, tx, ty], i) => ({ level, tx, ty, priority: i }));
  const arrived = [];
  for (const start = Date.now(); arrived.length < list.length;) {
    assert.ok(Date.now() - start < 3000, `${arrived.length} tiles after 3 s`);
    fetcher.want(list);
    for (const tile of fetcher.takeArrived()) arrived.push({ ...tile });
    assert.deepEqual(fetcher.takeFailures(), []);
    await sleep(4);
  }
  for (const tile of arrived) assert.deepEqual(tile.samples, expected(tile.level, tile.tx, tile.ty));
  assert.equal(fetcher.bytesFetched, pool.stats.bytes);
  assert.ok(fetcher.bytesFetched > 0);
  pool.close();
});

test('the worker script runs in a real thread: samples come back transferred and equal', async () => {
  // Node threads have no `self`: a few lines give the worker script the Web Worker face it expects.
  const script = `
    const { parentPort, workerData } = require('node:worker_threads');
    globalThis.self = {
      postMessage: (message, transfer) => parentPort.postMessage(message, transfer),
      set onmessage(handler) { parentPort.on('message', (data) => handler({ data })); },
    };
    import(workerData.url);`;
  const workerUrl = new URL('../../web/tiles/tile_worker.js', import.meta.url).href;
  class ThreadWorker {
    constructor() {
      this.thread = new NodeWorker(script, { eval: true, workerData: { url: workerUrl } });
      this.thread.on('message', (data) => this.onmessage?.({ data }));
      this.thread.on('error', (e) => this.onerror?.({ message: e.message }));
    }
    postMessage(message, transfer) { this.thread.postMessage(message, transfer); }
    terminate() { this.thread.terminate(); }
  }
  const pool = await openWorkerPool(url(), { workers: 2, createWorker: () => new ThreadWorker() });
  const tiles = await Promise.all([[0, 2, 3], [1, 1, 0], [2, 0, 0]].map((t) => pool.readTile(...t)));
  assert.deepEqual(tiles, [expected(0, 2, 3), expected(1, 1, 0), expected(2, 0, 0)]);
  assert.ok(tiles.every((t) => t.buffer.byteLength === 256 * 256 * 2), 'each tile owns its whole buffer');
  pool.close();
});
