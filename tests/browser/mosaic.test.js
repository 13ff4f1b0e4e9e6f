// Several GeoTIFF tiles dropped at once open as one terrain, with no seam: from straight above,
// the band of pixels along each join differs from its neighbours no more than neighbouring
// bands differ elsewhere, and the mosaic looks like the un-cut DEM it was cut from.
// Fixtures: tests/fixtures/mosaic/README.md.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, dropFiles, terrainShown, pageReady, converged, outDir } from '../../lib/page_harness.js';
import { lookStraightDown, screenPoint } from '../../lib/draped_points.js';

const tile = (name) => ({ name, bytes: new Uint8Array(readFileSync(new URL(`../fixtures/mosaic/${name}`, import.meta.url))) });
const DISTANCE_M = 12000; // close enough that the 19 x 18 km field fills the view
const BAND = 40; // pixels either side of a join judged as "elsewhere"
const VIEWPORT = { width: 480, height: 300 }; // small: SwiftShader draws each frame on the CPU

let viewer;
before(async () => { viewer = await startViewer(); });
after(async () => { await viewer?.close(); });

/** From straight above, converged, with only the canvas visible; returns the decoded screenshot and where the joins fall. */
async function viewFromAbove(page, label) {
  await lookStraightDown(page, DISTANCE_M);
  await converged(page);
  const view = await page.evaluate(() => {
    const h = window.hexlod, t = h.terrainObject();
    // The joins of the 2 x 2 tiles: column 128 and row 96 of the field (ground metres from sample 0).
    return { m: Array.from(h.camera.viewProjection), join: h.drawnPoint(128 * t.spacingX, 0, 96 * t.spacingY), width: innerWidth, height: innerHeight };
  });
  const [joinX, joinY] = screenPoint(view.m, view.join, view.width, view.height);
  const png = decode(await page.screenshot({ path: `${outDir}/mosaic-${label}.png` }));
  return { png, joinX, joinY };
}

/** Mean absolute RGB difference between neighbouring pixel lines: diff[i] between line i and i + 1. */
function lineDifferences({ width, height, data, channels }, vertical, from, to) {
  const lines = vertical ? width : height, across = vertical ? height : width;
  const at = (line, k) => (vertical ? (k * width + line) : (line * width + k)) * channels;
  const diff = new Float64Array(lines - 1);
  for (let i = 0; i < lines - 1; i++) {
    let sum = 0;
    for (let k = from; k < Math.min(to, across); k++) {
      for (let c = 0; c < 3; c++) sum += Math.abs(data[at(i, k) + c] - data[at(i + 1, k) + c]);
    }
    diff[i] = sum / (3 * (Math.min(to, across) - from));
  }
  return diff;
}

/** The largest neighbour difference at the join (the two line pairs either side) and the largest elsewhere within BAND. */
function seam(diff, join) {
  const atJoin = Math.max(...[join - 2, join - 1, join, join + 1].map((i) => diff[i]));
  const elsewhere = [];
  for (let i = join - BAND; i <= join + BAND; i++) if (Math.abs(i - join) > 3 && i >= 0 && i < diff.length) elsewhere.push(diff[i]);
  return { atJoin, elsewhere: Math.max(...elsewhere) };
}

test('dropped tiles open as one terrain with no seam, and look like the un-cut source', async () => {
  // The page opens on the un-cut field (a small one: the default terrain would cost most of the time).
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?src=${viewer.fixturesUrl}mosaic/source.tif`, VIEWPORT);
  await pageReady(page);
  await terrainShown(page, 'source.tif');
  // Only the terrain is judged: the HUD, panel and status line would differ by the name alone.
  await page.addStyleTag({ content: 'body * { visibility: hidden !important; } canvas { visibility: visible !important; }' });
  const source = await viewFromAbove(page, 'source');

  await dropFiles(page, ['shared_se.tif', 'shared_ne.tif', 'shared_nw.tif', 'shared_sw.tif'].map(tile));
  await terrainShown(page, 'shared_nw.tif + 3 more (mosaic 2 × 2)');
  const terrain = await page.evaluate(() => window.hexlod.terrain);
  assert.deepEqual([terrain.width, terrain.height], [257, 193], 'the shared edges are kept once');
  const mosaic = await viewFromAbove(page, 'tiles');
  const { width, height } = mosaic.png;
  assert.ok(mosaic.joinX > BAND && mosaic.joinX < width - BAND && mosaic.joinY > BAND && mosaic.joinY < height - BAND,
    `both joins are on screen, away from its edges: ${mosaic.joinX}, ${mosaic.joinY}`);

  // Across the north-south join (a vertical line on screen) and the east-west one.
  const columns = seam(lineDifferences(mosaic.png, true, 0, height), mosaic.joinX);
  const rows = seam(lineDifferences(mosaic.png, false, 0, width), mosaic.joinY);
  assert.ok(columns.atJoin <= columns.elsewhere, `no line of outliers along the vertical join: ${columns.atJoin.toFixed(2)} vs ${columns.elsewhere.toFixed(2)} beside it`);
  assert.ok(rows.atJoin <= rows.elsewhere, `no line of outliers along the horizontal join: ${rows.atJoin.toFixed(2)} vs ${rows.elsewhere.toFixed(2)} beside it`);

  // The same view of the un-cut field: the same picture, within the rasteriser's noise.
  assert.deepEqual([source.joinX, source.joinY], [mosaic.joinX, mosaic.joinY], 'the same camera over the same ground');
  let total = 0, far = 0;
  for (let k = 0; k < width * height; k++) {
    let d = 0;
    for (let c = 0; c < 3; c++) d += Math.abs(mosaic.png.data[k * mosaic.png.channels + c] - source.png.data[k * source.png.channels + c]);
    total += d / 3;
    if (d / 3 > 16) far++;
  }
  console.log(`mosaic vs source: mean ${(total / (width * height)).toFixed(3)}, ${far} pixels beyond 16; joins ${JSON.stringify(columns)} ${JSON.stringify(rows)}`);
  assert.ok(total / (width * height) < 1.5, `mean difference ${(total / (width * height)).toFixed(2)} per channel`);
  assert.ok(far / (width * height) < 0.005, `${far} pixels differ by more than 16`);
  assert.deepEqual(problems, []);
});
