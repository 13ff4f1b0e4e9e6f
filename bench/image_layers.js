#!/usr/bin/env node
// Image layers in other CRSs, in Node and in the page (headless Chromium, WebGL on SwiftShader). Prints:
//   1. the cost of placing an image in another CRS (web/imagery/placement.js: the exact map
//      and the control grid the shader interpolates), in Node: the real UTM DEM of
//      tests/fixtures/reprojection with its images in EPSG:4326 and 3857, and the same maps over
//      a 4096² field of 1 m (a lidar tile) with an orthophoto in EPSG:4326;
//   2. drop to the first frame that draws the reprojected image: the UTM DEM on screen, its
//      Blue Marble image in EPSG:4326 dropped on it (RUNS times);
//   3. frame time with 0, 1 and 3 image layers on the default terrain, the same fixed oblique
//      view, in blocks that alternate (0, 1, 3, 0, 1, 3, ...) so that all see the same load;
//      the ratios are the figures. The layers: the Blue Marble by its world file (the terrain's
//      CRS), the same in Web Mercator (reprojected), and the same as a GeoTIFF in EPSG:4326.
// Usage: node bench/image_layers.js [--viewport 640x360] [--runs 3] [--frames 20]
import { readFileSync } from 'node:fs';
import { placeImage } from '../web/imagery/placement.js';
import { crsOfEpsg, makeGeoref, parseEpsg, resolveGeoref } from '../web/geo/index.js';
import { useNodeCrsDefinitions } from '../lib/crs_definitions.js';
import { startViewer, openPage, pageReady, dropFiles, terrainShown } from '../lib/page_harness.js';
import { drawBlock, obliqueTimedPage, pageBenchOptions, median, formatMs } from '../lib/page_frames.js';

const { width, height, runs: RUNS, frames: FRAMES } = pageBenchOptions();
const SETTLE_FRAMES = 2;
const ms = formatMs;
const fixtures = new URL('../tests/fixtures/', import.meta.url);
const expected = JSON.parse(readFileSync(new URL('reprojection/expected.json', fixtures), 'utf8'));
useNodeCrsDefinitions();
const grid = (g) => resolveGeoref(makeGeoref(crsOfEpsg(parseEpsg(g.crs)), g.x0, g.y0, g.dx, g.dy, 'GeoTIFF'));
const utm11 = (x0, y0, step) => resolveGeoref(makeGeoref(crsOfEpsg(32611), x0, y0, step, -step, 'GeoTIFF'));
const file = (path) => ({ name: path.split('/').pop(), bytes: new Uint8Array(readFileSync(new URL(path, fixtures))) });

// 1. Placing, in Node.
function timePlacement(label, field, image) {
  placeImage(field, image); // proj4's definitions parsed once, as the page would have them
  const times = [];
  let placement;
  for (let run = 0; run < 5; run++) {
    const start = performance.now();
    placement = placeImage(field, image);
    times.push(performance.now() - start);
  }
  const { nodesX, nodesY, maxError } = placement.warp;
  console.log(`| ${label} | ${ms(median(times))} | ${nodesX} × ${nodesY} | ${maxError.toFixed(3)} px |`);
}
console.log('| placing (median of 5) | time | control grid nodes | its largest error |\n| --- | --- | --- | --- |');
const dem = { width: expected.dem.width, height: expected.dem.height, georef: await grid(expected.dem) };
for (const [code, source] of Object.entries(expected.images)) {
  timePlacement(`UTM DEM ${dem.width}², Blue Marble ${source.width} × ${source.height} in EPSG:${code}`, dem,
    { name: source.file, width: source.width, height: source.height, georef: await grid(source) });
}
const lidar = { width: 4096, height: 4096, georef: await utm11(500000.5, 4000000 - 0.5, 1) };
// An orthophoto of 0.25 m over it in EPSG:4326 (about 0.0000025° at 36° N).
timePlacement('4096² field of 1 m in UTM 11N, 16384² orthophoto in EPSG:4326', lidar,
  { name: 'ortho.tif', width: 16384, height: 16384, georef: await resolveGeoref(makeGeoref(crsOfEpsg(4326), -117.0 - 0.0000014, 36.14 + 0.0000011, 0.0000028, -0.00000225, 'GeoTIFF')) });
