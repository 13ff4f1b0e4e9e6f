// The fetch queue of a web tile layer (web/webtiles/tile_requests.js) against the tile server of
// lib/tile_server.js and a fetch the test holds in its hand: the most wanted first and never
// more than six at once, unwanted requests aborted when the view moves on, one message per
// kind of fault however many tiles fail, no request loop after a failure, and the figures of
// what was fetched.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, statSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { decode as decodePng } from 'fast-png';
import { TileRequests } from '../../web/webtiles/tile_requests.js';
import { parseTemplate } from '../../web/webtiles/tile_template.js';
import { tileKey } from '../../web/webtiles/tile_key.js';
import { startTileServer } from '../../lib/tile_server.js';

const fixtures = fileURLToPath(new URL('../fixtures/webtiles/', import.meta.url));
let server;
before(async () => { server = await startTileServer(`${fixtures}bmng`, { latencyMs: 10 }); });
after(() => server.close());

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
const until = async (condition, what) => {
  for (let i = 0; i < 2000 && !condition(); i++) await sleep(5);
  assert.ok(condition(), `waited for ${what}`);
};
const tile = (z, x, y) => ({ z, x, y, key: tileKey(z, x, y) });
// The zoom 7 tiles of the fixture, row by row: 64 that exist.
const ZOOM7 = [];
for (let y = 49; y <= 56; y++) for (let x = 89; x <= 96; x++) ZOOM7.push(tile(7, x, y));

/** Node has no createImageBitmap: a PNG decoded by fast-png stands in for the bitmap, anything else is refused as a browser would. */
async function decode(blob) {
  const bytes = new Uint8Array(await blob.arrayBuffer());
  const png = decodePng(bytes); // throws for what is not a PNG
  return { width: png.width, height: png.height, data: png.data, close() {} };
}

/** A queue on the tile server, recording what arrives and what is told. */
function queue(options = {}) {
  const arrived = [], messages = [];
  const requests = new TileRequests(parseTemplate(`${server.url}/{z}/{x}/{y}.png`), {
    onTile: (z, x, y, image) => arrived.push({ z, x, y, image }), onMessage: (fault) => messages.push(fault), decode, ...options });
  return { requests, arrived, messages };
}

/** A fetch the test answers by hand: each call waits in `calls` until resolved or aborted. */
function handFetch() {
  const calls = [];
  let active = 0, most = 0;
  const fetch = (url, { signal }) => new Promise((resolve, reject) => {
    most = Math.max(most, ++active);
    const call = { url, signal, answer: () => { active--; resolve(new Response(readFileSync(`${fixtures}bmng/7/89/49.png`))); } };
    signal.addEventListener('abort', () => { active--; reject(new DOMException('aborted', 'AbortError')); });
    calls.push(call);
  });
  return { fetch, calls, most: () => most };
}

test('the most wanted first, six at a time; the view moving on aborts what it no longer wants', async () => {
  const hand = handFetch();
  const { requests, arrived } = queue({ fetch: hand.fetch });
  const resident = new Set();
  requests.want(ZOOM7.slice(0, 20), (k) => resident.has(k));
  assert.deepEqual(hand.calls.map((c) => c.url.split('/').slice(-3).join('/')), ZOOM7.slice(0, 6).map((t) => `${t.z}/${t.x}/${t.y}.png`));
  hand.calls[2].answer();
  await until(() => arrived.length === 1 && hand.calls.length === 7, 'the third tile and the seventh request');
  resident.add(ZOOM7[2].key);
  assert.match(hand.calls[6].url, /\/7\/95\/49\.png$/, 'the seventh most wanted starts next');
  // The view moves on: tiles 30..39 now, nothing of before.
  requests.want(ZOOM7.slice(30, 40), (k) => resident.has(k));
  assert.ok(hand.calls.slice(0, 7).every((c, i) => i === 2 || c.signal.aborted), 'every request of the old view aborted');
  await until(() => hand.calls.length === 13, 'six requests of the new view');
  assert.deepEqual(hand.calls.slice(7).map((c) => c.url.split('/').slice(-3).join('/')), ZOOM7.slice(30, 36).map((t) => `${t.z}/${t.x}/${t.y}.png`));
  // Re-prioritised: the last of the new list first.
  requests.want([...ZOOM7.slice(30, 40)].reverse(), (k) => resident.has(k));
  hand.calls[7].answer();
  await until(() => hand.calls.length === 14, 'the next request');
  assert.match(hand.calls[13].url, /\/7\/96\/53\.png$/, 'the most wanted of the new order (tile 39)');
  assert.ok(hand.most() <= 6, `at most six in flight (${hand.most()})`);
  assert.equal(requests.figures.aborted, 6);
  requests.dispose();
});

