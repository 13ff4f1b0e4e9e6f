// A path measured on a streamed COG is measured again as finer tiles come: opened from the
// address bar with the terrain, its first figures come from the coarsest overview; once the view
// is at rest they are those of the heights then loaded, as measuring it afresh gives them.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startViewer, openPage, pageReady, projectDir } from '../../lib/page_harness.js';
import { startRangeServer } from '../../lib/range_server.js';
import { createNodeCore } from '../../lib/node_core.js';
import { openCog } from '../../web/tiles/cog_source.js';
import { openTiledTerrain } from '../../web/tiles/tiled_terrain.js';

const COGS = `${projectDir}tests/fixtures/cog/`;
const HIMALAYA = 'himalaya_1024_i16.tif'; // 1024², 256² tiles, overviews 512² and 256²

let viewer, ranged;
before(async () => {
  [viewer, ranged] = await Promise.all([startViewer(), startRangeServer(COGS, { latencyMs: 20 })]);
});
after(async () => {
  await Promise.all([viewer?.close(), ranged?.close()]);
});

/** The field's extent in the page's metres: the same code opens the COG in Node. */
async function extentOf(url) {
  const core = await createNodeCore();
  const { terrain, tiles } = await openTiledTerrain(core, await openCog(url));
  const extent = [(terrain.width - 1) * terrain.spacingX, (terrain.height - 1) * terrain.spacingY];
  tiles.close();
  terrain.destroy();
  return extent;
}

test('a path measured on a streamed COG is measured again as finer tiles come', async () => {
  const url = `${ranged.url}/${HIMALAYA}`;
  const [w, d] = await extentOf(url);
  // A zigzag over the field, so that it crosses tiles of every level.
  const points = [[0.1, 0.2], [0.9, 0.35], [0.1, 0.5], [0.9, 0.65], [0.1, 0.8]].map(([x, z]) => `${Math.round(x * w)},${Math.round(z * d)}`);
  const { page, problems } = await openPage(viewer.browser, 'about:blank', { width: 480, height: 300 });
  // The figures of the path as the page first shows them, and how many tiles were in then.
  await page.addInitScript(() => {
    const poll = () => {
      const result = window.hexlod?.measure?.result;
      if (!window.firstMeasure && result?.profile && window.hexlod.tiles) {
        window.firstMeasure = { summary: result.profile.summary, tilesIn: window.hexlod.tiles.tilesIn };
      }
      requestAnimationFrame(poll);
    };
    requestAnimationFrame(poll);
  });
  await page.goto(`${viewer.url}?budget=50&tau=3&measure=p:${points.join(';')}&src=${encodeURIComponent(url)}`);
  await pageReady(page);
  assert.equal(await page.evaluate(() => window.hexlod.status), 'ready', await page.evaluate(() => window.hexlod.error));
  await page.waitForFunction(() => window.hexlod.converged && window.hexlod.tiles?.settled && window.hexlod.hud?.errorProvisional === false,
    null, { timeout: 120000, polling: 100 });
  const seen = await page.evaluate(() => {
    const tool = window.hexlod.measure;
    const settled = tool.result.profile.summary;
    tool.update(); // measured afresh on the heights now loaded
    return { first: window.firstMeasure, settled, afresh: tool.result.profile.summary, tilesIn: window.hexlod.tiles.tilesIn };
  });
  console.log(`path of ${points.length} points: gain ${seen.first.summary.gain.toFixed(1)} m with ${seen.first.tilesIn} tiles in, ` +
    `${seen.settled.gain.toFixed(1)} m with ${seen.tilesIn}`);
  assert.equal(seen.first.tilesIn, 0, 'the first figures came from the overview the terrain opened with');
  assert.ok(seen.tilesIn > 0);
  assert.deepEqual(seen.settled, seen.afresh, 'the figures shown are those of the heights loaded');
  assert.notEqual(seen.settled.gain, seen.first.summary.gain, 'finer tiles changed the heights along the path');
  assert.deepEqual(problems, []);
  await page.close();
});
