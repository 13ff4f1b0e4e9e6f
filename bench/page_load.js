#!/usr/bin/env node
// Benchmark of height-field files in the page (headless Chromium, SwiftShader):
//   1. drop to first frame of public/terrain/globe_himalaya_2048.png + .json (decode included);
//   2. a 16385 x 16385 16-bit field, made by tiling and mirroring the same Himalaya, written
//      as a RAW .r16 file, opened with ?src=, then flown for a few frames: load time and peak
//      memory (RSS of every Chromium process, sampled; the page's WASM memory).
// Usage: node bench/page_load.js [--skip-large] [--runs N]
import { mkdirSync, openSync, writeSync, writeFileSync, closeSync, readFileSync, rmSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { decode } from 'fast-png';
import { startViewer, openPage, projectDir } from '../lib/page_harness.js';

const args = process.argv.slice(2);
const runs = Number(args[args.indexOf('--runs') + 1]) || 3;
const skipLarge = args.includes('--skip-large');
const LARGE = 16385;

/** Sum of the resident memory of every Chromium process, in MB. */
function chromiumRssMb() {
  try {
    const out = execFileSync('ps', ['-C', 'chromium', '-o', 'rss='], { encoding: 'utf8' });
    return out.split('\n').reduce((sum, line) => sum + (Number(line.trim()) || 0), 0) / 1024;
  } catch { return 0; }
}

async function dropToFirstFrame(viewer) {
  const png = readFileSync(`${projectDir}public/terrain/globe_himalaya_2048.png`);
  const json = readFileSync(`${projectDir}public/terrain/globe_himalaya_2048.json`);
  const times = [];
  for (let r = 0; r < runs; r++) {
    const { page } = await openPage(viewer.browser, `${viewer.url}?test=1`); // test mode publishes window.hexlod
    // An idle page, as a user has it: the default view has converged and stopped drawing.
    await page.waitForFunction(() => window.hexlod?.status === 'ready' && window.hexlod.converged, null, { timeout: 240000 });
    // The files exist in the page before the clock starts, as a user's dropped files do.
    await page.evaluate(([p, j]) => {
      const bytes = (b64) => Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
      window.benchFiles = [new File([bytes(p)], 'himalaya_drop.png'), new File([bytes(j)], 'himalaya_drop.json')];
    }, [png.toString('base64'), json.toString('base64')]);
    const ms = await page.evaluate(() => new Promise((resolve) => {
      const transfer = new DataTransfer();
      for (const f of window.benchFiles) transfer.items.add(f);
      const start = performance.now();
      window.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
      const poll = () => {
        const s = window.hexlod;
        if (s.terrain?.name === 'himalaya_drop.png') {
          const frames = s.frames;
          const wait = () => (window.hexlod.frames > frames ? resolve(performance.now() - start) : requestAnimationFrame(wait));
          return wait();
        }
        if (s.error) return resolve(NaN);
        requestAnimationFrame(poll);
      };
      poll();
    }));
    const hud = await page.evaluate(() => document.getElementById('hud').textContent);
    times.push({ ms, loadMs: Number(/loaded in (\d+) ms/.exec(hud)?.[1]) });
    await page.close();
  }
  return times;
}

/** Tiles the 2048^2 Himalaya, mirrored at every seam so the field stays continuous. */
function writeLargeField(path) {
  const { data } = decode(readFileSync(`${projectDir}public/terrain/globe_himalaya_2048.png`));
  const fd = openSync(path, 'w');
  const row = new Uint16Array(LARGE);
  const mirror = (i) => { const period = 2 * 2048 - 2, k = i % period; return k < 2048 ? k : period - k; };
  for (let y = 0; y < LARGE; y++) {
    const sy = mirror(y) * 2048;
    for (let x = 0; x < LARGE; x++) row[x] = data[sy + mirror(x)];
    writeSync(fd, new Uint8Array(row.buffer));
  }
  closeSync(fd);
}

async function largeField(viewer) {
  const dir = `${projectDir}build/bench`;
  mkdirSync(dir, { recursive: true });
  const path = `${dir}/himalaya_mirrored_${LARGE}.r16`;
  const t0 = performance.now();
  writeLargeField(path);
  // Its sidecar: the PNG's height range and the Himalaya's cell size (fetched beside ?src=).
  writeFileSync(path.replace(/\.r16$/, '.json'), JSON.stringify({ min: 0, max: 8752, cell_size_x_m: 806.9, cell_size_y_m: 926 }));
  const writeS = (performance.now() - t0) / 1000;
  let peakRss = chromiumRssMb();
  const sampler = setInterval(() => { peakRss = Math.max(peakRss, chromiumRssMb()); }, 200);
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1&src=${encodeURIComponent(`/@fs${path}`)}`);
  const loadStart = Date.now();
  await page.waitForFunction(() => window.hexlod?.status !== 'loading', null, { timeout: 1800000, polling: 1000 });
  const loadS = (Date.now() - loadStart) / 1000;
  const state = await page.evaluate(() => ({ status: window.hexlod.status, error: window.hexlod.error, terrain: window.hexlod.terrain,
    frames: window.hexlod.frames, hud: document.getElementById('hud').textContent }));
  // Fly: orbit the camera with the mouse for a few frames and count them.
  const framesBefore = state.frames;
  const flyStart = Date.now();
  await page.mouse.move(480, 300);
  await page.mouse.down();
  for (let i = 0; i < 10; i++) await page.mouse.move(480 + i * 20, 300 + i * 5);
  await page.mouse.up();
  await page.waitForFunction((f) => window.hexlod.frames >= f + 10, framesBefore, { timeout: 600000, polling: 500 });
  const flyS = (Date.now() - flyStart) / 1000;
  const after = await page.evaluate(() => ({ frames: window.hexlod.frames, triangles: window.hexlod.triangles }));
  clearInterval(sampler);
  peakRss = Math.max(peakRss, chromiumRssMb());
  await page.screenshot({ path: `${projectDir}tests/out/bench-large-field.png` });
  await page.close();
  rmSync(path);
  rmSync(path.replace(/\.r16$/, '.json'));
  return { writeS, loadS, state, flyS, frames: after.frames - framesBefore, triangles: after.triangles, peakRss, problems };
}

const viewer = await startViewer();
try {
  const times = await dropToFirstFrame(viewer);
  const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];
  console.log(`drop to first frame, globe_himalaya_2048.png + .json (2048^2 u16): ${times.map((t) => t.ms.toFixed(0)).join(', ')} ms; ` +
    `median ${median(times.map((t) => t.ms)).toFixed(0)} ms (goal <= 1500 ms); of which decode + prepare (HUD "loaded in"): ` +
    `${times.map((t) => t.loadMs).join(', ')} ms`);
  if (!skipLarge) {
    const r = await largeField(viewer);
    console.log(`16385^2 u16 field (Himalaya tiled and mirrored, .r16 via ?src=): wrote the file in ${r.writeS.toFixed(1)} s`);
    console.log(`  page status ${r.state.status}${r.state.error ? ` (${r.state.error})` : ''}, terrain ${JSON.stringify(r.state.terrain)}`);
    console.log(`  load (navigation to status ready, fetch + decode + prepare + first mesh): ${r.loadS.toFixed(1)} s`);
    console.log(`  flew ${r.frames} frames in ${r.flyS.toFixed(1)} s after an orbit drag; ${r.triangles} triangles`);
    console.log(`  peak RSS of all Chromium processes: ${r.peakRss.toFixed(0)} MB`);
    console.log(`  HUD: ${r.state.hud.split('\n').slice(0, 3).join(' | ')}`);
    if (r.problems.length) console.log(`  page problems: ${r.problems.join('; ')}`);
  }
} finally {
  await viewer.close();
}