timePlacement('the same field, an image in its own CRS', lidar,
  { name: 'same.tif', width: 16384, height: 16384, georef: await utm11(500000.125, 4000000 - 0.125, 0.25) });

const viewer = await startViewer();
try {
  // 2. Drop to the first frame of a reprojected image.
  const { page } = await openPage(viewer.browser, `${viewer.url}?test=1`, { width, height });
  await pageReady(page);
  await dropFiles(page, [file(`reprojection/${expected.dem.file}`)]);
  await terrainShown(page, expected.dem.file);
  const image = file(`reprojection/${expected.images['4326'].file}`);
  const drops = [];
  for (let run = 0; run < RUNS; run++) {
    const frames = await page.evaluate(() => window.hexlod.frames);
    const start = Date.now();
    await dropFiles(page, [image]);
    await page.waitForFunction((n) => window.hexlod.imageLayers.length === n, run + 1, { timeout: 120000, polling: 10 });
    await page.waitForFunction((f) => window.hexlod.frames > f, frames + 1, { timeout: 120000, polling: 10 });
    drops.push(Date.now() - start);
    await page.evaluate(() => window.hexlod.images.setVisible(window.hexlod.imageLayers.at(-1).id, false));
  }
  console.log(`\ndrop of ${image.name} (${(image.bytes.length / 1024).toFixed(0)} KB, 256 × 257) on the UTM DEM → first frame drawing it, reprojected: ` +
    `median ${ms(median(drops))} (${drops.map(ms).join(', ')})`);
  await page.close();

  // 3. Frame time with 0, 1 and 3 layers.
  const { page: p, view } = await obliqueTimedPage(viewer, '', { width, height });
  await dropFiles(p, [file('imagery/bmng_himalaya_4arcmin.jpg'), file('imagery/bmng_himalaya_4arcmin.jgw')]);
  await p.waitForFunction(() => window.hexlod.imageLayers.length === 1, null, { timeout: 120000 });
  for (const name of ['bmng_himalaya_3857.tif', 'bmng_himalaya_4326.tif']) {
    const n = await p.evaluate(() => window.hexlod.imageLayers.length);
    await dropFiles(p, [file(`reprojection/${name}`)]);
    await p.waitForFunction((k) => window.hexlod.imageLayers.length === k, n + 1, { timeout: 120000 });
  }
  const show = (count) => p.evaluate((k) => {
    const h = window.hexlod;
    h.imageLayers.forEach((layer, i) => h.images.setVisible(layer.id, i < k));
  }, count);
  const blocks = { 0: [], 1: [], 3: [] };
  for (let run = 0; run < RUNS; run++) {
    for (const count of [0, 1, 3]) {
      await show(count);
      const block = (await drawBlock(p, FRAMES + SETTLE_FRAMES)).slice(SETTLE_FRAMES);
      blocks[count].push(median(block.map((f) => f.cpuMs)));
    }
  }
  console.log(`\nframe time, ${view}, ` +
    `${RUNS} blocks of ${FRAMES} frames each way (median of each block, in order):`);
  console.log('| image layers | whole frame, GPU included | each block | ratio to none |\n| --- | --- | --- | --- |');
  const none = median(blocks[0]);
  for (const count of [0, 1, 3]) {
    console.log(`| ${count} | ${ms(median(blocks[count]))} | ${blocks[count].map(ms).join(', ')} | **${(median(blocks[count]) / none).toFixed(2)}** |`);
  }
  await p.close();
} finally {
  await viewer.close();
}
