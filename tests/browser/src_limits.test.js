// ?src=URL has limits: a time limit without progress, a size cap checked against
// Content-Length before the body and while it streams, a Cancel button, and a file the user
// opens meanwhile wins over a late answer. The address bar names a src only while its terrain
// is on screen, and a cross-origin file's NAME.json comes from beside it. The data comes from
// small HTTP servers on 127.0.0.1 started here, slow or broken on purpose; the assertions are on
// what a person sees: the status line, the terrain (its name and size in the HUD, its spacing),
// and the address bar.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { createServer } from 'node:http';
import { readFileSync } from 'node:fs';
import { startViewer, openPage, dropFiles, terrainShown, outDir, projectDir } from '../../lib/page_harness.js';

const VIEWPORT = { width: 480, height: 300 };
const FIXTURES = `${projectDir}tests/fixtures/`;
const DEFAULT_NAME = 'globe_himalaya_2048.png';
const WHERE = '; the limits are under Controls › Loading from a URL';
const TYPES = { png: 'image/png', json: 'application/json' };
const fixtureFiles = (...names) => names.map((name) => ({ name, bytes: readFileSync(`${FIXTURES}${name}`) }));

/**
 * A data server with routes that misbehave on purpose (every answer allows any origin):
 *   /files/NAME          the fixture NAME
 *   /slow/MS/NAME        the fixture after MS milliseconds
 *   /fail/MS/NAME        HTTP 500 after MS milliseconds
 *   /silent/NAME         no answer at all
 *   /stall/NAME          the headers and 1000 bytes, then nothing
 *   /huge/NAME           Content-Length 5 GiB, 64 KiB, then nothing
 *   /endless/NAME        64 KiB every 20 ms, without end (no Content-Length)
 * `log` holds { path, sent, aborted } for every request: `aborted` when the client closed the
 * connection before the answer was complete.
 */
