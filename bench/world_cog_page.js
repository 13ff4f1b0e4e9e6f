#!/usr/bin/env node
// The world from one URL in the page: headless Chromium (SwiftShader) opens the virtual world COG
// of lib/world_cog_server.js (1,296,000 x 626,400 samples at 1″, 2.2 TB, every answer delayed by
// --latency ms) by ?src=, and this prints the time from the navigation to the first frame that
// draws the terrain, with the requests and bytes the server answered before it; then the same
// for the page opening its built-in terrain, for scale (SwiftShader draws on the CPU). Runs
// --runs times, alternating. Figures printed, never asserted.
//
//   node bench/world_cog_page.js [--runs N] [--latency MS]   (defaults 3, 20)
import { startViewer, openPage } from '../lib/page_harness.js';
import { startWorldCogServer } from '../lib/world_cog_server.js';
import { median } from '../lib/page_frames.js';

const args = process.argv.slice(2);
const option = (name, fallback) => (args.includes(name) ? Number(args[args.indexOf(name) + 1]) : fallback);
const RUNS = option('--runs', 3), LATENCY = option('--latency', 20);
const VIEW = { width: 1280, height: 720 };

const [viewer, world] = await Promise.all([startViewer(), startWorldCogServer({ latencyMs: LATENCY })]);
const times = { world: [], builtIn: [] };
let before = null;
try {
  for (let run = 0; run < RUNS; run++) {
    for (const which of ['world', 'builtIn']) {
      world.reset();
      const url = which === 'world' ? `${viewer.url}?src=${encodeURIComponent(world.url)}` : viewer.url;
      const start = performance.now();
      const { page } = await openPage(viewer.browser, url, VIEW);
      await page.waitForFunction(() => window.hexlod?.triangles > 0 && window.hexlod.frames > 0, null, { timeout: 300000, polling: 20 });
      times[which].push(performance.now() - start);
      if (which === 'world') before = world.stats();
      await page.close();
    }
  }
} finally {
  await Promise.all([viewer.close(), world.close()]);
}
const ms = (list) => `${Math.round(median(list))} ms (runs: ${list.map(Math.round).join(', ')})`;
console.log(`world COG in the page, ${LATENCY} ms latency, ${VIEW.width} x ${VIEW.height}:`);
console.log(`  to the first frame: ${ms(times.world)}; before it ${before.requests} requests, ${before.bytes} bytes`);
console.log(`  the built-in terrain to its first frame: ${ms(times.builtIn)}`);
console.log(`  ratio world / built-in: ${(median(times.world) / median(times.builtIn)).toFixed(2)}`);
