// A real satellite image (NASA Blue Marble, tests/fixtures/imagery/) draped on the default
// terrain by its world file, judged by pixels: known ground points (a sea, a desert, a plain)
// are projected to the screen and the colour there is the image's; the same view with the image
// cut into small tiles (?imagetile=64) draws the same pixels; and a refused image (another CRS)
// keeps the one on screen.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { decode } from 'fast-png';
import { readFileSync } from 'node:fs';
import { startViewer, openPage, dropFiles, terrainShown } from '../../lib/page_harness.js';
import { BLUE_MARBLE_POINTS as POINTS, groundPoint, screenPoint, colourAt, coloursMatch } from '../../lib/draped_points.js';

/** Opens the page, drapes the Blue Marble crop unlit from straight above, and returns the screenshot and the points' pixels. */
async function drapedView(viewer, query = '') {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1${query}`, { width: 800, height: 800 });
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });
  const draped = await page.evaluate(async (base) => {
    const get = async (name) => ({ name, blob: await (await fetch(base + name)).blob() });
    const d = await window.hexlod.images.drape(await get('bmng_himalaya_4arcmin.jpg'), await get('bmng_himalaya_4arcmin.jgw'));
    return d && { width: d.width, height: d.height, coverage: d.placement.coverage };
  }, `${viewer.fixturesUrl}imagery/`);
  await page.evaluate(() => {
    const h = window.hexlod;
    h.setSetting('imageUnlit', true);
    h.setSetting('camera', 'orbit');
    const t = h.terrainObject(), orbit = h.rig.cameras.orbit;
    const x = ((t.width - 1) * t.spacingX) / 2, z = ((t.height - 1) * t.spacingY) / 2;
    orbit.target[0] = x; orbit.target[1] = 0; orbit.target[2] = z;
    orbit.yaw = 0; orbit.pitch = 1.55; orbit.distance = 3.2e6;
    h.setSetting('freeze', false);
    h.requestRender();
  });
  for (let i = 0; i < 4; i++) await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
  const png = decode(await page.screenshot());
  const view = await page.evaluate(() => {
    const h = window.hexlod, t = h.terrainObject();
    return { m: Array.from(h.camera.viewProjection), spacingX: t.spacingX, spacingY: t.spacingY, width: innerWidth, height: innerHeight };
  });
  const pixels = {};
  for (const [name, [lon, lat]] of Object.entries(POINTS)) {
    pixels[name] = screenPoint(view.m, groundPoint(lon, lat, view.spacingX, view.spacingY), view.width, view.height);
  }
  return { page, problems, png, draped, pixels };
}

test('a satellite image placed by its world file shows its colours at known ground points, tiled or not', async () => {
  const viewer = await startViewer();
  try {
    const whole = await drapedView(viewer);
    assert.deepEqual(whole.draped, { width: 256, height: 257, coverage: 1 });
    for (const [name, [, , expected]] of Object.entries(POINTS)) {
      const at = whole.pixels[name], got = colourAt(whole.png, at);
      assert.ok(at[0] > 0 && at[0] < 800 && at[1] > 0 && at[1] < 800, `${name} is on screen at ${at}`);
      assert.ok(coloursMatch(got, expected, 24), `${name} at ${at}: ${got}, the image has ${expected}`);
    }
    assert.deepEqual(whole.problems, []);

    // Cut into 64-pixel tiles with aprons and an overview: the same picture.
    const tiled = await drapedView(viewer, '&imagetile=64');
    let differing = 0, largest = 0;
    for (let i = 0; i < whole.png.data.length; i += whole.png.channels) {
      const d = Math.max(...[0, 1, 2].map((k) => Math.abs(whole.png.data[i + k] - tiled.png.data[i + k])));
      if (d > 8) differing++;
      largest = Math.max(largest, d);
    }
    assert.ok(differing / (800 * 800) < 0.01, `${(100 * differing / 640000).toFixed(2)} % of pixels differ by more than 8 (largest ${largest})`);

    // An image in another CRS is refused by name; the Blue Marble stays.
    const refused = await tiled.page.evaluate(async (base) => {
      const blob = await (await fetch(`${base}haiti_rgb_5m_tiled_deflate.tif`)).blob();
      await window.hexlod.images.drape({ name: 'haiti.tif', blob }, null);
      return { status: document.getElementById('status').textContent, still: window.hexlod.images.current?.name };
    }, `${viewer.fixturesUrl}imagery/`);
    assert.match(refused.status, /^haiti\.tif: it is in EPSG:32618 and the terrain in EPSG:4326/);
    assert.equal(refused.still, 'bmng_himalaya_4arcmin.jpg');
  } finally {
    await viewer.close();
  }
});

const fixture = (path) => ({ name: path.split('/').pop(), bytes: new Uint8Array(readFileSync(new URL(`../fixtures/${path}`, import.meta.url))) });

test('dropped with its DEM in either order, the image drapes it; a new DEM alone takes the image away', async () => {
  const viewer = await startViewer();
  try {
    const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1`, { width: 640, height: 400 });
    await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });
    const dem = fixture('formats/everest_i16_strips.tif');
    const image = [fixture('imagery/bmng_everest_4arcmin.jpg'), fixture('imagery/bmng_everest_4arcmin.jgw')];
    for (const files of [[dem, ...image], [...image.reverse(), dem]]) {
      await dropFiles(page, files);
      await terrainShown(page, 'everest_i16_strips.tif');
      await page.waitForFunction(() => window.hexlod.images.current !== null, null, { timeout: 60000 });
      const draped = await page.evaluate(() => ({ name: window.hexlod.images.current.name, coverage: window.hexlod.images.current.placement.coverage }));
      assert.equal(draped.name, 'bmng_everest_4arcmin.jpg');
      assert.ok(draped.coverage > 0.99, `the image covers the Everest field (${draped.coverage})`);
    }
    await dropFiles(page, [fixture('formats/everest_16bit.png')]);
    await terrainShown(page, 'everest_16bit.png');
    assert.equal(await page.evaluate(() => window.hexlod.images.current), null, 'the old image went with the old ground');
    assert.deepEqual(problems, []);
  } finally {
    await viewer.close();
  }
});
