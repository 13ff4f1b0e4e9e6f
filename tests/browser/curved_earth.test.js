// The curved Earth in the page: a georeferenced terrain is drawn on WGS 84 (web/geo/earth_shape.js,
// shaders/earth.glsl), so from 10 km up the ground ends at the geometric horizon's dip, 3.2
// degrees below eye level; flattened (the Earth setting, ?earth=flat) the same plain reaches
// almost to eye level, its far edge 550 km away. Picking follows the drawn surface.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { decode } from 'fast-png';
import { startViewer, openPage, pageReady, nextFrame, converged, outDir } from '../../lib/page_harness.js';
import { writeFileSync } from 'node:fs';

let viewer;
before(async () => { viewer = await startViewer(); });
after(async () => { await viewer?.close(); });

const VIEW = { width: 640, height: 400 };
const EYE = 10000; // metres above the sea-level plain (heights 0 to 2 m)
const FOV_Y = (50 * Math.PI) / 180; // web/cameras/clip_planes.js
// WGS 84 by the textbook: the meridian's radius of curvature on the equator, a (1 - e^2).
const A = 6378137, E2 = (1 / 298.257223563) * (2 - 1 / 298.257223563);
const MERIDIAN = A * (1 - E2);

/** Puts the fly camera over the plain's centre, `EYE` up, looking level and north. */
async function flyLevelOverTheCentre(page) {
  await page.evaluate((eye) => {
    const { rig, terrainObject } = window.hexlod, t = terrainObject(), fly = rig.cameras.fly;
    fly.position[0] = 0.5 * (t.width - 1) * t.spacingX;
    fly.position[1] = eye;
    fly.position[2] = 0.5 * (t.height - 1) * t.spacingY;
    fly.yaw = 0;
    fly.pitch = 0;
    rig.active = fly;
    window.hexlod.requestRender();
  }, EYE);
}

/** The first row from the top where the terrain is drawn, per column (the terrain alone, in magenta). */
async function groundTopRows(page) {
  await page.evaluate(() => { window.hexlod.view.terrainMask = true; window.hexlod.requestRender(); });
  await nextFrame(page);
  const shot = decode(await page.screenshot());
  await page.evaluate(() => { window.hexlod.view.terrainMask = false; window.hexlod.requestRender(); });
  const { width, height, data, channels } = shot;
  const rows = [];
  // Columns left of the panel, clear of the file bar and the HUD's rows.
  for (let x = 20; x < 0.5 * width; x += 7) {
    for (let y = 60; y < height - 60; y++) {
      const k = (y * width + x) * channels;
      if (data[k] > 128 && data[k + 2] > 128 && data[k + 1] < 64) { rows.push({ x, y }); break; }
    }
  }
  return rows;
}

/**
 * The screen row (pixel rows from the top, fractional) of the direction `depression` radians
 * below eye level in column x: with screen tangents (tx, ty), tan(depression) = ty / sqrt(1 + tx^2).
 */
function rowBelowLevel(x, depression) {
  const pxPerTangent = (0.5 * VIEW.height) / Math.tan(0.5 * FOV_Y);
  const tx = (x + 0.5 - 0.5 * VIEW.width) / pxPerTangent;
  return 0.5 * VIEW.height + pxPerTangent * Math.tan(depression) * Math.sqrt(1 + tx * tx);
}

test('from 10 km up the curved ground ends at the horizon dip, 3.2 degrees down; flattened, near eye level', async () => {
  const src = `${viewer.fixturesUrl}earth/sea_level_10deg.tif`;
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?src=${encodeURIComponent(src)}&exag=1`, VIEW);
  await pageReady(page);
  assert.equal(await page.evaluate(() => window.hexlod.status), 'ready', await page.evaluate(() => window.hexlod.error));
  await flyLevelOverTheCentre(page);
  await converged(page);
  const dip = Math.acos(MERIDIAN / (MERIDIAN + EYE));
  const curved = await groundTopRows(page);
  writeFileSync(`${outDir}/curved_earth_horizon.png`, await page.screenshot());
  assert.ok(curved.length > 30, 'the ground is drawn across the view');
  // The first ground row's centre against the horizon's: a circle around the eye, lower on the
  // screen towards the sides.
  for (const { x, y } of curved) {
    const expected = rowBelowLevel(x, dip);
    assert.ok(Math.abs(y + 0.5 - expected) <= 2,
      `column ${x}: the ground ends at row ${y}; the horizon ${(dip * 180 / Math.PI).toFixed(2)} degrees down is at ${expected.toFixed(1)}`);
  }

  // Flattened: the far edge of the plane, half the field north, is all that bounds it.
  await page.evaluate(() => window.hexlod.setSetting('earth', 'flat'));
  await converged(page);
  const flat = await groundTopRows(page);
  const edge = await page.evaluate(() => { const t = window.hexlod.terrainObject(); return 0.5 * (t.height - 1) * t.spacingY; });
  for (const { x, y } of flat) {
    // The edge is a straight line on the plane: EYE below eye level at `edge` ahead.
    const pxPerTangent = (0.5 * VIEW.height) / Math.tan(0.5 * FOV_Y);
    const expected = 0.5 * VIEW.height + pxPerTangent * (EYE / edge);
    assert.ok(Math.abs(y + 0.5 - expected) <= 2, `flat, column ${x}: the far edge at row ${y}, expected ${expected.toFixed(1)}`);
  }
  assert.match(await page.evaluate(() => location.search), /earth=flat/, 'the address keeps the flattened Earth');
  assert.deepEqual(problems, []);
  await page.close();
});
