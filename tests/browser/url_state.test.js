// The URL holds the view: opening a link restores camera, τ, budget and exaggeration exactly;
// the page writes them back as the view moves; bad parameters get a message and the defaults.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startViewer, openPage } from '../../lib/page_harness.js';

let viewer;
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

const ready = (page) => page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
const viewOf = (page) => page.evaluate(() => {
  const h = window.hexlod, c = h.rig.active;
  return { mode: c.mode, position: Array.from(c.position).map((v) => Math.round(v * 1000) / 1000), yaw: c.yaw, pitch: c.pitch,
    tau: h.settings.tau, budget: h.settings.budgetMs, exag: h.settings.exaggeration, error: h.error };
});

test('a shared link restores the view exactly, and the page writes the moved view back', async () => {
  const link = `${viewer.url}?tau=2.5&budget=6&exag=3&cam=fly,1400000.5,30000.25,1100000.75,0.7,-0.2`;
  const first = await openPage(viewer.browser, link, { width: 480, height: 300 });
  await ready(first.page);
  const opened = await viewOf(first.page);
  assert.deepEqual(opened, { mode: 'fly', position: [1400000.5, 30000.25, 1100000.75], yaw: 0.7, pitch: -0.2,
    tau: 2.5, budget: 6, exag: 3, error: null });
  // Move the view, let the page write the address bar, and open that address in a new page.
  await first.page.evaluate(() => { const c = window.hexlod.rig.active; c.yaw = 1.234567; c.position[0] += 1234.5678; window.hexlod.requestRender(); });
  await first.page.waitForFunction(() => /1\.234567/.test(location.search), null, { timeout: 20000, polling: 100 });
  const moved = await viewOf(first.page);
  const shared = await first.page.evaluate(() => location.href);
  await first.page.close();
  const second = await openPage(viewer.browser, shared, { width: 480, height: 300 });
  await ready(second.page);
  assert.deepEqual(await viewOf(second.page), moved);
  assert.deepEqual([...first.problems, ...second.problems], []);
  await second.page.close();
});

test('bad parameters get a message, the defaults and a working page', async () => {
  const { page } = await openPage(viewer.browser, `${viewer.url}?tau=abc&budget=-3&exag=1e9&cam=orbit,1,2`, { width: 480, height: 300 });
  await ready(page);
  const state = await page.evaluate(() => ({ status: window.hexlod.status, error: window.hexlod.error,
    message: document.getElementById('status').textContent, settings: window.hexlod.settings, mode: window.hexlod.rig.mode }));
  assert.equal(state.status, 'ready');
  assert.match(state.error, /tau=abc is not a number from 0\.25 to 16/);
  assert.match(state.error, /budget=-3 is not a number/);
  assert.match(state.error, /exag=1e9 is not a number/);
  assert.match(state.error, /cam=orbit,1,2: 6 numbers needed/);
  assert.match(state.message, /defaults used/);
  assert.deepEqual([state.settings.tau, state.settings.budgetMs, state.settings.exaggeration, state.mode], [1, 4, 2, 'orbit']);
  await page.close();
});
