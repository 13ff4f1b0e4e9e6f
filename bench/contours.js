#!/usr/bin/env node
// What the contour overlay costs a frame: lines per pixel from the exact height texture (four
// texelFetch and a bilinear blend in the terrain's fragment stage) and the labels (placed on the
// CPU with sight-line tests, drawn as instanced glyphs), as the ratio of the median frame time
// with contours to that without, from one headless run. The page waits for the GPU after drawing
// (?timing=1), so the times include SwiftShader's rasterisation. The view holds still and
// converged; contours go on and off frame by frame so that both see the same load.
//   node bench/contours.js [--frames 20] [--size 640x360] [--src URL] [--cint 50]
import { startViewer } from '../lib/page_harness.js';
import { openConvergedView, frameWithSetting } from '../lib/page_frames.js';

const args = process.argv.slice(2);
const option = (name, fallback) => { const k = args.indexOf(`--${name}`); return k >= 0 ? args[k + 1] : fallback; };
const frames = Number(option('frames', '20'));
const [width, height] = option('size', '640x360').split('x').map(Number);
const src = option('src', null);
const cint = option('cint', 'auto');
const median = (v) => [...v].sort((a, b) => a - b)[v.length >> 1];

const viewer = await startViewer();
try {
  const url = `${viewer.url}?timing=1&budget=40&cint=${encodeURIComponent(cint)}${src ? `&src=${encodeURIComponent(src)}` : ''}`;
  const { page, problems } = await openConvergedView(viewer.browser, url, { width, height });
  const samples = { off: [], on: [] }, draws = { off: [], on: [] };
  for (let f = 0; f < 2 * (frames + 2); ++f) {
    const on = f % 2 === 1;
    const log = await frameWithSetting(page, 'contours', on);
    if (f < 4) continue; // the first frame with contours makes the height texture and the label points
    samples[on ? 'on' : 'off'].push(log.cpuMs);
    draws[on ? 'on' : 'off'].push(log.drawMs);
  }
  const info = await page.evaluate(() => ({ triangles: window.hexlod.triangles, name: window.hexlod.terrain?.name,
    contours: { ...window.hexlod.contours } }));
  await page.close();
  if (problems.length) throw new Error(problems.join('\n'));
  const off = median(samples.off), on = median(samples.on);
  console.log(`${info.name}, ${width}x${height}, ${info.triangles} triangles, ${frames} frames each, interval ${info.contours.interval} m, `
    + `${info.contours.labels} labels, height texture ${(info.contours.textureBytes / 2 ** 20).toFixed(1)} MB made in ${info.contours.textureMs.toFixed(0)} ms`);
  console.log(`  median frame time (GPU included): off ${off.toFixed(1)} ms, on ${on.toFixed(1)} ms; ratio on/off ${(on / off).toFixed(2)}`);
  console.log(`  median draw time: off ${median(draws.off).toFixed(1)} ms, on ${median(draws.on).toFixed(1)} ms`);
} finally {
  await viewer.close();
}
