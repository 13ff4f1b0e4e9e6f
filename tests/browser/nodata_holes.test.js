// No-data as holes or filled, a setting (nodata=filled|holes): a DEM with voids, seen from
// above, shows ground where its samples are and, with holes, nothing of the terrain where they
// are not (the plain ground beyond shows through). Two ways in: a grid loaded whole (an ESCRI
// ASCII grid made here, its voids exact), whose holes come from the loader's mask of no-data
// samples; and a Cloud-Optimized GeoTIFF that streams (tests/fixtures/cog/README.md), whose
// holes come from the core's marks on the stream's vertices as the tiles arrive.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, pageReady, dropFiles, terrainShown, nextFrame, outDir, projectDir } from '../../lib/page_harness.js';

const VIEW = { width: 640, height: 480 };
const HIDE_BOXES = '#hud, #side, #drop-hint, #status, #intake, #panel { display: none !important; }';

// The grid loaded whole: 200 x 160 samples, 30 m apart; a void rectangle and a void disc.
const GRID = { width: 200, height: 160, cell: 30 };
const inRect = (c, r, rect) => c >= rect.c0 && c <= rect.c1 && r >= rect.r0 && r <= rect.r1;
const GRID_RECT = { c0: 60, c1: 119, r0: 50, r1: 99 };
const GRID_DISC = { c: 160, r: 40, radius: 15 };
const gridVoid = (c, r) => inRect(c, r, GRID_RECT) || (c - GRID_DISC.c) ** 2 + (r - GRID_DISC.r) ** 2 <= GRID_DISC.radius ** 2;

function voidGrid() {
  const lines = [`ncols ${GRID.width}`, `nrows ${GRID.height}`, 'xllcorner 500000', 'yllcorner 4000000', `cellsize ${GRID.cell}`, 'NODATA_value -9999'];
  for (let r = 0; r < GRID.height; r++) {
    const row = [];
    for (let c = 0; c < GRID.width; c++) {
      row.push(gridVoid(c, r) ? -9999 : (600 + 120 * Math.sin(c / 17) * Math.cos(r / 13) + 2 * r).toFixed(1));
    }
    lines.push(row.join(' '));
  }
  return { name: 'voids.asc', bytes: Buffer.from(`${lines.join('\n')}\n`) };
}

// The streamed COG: 384 x 384 GLOBE samples with a void rectangle and a void disc.
const COG_RECT = { c0: 120, c1: 219, r0: 150, r1: 229 };
// Samples of margin around a void's outline. A streamed field's hole is every triangle with a
// no-data corner, so its edge is as fine as the mesh there: seen whole, a sample is under a
// pixel, and where the ground beside a void is low its walls are short and the cells along it
// stay up to 16 samples across; a cell reaching into a void is discarded whole.
// Seen at a slant, a void's walls (the lowest height, under holes) refine the mesh along its
// edge as far as they show; straight down they hardly do.
const STREAMED_MARGIN = 16;

let viewer;
before(async () => { viewer = await startViewer(); });
after(async () => { await viewer?.close(); });

/** Looks down on the middle of the field at `pitch` from far enough to see all of it, and waits for the view to settle. */
async function lookDown(page, pitch) {
  await page.evaluate((pitch) => {
    const h = window.hexlod, t = h.terrainObject(), orbit = h.rig.cameras.orbit;
    const w = (t.width - 1) * t.spacingX, d = (t.height - 1) * t.spacingY;
    orbit.target[0] = w / 2, orbit.target[2] = d / 2;
    orbit.target[1] = t.maxHeight * h.settings.exaggeration;
    orbit.distance = 1.15 * Math.max(w, d * 640 / 480) / (2 * Math.tan(Math.PI / 8));
    orbit.pitch = pitch;
    orbit.yaw = 0;
    h.setSetting('camera', 'orbit');
    h.requestRender();
  }, pitch);
  await settle(page);
}

async function settle(page) {
  // A change of heights (the void fill) is applied at the end of a frame and re-tested in the
  // next ones: the figures of the frames before still say converged.
  for (let k = 0; k < 4; k++) await nextFrame(page);
  const settled = () => page.waitForFunction(() => {
    const h = window.hexlod;
    return h.converged && (!h.tiles || (h.tiles.settled && h.tiles.waiting === 0)) && h.hud?.errorProvisional !== true;
  }, null, { timeout: 240000, polling: 250 });
  await settled();
  await nextFrame(page);
  await settled();
}

/** The terrain's pixels (view.terrainMask) as a function of (x, y): true where the terrain is drawn. */
async function terrainMask(page) {
  await page.evaluate(() => { window.hexlod.view.terrainMask = true; });
  await nextFrame(page);
  const { width, data, channels } = decode(await page.screenshot());
  await page.evaluate(() => { window.hexlod.view.terrainMask = false; });
  await nextFrame(page);
  return (x, y) => data[(Math.round(y) * width + Math.round(x)) * channels] >= 128;
}

/**
 * Where sample (column, row) of the field is drawn on the screen, in CSS pixels, at the highest
 * height within `around` samples: a void's fill may lie far below the ground around it, which
 * stands in front of it seen from the eye; the hole's outline is the ground's.
 */
