// The page survives what a person's browser does to it: a lost WebGL context comes back
// without a reload, screenshots save PNGs at 1x and 2x, and a phone-sized viewport fits.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, outDir, pixelStats, drawFrames } from '../../lib/page_harness.js';

let viewer;
before(async () => { viewer = await startViewer(); });
after(async () => { await viewer?.close(); });

const ready = (page) => page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });

test('a lost WebGL context is restored without a reload; screenshots save 1x and 2x PNGs', async () => {
  const { page, problems } = await openPage(viewer.browser, viewer.url, { width: 480, height: 300 });
  await ready(page);
  await drawFrames(page, 3);
  const before = await page.evaluate(() => window.hexlod.triangles);
  await page.evaluate(() => {
    window.loseContext = document.getElementById('view').getContext('webgl2').getExtension('WEBGL_lose_context');
    window.loseContext.loseContext();
  });
  await page.waitForFunction(() => window.hexlod.contextLost, null, { timeout: 10000 });
  await page.evaluate(() => window.loseContext.restoreContext());
  await page.waitForFunction(() => !window.hexlod.contextLost && window.hexlod.contextRestores === 1, null, { timeout: 30000 });
  await drawFrames(page, 3);
  const state = await page.evaluate(() => ({ glError: window.hexlod.glError(), triangles: window.hexlod.triangles,
    uploaded: window.hexlod.uploadBytes, status: document.getElementById('status').textContent }));
  assert.equal(state.glError, 0);
  assert.ok(state.triangles >= before * 0.5, 'the core kept its mesh');
  assert.equal(state.status, '');
  const png = await page.screenshot({ path: `${outDir}/robust-restored.png` });
  const stats = pixelStats(png);
  assert.ok(stats.colours > 60 && stats.skyFraction < 0.6, `the terrain is drawn again: ${JSON.stringify(stats)}`);

  for (const scale of [1, 2]) {
    const [download] = await Promise.all([page.waitForEvent('download'), page.evaluate((s) => window.hexlod.screenshot(s), scale)]);
    const path = `${outDir}/robust-screenshot-${scale}x.png`;
    await download.saveAs(path);
    const image = decode(readFileSync(path));
    assert.deepEqual([image.width, image.height], [480 * scale, 300 * scale], `${scale}x screenshot size`);
    assert.ok(pixelStats(readFileSync(path)).colours > 60, `the ${scale}x screenshot shows the terrain`);
  }
  assert.deepEqual(problems, []);
  await page.close();
});

test('a phone-sized viewport: the canvas fills it, the panel folds and unfolds, nothing overflows', async () => {
  const { page, problems } = await openPage(viewer.browser, viewer.url, { width: 390, height: 844 });
  await ready(page);
  const overflow = () => page.evaluate(() => {
    const out = [];
    for (const id of ['hud', 'side', 'status', 'view']) {
      const r = document.getElementById(id).getBoundingClientRect();
      if (r.width && (r.left < -1 || r.top < -1 || r.right > innerWidth + 1 || r.bottom > innerHeight + 1)) out.push(`${id} ${JSON.stringify(r)}`);
    }
    const canvas = document.getElementById('view').getBoundingClientRect();
    return { out, canvas: [canvas.width, canvas.height], scroll: [document.documentElement.scrollWidth, document.documentElement.scrollHeight],
      closed: document.querySelector('#panel .lil-gui.lil-root').classList.contains('lil-closed') };
  });
  let layout = await overflow();
  assert.deepEqual(layout.canvas, [390, 844]);
  assert.deepEqual(layout.out, []);
  assert.ok(layout.scroll[0] <= 390 && layout.scroll[1] <= 844, `the page scrolls: ${layout.scroll}`);
  assert.equal(layout.closed, true, 'the panel starts folded on a phone');
  await page.click('#panel .lil-gui.lil-root > .lil-title');
  layout = await overflow();
  assert.equal(layout.closed, false);
  assert.deepEqual(layout.out, [], 'the unfolded panel stays on screen');
  await page.screenshot({ path: `${outDir}/robust-phone.png` });
  assert.deepEqual(problems, []);
  await page.close();
});
