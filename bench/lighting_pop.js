#!/usr/bin/env node
// Lighting pops: the largest per-pixel change of the lighting between consecutive
// frames while the mesh refines under a slow flight, with the mesh's normals (paper §7: averaged
// from the adjacent triangles, so every split and merge changes them at once) and with the
// normals of the full-resolution field (a texture; the mesh does not change them).
// The drawn view stays still while the LOD camera flies, so every change on screen comes from
// the mesh: the page is frozen (F) and this script moves the core's camera and runs the LOD
// update itself, one step per frame, geomorphing on. The page draws in the hillshade mode
// (lighting only, grey) and every frame is read back. Reported: the largest change of any
// pixel (8-bit levels) over all frames, the median over frames of each frame's largest change,
// the 99.9th and 99.99th percentiles of all per-pixel changes, the pixels per frame that change
// by more than 16 levels, and the mean change per pixel and frame.
//   node bench/lighting_pop.js [--frames 40] [--size 480x270]
import { decode } from 'fast-png';
import { startViewer, openPage } from '../lib/page_harness.js';

const args = process.argv.slice(2);
const option = (name, fallback) => { const k = args.indexOf(`--${name}`); return k >= 0 ? args[k + 1] : fallback; };
const frames = Number(option('frames', '40'));
const [width, height] = option('size', '480x270').split('x').map(Number);

/** Grey levels of a screenshot (the hillshade mode draws grey). */
function grey(png) {
  const { data, channels } = decode(png);
  const out = new Uint8Array(data.length / channels);
  for (let k = 0; k < out.length; ++k) out[k] = data[k * channels + 1];
  return out;
}

async function measure(viewer, normals) {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?shading=hillshade`, { width, height });
  await page.addStyleTag({ content: '#hud,#side,#drop-hint,#status{display:none !important}' });
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
  await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged; }, null, { timeout: 240000, polling: 200 });
  await page.evaluate((n) => {
    const h = window.hexlod;
    h.setSetting('normals', n);
    h.setSetting('freeze', true);
    const c = h.camera;
    // The LOD camera starts at the drawn view and flies slowly towards its target.
    h.popFlight = { eye: Array.from(c.position), target: Array.from(c.target), fovY: c.fovY, aspect: c.aspect, near: c.near, far: c.far };
  }, normals);
  const images = [];
  for (let f = 0; f <= frames; ++f) {
    await page.evaluate((step) => {
      const h = window.hexlod, fl = h.popFlight, t = h.terrainObject();
      const k = 1 - 0.6 * (step / 40); // 1.5 % of the starting distance closer per frame
      const eye = fl.eye.map((e, i) => fl.target[i] + (e - fl.target[i]) * k);
      t.setLodCamera({ eye, target: fl.target, fovY: fl.fovY, aspect: fl.aspect, viewportHeight: innerHeight, near: fl.near, far: fl.far });
      t.updateLod();
      h.wantFrame = h.frames + 1;
      h.requestRender();
    }, f);
    await page.waitForFunction(() => window.hexlod.frames >= window.hexlod.wantFrame, null, { timeout: 60000, polling: 20 });
    images.push(grey(await page.screenshot()));
  }
  const stats = await page.evaluate(() => ({ triangles: window.hexlod.triangles }));
  await page.close();
  if (problems.length) throw new Error(problems.join('\n'));
  let largest = 0, sum = 0, count = 0;
  const maxima = [], histogram = new Float64Array(256);
  for (let f = 1; f < images.length; ++f) {
    let frameMax = 0;
    for (let k = 0; k < images[f].length; ++k) {
      const d = Math.abs(images[f][k] - images[f - 1][k]);
      frameMax = Math.max(frameMax, d);
      histogram[d] += 1;
      sum += d;
      ++count;
    }
    maxima.push(frameMax);
    largest = Math.max(largest, frameMax);
  }
  maxima.sort((a, b) => a - b);
  // Percentiles of all per-pixel changes: the largest ones are silhouettes that a blending
  // vertex moves (terrain against sky or a farther slope), which no normal can prevent.
  const percentile = (p) => { let seen = 0, d = 0; while (d < 255 && (seen += histogram[d]) < p * count) d += 1; return d; };
  const over = (levels) => histogram.slice(levels).reduce((a, b) => a + b, 0) / (images.length - 1);
  return { normals, largest, medianFrameMax: maxima[maxima.length >> 1], p999: percentile(0.999), p9999: percentile(0.9999),
    pixelsOver16PerFrame: Math.round(over(17)), meanChange: Number((sum / count).toFixed(3)), triangles: stats.triangles };
}

const viewer = await startViewer();
try {
  console.log(`lighting pops, ${frames} frames at ${width}x${height}, hillshade mode, geomorphing on`);
  for (const normals of ['mesh', 'field']) console.log(JSON.stringify(await measure(viewer, normals)));
} finally {
  await viewer.close();
}
