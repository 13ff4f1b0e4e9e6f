// Files reach the page: the file picker and drag & drop switch the terrain for several formats,
// a RAW file of unknown size asks for it, a bad file shows its message and leaves the terrain,
// and ?src=URL opens a file at start-up.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { startViewer, openPage, outDir, projectDir, dropFiles } from '../../lib/page_harness.js';

const FIXTURES = `${projectDir}tests/fixtures/formats/`;
let viewer;
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

// The pages run at a 50 ms frame budget: the views converge in few of SwiftShader's slow frames.
const quick = (query = '') => `${viewer.url}?budget=50${query}`;
const ready = (page) => page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });

const drop = dropFiles;
const fixture = (name) => ({ name, bytes: readFileSync(FIXTURES + name) });
const settled = (page) => page.waitForFunction(() => !window.hexlod.loading, null, { timeout: 60000 });
const terrainName = (page, name) => page.waitForFunction((n) => window.hexlod.terrain?.name === n && !window.hexlod.loading, name, { timeout: 60000 });

test('picker and drop switch formats; RAW asks its size; a bad file keeps the terrain', async () => {
  const { page, problems } = await openPage(viewer.browser, quick());
  await ready(page);
  assert.equal(await page.evaluate(() => window.hexlod.status), 'ready');

  // GeoTIFF through the file picker.
  await page.setInputFiles('#file-input', FIXTURES + 'canyon_u16_tiled_deflate.tif');
  await terrainName(page, 'canyon_u16_tiled_deflate.tif');
  let state = await page.evaluate(() => window.hexlod);
  assert.deepEqual([state.terrain.width, state.terrain.height, state.error], [192, 192, null]);
  assert.ok(state.terrain.maxHeight - state.terrain.minHeight > 500, 'the canyon has relief');

  // ESRI ASCII grid with voids, dropped.
  await drop(page, [fixture('jacksboro_voids.asc')]);
  await terrainName(page, 'jacksboro_voids.asc');
  state = await page.evaluate(() => window.hexlod);
  assert.deepEqual([state.terrain.width, state.terrain.height], [250, 190]);
  assert.ok(state.terrain.minHeight > 200, `voids filled, not -9999: min ${state.terrain.minHeight}`);

  // Terrarium PNG, dropped; take a look at it.
  await drop(page, [fixture('etopo_terrarium.png')]);
  await terrainName(page, 'etopo_terrarium.png');
  state = await page.evaluate(() => window.hexlod);
  assert.ok(state.terrain.minHeight < -5000 && state.terrain.maxHeight > 2000, 'sea floor and mountains');
  await page.waitForFunction(() => window.hexlod.converged, null, { timeout: 120000 });
  await page.screenshot({ path: `${outDir}/files-terrarium.png` });

  // A bad file: its message shows, the terrain and the camera stay.
  const before = await page.evaluate(() => ({ terrain: window.hexlod.terrain, frames: window.hexlod.frames }));
  const pgm = fixture('everest.pgm');
  await drop(page, [{ name: 'everest.pgm', bytes: pgm.bytes.subarray(0, 5000) }]);
  await page.waitForFunction(() => window.hexlod.error !== null && !window.hexlod.loading, null, { timeout: 60000 });
  state = await page.evaluate(() => ({ ...window.hexlod, status: document.getElementById('status').textContent }));
  assert.match(state.error, /^everest\.pgm: truncated: \d+ bytes of samples, 80000 needed/);
  assert.equal(state.status, state.error, 'the message is on screen');
  assert.deepEqual(state.terrain, before.terrain);

  // RAW of unknown size: the dialog asks, the terrain loads.
  await drop(page, [fixture('volcano.r16'), fixture('volcano.json')]);
  await page.waitForSelector('#raw-dialog[open]');
  await page.fill('#raw-width', '87');
  assert.equal(await page.inputValue('#raw-height'), '61', 'the height follows from the width');
  await page.click('#raw-form button[type=submit]');
  await terrainName(page, 'volcano.r16');
  state = await page.evaluate(() => window.hexlod);
  assert.deepEqual([state.terrain.width, state.terrain.height, state.error], [87, 61, null]);
  assert.ok(Math.abs(state.terrain.maxHeight - 195) < 0.01, 'metres from the sidecar range');
  await settled(page);
  assert.deepEqual(problems, []);
  await page.close();
});

test('?src=URL opens that file at start-up; a bad URL falls back to the default terrain with its message', async () => {
  const src = `/@fs${FIXTURES}everest_i16_strips.tif`;
  const { page, problems } = await openPage(viewer.browser, quick(`&src=${encodeURIComponent(src)}`));
  await ready(page);
  let state = await page.evaluate(() => window.hexlod);
  assert.equal(state.status, 'ready', state.error);
  assert.deepEqual([state.terrain.name, state.terrain.width], ['everest_i16_strips.tif', 200]);
  assert.ok(state.terrain.maxHeight > 8000, 'Everest');
  assert.deepEqual(problems, []);
  await page.close();

  const missing = await openPage(viewer.browser, quick('&src=/nothing/here.hgt'));
  await ready(missing.page);
  state = await missing.page.evaluate(() => window.hexlod);
  assert.equal(state.terrain.name, 'globe_himalaya_2048.png');
  assert.match(state.error, /^here\.hgt: cannot fetch \/nothing\/here\.hgt \((HTTP 404|the server sent an HTML page)\)$/);
  await missing.page.close();
});