function project(page, samples, around) {
  return page.evaluate(({ list, around }) => {
    const h = window.hexlod, t = h.terrainObject(), m = h.camera.viewProjection;
    const highest = (c, r) => {
      let top = -Infinity;
      for (let i = Math.max(0, r - around); i <= Math.min(t.height - 1, r + around); i++) {
        for (let j = Math.max(0, c - around); j <= Math.min(t.width - 1, c + around); j++) top = Math.max(top, t.heightAt(j * t.spacingX, i * t.spacingY));
      }
      return top;
    };
    return list.map(([c, r]) => {
      const x = c * t.spacingX, z = r * t.spacingY;
      const p = [...h.drawnPoint(x, highest(c, r) * h.settings.exaggeration, z), 1];
      const clip = [0, 1, 3].map((k) => m[k] * p[0] + m[4 + k] * p[1] + m[8 + k] * p[2] + m[12 + k] * p[3]);
      return [(clip[0] / clip[2] + 1) * innerWidth / 2, (1 - clip[1] / clip[2]) * innerHeight / 2];
    });
  }, { list: samples, around });
}

/**
 * Samples of a grid over the field, inside a void (at least `margin` samples from valid ground)
 * and on valid ground (as far from any void and from the field's edge), with where they are drawn.
 */
async function probes(page, width, height, isVoid, margin) {
  const near = (c, r, want) => {
    for (let dr = -margin; dr <= margin; dr++) for (let dc = -margin; dc <= margin; dc++) {
      const cc = c + dc, rr = r + dr;
      if (cc < 0 || rr < 0 || cc >= width || rr >= height || isVoid(cc, rr) !== want) return false;
    }
    return true;
  };
  const inside = [], ground = [];




  for (let r = margin; r < height - margin; r += 3) for (let c = margin; c < width - margin; c += 3) {
    if (near(c, r, true)) inside.push([c, r]);
    else if (near(c, r, false)) ground.push([c, r]);
  }
  // A void's probe at the height of the ground past its edge: what outlines the hole on the screen.
  return { inside: await project(page, inside, 2 * margin + 2), ground: await project(page, ground, 0) };
}

/** The share of the points where the terrain is drawn. */
const drawnShare = (mask, points) => points.filter(([x, y]) => x >= 0 && y >= 0 && x < VIEW.width && y < VIEW.height && mask(x, y)).length / points.length;

async function judge(page, label, width, height, isVoid, margin, pitch) {
  await lookDown(page, pitch);
  const { inside, ground } = await probes(page, width, height, isVoid, margin);
  assert.ok(inside.length > 50 && ground.length > 200, `${label}: probes ${inside.length} in voids, ${ground.length} on ground`);
  for (const [x, y] of [...inside, ...ground]) assert.ok(x > 0 && y > 0 && x < VIEW.width && y < VIEW.height, `${label}: the field is in view`);
  const filled = await terrainMask(page);
  await page.screenshot({ path: `${outDir}/nodata-${label}-filled.png` });
  await page.evaluate(() => window.hexlod.setSetting('nodata', 'holes'));
  await settle(page);
  const holes = await terrainMask(page);
  const shot = decode(await page.screenshot({ path: `${outDir}/nodata-${label}-holes.png` }));
  await page.evaluate(() => window.hexlod.setSetting('nodata', 'filled'));
  await settle(page);
  const back = await terrainMask(page);
  return { filled, holes, back, inside, ground, shot };
}

test('no-data of a grid loaded whole: filled, or holes exactly where the voids are, and filled again', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?exag=1`, VIEW);
  await pageReady(page);
  await page.addStyleTag({ content: HIDE_BOXES });
  await dropFiles(page, [voidGrid()]);
  await terrainShown(page, 'voids.asc');
  const { filled, holes, back, inside, ground, shot } = await judge(page, 'whole', GRID.width, GRID.height, gridVoid, 2, Math.PI / 2 - 0.02);
  assert.equal(drawnShare(filled, inside), 1, 'filled: the voids are ground');
  assert.equal(drawnShare(filled, ground), 1);
  assert.equal(drawnShare(holes, inside), 0, 'holes: nothing of the terrain in the voids');
  assert.equal(drawnShare(holes, ground), 1, 'holes: every valid sample is drawn');
  assert.equal(drawnShare(back, inside), 1, 'filled again');
  // Through a hole the plain ground beyond is drawn, lit: not the clear colour, not black.
  const [x, y] = inside[Math.floor(inside.length / 2)];
  const k = (Math.round(y) * shot.width + Math.round(x)) * shot.channels;
  assert.ok(shot.data[k] + shot.data[k + 1] + shot.data[k + 2] > 60, `the ground beyond shows through: ${[...shot.data.subarray(k, k + 3)]}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('no-data of a streamed COG: holes where its tiles say, at the resolution that came', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?exag=1`, VIEW);
  await pageReady(page);
  await page.addStyleTag({ content: HIDE_BOXES });
  const name = 'himalaya_384_voids_i16.tif';
  await dropFiles(page, [{ name, bytes: readFileSync(`${projectDir}tests/fixtures/cog/${name}`) }]);
  await terrainShown(page, name);
  assert.ok(await page.evaluate(() => window.hexlod.terrainObject().tiled), 'the COG streams');
  const isVoid = (c, r) => inRect(c, r, COG_RECT) || (c - 290) ** 2 + (r - 90) ** 2 <= 32 * 32;
  const { filled, holes, back, inside, ground } = await judge(page, 'streamed', 384, 384, isVoid, STREAMED_MARGIN, 1.1);
  assert.equal(drawnShare(filled, inside), 1, 'filled: the voids are ground');
  assert.equal(drawnShare(holes, inside), 0, 'holes: nothing of the terrain in the voids');
  assert.equal(drawnShare(holes, ground), 1, 'holes: every valid sample is drawn');
  assert.equal(drawnShare(back, inside), 1, 'filled again');
  assert.deepEqual(problems, []);
  await page.close();
});
