#!/usr/bin/env node
// Benchmark of the page in headless Chromium: per frame the core's LOD
// update, the stream update, the upload and the draw (waited for with a one-pixel readPixels,
// ?timing=1), the interval between animation frames (what a person sees)
// along a scripted flight over the default terrain, the bytes uploaded per frame, and the
// same converged mesh drawn as TRIANGLE_FAN with primitive restart against an indexed
// TRIANGLES list. WebGL2 runs on SwiftShader (the CPU) here, so draw times are the CPU
// rasteriser's; the ratios are what carries over. It prints figures and asserts nothing.
import { parseArgs } from 'node:util';
import { startViewer, openPage } from '../lib/page_harness.js';

const USAGE = `usage: node bench/page.js [--viewport WxH] [--frames N] [--draws N]
  --viewport WxH  page size in CSS pixels (default 1280x720)
  --frames N      frames of the scripted flight (default 90)
  --draws N       timed draws per layout and round, three rounds (default 10)`;

const { values } = parseArgs({ options: { viewport: { type: 'string' }, frames: { type: 'string' }, draws: { type: 'string' },
  help: { type: 'boolean' } } });
if (values.help) {
  console.log(USAGE);
  process.exit(0);
}
const [width, height] = (values.viewport ?? '1280x720').split('x').map(Number);
const frames = Number(values.frames ?? 90), draws = Number(values.draws ?? 10);
if (!(width > 0 && height > 0 && frames > 0 && draws > 0)) {
  console.error(`hexlod bench-page: bad arguments\n${USAGE}`);
  process.exit(2);
}

const quantile = (values, q) => {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.round(q * (sorted.length - 1)))];
};
const ms = (v) => `${v.toFixed(2)} ms`;
const kb = (v) => `${(v / 1024).toFixed(1)} KB`;

/** Asks the page for one frame and waits until it is drawn; returns the frame's figures. */
async function drawFrame(page) {
  return page.evaluate(() => new Promise((resolve) => {
    const target = window.hexlod.frames + 1;
    const begin = performance.now();
    window.hexlod.requestRender();
    const check = () => (window.hexlod.frames >= target
      ? resolve({ ...window.hexlod.timing, wallMs: performance.now() - begin, uploadBytes: window.hexlod.uploadBytes, streamBytes: window.hexlod.streamBytes,
        triangles: window.hexlod.triangles })
      : requestAnimationFrame(check));
    requestAnimationFrame(check);
  }));
}

const viewer = await startViewer();
try {
  const { page } = await openPage(viewer.browser, `${viewer.url}?timing=1`, { width, height });
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 60000 });
  await page.waitForFunction(() => window.hexlod.status !== 'ready' || window.hexlod.converged, null, { timeout: 300000 });
  const start = await page.evaluate(() => {
    const { camera } = window.hexlod;
    return { x: camera.target[0], z: camera.target[2], distance: camera.distance, yaw: camera.yaw };
  });
  console.log(`page ${width}x${height}, default terrain, converged at load; flight of ${frames} frames (4 ms LOD budget, ` +
    'geomorph 8 frames, the default triangle-list layout)');

  // 1. The flight: northwards and lower, turning slowly; one camera step per drawn frame.
  const flight = [];
  for (let i = 0; i < frames; i++) {
    const t = i / frames;
    await page.evaluate(({ x, z, distance, yaw }) => {
      const { camera } = window.hexlod;
      camera.target[0] = x;
      camera.target[2] = z;
      camera.distance = distance;
      camera.yaw = yaw;
      camera.pitch = 0.3;
    }, { x: start.x + 30000 * t, z: start.z - 120000 * t, distance: start.distance * (1 - 0.6 * t), yaw: start.yaw + 0.5 * t });
    flight.push(await drawFrame(page));
  }
  const col = (key) => flight.map((f) => f[key]);
  const row = (name, key) => console.log(`  ${name.padEnd(28)} p50 ${ms(quantile(col(key), 0.5))}, p95 ${ms(quantile(col(key), 0.95))}, ` +
    `max ${ms(Math.max(...col(key)))}`);
  row('LOD update (core)', 'updateMs');
  row('stream update (core)', 'streamMs');
  row('upload (bufferSubData)', 'uploadMs');
  row('draw (until done)', 'drawMs');
  row('whole frame (our code)', 'frameMs');
  row('request to drawn (rAF)', 'wallMs');
  console.log(`  uploaded per frame           p50 ${kb(quantile(col('uploadBytes'), 0.5))}, p95 ${kb(quantile(col('uploadBytes'), 0.95))}, ` +
    `max ${kb(Math.max(...col('uploadBytes')))}; whole stream p50 ${kb(quantile(col('streamBytes'), 0.5))}`);
  console.log(`  triangles                    p50 ${quantile(col('triangles'), 0.5)}, max ${Math.max(...col('triangles'))}`);

  // 2. Fans against a triangle list on the same mesh: the LOD frozen at the last camera, then
  // alternating layouts, the first draw after each switch (the full upload) not timed.
  await page.evaluate(() => window.hexlod.setSetting('freeze', true));
  const times = { fans: [], triangles: [] };
  let triangles = 0;
  for (let round = 0; round < 3; round++) {
    for (const layout of ['fans', 'triangles']) {
      await page.evaluate((l) => window.hexlod.setLayout(l), layout);
      await drawFrame(page);
      for (let k = 0; k < draws; k++) {
        const f = await drawFrame(page);
        times[layout].push(f.drawMs);
        triangles = f.triangles;
      }
    }
  }
  const fans = quantile(times.fans, 0.5), list = quantile(times.triangles, 0.5);
  console.log(`layouts on the same mesh (${triangles} triangles), draw until done, median of ${3 * draws}:`);
  console.log(`  TRIANGLE_FAN + restart ${ms(fans)}; TRIANGLES list ${ms(list)}; list / fans ${(list / fans).toFixed(3)}`);
  console.log(`  index bytes per cell: fans 36, list 72`);
} finally {
  await viewer.close();
}
