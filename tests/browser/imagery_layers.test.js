// Image layers in other CRSs, several at once, by what a person sees: a real UTM DEM dropped
// with the Blue Marble image in EPSG:4326 shows the image's colours at known ground points
// (expected values from GDAL: tests/fixtures/reprojection/expected.json); the same image in
// Web Mercator dropped over it adds a second layer; the panel hides, shows, fades, reorders and
// removes them, and the pixels and the HUD follow; a fifth visible layer is refused with a message.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { decode } from 'fast-png';
import { readFileSync } from 'node:fs';
import { startViewer, openPage, dropFiles, terrainShown, outDir, FULL_RESOLUTION } from '../../lib/page_harness.js';
import { colourAt, coloursMatch, lookStraightDown, screenPoint } from '../../lib/draped_points.js';

let viewer;
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

const dir = new URL('../fixtures/reprojection/', import.meta.url);
const expected = JSON.parse(readFileSync(new URL('expected.json', dir), 'utf8'));
const fixture = (name) => ({ name, bytes: new Uint8Array(readFileSync(new URL(name, dir))) });
const VIEW = 600;

/** Screen pixels of the expected ground points (UTM x, y) on the terrain as drawn now. */
async function groundPixels(page) {
  const { dem } = expected;
  const samples = expected.points.map((p) => [(p.x - dem.x0) / dem.dx, (p.y - dem.y0) / dem.dy]);
  const view = await page.evaluate((samples) => {
    const h = window.hexlod, t = h.terrainObject();
    const points = samples.map(([column, row]) => {
      const x = column * t.spacingX, z = row * t.spacingY;
      return h.drawnPoint(x, t.heightAt(x, z) * h.settings.exaggeration, z);
    });
    return { m: Array.from(h.camera.viewProjection), width: innerWidth, height: innerHeight, points };
  }, samples);
  return view.points.map((p) => screenPoint(view.m, p, view.width, view.height));
}

async function shot(page, label) {
  for (let i = 0; i < 3; i++) await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
  return decode(await page.screenshot(label ? { path: `${outDir}/layers-${label}.png` } : {}));
}

/** Clicks a control of the layer's row in the panel: 'visible' (the checkbox) or a button by its label. */
async function panelClick(page, layerId, control) {
  await page.evaluate(([id, control]) => {
    const row = document.querySelector(`#panel [data-layer-id="${id}"]`);
    if (control === 'visible') row.querySelector('input[type=checkbox]').click();
    else [...row.querySelectorAll('button')].find((b) => b.textContent.trim() === control).click();
  }, [layerId, control]);
}