async function startDataServer() {
  const log = [];
  const server = createServer((request, response) => {
    const path = new URL(request.url, 'http://x').pathname;
    const entry = { path, sent: 0, aborted: false };
    log.push(entry);
    response.on('close', () => { entry.aborted = !response.writableFinished; });
    const [, route, ...rest] = path.split('/');
    const name = rest.at(-1), ms = Number(rest[0]);
    const headers = { 'access-control-allow-origin': '*', 'content-type': TYPES[name.split('.').pop()] ?? 'application/octet-stream' };
    const send = (bytes) => { entry.sent += bytes.length; return response.write(bytes); };
    const serve = () => {
      let bytes;
      try { bytes = readFileSync(`${FIXTURES}${name}`); } catch {
        response.writeHead(404, { ...headers, 'content-type': 'text/plain' }).end('not found');
        return;
      }
      response.writeHead(200, { ...headers, 'content-length': bytes.length });
      send(bytes);
      response.end();
    };
    if (route === 'files') serve();
    else if (route === 'slow') setTimeout(serve, ms);
    else if (route === 'fail') setTimeout(() => response.writeHead(500, headers).end('broken'), ms);
    else if (route === 'silent') { /* never answers */ }
    else if (route === 'stall') {
      response.writeHead(200, { ...headers, 'content-length': 100000 });
      send(new Uint8Array(1000));
    } else if (route === 'huge') {
      response.writeHead(200, { ...headers, 'content-length': 5 * 2 ** 30 });
      send(new Uint8Array(65536));
    } else if (route === 'endless') {
      response.writeHead(200, headers);
      const timer = setInterval(() => send(new Uint8Array(65536)), 20);
      response.on('close', () => clearInterval(timer));
    } else response.writeHead(404, headers).end();
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return {
    origin: `http://127.0.0.1:${server.address().port}`,
    log,
    close: () => new Promise((resolve) => { server.closeAllConnections(); server.close(resolve); }),
  };
}

let viewer, data, other;
before(async () => {
  [viewer, data, other] = await Promise.all([startViewer({ pixelRatio: 0.5 }), startDataServer(), startDataServer()]);
});
after(async () => { await Promise.all([viewer?.close(), data?.close(), other?.close()]); });

/** Opens the page with ?src=URL and more parameters; returns { page, problems }. */
function openSrc(url, more = '') {
  return openPage(viewer.browser, `${viewer.url}?src=${encodeURIComponent(url)}${more}`, VIEWPORT);
}

/** What a person sees: the status line, the terrain's line in the HUD, the spacing field, the address bar. */
const seen = (page) => page.evaluate(() => {
  const status = document.getElementById('status');
  return { status: status.textContent, statusIsError: status.classList.contains('error'),
    terrain: document.querySelector('#hud .hud-more')?.textContent.split('\n')[0] ?? '',
    spacing: document.getElementById('spacing-input').value, search: location.search,
    loading: window.hexlod.loading, cancelShown: !document.getElementById('load-cancel')?.hidden };
});

/** Waits until the page is ready (its first terrain on screen) with nothing loading. */
const settled = (page, timeout = 60000) => page.waitForFunction(
  () => window.hexlod && window.hexlod.status !== 'loading' && !window.hexlod.loading, null, { timeout });

/** Waits until the address bar no longer names a src (the page writes it a moment after a frame). */
const srcLeavesAddressBar = (page) => page.waitForFunction(
  () => { window.hexlod.requestRender(); return !new URLSearchParams(location.search).has('src'); }, null, { timeout: 15000, polling: 100 });

/** Problems other than the failed and aborted requests a test provokes on purpose. */
const unexpected = (problems) => problems.filter((p) => !/^request failed: |status of 500|net::ERR_|Failed to load resource/.test(p));

test('no answer, or a body that stops: the time limit gives a message, the default terrain and no src in the address bar', async () => {
  for (const [route, why] of [['silent', 'no answer in 2 s'], ['stall', 'no data for 2 s']]) {
    const url = `${data.origin}/${route}/volcano_maungawhau.png`;
    const started = Date.now();
    const { page, problems } = await openSrc(url, '&timeout=2&tau=2.5');
    await settled(page);
    const view = await seen(page);
    assert.equal(view.status, `volcano_maungawhau.png: cannot fetch ${url} (${why}${WHERE})`);
    assert.ok(view.statusIsError);
    assert.match(view.terrain, new RegExp(`^${DEFAULT_NAME}  2048 × 2048`), 'the default terrain instead');
    assert.ok(Date.now() - started < 30000, 'the limit, not a test timeout, ended the load');
    await srcLeavesAddressBar(page);
    assert.match(await page.evaluate(() => location.search), /timeout=2&.*tau=2\.5|tau=2\.5.*timeout=2/, 'the settings stay');
    assert.ok(data.log.some((r) => r.path === `/${route}/volcano_maungawhau.png` && r.aborted), 'the download was stopped');
    assert.deepEqual(unexpected(problems), []);
    await page.close();
  }
});

test('a Content-Length past the size cap is refused before the body; an endless body stops at the cap', async () => {
  const huge = `${data.origin}/huge/big.r16`;
  const started = Date.now();
  const first = await openSrc(huge);
  await settled(first.page);
  let view = await seen(first.page);
  assert.equal(view.status, `big.r16: cannot fetch ${huge} (5120 MB, more than the 1024 MB size cap${WHERE})`);
  assert.ok(view.statusIsError);
  assert.ok(Date.now() - started < 30000, 'refused at once, not after the 60 s limit');
  assert.match(view.terrain, new RegExp(`^${DEFAULT_NAME}`));
  const hugeRequest = data.log.find((r) => r.path === '/huge/big.r16');
  assert.ok(hugeRequest.aborted && hugeRequest.sent <= 65536, 'the body was not read');
  await srcLeavesAddressBar(first.page);
  assert.deepEqual(unexpected(first.problems), []);
  await first.page.close();

  const endless = `${data.origin}/endless/big.r16`;
  const second = await openSrc(endless, '&maxmb=1');
  await settled(second.page);
  view = await seen(second.page);
  assert.equal(view.status, `big.r16: cannot fetch ${endless} (more than the 1 MB size cap${WHERE})`);
  assert.match(view.terrain, new RegExp(`^${DEFAULT_NAME}`));
  const endlessRequest = data.log.find((r) => r.path === '/endless/big.r16');
  await new Promise((resolve) => setTimeout(resolve, 500)); // the server notices the closed connection
  assert.ok(endlessRequest.aborted && endlessRequest.sent < 4 * 2 ** 20, `the download stopped (${endlessRequest.sent} bytes sent)`);
  assert.deepEqual(unexpected(second.problems), []);
  await second.page.close();
});

test('Cancel while a URL loads: the load stops, the page says so, the settings stay', async () => {
  const url = `${data.origin}/silent/volcano_maungawhau.png`;
  const { page, problems } = await openSrc(url, '&tau=2.5&exag=3');
  await page.waitForSelector('#load-cancel:not([hidden])', { timeout: 120000 }); // the page boots first, slow on a loaded machine
  let view = await seen(page);
  assert.equal(view.status, 'Loading volcano_maungawhau.png…');
  await page.screenshot({ path: `${outDir}/src-limits-cancel-button.png` });
  await page.click('#load-cancel');
  await settled(page);
  view = await seen(page);
  assert.equal(view.status, 'volcano_maungawhau.png: loading cancelled');
  assert.ok(!view.statusIsError && !view.cancelShown);
  assert.match(view.terrain, new RegExp(`^${DEFAULT_NAME}`), 'with nothing on screen yet, the default terrain');
  assert.deepEqual(await page.evaluate(() => [window.hexlod.settings.tau, window.hexlod.settings.exaggeration]), [2.5, 3]);
  await page.screenshot({ path: `${outDir}/src-limits-cancelled.png` });
  await srcLeavesAddressBar(page);
  assert.ok(data.log.some((r) => r.path === '/silent/volcano_maungawhau.png' && r.aborted), 'the request was closed');
  assert.deepEqual(unexpected(problems), []);
  await page.close();
});

test('a file dropped while a src loads wins: neither a late failure nor a late success replaces it', async () => {
  for (const route of ['fail', 'slow']) {
    const path = `/${route}/2500/grandcanyon_512.png`;
    const { page, problems } = await openSrc(`${data.origin}${path}`);
    await page.waitForFunction(() => window.hexlod?.loading, null, { timeout: 120000 });
    await dropFiles(page, fixtureFiles('volcano_maungawhau.png', 'volcano_maungawhau.json'));
    await terrainShown(page, 'volcano_maungawhau.png');
    await new Promise((resolve) => setTimeout(resolve, 4000)); // past the server's late answer
    await settled(page);
    const view = await seen(page);
    assert.match(view.terrain, /^volcano_maungawhau\.png  87 × 61/, `${route}: the dropped file stays`);
    assert.equal(view.spacing, '10');
    assert.ok(!view.statusIsError, `${route}: no message about the src: ${view.status}`);
    await srcLeavesAddressBar(page);
    assert.ok(data.log.some((r) => r.path === path && r.aborted), `${route}: the src download was cancelled by the drop`);
    assert.equal(await page.evaluate(() => window.hexlod.memory().liveTerrains), 1, 'the core holds the terrain on screen alone');
    assert.deepEqual(unexpected(problems), []);
    await page.close();
  }
});

test('files dropped in quick succession: the last one is shown, the first is cancelled without a message', async () => {
  const { page, problems } = await openPage(viewer.browser, viewer.url, VIEWPORT);
  await settled(page, 180000);
  // The first takes most of a second to decode: the second arrives while it does.
  await dropFiles(page, ['globe_himalaya_2048.png', 'globe_himalaya_2048.json']
    .map((name) => ({ name: `first_${name}`, bytes: readFileSync(`${projectDir}public/terrain/${name}`) })));
  await dropFiles(page, fixtureFiles('volcano_maungawhau.png', 'volcano_maungawhau.json'));
  await page.waitForFunction(() => window.hexlod.terrain.name === 'volcano_maungawhau.png', null, { timeout: 30000 });
  await settled(page);
  await new Promise((resolve) => setTimeout(resolve, 1500));
  const view = await seen(page);
  assert.match(view.terrain, /^volcano_maungawhau\.png  87 × 61/);
  assert.equal(view.status, '');
  assert.equal(await page.evaluate(() => window.hexlod.memory().liveTerrains), 1, 'the cancelled decode freed its terrain');
  assert.deepEqual(problems, []);
  await page.close();
});

test('a cross-origin src reads its NAME.json from beside the data, not from the page\'s server', async () => {
  const url = `${other.origin}/files/volcano_maungawhau.png`;
  const { page, problems } = await openPage(viewer.browser, 'about:blank', VIEWPORT);
  const pageRequests = [];
  page.on('request', (request) => pageRequests.push(request.url()));
  await page.goto(`${viewer.url}?src=${encodeURIComponent(url)}`);
  await settled(page);
  const view = await seen(page);
  assert.match(view.terrain, /^volcano_maungawhau\.png  87 × 61/);
  assert.equal(view.spacing, '10', 'the sidecar\'s cell size');
  assert.match(await page.evaluate(() => document.getElementById('hud').textContent), /spacing 10\.0 × 10\.0 m, heights 94 … 195 m/);
  assert.ok(other.log.some((r) => r.path === '/files/volcano_maungawhau.json'), 'the sidecar was asked of the data\'s server');
  assert.deepEqual(pageRequests.filter((u) => u.includes('volcano_maungawhau.json') && !u.startsWith(other.origin)), []);
  assert.match(await page.evaluate(() => location.search), /src=/, 'the address bar keeps the src on screen');
  assert.deepEqual(problems, []);
  await page.close();
});
