#!/usr/bin/env node
// Benchmark of streaming a Cloud-Optimized GeoTIFF far larger than memory, against opening a
// 16385² field whole. Prints figures, asserts nothing.
//   1. Writes (once; kept in build/bench/) a SIDE² int16 COG from real data: the GLOBE Himalaya
//      (public/terrain/globe_himalaya_2048.png) tiled and mirrored at every seam, 512² tiles,
//      no compression, GDAL's averaged overviews and statistics (needs gdal_translate, Debian
//      gdal-bin). At the default 40000², 3.2 GB of full resolution, 4.3 GB with overviews.
//   2. Serves it with lib/range_server.js, every request delayed by --latency ms.
//   3. In a child process (its own memory high-water mark): opens it by URL with the page's
//      streaming code and the WASM core, then flies a low-altitude flight at 60 frames a
//      second of wall time: time to the first frame, bytes fetched against the file's size,
//      the share of frames that waited for tiles, peak resident memory.
//   4. In another child: the 16385² field (the same Himalaya, as page_load.js makes it) read
//      from disk and opened whole, to its first frame: time and peak memory.
//   5. With --page, the same in the page (headless Chromium, SwiftShader): ?src= of the COG on
//      the range server, then a drag across the view, against ?src= of the 16385² .r16: time to
//      the first frame, bytes fetched, the share of frames that waited, the peak memory of
//      Chromium (proportional set size of all its processes, a browser for each phase) and the
//      core's WebAssembly memory.
// Usage: node bench/cog_tiles.js [--side N] [--latency MS] [--frames N] [--tau PX] [--page]
import { spawn, execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, openSync, writeSync, closeSync, readFileSync, readdirSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { decode } from 'fast-png';
import { startRangeServer } from '../lib/range_server.js';
import { createNodeCore } from '../lib/node_core.js';
import { openCog } from '../web/tiles/cog_source.js';
import { openTiledTerrain } from '../web/tiles/tiled_terrain.js';
import { loadTerrain } from '../web/loaders/terrain_source.js';
import { startViewer, openPage } from '../lib/page_harness.js';
import { SETTINGS } from '../web/app/settings_table.js';

const root = fileURLToPath(new URL('..', import.meta.url));
const benchDir = `${root}build/bench`;
const args = process.argv.slice(2);
const option = (name, fallback) => (args.includes(name) ? Number(args[args.indexOf(name) + 1]) : fallback);
const SIDE = option('--side', 40000), LATENCY = option('--latency', 30), FRAMES = option('--frames', 600), TAU = option('--tau', 1);
const WHOLE_SIDE = 16385;
const CAP_MB = SETTINGS.tileCacheMB.default; // the tile cache's cap in the page
const HIMALAYA = { min: 0, max: 8752, cellX: 806.9, cellY: 926 }; // public/terrain/globe_himalaya_2048.json

/** Row y of the Himalaya tiled and mirrored at every seam, as int16 metres. */
function mirroredRows(out) {
  const { data } = decode(readFileSync(`${root}public/terrain/globe_himalaya_2048.png`));
  const mirror = (i) => { const period = 2 * 2048 - 2, k = i % period; return k < 2048 ? k : period - k; };
  const metres = Int16Array.from({ length: 65536 }, (_, v) => Math.round(HIMALAYA.min + (v / 65535) * (HIMALAYA.max - HIMALAYA.min)));
  return (y) => {
    const sy = mirror(y) * 2048;
    for (let x = 0; x < out.length; x++) out[x] = metres[data[sy + mirror(x)]];
    return out;
  };
}

function writeRaw(path, side, Type) {
  const row = mirroredRows(new Type(side));
  const fd = openSync(path, 'w');
  for (let y = 0; y < side; y++) writeSync(fd, new Uint8Array(row(y).buffer));
  closeSync(fd);
}

/** The COG, written once. */
function makeCog(side) {
  const path = `${benchDir}/himalaya_${side}_cog.tif`;
  if (existsSync(path)) return { path, madeS: null };
  const start = performance.now();
  const raw = `${benchDir}/himalaya_${side}.i16`, vrt = `${benchDir}/himalaya_${side}.vrt`;
  writeRaw(raw, side, Int16Array);
  // GDAL's view of the raw file, georeferenced at the Himalaya's cell size (a local metric CRS).
  writeFileSync(vrt, `<VRTDataset rasterXSize="${side}" rasterYSize="${side}">
  <SRS>EPSG:3857</SRS>
  <GeoTransform>0, ${HIMALAYA.cellX}, 0, 0, 0, -${HIMALAYA.cellY}</GeoTransform>
  <VRTRasterBand dataType="Int16" band="1" subClass="VRTRawRasterBand">
    <SourceFilename relativeToVRT="0">${raw}</SourceFilename>
    <ImageOffset>0</ImageOffset><PixelOffset>2</PixelOffset><LineOffset>${2 * side}</LineOffset><ByteOrder>LSB</ByteOrder>
  </VRTRasterBand>
</VRTDataset>
`);
  execFileSync('gdal_translate', ['-q', '-of', 'COG', '-stats', '-co', 'BLOCKSIZE=512', '-co', 'COMPRESS=NONE',
    '-co', 'RESAMPLING=AVERAGE', '-co', 'NUM_THREADS=ALL_CPUS', '-co', 'BIGTIFF=YES', vrt, path], { stdio: 'inherit' });
  rmSync(raw);
  rmSync(vrt);
  return { path, madeS: (performance.now() - start) / 1000 };
}

/** Peak resident memory of this process so far, MB (the kernel's high-water mark). */
function peakRssMb() {
  const line = readFileSync('/proc/self/status', 'utf8').split('\n').find((l) => l.startsWith('VmHWM:'));
  return Number(/(\d+)/.exec(line)[1]) / 1024;
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// A straight flight 800 m over the highest ground below, looking 10° down, across a part of the
// field at 150 m a frame (9 km/s at 60 frames a second: a fast jet's ground track times 30).
function flightCamera(terrain, k) {
  const w = (terrain.width - 1) * terrain.spacingX, d = (terrain.height - 1) * terrain.spacingY;
  const x = 0.3 * w + 150 * k, z = 0.6 * d - 60 * k, y = 9500;
  const look = 10 * Math.PI / 180;
  return { eye: [x, y, z], target: [x + 1000 * Math.cos(look) * 0.93, y - 1000 * Math.sin(look), z - 1000 * Math.cos(look) * 0.37],
    up: [0, 1, 0], fovY: Math.PI / 3, aspect: 16 / 9, viewportHeight: 1080, near: 1, far: 2e7 };
}

async function streamPhase(url) {
  const start = performance.now();
  const core = await createNodeCore();
  const source = await openCog(url);
  const { terrain, tiles } = await openTiledTerrain(core, source);
  terrain.resetMesh('exact');
  terrain.configure({ tauPx: TAU, budgetMs: 4, morphFrames: 8 });
  terrain.frame(flightCamera(terrain, 0));
  const firstFrameS = (performance.now() - start) / 1000;
  const bytesAtFirstFrame = tiles.bytesFetched;
  let waited = 0, triangles = 0;
  const flightStart = performance.now();
  for (let k = 0; k < FRAMES; k++) {
    const frameStart = performance.now();
    const stats = terrain.frame(k === 0 ? null : flightCamera(terrain, k));
    tiles.tick();
    if (tiles.waiting > 0) waited++;
    triangles = stats.triangles;
    await sleep(Math.max(0, 1000 / 60 - (performance.now() - frameStart)));
  }
  const flightS = (performance.now() - flightStart) / 1000;
  const out = { firstFrameS, bytesAtFirstFrame, bytesFetched: tiles.bytesFetched, fileBytes: tiles.fileBytes,
    tiles: tiles.tilesIn, heldMb: tiles.heldBytes / 2 ** 20, waitedShare: waited / FRAMES, frames: FRAMES, flightS, triangles,
    coreMb: terrain.query().memoryBytes / 2 ** 20, wasmMb: core.buffer.byteLength / 2 ** 20, peakRssMb: peakRssMb() };
  tiles.close();
  return out;
}

async function wholePhase(path) {
  const start = performance.now();
  const core = await createNodeCore();
  const bytes = new Uint8Array(readFileSync(path));
  const files = [{ name: 'himalaya.r16', bytes }, { name: 'himalaya.json', bytes: new TextEncoder().encode(JSON.stringify(
    { min: 0, max: 65535, cell_size_x_m: HIMALAYA.cellX, cell_size_y_m: HIMALAYA.cellY })) }]; // raw = metres
  const { terrain } = await loadTerrain(core, files);
  terrain.resetMesh('exact');
  terrain.configure({ tauPx: TAU, budgetMs: 4, morphFrames: 8 });
  terrain.frame(flightCamera(terrain, 0));
  return { firstFrameS: (performance.now() - start) / 1000, fileBytes: bytes.length, peakRssMb: peakRssMb() };
}

/** Runs a phase in a child process (its own peak memory); its figures come back as JSON. */
function child(phase, target) {
  return new Promise((resolve, reject) => {
    const proc = spawn(process.execPath, [fileURLToPath(import.meta.url), '--phase', phase, target, ...args], { stdio: ['ignore', 'pipe', 'inherit'] });
    let out = '';
    proc.stdout.on('data', (d) => (out += d));
    proc.on('close', (code) => (code === 0 ? resolve(JSON.parse(out)) : reject(new Error(`${phase} phase failed (${code})`))));
  });
}

/**
 * Memory of the Chromium this process started, MB: the proportional set size of each of its
 * processes (shared pages split among the processes that map them, so shared libraries are
 * not counted once per process). Other browsers on the machine are not counted.
 */
function chromiumPssMb() {
  const parents = new Map();
  for (const pid of readdirSync('/proc').filter((name) => /^\d+$/.test(name))) {
    try {
      const stat = readFileSync(`/proc/${pid}/stat`, 'utf8');
      parents.set(Number(pid), { ppid: Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]), comm: stat.slice(stat.indexOf('(') + 1, stat.lastIndexOf(')')) });
    } catch { /* the process ended */ }
  }
  const ours = (pid) => { for (let p = pid; p > 1; p = parents.get(p)?.ppid ?? 0) if (p === process.pid) return true; return false; };
  let sum = 0;
  for (const [pid, { comm }] of parents) {
    if (pid === process.pid || !/chrom/i.test(comm) || !ours(pid)) continue;
    try {
      const line = readFileSync(`/proc/${pid}/smaps_rollup`, 'utf8').split('\n').find((l) => l.startsWith('Pss:'));
      sum += Number(/(\d+)/.exec(line)[1]);
    } catch { /* the process ended */ }
  }
  return sum / 1024;
}

