// A valley floor anywhere on a world DEM is drawn as precisely as at its centre. The virtual world
// COG of lib/world_cog_server.js (1,296,000 x 626,400 samples at 1″), its heights rolling hills
// that repeat every 192 samples east-west, is viewed from 3 m above a sample at 45° N three
// times: at the field's centre (0° E, where the drawn frame's numbers are small), and 176.8° W
// and 172° E, 40,000 km from the first sample in flat metres and 12,000 km from the drawn
// frame's origin. The ellipsoid is the same at every longitude, and so are the hills: the three
// skylines must be one. Floats keep those distances to metres, so unless the page draws
// relative to the eye (shaders/terrain.vert, web/render/shading/eye_anchor.js) the far ones
// are lost: hills flattened into noise a metre deep.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { writeFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, pageReady, nextFrame, outDir } from '../../lib/page_harness.js';
import { startWorldCogServer } from '../../lib/world_cog_server.js';

const VIEW = { width: 480, height: 300 };
const PERIOD = 192; // samples: every term below repeats after it east-west
const ROW = 162000; // 45° N
const EYE = 3; // metres above the sample under the camera
const HIDE_BOXES = '#hud, #side, #drop-hint, #status, #intake, #panel { display: none !important; }';

/** Rolling hills, 70 m deep, 2 to 3 km across: the same east-west every PERIOD samples. */
function hills(lon, lat) {
  const column = (lon + 180) * 3600 - 0.5, row = (90 - lat) * 3600 - 0.5; // the full resolution's sample indices
  return Math.round(800 + 30 * Math.sin((2 * Math.PI * column) / 64) + 25 * Math.cos((2 * Math.PI * row) / 40)
    + 12 * Math.sin((2 * Math.PI * (column + row)) / 96));
}
const heightAt = (column, row) => hills(-180 + (column + 0.5) / 3600, 90 - (row + 0.5) / 3600);

let viewer, world;
before(async () => { [viewer, world] = await Promise.all([startViewer(), startWorldCogServer({ heights: hills })]); });
after(async () => { await Promise.all([viewer?.close(), world?.close()]); });

/**
 * The first row from the top where the terrain is drawn, per column (the terrain alone, in one
 * colour), and how many columns of the bottom row it covers.
 */
async function skyline(page) {
  await page.evaluate(() => { window.hexlod.view.terrainMask = true; });
  await nextFrame(page);
  const { width, height, data, channels } = decode(await page.screenshot());
  await page.evaluate(() => { window.hexlod.view.terrainMask = false; });
  const rows = [];
  for (let x = 0; x < width; x++) {
    let y = 0;
    while (y < height && data[(y * width + x) * channels] < 128) y++;
    rows.push(y);
  }
  let floor = 0;
  for (let x = 0; x < width; x++) floor += data[((height - 1) * width + x) * channels] >= 128 ? 1 : 0;
  return { rows, floor };
}

/** Flies to 3 m above sample (column, ROW), looking north-east and a little down, and waits for the view to settle. */
async function standAt(page, column) {
  await page.evaluate(({ column, row, height }) => {
    const { rig, terrainObject } = window.hexlod, t = terrainObject(), fly = rig.cameras.fly;
    fly.position[0] = column * t.spacingX, fly.position[1] = height, fly.position[2] = row * t.spacingY;
    fly.yaw = 1.1, fly.pitch = -0.12;
    rig.active = fly;
    window.hexlod.requestRender();
  }, { column, row: ROW, height: heightAt(column, ROW) + EYE });
  // Settled twice, a frame apart: every tile in view in, the mesh converged on them (not on a
  // coarser level that a tile still awaited stands for).
  const settled = () => page.waitForFunction(() => {
    const h = window.hexlod;
    return h.converged && h.tiles?.settled && h.tiles.waiting === 0 && h.hud?.errorProvisional === false;
  }, null, { timeout: 240000, polling: 250 });
  await settled();
  await nextFrame(page);
  await settled();
}

test('3 m above a valley floor at 172° E and 176.8° W the world COG is drawn as at its centre', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?src=${encodeURIComponent(world.url)}&exag=1&tau=1&budget=50`, VIEW);
  await pageReady(page);
  assert.equal(await page.evaluate(() => window.hexlod.status), 'ready', await page.evaluate(() => window.hexlod.error));
  await page.addStyleTag({ content: HIDE_BOXES });
  const centre = 648000; // 0° E
  assert.equal(centre % PERIOD, 0);
  await standAt(page, centre);
  const { rows: reference, floor } = await skyline(page);
  await nextFrame(page);
  writeFileSync(`${outDir}/world_precision_centre.png`, await page.screenshot());
  // The valley floor under the eye is drawn, to the view's bottom edge 5 m away (the near plane
  // follows the eye's height, not the field's 40,000 km).
  assert.equal(floor, VIEW.width, 'the ground fills the bottom row');
  // The hills stand above the horizon over part of the view, and the sky is above them.
  const sky = reference.filter((y) => y > 0 && y < VIEW.height).length;
  assert.ok(sky > 0.9 * VIEW.width, `the skyline crosses the view (${sky} columns)`);
  const spread = Math.max(...reference) - Math.min(...reference);
  assert.ok(spread >= 8, `hills stand out of the skyline by ${spread} px`);
  for (const column of [60 * PERIOD, 6600 * PERIOD]) {
    await standAt(page, column);
    const { rows, floor: under } = await skyline(page);
    await nextFrame(page);
    writeFileSync(`${outDir}/world_precision_${column}.png`, await page.screenshot());
    assert.equal(under, VIEW.width, 'the ground fills the bottom row');
    const off = rows.map((y, x) => Math.abs(y - reference[x]));
    const within = off.filter((d) => d <= 1).length / off.length;
    const mean = off.reduce((a, b) => a + b, 0) / off.length;
    const lon = -180 + column / 3600;
    console.log(`world precision at ${lon.toFixed(1)}°: skyline within 1 px of the centre's in ${(100 * within).toFixed(1)} % of columns, mean ${mean.toFixed(2)} px`);
    assert.ok(within >= 0.95 && mean <= 0.8, `at ${lon.toFixed(1)}° the skyline is within 1 px of the centre's in ` +
      `${(100 * within).toFixed(1)} % of columns (mean ${mean.toFixed(2)} px)`);
  }
  assert.deepEqual(problems, []);
  await page.close();
});