test('a UTM DEM with images in EPSG:4326 and 3857: reprojected where GDAL puts them, as layers the panel orders, hides, fades and removes', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1`, { width: VIEW, height: VIEW }, FULL_RESOLUTION);
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });
  await dropFiles(page, [fixture(expected.dem.file)]);
  await terrainShown(page, expected.dem.file);
  await lookStraightDown(page, 9e5);
  const at = await groundPixels(page);
  for (const p of at) assert.ok(p[0] > 0 && p[0] < VIEW && p[1] > 0 && p[1] < VIEW, `ground point on screen at ${p}`);
  const bare = await shot(page);

  // The image in EPSG:4326 dropped alone on the UTM terrain: reprojected onto it.
  await dropFiles(page, [fixture(expected.images['4326'].file)]);
  await page.waitForFunction(() => window.hexlod.imageLayers.length === 1, null, { timeout: 60000 });
  const first = await page.evaluate(() => ({ image: window.hexlod.image, status: document.getElementById('status').textContent }));
  assert.equal(first.image.how, 'reprojected');
  assert.ok(first.image.maxWarpError <= 0.25, `the control grid within a quarter texel (${first.image.maxWarpError})`);
  assert.ok(first.image.coverage > 0.99, `it covers the DEM (${first.image.coverage})`);
  assert.match(first.status, /bmng_himalaya_4326\.tif: reprojected from EPSG:4326 to EPSG:32645/);
  assert.ok(first.image.metresPerPixel > 6400 && first.image.metresPerPixel < 6550, `1/15° across at 29° N: ${first.image.metresPerPixel} m`);
  const geographic = await shot(page, 'utm-4326');
  expected.points.forEach((p, k) => assert.ok(coloursMatch(colourAt(geographic, at[k]), p.rgb4326, 16),
    `${p.lon.toFixed(3)} E ${p.lat.toFixed(3)} N at ${at[k]}: ${colourAt(geographic, at[k])}, gdal has ${p.rgb4326}`));

  // The same in Web Mercator over it: a second layer, on top.
  await dropFiles(page, [fixture(expected.images['3857'].file)]);
  await page.waitForFunction(() => window.hexlod.imageLayers.length === 2, null, { timeout: 60000 });
  const layers = await page.evaluate(() => window.hexlod.imageLayers);
  assert.deepEqual(layers.map((l) => [l.name, l.visible, l.opacity]), [['bmng_himalaya_4326.tif', true, 1], ['bmng_himalaya_3857.tif', true, 1]]);
  const hudLines = () => page.evaluate(() => document.querySelector('#hud .hud-image').textContent.split('\n'));
  assert.deepEqual((await hudLines()).map((l) => l.split('  ')[0]), ['image bmng_himalaya_4326.tif', 'image bmng_himalaya_3857.tif']);
  const mercator = await shot(page, 'utm-3857');
  expected.points.forEach((p, k) => assert.ok(coloursMatch(colourAt(mercator, at[k]), p.rgb3857, 16),
    `3857 at ${at[k]}: ${colourAt(mercator, at[k])}, gdal has ${p.rgb3857}`));

  // Both hidden in the panel: the bare ground; the bottom one shown again: its colours.
  const [bottom, top] = layers.map((l) => l.id);
  await panelClick(page, top, 'visible');
  await panelClick(page, bottom, 'visible');
  const hidden = await shot(page);
  at.forEach((p) => assert.ok(coloursMatch(colourAt(hidden, p), colourAt(bare, p), 4), `hidden: the ground at ${p}`));
  await panelClick(page, bottom, 'visible');
  const shownAgain = await shot(page);
  expected.points.forEach((p, k) => assert.ok(coloursMatch(colourAt(shownAgain, at[k]), p.rgb4326, 16), `shown again at ${at[k]}`));

  // Half opacity, typed into the layer's opacity field: halfway between the ground and the image.
  await page.evaluate((id) => {
    const field = document.querySelector(`#panel [data-layer-id="${id}"] .lil-controller.lil-number input`);
    field.value = '0.5';
    field.dispatchEvent(new Event('input'));
    field.dispatchEvent(new Event('change'));
  }, bottom);
  assert.equal(await page.evaluate((id) => window.hexlod.imageLayers.find((l) => l.id === id).opacity, bottom), 0.5);
  const faded = await shot(page);
  expected.points.forEach((p, k) => {
    const want = p.rgb4326.map((v, c) => (v + colourAt(bare, at[k])[c]) / 2);
    assert.ok(coloursMatch(colourAt(faded, at[k]), want, 16), `half opacity at ${at[k]}: ${colourAt(faded, at[k])}, want ${want}`);
  });

  // Reordered by the panel: the Mercator layer to the bottom; the HUD follows.
  await panelClick(page, top, 'visible');
  await panelClick(page, top, 'move down');
  await page.waitForFunction((id) => window.hexlod.imageLayers[0].id === id, top, { timeout: 10000 });
  assert.deepEqual((await hudLines()).map((l) => l.split('  ')[0]), ['image bmng_himalaya_3857.tif', 'image bmng_himalaya_4326.tif']);

  // At most four show at once: a fifth is added hidden, and showing it is refused by name.
  for (let i = 0; i < 3; i++) {
    await dropFiles(page, [fixture(expected.images['3857'].file)]);
    await page.waitForFunction((n) => window.hexlod.imageLayers.length === n, 3 + i, { timeout: 60000 });
  }
  const five = await page.evaluate(() => ({ layers: window.hexlod.imageLayers, status: document.getElementById('status').textContent }));
  assert.deepEqual(five.layers.map((l) => l.visible), [true, true, true, true, false]);
  assert.match(five.status, /bmng_himalaya_3857\.tif: reprojected from EPSG:3857 to EPSG:32645; added hidden; at most 4 image layers show at once/);
  await panelClick(page, five.layers[4].id, 'visible');
  assert.match(await page.evaluate(() => document.getElementById('status').textContent), /at most 4 image layers show at once; hide one first/);
  assert.equal(await page.evaluate(() => window.hexlod.imageLayers[4].visible), false);

  // Removed one by one from the panel: the ground as it was.
  for (const layer of five.layers) await panelClick(page, layer.id, 'remove layer');
  await page.waitForFunction(() => window.hexlod.imageLayers.length === 0, null, { timeout: 10000 });
  const removed = await shot(page);
  at.forEach((p) => assert.ok(coloursMatch(colourAt(removed, p), colourAt(bare, p), 4), `removed: the ground at ${p}`));
  assert.ok(!(await page.isVisible('#hud .hud-image')), 'no layer lines in the HUD');
  assert.equal(await page.evaluate(() => window.hexlod.terrain.name), expected.dem.file);
  assert.deepEqual(problems, []);
  await page.close();
});