/**
 * Opens `src` in the page and measures: navigation to the first frame of that terrain, then a
 * slow drag (orbiting the view) for `seconds`, counting the frames that waited for tiles.
 */
async function pagePhase(src, seconds) {
  // A browser of its own, so that one phase's memory does not linger into the other's.
  const viewer = await startViewer();
  const idle = chromiumPssMb();
  let peak = idle;
  const sampler = setInterval(() => { peak = Math.max(peak, chromiumPssMb()); }, 200);
  try {
    const start = Date.now();
    const { page } = await openPage(viewer.browser, `${viewer.url}?test=1${src ? `&src=${encodeURIComponent(src)}` : ''}`, { width: 1280, height: 720 });
    await page.waitForFunction(() => window.hexlod?.status !== 'loading' && window.hexlod?.frames > 0, null, { timeout: 1800000, polling: 100 });
    const firstFrameS = (Date.now() - start) / 1000;
    const opened = await page.evaluate(() => ({ status: window.hexlod.status, error: window.hexlod.error, terrain: window.hexlod.terrain }));
    // Count the frames, and those drawn while tiles were awaited, from inside the page.
    await page.evaluate(() => {
      window.benchCount = { frames: 0, waited: 0, last: window.hexlod.frames };
      const count = () => {
        const s = window.hexlod, c = window.benchCount;
        if (s.frames > c.last) { c.frames += s.frames - c.last; if (s.tiles && s.tiles.waiting > 0) c.waited += s.frames - c.last; c.last = s.frames; }
        requestAnimationFrame(count);
      };
      count();
    });
    await page.mouse.move(400, 360);
    await page.mouse.down();
    const steps = Math.max(1, Math.round(seconds * 4));
    for (let i = 0; i < steps; i++) {
      await page.mouse.move(400 + (i * 480) / steps, 360 + 40 * Math.sin(i / 5));
      await new Promise((resolve) => setTimeout(resolve, 250));
    }
    await page.mouse.up();
    const end = await page.evaluate(() => ({ count: window.benchCount, tiles: window.hexlod.tiles, triangles: window.hexlod.triangles,
      wasmMb: window.hexlod.memory().wasmBytes / 2 ** 20 }));
    peak = Math.max(peak, chromiumPssMb());
    await page.close();
    return { firstFrameS, opened, ...end, idleMb: idle, peakMb: peak };
  } finally {
    clearInterval(sampler);
    await viewer.close();
  }
}

