#!/usr/bin/env node
// Vector overlays (GPX, KML, GeoJSON) on the terrain, in Node and in the page (headless
// Chromium, WebGL on SwiftShader). Prints:
//   1. reading, placing and building what is drawn of a made-up GPX track of 100 000 and
//      500 000 points on the default terrain (EPSG:4326), in Node: each step's time;
//   2. drop of the 100 000-point GPX onto the default terrain → the first frame that draws it
//      (RUNS times);
//   3. frame time with the track shown, with a 1 000-point track instead, and with none, the same
//      fixed oblique view, in blocks that alternate so that all see the same load; the ratios
//      are the figures;
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
  // The file is made a File in the page first (the harness's transfer is no part of a drop);
  // the time runs in the page from the drop event to the end of the first frame that draws it.
  await page.evaluate((data) => {
    window.benchFile = new File([Uint8Array.from(atob(data), (c) => c.charCodeAt(0))], 'track-100000.gpx');
  }, Buffer.from(file.bytes).toString('base64'));
  const drops = [];
  for (let run = 0; run < RUNS; run++) {
    drops.push(await page.evaluate(() => new Promise((resolve) => {
      const h = window.hexlod, transfer = new DataTransfer();
      transfer.items.add(window.benchFile);
      const start = performance.now();
      window.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
      let drawnFrom = -1;
      const poll = () => {
        if (drawnFrom < 0 && h.layers.overlays.length === 1) drawnFrom = h.frames;
        if (drawnFrom >= 0 && h.frames > drawnFrom) resolve(performance.now() - start);
        else setTimeout(poll, 2);
      };
      poll();
    })));
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
  // The heap's figure leaves out typed arrays' contents (kept outside it): those the layer holds are summed.
  const held = await page.evaluate(() => {
    const layer = window.hexlod.layers.overlays[0], seen = new Set();
    let bytes = 0;
    const visit = (value, depth) => {
      if (value === null || typeof value !== 'object' || seen.has(value) || depth > 8) return;
      seen.add(value);
      if (ArrayBuffer.isView(value)) { bytes += value.byteLength; return; }
      for (const key of Object.keys(value)) visit(value[key], depth + 1);
    };
    visit({ overlay: layer.overlay, placed: layer.placed, geometry: layer.geometry }, 0);
    const g = layer.geometry;
    return { bytes, gpu: g.segments.byteLength + g.curtain.byteLength + g.markers.byteLength };
  });
  const perPoint = (held.bytes + Math.max(0, after - before)) / 100000;
  console.log(`\nmemory of the 100 000-point track: its arrays ${(held.bytes / 2 ** 20).toFixed(1)} MB and the JS heap +${((after - before) / 2 ** 20).toFixed(1)} MB: ` +
    `**${perPoint.toFixed(0)} bytes a point**; on the GPU ${(held.gpu / 2 ** 20).toFixed(2)} MB, ${(held.gpu / 100000).toFixed(1)} bytes a point`);
  await page.close();

  // 3. Frame time with it, with a 1 000-point track instead (what costs the same whatever the
  // track's size), and with none.
  const { page: p, view } = await obliqueTimedPage(viewer, '', { width, height });
  await dropFiles(p, [file]);
  await p.waitForFunction(() => window.hexlod.layers.overlays.length === 1, null, { timeout: 120000 });
  await dropFiles(p, [gpx(1000)]);
  await p.waitForFunction(() => window.hexlod.layers.overlays.length === 2, null, { timeout: 120000 });
  const show = (which) => p.evaluate((k) => {
    const h = window.hexlod;
    h.layers.overlays.forEach((layer, i) => h.overlays.setStyle(layer, { visible: i === k }));
  }, which);
  const ways = { none: -1, '1 000 points': 1, '100 000 points': 0 }, blocks = { none: [], '1 000 points': [], '100 000 points': [] };
  for (let run = 0; run < RUNS; run++) {
    for (const [which, k] of Object.entries(ways)) {
      await show(k);
      const block = (await drawBlock(p, FRAMES + SETTLE_FRAMES)).slice(SETTLE_FRAMES);
      blocks[which].push(median(block.map((f) => f.cpuMs)));
    }
  }
  const none = median(blocks.none);
  console.log(`\nframe time, ${view}, ${RUNS} blocks of ${FRAMES} frames each way (median of each block, in order):`);
  console.log('| track shown | whole frame, GPU included | each block | ratio to none |\n| --- | --- | --- | --- |');
  for (const which of Object.keys(ways)) {
    console.log(`| ${which} | ${ms(median(blocks[which]))} | ${blocks[which].map(ms).join(', ')} | **${(median(blocks[which]) / none).toFixed(2)}** |`);
  }
  await p.close();
} finally {
  await viewer.close();
}
