#!/usr/bin/env node
// Web map tiles in the page (headless Chromium, WebGL on SwiftShader), served by the test tile
// server (lib/tile_server.js) with LATENCY ms a request from gdal2tiles' pyramid of the Blue
// Marble (tests/fixtures/webtiles/bmng, zooms 3-7) over the default terrain. Prints:
//   1. for fixed views (the whole terrain from above, an oblique view, a close view), the tiles
//      fetched and their bytes, the tiles on the GPU, and the time from the view to the last tile;
//   2. for a flight (a scripted orbit from the whole terrain down to a valley and along it, a
//      new view every frame, frames as fast as the page draws them), the tiles fetched and
//      their bytes, the requests aborted because the view moved on, and the tiles evicted.
// Usage: node bench/web_tiles.js [--viewport 960x600] [--latency 20] [--steps 60]
import { parseArgs } from 'node:util';
import { startViewer, openPage, pageReady, projectDir } from '../lib/page_harness.js';
import { startTileServer } from '../lib/tile_server.js';

const { values } = parseArgs({ options: { viewport: { type: 'string' }, latency: { type: 'string' }, steps: { type: 'string' } } });
const [width, height] = (values.viewport ?? '960x600').split('x').map(Number);
const LATENCY = Number(values.latency ?? 20);
const STEPS = Number(values.steps ?? 60);
const kb = (bytes) => `${(bytes / 1024).toFixed(0)} KB`;

/** Puts the orbit camera at { x, z (fractions of the extent), distance (fraction of its width), yaw, pitch }. */
const pose = (page, view) => page.evaluate((v) => {
  const { camera, rig } = window.hexlod;
  camera.target[0] = v.x * rig.world.extentX; camera.target[1] = 0; camera.target[2] = v.z * rig.world.extentZ;
  camera.distance = v.distance * rig.world.extentX; camera.yaw = v.yaw; camera.pitch = v.pitch;
  window.hexlod.requestRender();
}, view);

const figures = (page) => page.evaluate(() => window.hexlod.imageLayers[0].tiles);

/** Draws until the tile layer has nothing in flight for a few frames; the milliseconds it took. */
const settle = (page) => page.evaluate(() => new Promise((resolve) => {
  const start = performance.now();
  let quiet = 0;
  const look = () => {
    const h = window.hexlod, t = h.imageLayers[0].tiles;
    quiet = t.inFlight === 0 && t.resident > 0 ? quiet + 1 : 0;
    if (quiet >= 5) resolve(performance.now() - start);
    else { h.requestRender(); setTimeout(look, 50); }
  };
  look();
}));

const VIEWS = {
  'whole terrain from above': { x: 0.5, z: 0.5, distance: 2.0, yaw: 0, pitch: 1.55 },
  'oblique, over the middle': { x: 0.5, z: 0.5, distance: 0.6, yaw: 0.5, pitch: 0.45 },
  'close, Everest from 150 km': { x: 0.82, z: 0.58, distance: 0.1, yaw: 0.3, pitch: 0.6 },
};

const viewer = await startViewer();
const server = await startTileServer(`${projectDir}tests/fixtures/webtiles/bmng`, { latencyMs: LATENCY });
try {
  console.log(`${width} × ${height}, tile server latency ${LATENCY} ms, Blue Marble tiles zooms 3-7 (256², PNG)\n`);
  console.log('| fixed view (a fresh page each) | tiles fetched | bytes | on the GPU | view → last tile |\n| --- | --- | --- | --- | --- |');
  for (const [name, view] of Object.entries(VIEWS)) {
    const spec = `${server.url}/{z}/{x}/{y}.png|zoom=3-7`;
    const { page } = await openPage(viewer.browser, `${viewer.url}?test=1&tiles=${encodeURIComponent(spec)}`, { width, height });
    await pageReady(page);
    await pose(page, view);
    const ms = await settle(page);
    const f = await figures(page);
    console.log(`| ${name} | ${f.fetched} | ${kb(f.bytesFetched)} | ${f.resident} | ${Math.round(ms).toLocaleString('en')} ms |`);
    await page.close();
  }

  const spec = `${server.url}/{z}/{x}/{y}.png|zoom=3-7`;
  const { page } = await openPage(viewer.browser, `${viewer.url}?test=1&tiles=${encodeURIComponent(spec)}`, { width, height });
  await pageReady(page);
  await pose(page, VIEWS['whole terrain from above']);
  await settle(page);
  const start = await figures(page);
  // From above the whole terrain down to Everest, then west along the range, a view a frame.
  const began = Date.now();
  for (let i = 0; i <= STEPS; i++) {
    const t = i / STEPS, down = Math.min(1, 2 * t), along = Math.max(0, 2 * t - 1);
    await pose(page, { x: 0.5 + 0.32 * down - 0.4 * along, z: 0.5 + 0.08 * down - 0.1 * along, distance: 2.0 * (1 - down) + 0.1 * down,
      yaw: 0.3 * down, pitch: 1.55 - 0.95 * down });
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
  }
  const flownMs = Date.now() - began;
  await settle(page);
  const end = await figures(page);
  console.log(`\nflight: ${STEPS + 1} views in ${(flownMs / 1000).toFixed(1)} s, then until the last tile came`);
  console.log('| tiles fetched | bytes | requests aborted (the view moved on) | evicted | on the GPU at the end | failed |\n| --- | --- | --- | --- | --- | --- |');
  console.log(`| ${end.fetched - start.fetched} | ${kb(end.bytesFetched - start.bytesFetched)} | ${end.aborted - start.aborted} | ` +
    `${end.evictions - start.evictions} | ${end.resident} | ${end.failed - start.failed} |`);
  console.log(`(the whole terrain first: ${start.fetched} tiles, ${kb(start.bytesFetched)}; the server saw ${server.tilesRequested().length} tile requests in all)`);
  await page.close();
} finally {
  await viewer.close();
  await server.close();
}