const mb = (bytes) => (bytes / 2 ** 20).toFixed(bytes < 100 * 2 ** 20 ? 1 : 0);

if (args[0] === '--phase') {
  const result = args[1] === 'stream' ? await streamPhase(args[2]) : await wholePhase(args[2]);
  process.stdout.write(JSON.stringify(result));
} else {
  mkdirSync(benchDir, { recursive: true });
  const cog = makeCog(SIDE);
  const size = statSync(cog.path).size;
  console.log(`${SIDE}² int16 COG (the Himalaya tiled and mirrored, 512² tiles, uncompressed, averaged overviews): ` +
    `${mb(size)} MB${cog.madeS === null ? ' (made by an earlier run)' : `, written in ${cog.madeS.toFixed(0)} s`}`);
  const server = await startRangeServer(benchDir, { latencyMs: LATENCY });
  const cogUrl = `${server.url}/${cog.path.split('/').pop()}`;
  const wholePath = `${benchDir}/himalaya_${WHOLE_SIDE}.r16`;
  let streamed, whole;
  try {
    // Each phase prints as it ends: the page phases take minutes on SwiftShader.
    streamed = await child('stream', cogUrl);
    console.log(`streamed by HTTP Range (${LATENCY} ms a request), WASM core in Node, tau ${TAU} px, 4 ms a frame:`);
    console.log(`  first frame ${streamed.firstFrameS.toFixed(2)} s after the open began (goal <= 2 s), ${mb(streamed.bytesAtFirstFrame)} MB read by then`);
    console.log(`  flight of ${streamed.frames} frames (${streamed.flightS.toFixed(1)} s): ${mb(streamed.bytesFetched)} MB of ${mb(streamed.fileBytes)} MB fetched ` +
      `(${(100 * streamed.bytesFetched / streamed.fileBytes).toFixed(2)} %), ${streamed.tiles} tiles, ${(100 * streamed.waitedShare).toFixed(0)} % of frames waited for tiles`);
    console.log(`  peak resident memory ${streamed.peakRssMb.toFixed(0)} MB (tiles held ${streamed.heldMb.toFixed(0)} MB of the 512 MB cap, mesh ${streamed.coreMb.toFixed(0)} MB, ` +
      `the core's WebAssembly memory ${streamed.wasmMb.toFixed(0)} MB in all); ${streamed.triangles} triangles`);
    writeRaw(wholePath, WHOLE_SIDE, Uint16Array);
    whole = await child('whole', wholePath);
    console.log(`opened whole: ${WHOLE_SIDE}² u16 (.r16 from disk, ${mb(whole.fileBytes)} MB): first frame ${whole.firstFrameS.toFixed(2)} s, ` +
      `peak resident memory ${whole.peakRssMb.toFixed(0)} MB`);
    console.log(`ratios, streamed ${SIDE}² / whole ${WHOLE_SIDE}²: first frame ${(streamed.firstFrameS / whole.firstFrameS).toFixed(2)}, ` +
      `peak memory ${(streamed.peakRssMb / whole.peakRssMb).toFixed(2)}, file ${(streamed.fileBytes / whole.fileBytes).toFixed(1)}`);
    if (args.includes('--page')) {
      writeFileSync(wholePath.replace(/\.r16$/, '.json'), JSON.stringify({ cell_size_x_m: HIMALAYA.cellX, cell_size_y_m: HIMALAYA.cellY }));
      const memory = (r) => `Chromium's memory (PSS, all processes) at its peak ${r.peakMb.toFixed(0)} MB, ${(r.peakMb - r.idleMb).toFixed(0)} MB over the browser ` +
        `before the page; the core's WebAssembly memory ${r.wasmMb.toFixed(0)} MB`;
      const s = await pagePhase(cogUrl, 60), st = s.tiles ?? {};
      console.log(`in the page (headless Chromium, SwiftShader, 1280x720), ?src= of the COG: ${s.opened.status}${s.opened.error ? ` (${s.opened.error})` : ''}`);
      console.log(`  navigation to first frame ${s.firstFrameS.toFixed(1)} s; after a 60 s drag: ${mb(st.bytesFetched ?? 0)} MB of ${mb(st.fileBytes ?? 1)} MB fetched, ` +
        `${st.tilesIn} tiles, ${s.count.waited} of ${s.count.frames} frames waited for tiles`);
      console.log(`  ${memory(s)}`);
      const w = await pagePhase(`${server.url}/${wholePath.split('/').pop()}`, 2);
      console.log(`  ?src= of the ${WHOLE_SIDE}² .r16, whole: ${w.opened.status}, navigation to first frame ${w.firstFrameS.toFixed(1)} s`);
      console.log(`  ${memory(w)}`);
      console.log(`  ratios, streamed / whole: first frame ${(s.firstFrameS / w.firstFrameS).toFixed(2)}, ` +
        `memory over the idle browser ${((s.peakMb - s.idleMb) / (w.peakMb - w.idleMb)).toFixed(2)}`);
      // The viewer's own memory, on its default terrain (2049², 8 MB of samples): what a tab holds
      // whatever it streams, so that the streamed terrain's share can be told from it.
      const b = await pagePhase(null, 2);
      console.log(`  the default terrain, for the viewer's own share: navigation to first frame ${b.firstFrameS.toFixed(1)} s`);
      console.log(`  ${memory(b)}`);
      console.log(`  the streamed COG over the viewer on its default terrain: ${(s.peakMb - b.peakMb).toFixed(0)} MB of Chromium's memory, ` +
        `${(s.wasmMb - b.wasmMb).toFixed(0)} MB of it in the core's WebAssembly memory (cap ${CAP_MB} MB of samples)`);
    }
  } finally {
    await server.close();
    rmSync(wholePath, { force: true });
    rmSync(wholePath.replace(/\.r16$/, '.json'), { force: true });
  }
}
