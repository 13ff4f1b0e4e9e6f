#!/usr/bin/env node
// Vector overlays (GPX, KML, GeoJSON) on the terrain, in Node and in the page (headless
// Chromium, WebGL on SwiftShader). Prints:
//   1. reading, placing and building what is drawn of a made-up GPX track of 100 000 and
//      500 000 points on the default terrain (EPSG:4326), in Node: each step's time;
//   2. drop of the 100 000-point GPX onto the default terrain → the first frame that draws it
//      (RUNS times);
//   3. frame time with the track shown and hidden, the same fixed oblique view, in blocks that
//      alternate so that both see the same load; the ratio is the figure;
//   4. memory per point: the page's JS heap after a garbage collection, with and without the
//      track, and the GPU buffers its drawing holds, each divided by the file's points.
// Usage: node bench/overlays.js [--viewport 640x360] [--runs 3] [--frames 20]
import { readFileSync } from 'node:fs';
import { readOverlay } from '../web/overlays/read_overlay.js';
import { placeOverlay } from '../web/overlays/place_overlay.js';
import { overlayGeometry } from '../web/render/overlays/overlay_geometry.js';
import { samplerOfArray } from '../web/measure/field_sampler.js';
import { crsOfEpsg, makeGeoref, resolveGeoref } from '../web/geo/index.js';
import { useNodeCrsDefinitions } from '../lib/crs_definitions.js';
import { lissajousGpx } from '../lib/track_files.js';
import { startViewer, openPage, pageReady, dropFiles } from '../lib/page_harness.js';
import { drawBlock, obliqueTimedPage, pageBenchOptions, median, formatMs } from '../lib/page_frames.js';

const { width, height, runs: RUNS, frames: FRAMES } = pageBenchOptions();
const SETTLE_FRAMES = 2;
const ms = formatMs;
useNodeCrsDefinitions();

// The default terrain: 2048² samples of 30" in EPSG:4326 (public/terrain/globe_himalaya_2048.json).
const meta = JSON.parse(readFileSync(new URL('../public/terrain/globe_himalaya_2048.json', import.meta.url), 'utf8'));
const b = meta.bounds_deg, step = meta.cell_size_deg;
const georef = await resolveGeoref(makeGeoref(crsOfEpsg(4326, true), b.west + step / 2, b.north - step / 2, step, -step, 'json'));
const ground = { columns: meta.width, rows: meta.height, spacingX: meta.cell_size_x_m, spacingY: meta.cell_size_y_m };
// Over the middle of the terrain: Everest's side of the Himalaya.
const BOX = { west: 84.5, east: 88.5, south: 26.5, north: 29.5 };
const gpx = (count) => ({ name: `track-${count}.gpx`, bytes: new TextEncoder().encode(lissajousGpx(count, BOX)) });

// 1. In Node.
console.log('| points | file | read | place | build what is drawn | drawn segments |\n| --- | --- | --- | --- | --- | --- |');
// A flat field of the terrain's size: the steps' costs do not depend on the heights.
const sampler = samplerOfArray(new Float32Array(meta.width * meta.height).fill(4000), meta.width, meta.height, ground.spacingX, ground.spacingY);
for (const count of [100000, 500000]) {
  const file = gpx(count);
  const t0 = performance.now();
  const overlay = await readOverlay(file.name, file.bytes);
  const t1 = performance.now();
  const placed = placeOverlay(overlay, georef, ground);
  const t2 = performance.now();
  const geometry = overlayGeometry(placed, sampler);
  const t3 = performance.now();
  console.log(`| ${count.toLocaleString('en')} | ${(file.bytes.length / 2 ** 20).toFixed(1)} MB | ${ms(t1 - t0)} | ${ms(t2 - t1)} | ${ms(t3 - t2)} | ${(geometry.segments.length / 6).toLocaleString('en')} |`);
}

const viewer = await startViewer();
try {
  const file = gpx(100000);
  // 2. Drop to the first frame that draws the track.
  const { page } = await openPage(viewer.browser, `${viewer.url}?test=1`, { width, height });
  await pageReady(page);
  const drops = [];
  for (let run = 0; run < RUNS; run++) {
    const frames = await page.evaluate(() => window.hexlod.frames);
    const start = Date.now();
    await dropFiles(page, [file]);
    await page.waitForFunction((n) => window.hexlod.layers.overlays.length === n, run + 1, { timeout: 120000, polling: 10 });
    await page.waitForFunction((f) => window.hexlod.frames > f, frames + 1, { timeout: 120000, polling: 10 });
    drops.push(Date.now() - start);
    await page.evaluate(() => { const h = window.hexlod; h.overlays.remove(h.layers.overlays.at(-1)); });
  }
  console.log(`\ndrop of ${file.name} (${(file.bytes.length / 2 ** 20).toFixed(1)} MB, 100 000 points) on the default terrain → first frame drawing it: ` +
    `median ${ms(median(drops))} (${drops.map(ms).join(', ')})`);

  // 4. Memory per point.
  const cdp = await page.context().newCDPSession(page);
  const heap = async () => {
    await cdp.send('HeapProfiler.collectGarbage');
    return (await cdp.send('Runtime.getHeapUsage')).usedSize;
  };
  const before = await heap();
  await dropFiles(page, [file]);
  await page.waitForFunction(() => window.hexlod.layers.overlays.length === 1, null, { timeout: 120000 });
  const after = await heap();
  const gpu = await page.evaluate(() => {
    const g = window.hexlod.layers.overlays[0].geometry;
    return g.segments.byteLength + g.curtain.byteLength + g.markers.byteLength;
  });
  console.log(`\nmemory of the 100 000-point track: JS heap +${((after - before) / 2 ** 20).toFixed(1)} MB, ` +
    `**${((after - before) / 100000).toFixed(0)} bytes a point**; GPU buffers ${(gpu / 2 ** 20).toFixed(2)} MB, ${(gpu / 100000).toFixed(1)} bytes a point`);
  await page.close();

  // 3. Frame time with and without it.
  const { page: p, view } = await obliqueTimedPage(viewer, '', { width, height });
  await dropFiles(p, [file]);
  await p.waitForFunction(() => window.hexlod.layers.overlays.length === 1, null, { timeout: 120000 });
  const show = (on) => p.evaluate((visible) => { const h = window.hexlod; h.overlays.setStyle(h.layers.overlays[0], { visible }); }, on);
  const blocks = { hidden: [], shown: [] };
  for (let run = 0; run < RUNS; run++) {
    for (const which of ['hidden', 'shown']) {
      await show(which === 'shown');
      const block = (await drawBlock(p, FRAMES + SETTLE_FRAMES)).slice(SETTLE_FRAMES);
      blocks[which].push(median(block.map((f) => f.cpuMs)));
    }
  }
  const ratio = median(blocks.shown) / median(blocks.hidden);
  console.log(`\nframe time, ${view}, ${RUNS} blocks of ${FRAMES} frames each way (median of each block, in order):`);
  console.log('| the 100 000-point track | whole frame, GPU included | each block |\n| --- | --- | --- |');
  for (const which of ['hidden', 'shown']) console.log(`| ${which} | ${ms(median(blocks[which]))} | ${blocks[which].map(ms).join(', ')} |`);
  console.log(`ratio shown / hidden: **${ratio.toFixed(2)}**`);
  await p.close();
} finally {
  await viewer.close();
}
