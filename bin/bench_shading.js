#!/usr/bin/env node
// Frame time of the full shading (issue 14: scattering, field normals, shadows, AO, procedural
// ground, sky, tone mapping) against the plain one (the former Lambert shading with mesh
// normals and a clear colour), as a ratio from one headless run. The page waits for the GPU
// after drawing (?timing=1), so drawMs includes SwiftShader's rasterisation. The view holds
// still and converged; the modes alternate frame by frame so that both see the same load.
// Also prints the core's share (LOD update and fan stream) of the same frames.
//   node bin/bench_shading.js [--frames 20] [--size 640x360]
import { startViewer, openPage } from '../tests/browser/harness.js';

const args = process.argv.slice(2);
const option = (name, fallback) => { const k = args.indexOf(`--${name}`); return k >= 0 ? args[k + 1] : fallback; };
const frames = Number(option('frames', '20'));
const [width, height] = option('size', '640x360').split('x').map(Number);
const median = (v) => [...v].sort((a, b) => a - b)[v.length >> 1];

const viewer = await startViewer();
try {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?timing=1&budget=40`, { width, height });
  await page.addStyleTag({ content: '#hud,#side,#drop-hint,#status{display:none !important}' });
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
  await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged; }, null, { timeout: 300000, polling: 200 });
  const samples = { natural: [], plain: [] };
  const core = [];
  for (let f = 0; f < 2 * frames + 4; ++f) {
    const mode = f % 2 ? 'plain' : 'natural';
    const log = await page.evaluate((m) => new Promise((resolve) => {
      const h = window.hexlod;
      h.setSetting('shading', m);
      h.frameLog = [];
      h.recordFrames = true;
      const want = h.frames + 1;
      const wait = () => (h.frames >= want ? resolve(h.frameLog.at(-1)) : requestAnimationFrame(wait));
      h.requestRender();
      requestAnimationFrame(wait);
    }), mode);
    if (f < 4) continue; // the first frames of each mode make its textures
    samples[mode].push(log.drawMs);
    core.push(log.lodMs + log.streamMs);
  }
  const info = await page.evaluate(() => ({ triangles: window.hexlod.triangles, times: window.hexlod.shadingTimes }));
  await page.close();
  if (problems.length) throw new Error(problems.join('\n'));
  const natural = median(samples.natural), plain = median(samples.plain);
  console.log(`${width}x${height}, ${info.triangles} triangles, ${frames} frames per mode, median draw time (GPU included):`);
  console.log(`  full shading ${natural.toFixed(1)} ms, plain ${plain.toFixed(1)} ms, ratio ${(natural / plain).toFixed(2)}`);
  console.log(`  core (LOD update + fan stream) median ${median(core).toFixed(1)} ms per frame`);
  console.log(`  field textures of this field (ms): ${JSON.stringify(info.times)}`);
} finally {
  await viewer.close();
}
