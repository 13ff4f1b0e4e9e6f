// The control panel drives the core: a larger τ draws fewer triangles, a larger budget refines
// further in the same frames, freeze LOD keeps the mesh while the camera moves, and the panel's
// inputs reach the settings.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { startViewer, openPage, outDir, pixelStats, dropFiles, terrainShown, projectDir, drawFrames, nextFrame } from '../../lib/page_harness.js';

let viewer, page, problems;
// The pages open at a 50 ms frame budget: SwiftShader draws about a frame a second, and at the
// default 4 ms the default view takes some 160 frames to converge. The budget test sets its own.
before(async () => {
  viewer = await startViewer({ pixelRatio: 0.5 });
  ({ page, problems } = await openPage(viewer.browser, `${viewer.url}?budget=50`, { width: 480, height: 300 }));
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
});
after(async () => { await viewer?.close(); });

const frames = (n, on = page) => drawFrames(on, n);
const converged = () => page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged; },
  null, { timeout: 240000, polling: 100 });
// Converged, and no operation in 10 frames: a merge that completes can free a blocked neighbour
// whose own fade then starts, so one converged frame can still be followed by a few merges.
async function settled() {
  for (let attempt = 0; attempt < 30; attempt++) {
    await converged();
    const before = await triangles();
    await frames(10);
    if (await page.evaluate(() => window.hexlod.converged) && await triangles() === before) return;
  }
  assert.fail('the mesh never held still for 10 frames');
}
// Tests that judge triangle counts, not pixels, run in a quarter of the pixels: SwiftShader's
// frame time follows the triangles drawn, and at a given τ a smaller window needs fewer.
// A frame at the new size first: until then "converged" is the old size's.
const resize = async (width, height) => { await page.setViewportSize({ width, height }); await nextFrame(page); };
const small = () => resize(240, 150);
const full = () => resize(480, 300);
const set = (key, value) => page.evaluate(([k, v]) => window.hexlod.setSetting(k, v), [key, value]);
const triangles = () => page.evaluate(() => window.hexlod.triangles);

test('τ: a larger tolerance converges to fewer triangles, a smaller one to more', async () => {
  await small();
  await set('budgetMs', 50); // converge in few frames
  await converged();
  const atOne = await triangles();
  await set('tau', 4);
  await converged();
  const atFour = await triangles();
  await set('tau', 0.5);
  await converged();
  const atHalf = await triangles();
  assert.ok(atFour < atOne && atOne < atHalf, `triangles at τ 4, 1, 0.5: ${atFour}, ${atOne}, ${atHalf}`);
  await set('tau', 1);
  await full();
});

test('budget: more operations or milliseconds per frame refine further in the same frames', async () => {
  const after = async (key, value) => {
    await set('budgetMs', 50);
    await set(key, value);
    await set('embedding', 'exact'); // a fresh base mesh
    await frames(3);
    return triangles();
  };
  const fewOps = await after('maxOperations', 20), manyOps = await after('maxOperations', 2000);
  assert.ok(manyOps > fewOps, `20 then 2000 operations a frame: ${fewOps}, ${manyOps} triangles`);
  await set('maxOperations', 0);
  const short = await after('budgetMs', 0.5), long = await after('budgetMs', 40);
  assert.ok(long > short, `0.5 then 40 ms a frame: ${short}, ${long} triangles`);
  await set('budgetMs', 50);
});

test('freeze LOD keeps the mesh while the camera moves; thawing refines for the new view', async () => {
  await set('budgetMs', 50);
  await converged();
  await set('freeze', true);
  const frozen = await triangles();
  await page.evaluate(() => { const c = window.hexlod.rig.cameras.orbit; c.yaw += 1.2; c.distance *= 0.4; });
  await frames(4);
  assert.equal(await triangles(), frozen, 'a frozen mesh keeps its triangles');
  await page.screenshot({ path: `${outDir}/controls-frozen.png` });
  await set('freeze', false);
  await frames(4);
  assert.notEqual(await triangles(), frozen, 'thawed, the mesh follows the camera');
});

test('the panel edits the settings; the HUD shows the figures', async () => {
  await page.evaluate(() => window.hexlod.setSetting('tau', 1));
  // A small viewport starts with the panel folded: unfold it, then type into τ's number box.
  await page.click('#panel .lil-gui.lil-root > .lil-title');
  const box = page.locator('.lil-gui .lil-controller', { hasText: 'error τ' }).locator('input').last();
  await box.fill('2.5');
  await box.press('Enter');
  assert.equal(await page.evaluate(() => window.hexlod.settings.tau), 2.5);
  await frames(2);
  const hud = await page.evaluate(() => ({ text: document.getElementById('hud').textContent, values: window.hexlod.hud }));
  for (const pattern of [/\d+ fps|idle/, /frame \d+\.\d ms/, /LOD \d+\.\d ms/, /[\d,]+ triangles/, /full, [\d,]+ semi/, /vertices/,
    /splits, [\d,]+ merges/, /core \d+\.\d MB/, /B\/triangle/, /screen error \d+\.\d\d px/]) {
    assert.match(hud.text, pattern);
  }
  assert.ok(hud.values.full > 0 && hud.values.semi > 0 && hud.values.bytesPerTriangle > 0);
  await page.evaluate(() => window.hexlod.setSetting('tau', 1));
  assert.deepEqual(problems, []);
});

