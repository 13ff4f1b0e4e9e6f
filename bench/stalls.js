#!/usr/bin/env node
// Frame stalls during a scripted flight in headless Chromium (the goal: none over 100 ms
// after load). Opens the page on the default terrain, waits until it is ready (not
// converged: the flight starts while the mesh still refines), flies the fly camera low over the
// Himalaya for a fixed time, and reports from the page's requestAnimationFrame timestamps the
// longest frame-to-frame interval and how many exceeded 100 ms, with the core's share (LOD
// update + fan stream) and the drawing's. SwiftShader draws on the CPU here, so the figures are
// given at a small and a normal viewport.
// With --timing the page waits for the GPU after drawing (?timing=1, gl.finish), so that the
// drawing's share includes SwiftShader's rasterisation.
//   node bench/stalls.js [--seconds 12] [--sizes 480x300,960x600] [--timing]
import { startViewer, openPage } from '../lib/page_harness.js';

const args = process.argv.slice(2);
const option = (name, fallback) => { const k = args.indexOf(`--${name}`); return k >= 0 ? args[k + 1] : fallback; };
if (args.includes('--help')) {
  console.log('usage: node bench/stalls.js [--seconds 12] [--sizes 480x300,960x600] [--timing]');
  process.exit(0);
}
const seconds = Number(option('seconds', '12'));
const sizes = option('sizes', '480x300,960x600').split(',').map((s) => s.split('x').map(Number));

const max = (values) => values.reduce((m, v) => Math.max(m, v), 0);
const percentile = (values, p) => [...values].sort((a, b) => a - b)[Math.min(values.length - 1, Math.floor(p * values.length))];

const viewer = await startViewer();
try {
  for (const [width, height] of sizes) {
    const url = viewer.url + (args.includes('--timing') ? '?timing=1' : '');
    const { page, problems } = await openPage(viewer.browser, url, { width, height });
    await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
    // The flight: from the opening view, switch to the fly camera and cruise north-west at
    // 3 km above the ground, turning slowly, for `seconds`.
    await page.evaluate((duration) => new Promise((resolve) => {
      const h = window.hexlod;
      h.setSetting('camera', 'fly');
      const fly = h.rig.active;
      let t0 = null;
      h.frameLog = [];
      h.recordFrames = true;
      const step = (now) => {
        t0 ??= now;
        const t = (now - t0) / 1000;
        fly.yaw = 0.3 + 0.05 * t;
        fly.pitch = -0.25;
        fly.position[0] -= 200 * Math.sin(fly.yaw);
        fly.position[2] -= 200 * Math.cos(fly.yaw);
        fly.position[1] = fly.world.ground(fly.position[0], fly.position[2]) + 3000 * h.settings.exaggeration;
        h.requestRender();
        if (t < duration) requestAnimationFrame(step);
        else { h.recordFrames = false; resolve(); }
      };
      requestAnimationFrame(step);
    }), seconds);
    const log = await page.evaluate(() => window.hexlod.frameLog);
    const intervals = log.slice(1).map((f, k) => f.time - log[k].time);
    const core = log.map((f) => f.lodMs + f.streamMs);
    const draw = log.map((f) => f.drawMs + f.uploadMs);
    const cpu = log.map((f) => f.cpuMs);
    const result = {
      viewport: `${width}x${height}`, frames: log.length,
      longestFrameMs: +max(intervals).toFixed(1), over100ms: intervals.filter((v) => v > 100).length,
      medianFrameMs: +percentile(intervals, 0.5).toFixed(1),
      coreMaxMs: +max(core).toFixed(1), coreMedianMs: +percentile(core, 0.5).toFixed(1),
      drawUploadMaxMs: +max(draw).toFixed(1), drawUploadMedianMs: +percentile(draw, 0.5).toFixed(1),
      frameWorkMaxMs: +max(cpu).toFixed(1), frameWorkMedianMs: +percentile(cpu, 0.5).toFixed(1),
      timing: args.includes('--timing'), problems: problems.length,
    };
    console.log(JSON.stringify(result));
    await page.close();
  }
} finally {
  await viewer.close();
}
