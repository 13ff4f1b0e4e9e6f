#!/usr/bin/env node
// Frame time of the full shading (scattering, field normals, shadows, AO, procedural
// ground, sky, tone mapping) against the plain one (the former Lambert shading with mesh
// normals and a clear colour), as a ratio from one headless run. The page waits for the GPU
// after drawing (?timing=1), so drawMs includes SwiftShader's rasterisation. The view holds
// still and converged; the modes alternate frame by frame so that both see the same load.
// Also prints the core's share (LOD update and fan stream) of the same frames.
// --modes lists more modes to compare (web/app/settings_table.js SHADING_MODES); the ratio is of the first two.
//   node bench/shading.js [--frames 20] [--size 640x360] [--modes natural,plain,hillshade]
import { startViewer } from '../lib/page_harness.js';
import { openConvergedView, frameWithSetting } from '../lib/page_frames.js';

const args = process.argv.slice(2);
const option = (name, fallback) => { const k = args.indexOf(`--${name}`); return k >= 0 ? args[k + 1] : fallback; };
const frames = Number(option('frames', '20'));
const [width, height] = option('size', '640x360').split('x').map(Number);
const modes = option('modes', 'natural,plain').split(',');
const median = (v) => [...v].sort((a, b) => a - b)[v.length >> 1];

const viewer = await startViewer();
try {
  const { page, problems } = await openConvergedView(viewer.browser, `${viewer.url}?timing=1&budget=40`, { width, height });
  const samples = Object.fromEntries(modes.map((m) => [m, []]));
  const core = [];
  for (let f = 0; f < modes.length * (frames + 2); ++f) {
    const mode = modes[f % modes.length];
    const log = await frameWithSetting(page, 'shading', mode);
    if (f < 2 * modes.length) continue; // the first frames of each mode make its textures
    samples[mode].push(log.drawMs);
    core.push(log.lodMs + log.streamMs);
  }
  const info = await page.evaluate(() => ({ triangles: window.hexlod.triangles, times: window.hexlod.shadingTimes }));
  await page.close();
  if (problems.length) throw new Error(problems.join('\n'));
  const medians = modes.map((m) => median(samples[m]));
  console.log(`${width}x${height}, ${info.triangles} triangles, ${frames} frames per mode, median draw time (GPU included):`);
  console.log(`  ${modes.map((m, k) => `${m} ${medians[k].toFixed(1)} ms`).join(', ')}; ratio ${modes[0]}/${modes[1]} ${(medians[0] / medians[1]).toFixed(2)}`);
  console.log(`  core (LOD update + fan stream) median ${median(core).toFixed(1)} ms per frame`);
  console.log(`  field textures of this field (ms): ${JSON.stringify(info.times)}`);
} finally {
  await viewer.close();
}