test('tiles arrive from the server most wanted first, with the figures of what was fetched', async () => {
  server.reset();
  const { requests, arrived, messages } = queue();
  const wanted = ZOOM7.slice(0, 16);
  requests.want(wanted, () => false);
  await until(() => arrived.length === 16, 'sixteen tiles');
  assert.deepEqual(server.tilesRequested().slice(0, 6).sort(), wanted.slice(0, 6).map((t) => `${t.z}/${t.x}/${t.y}`).sort(), 'the first six first');
  assert.deepEqual(server.tilesRequested().sort(), wanted.map((t) => `${t.z}/${t.x}/${t.y}`).sort(), 'each once');
  assert.equal(messages.length, 0);
  const bytes = wanted.reduce((sum, t) => sum + statSync(`${fixtures}bmng/${t.z}/${t.x}/${t.y}.png`).size, 0);
  assert.deepEqual({ ...requests.figures }, { fetched: 16, bytes, failed: 0, aborted: 0, requested: 16 });
  assert.ok(arrived.every((a) => a.image.width === 256 && a.image.height === 256));
  requests.dispose();
});

test('missing tiles: one message however many fail, and none asked for again', async () => {
  server.reset();
  await server.setFault('missing');
  try {
    const { requests, messages } = queue();
    requests.want(ZOOM7.slice(0, 12), () => false);
    await until(() => requests.figures.failed === 12, 'twelve failures');
    assert.equal(messages.length, 1);
    assert.equal(messages[0].kind, 'http');
    assert.match(messages[0].message, /^HTTP 404 for http:\/\/127\.0\.0\.1:\d+\/7\/\d+\/\d+\.png$/);
    requests.want(ZOOM7.slice(0, 12), () => false);
    await sleep(50);
    assert.equal(server.tilesRequested().length, 12, 'a missing tile is not asked for again');
    assert.ok(ZOOM7.slice(0, 12).every((t) => requests.isFailed(t.key)));
    requests.dispose();
  } finally {
    await server.setFault(null);
  }
});

test('an answer that is not an image: one message naming what came', async () => {
  await server.setFault('not-image');
  try {
    const { requests, messages, arrived } = queue();
    requests.want(ZOOM7.slice(0, 8), () => false);
    await until(() => requests.figures.failed === 8, 'eight failures');
    assert.equal(arrived.length, 0);
    assert.equal(messages.length, 1);
    assert.match(messages[0].message, /^not an image \(text\/html, 55 bytes\): http:\/\/127\.0\.0\.1:\d+\/7\/89\/49\.png$/);
    requests.dispose();
  } finally {
    await server.setFault(null);
  }
});

test('a server that is down: one message, the layer waits instead of asking for every tile, and resumes', async () => {
  server.reset();
  await server.setFault('down');
  let calls = 0;
  const counting = (url, init) => { calls++; return fetch(url, init); };
  const { requests, messages, arrived } = queue({ fetch: counting, firstDelayMs: 300 });
  try {
    requests.want(ZOOM7.slice(0, 12), () => false);
    await until(() => messages.length === 1 && requests.pending === 0, 'the fault');
    assert.equal(messages[0].kind, 'unreachable');
    assert.match(messages[0].message, /^cannot reach the tile server 127\.0\.0\.1:\d+ \(it is down, or the address is wrong\): http:/);
    const failed = requests.figures.failed, tried = calls;
    assert.ok(failed <= 6, `only the first requests failed (${failed}): the layer waits`);
    requests.want(ZOOM7.slice(0, 12), () => false);
    assert.equal(calls, tried, 'no request while the layer waits');
    await server.setFault(null);
    await until(() => arrived.length === 12, 'every tile once the server is back');
    assert.equal(messages.length, 1, 'still one message');
  } finally {
    requests.dispose();
    await server.setFault(null);
  }
});

test('a server that refuses cross-origin reads is told apart from one that is down', async () => {
  // As a browser does: the CORS request fails like a network error, the no-cors one gets an opaque answer.
  const refusing = async (url, { mode }) => {
    if (mode === 'cors') throw new TypeError('Failed to fetch');
    return { type: 'opaque', ok: false, status: 0 };
  };
  const { requests, messages } = queue({ fetch: refusing });
  requests.want(ZOOM7.slice(0, 10), () => false);
  await until(() => messages.length === 1 && requests.pending === 0, 'the fault');
  assert.equal(messages[0].kind, 'cors');
  assert.match(messages[0].message, /^the tile server 127\.0\.0\.1:\d+ answers but does not let this page read its tiles \(no Access-Control-Allow-Origin header\): /);
  requests.dispose();
});

test('a tile that fails for a while is retried after a delay that doubles, not in a loop', async () => {
  let now = 0, calls = 0;
  const flaky = async () => { calls++; return new Response('busy', { status: 503 }); };
  const { requests, messages } = queue({ fetch: flaky, now: () => now, firstDelayMs: 1000 });
  const one = [ZOOM7[0]];
  requests.want(one, () => false);
  await until(() => requests.pending === 0 && calls === 1, 'the first try');
  for (const [at, expected] of [[500, 1], [999, 1], [1001, 2], [2500, 2], [3002, 3], [7000, 3], [7003, 4]]) {
    now = at;
    requests.want(one, () => false);
    await until(() => requests.pending === 0, 'the try to end');
    assert.equal(calls, expected, `tries by ${at} ms`);
  }
  assert.equal(messages.length, 1);
  assert.match(messages[0].message, /^HTTP 503 for /);
  requests.dispose();
});
