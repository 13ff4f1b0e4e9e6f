#!/usr/bin/env node
// A viewer's start in someone else's page: figures printed, never asserted. The package's
// browser library (library/, ./build.sh library) is served by a plain static server beside a
// page that imports it by an import map; each run opens the page afresh in headless Chromium
// (its HTTP cache warm after the first) and times, inside the page, from the createViewer()
// call to its 'loaded' event (core instantiated, default terrain fetched, decoded and its mesh
// made) and to the first frame drawn. Prints the median, fastest and slowest of N runs. The
// frame is drawn by SwiftShader on the CPU here: judge the figure by its parts and by ratios.
//
//   node bench/viewer_start.js [--runs N]   (default 5)
import { existsSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { countOption } from '../lib/script_options.js';
import { startFileServer } from '../lib/static_site.js';
import { launchChromium } from '../lib/chromium.js';
import { median, formatMs } from '../lib/page_frames.js';

const USAGE = 'usage: node bench/viewer_start.js [--runs N]\n  N fresh pages, each timing createViewer() to its first frame (default 5)';
const { count: runCount, exitCode } = countOption('bench/viewer_start.js', USAGE, 'runs', 5);
if (runCount === null) process.exit(exitCode);

const root = fileURLToPath(new URL('..', import.meta.url));
if (!existsSync(join(root, 'library/hexlod.js'))) {
  console.error('bench/viewer_start.js: library/ is not built: run ./build.sh library');
  process.exit(2);
}
const pageDir = mkdtempSync(join(tmpdir(), 'hexlod-bench-start-'));
writeFileSync(join(pageDir, 'index.html'), `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>start</title>
<link rel="icon" href="data:,">
<script type="importmap">{ "imports": { "hexlod": "./library/hexlod.js" } }</script></head>
<body style="margin:0"><div id="terrain" style="height:100vh"></div>
<script type="module">
  import { createViewer } from 'hexlod';
  const start = performance.now(), times = {};
  window.times = new Promise((resolve) => { const viewer = createViewer(document.getElementById('terrain'), { ui: false, on: {
    loaded: () => { times.loaded = performance.now() - start; viewer.then((v) => { times.terrain = v.terrain; }); },
    frame: () => { if (!times.frame) { times.frame = performance.now() - start; resolve(times); } } } }); });
</script></body></html>`);
const server = await startFileServer({ mounts: [['/library/', join(root, 'library/')], ['/', `${pageDir}/`]] });
const browser = await launchChromium();
const page = await browser.newPage({ viewport: { width: 960, height: 600 } });
const runs = [];
try {
  for (let k = 0; k < runCount; ++k) {
    await page.goto(`${server.origin}/index.html`);
    runs.push(await page.evaluate(() => window.times));
  }
} finally {
  await browser.close();
  await server.close();
  rmSync(pageDir, { recursive: true, force: true });
}
const line = (name, values) => `${name.padEnd(34)} median ${formatMs(median(values))}  (${formatMs(Math.min(...values))} to ${formatMs(Math.max(...values))})`;
const { name, width, height } = runs[0].terrain;
console.log(`createViewer() in a page of its own, default terrain ${name} (${width} x ${height} samples), 960 x 600, ${runCount} runs, SwiftShader`);
console.log(line('createViewer() to "loaded"', runs.map((r) => r.loaded)));
console.log(line('createViewer() to the first frame', runs.map((r) => r.frame)));