test('a refused value keeps the previous one everywhere and says why; the terrain stays', async () => {
  await small();
  await set('budgetMs', 50);
  await settled();
  const before = await page.evaluate(() => ({ tau: window.hexlod.settings.tau, cellSize: window.hexlod.settings.cellSize,
    triangles: window.hexlod.triangles, name: window.hexlod.terrain.name }));
  for (const [key, value, message] of [['tau', -2, /tau=-2 is not a number from 0.25 to 16/], ['cellSize', 0, /cell size must be a positive/],
    ['shading', 'sepia', /shading must be one of natural/], ['freeze', 'yes', /freeze is on or off/]]) {
    await set(key, value);
    const status = await page.evaluate(() => document.getElementById('status').textContent);
    assert.match(status, message, `${key} = ${value}`);
    assert.notEqual(await page.evaluate((k) => window.hexlod.settings[k], key), value, `${key} kept its value`);
  }
  await frames(3);
  const after = await page.evaluate(() => ({ tau: window.hexlod.settings.tau, cellSize: window.hexlod.settings.cellSize,
    triangles: window.hexlod.triangles, name: window.hexlod.terrain.name }));
  assert.deepEqual(after, before, 'the settings, the terrain and its mesh are as before');
  await set('tau', 2); // a good value afterwards still applies
  assert.equal(await page.evaluate(() => window.hexlod.settings.tau), 2);
  assert.equal(await page.evaluate(() => document.getElementById('status').textContent), '');
  await set('tau', 1);
  await full();
});

// The intake bar's spacing field (hidden on a phone, where the panel's cell size is the control).
test('the spacing field: shows both spacings of non-square cells, scales them together in place, refuses bad values', async () => {
  // Wider than a phone (600 px), where the field shows.
  const { page: wide, problems: wideProblems } = await openPage(viewer.browser, `${viewer.url}?budget=50`, { width: 640, height: 400 });
  await wide.waitForFunction(() => window.hexlod && window.hexlod.status === 'ready', null, { timeout: 120000 });
  const readout = () => wide.evaluate(() => {
    const t = window.hexlod.terrainObject();
    const ratio = document.getElementById('spacing-ratio');
    return { x: t.spacingX, y: t.spacingY, cellSize: window.hexlod.settings.cellSize, field: document.getElementById('spacing-input').value,
      ratio: ratio.textContent, ratioHidden: ratio.hidden, status: document.getElementById('status').textContent,
      distance: window.hexlod.rig.cameras.orbit.distance, name: window.hexlod.terrain.name };
  });
  const apply = async (text) => {
    await wide.fill('#spacing-input', text);
    await wide.click('#spacing-form button[type=submit]');
    await frames(2, wide);
    return readout();
  };
  // The default terrain's sidecar gives 806.9 m east-west and 926 m north-south.
  const start = await readout();
  assert.deepEqual([start.x, start.y, start.field, start.ratioHidden], [806.9, 926, '806.9', false]);
  assert.match(start.ratio, /926 m north–south/);

  // Apply unchanged: nothing changes (it used to reload the file with square 806.9 m cells).
  let now = await apply('806.9');
  assert.deepEqual([now.x, now.y, now.distance, now.name], [start.x, start.y, start.distance, start.name]);

  // Twice the spacing: both double, in place, and the camera keeps its framing (its distance doubles).
  now = await apply('1613.8');
  assert.equal(now.x, 1613.8);
  assert.ok(Math.abs(now.y - 1852) < 1e-9, `north-south kept its ratio: ${now.y}`);
  assert.equal(now.cellSize, 1613.8, 'the panel\'s cell size is the same setting');
  assert.ok(Math.abs(now.distance / start.distance - 2) < 1e-9, `the orbit scaled with the ground: ${now.distance}`);
  assert.match(now.ratio, /1852 m north–south/);
  assert.equal(now.status, '');
  await frames(5, wide);
  const stats = pixelStats(await wide.screenshot({ path: `${outDir}/controls-spacing-doubled.png` }));
  assert.ok(stats.colours > 60 && stats.skyFraction < 0.6, `the terrain is on screen: ${JSON.stringify(stats)}`);

  // Bad values: the page says why; the spacing, the field and the camera stay.
  for (const [text, message] of [['-5', /cell size must be a positive/], ['0', /cell size must be a positive/], ['', /type the metres/]]) {
    const after = await apply(text);
    assert.match(after.status, message, `'${text}'`);
    assert.deepEqual([after.x, after.y, after.cellSize, after.field, after.distance], [now.x, now.y, now.cellSize, '1613.8', now.distance],
      `'${text}' changed nothing`);
  }

  // The panel's cell size shows in the field too; back to the file's spacing.
  await wide.evaluate(() => window.hexlod.setSetting('cellSize', 806.9));
  now = await readout();
  assert.deepEqual([now.x, now.field, now.status], [806.9, '806.9', '']);
  assert.ok(Math.abs(now.y - 926) < 1e-9);
  assert.match(now.ratio, /926 m north–south/);
  assert.equal(await wide.evaluate(() => document.getElementById('spacing-form').classList.contains('assumed')), false);

  // A file that gives no spacing: the guess is outlined until the user sets one.
  await dropFiles(wide, [{ name: 'volcano_maungawhau.png', bytes: readFileSync(`${projectDir}tests/fixtures/volcano_maungawhau.png`) }]);
  await terrainShown(wide, 'volcano_maungawhau.png');
  const outlined = () => wide.evaluate(() => document.getElementById('spacing-form').classList.contains('assumed'));
  now = await readout();
  assert.equal(now.x, now.y, 'a guessed spacing is square');
  assert.deepEqual([now.field, now.ratioHidden, await outlined()], [String(now.x), true, true]);
  assert.match((await apply('-1')).status, /cell size must be a positive/);
  assert.equal(await outlined(), true, 'a refused value is no answer');
  now = await apply('10');
  assert.deepEqual([now.x, now.y, now.field, now.status, await outlined()], [10, 10, '10', '', false]);
  assert.deepEqual(wideProblems, []);
  await wide.close();
});
