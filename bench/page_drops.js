#!/usr/bin/env node
// Page soak: 100 files dropped on the page in a row, good and bad alternating (the
// format fixtures, and broken copies of them: truncated, empty, garbage, a lone sidecar, a PNG
// that declares 100000 x 100000 samples). After each drop has ended (shown, or refused with
// its message) and a few frames are drawn, the page's memory is read:
//   terrains   the terrains the core holds (test API: created and not destroyed): 1, always
//   WASM   the core's WebAssembly memory (it grows, never shrinks: a terrain left behind shows
//          as growth once the largest file has been seen)
//   heap   the page's JavaScript heap after a forced garbage collection (CDP)
//   nodes, listeners   DOM nodes and JavaScript event listeners (CDP)
//   RSS    the browser's processes together (the GPU process holds WebGL buffers and textures)
// Verdict: after a warm-up (every file dropped once), every time the same file is on screen
// again the page is back at the memory it had then (WASM equal, heap within 2 MB, the same
// listeners, nodes within 50), the core holds one terrain after every drop, and a refused file
// leaves the page as the terrain before it did.
// Usage: node bench/page_drops.js [--drops N]   (headless Chromium, SwiftShader, 320 x 200)
import { readFileSync } from 'node:fs';
import { crc32 } from 'node:zlib';
import { startViewer, openPage, dropFiles, drawFrames, projectDir } from '../lib/page_harness.js';

const args = process.argv.slice(2);
const DROPS = Number(args[args.indexOf('--drops') + 1]) || 100;
const HEAP_TOLERANCE_MB = 2;
const FIXTURES = `${projectDir}tests/fixtures/`;
const MB = 2 ** 20;

const read = (path) => ({ name: path.split('/').pop(), bytes: new Uint8Array(readFileSync(`${FIXTURES}${path}`)) });

/** Good drops: one height field (with its sidecar when it has one) each. */
const GOOD = [
  ['formats/everest_16bit.png'], ['formats/jacksboro_8bit.png', 'formats/jacksboro_8bit.json'],
  ['formats/canyon.r16', 'formats/canyon.json'], ['formats/everest_i16_strips.tif'],
  ['formats/jacksboro_f32_tiled_lzw.tif'], ['formats/jacksboro_voids.asc'], ['formats/everest.pgm', 'formats/everest.json'],
  ['formats/canyon_u16_tiled_deflate.tif'], ['grandcanyon_512.png', 'grandcanyon_512.json'],
  ['volcano_maungawhau.png', 'volcano_maungawhau.json'],
].map((paths) => paths.map(read));

/** A PNG that declares `width` x `height` 16-bit grey samples and holds none. */
function pngDeclaring(width, height) {
  const chunk = (type, data) => {
    const body = Buffer.concat([Buffer.from(type, 'latin1'), data]);
    const out = Buffer.alloc(12 + data.length);
    out.writeUInt32BE(data.length, 0);
    body.copy(out, 4);
    out.writeUInt32BE(crc32(body), 8 + data.length);
    return out;
  };
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header[8] = 16; // bit depth; colour type 0 (grey), deflate, no filter, no interlace
  return new Uint8Array(Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', header), chunk('IEND', Buffer.alloc(0))]));
}

/** Bad drops: broken copies of the good files and files that are no height field. */
function badDrops() {
  const bad = GOOD.map(([main]) => [{ name: `truncated_${main.name}`, bytes: main.bytes.slice(0, Math.floor(main.bytes.length / 2)) }]);
  let seed = 1;
  const garbage = new Uint8Array(65536).map(() => (seed = (seed * 1103515245 + 12345) >>> 0) >>> 24);
  bad.push(
    [{ name: 'empty.tif', bytes: new Uint8Array(0) }],
    [{ name: 'garbage.png', bytes: garbage }],
    [{ name: 'notes.hgt', bytes: new TextEncoder().encode('not a height field\n'.repeat(100)) }],
    [{ name: 'lonely.json', bytes: new TextEncoder().encode('{"cell_size_m": 30}') }],
    [{ name: 'absurd_size.png', bytes: pngDeclaring(100000, 100000) }],
  );
  return bad;
}

/** Resident memory of this browser's processes together (not other Chromiums on the machine), in MB. */
async function browserRssMb(browserCdp) {
  const { processInfo } = await browserCdp.send('SystemInfo.getProcessInfo');
  let kb = 0;
  for (const { id } of processInfo) {
    try { kb += Number(/VmRSS:\s+(\d+)/.exec(readFileSync(`/proc/${id}/status`, 'utf8'))?.[1] ?? 0); } catch { /* ended */ }
  }
  return kb / 1024;
}

/** The page's memory now (after a garbage collection). */
async function memory(page, cdp, browserCdp) {
  // The inspector keeps every console message (a refused file's warning) while a tool is
  // attached; a page in a person's browser does not: those are let go first.
  await cdp.send('Runtime.discardConsoleEntries');
  await cdp.send('HeapProfiler.collectGarbage');
  const { usedSize } = await cdp.send('Runtime.getHeapUsage');
  const { nodes, jsEventListeners } = await cdp.send('Memory.getDOMCounters');
  const { wasmBytes, liveTerrains } = await page.evaluate(() => window.hexlod.memory());
  return { terrains: liveTerrains, wasmMB: wasmBytes / MB, heapMB: usedSize / MB, nodes, listeners: jsEventListeners, rssMB: await browserRssMb(browserCdp) };
}

const viewer = await startViewer();
try {
  const { page, problems } = await openPage(viewer.browser, viewer.url, { width: 320, height: 200 });
  const cdp = await page.context().newCDPSession(page);
  const browserCdp = await viewer.browser.newBrowserCDPSession();
  await page.waitForFunction(() => window.hexlod?.status === 'ready' && !window.hexlod.loading, null, { timeout: 240000 });
  await drawFrames(page, 3);
  const bad = badDrops();
  const rows = [{ drop: 0, file: '(default terrain)', outcome: 'shown', shown: 'globe_himalaya_2048.png', ...await memory(page, cdp, browserCdp) }];
  const started = Date.now();
  for (let k = 0; k < DROPS; ++k) {
    const good = k % 2 === 0;
    const files = good ? GOOD[(k / 2) % GOOD.length] : bad[((k - 1) / 2) % bad.length];
    await page.evaluate(() => { window.hexlod.error = null; });
    await dropFiles(page, files);
    // The drop starts its load at once; wait until it has ended, shown or refused. A RAW file
    // that does not give its size (a truncated .r16) makes the page ask: the soak answers Cancel.
    await page.waitForFunction(() => !window.hexlod.loading || document.getElementById('raw-dialog').open, null,
      { timeout: 120000, polling: 50 });
    if (await page.evaluate(() => document.getElementById('raw-dialog').open)) {
      await page.click('#raw-cancel');
      await page.waitForFunction(() => !window.hexlod.loading, null, { timeout: 120000, polling: 50 });
    }
    await drawFrames(page, 3);
    const { shown, error } = await page.evaluate(() => ({ shown: window.hexlod.terrain?.name, error: window.hexlod.error }));
    const outcome = error ? 'refused' : shown === files[0].name ? 'shown' : `?? ${shown}`;
    rows.push({ drop: k + 1, file: files.map((f) => f.name).join(' + '), outcome, shown, error, ...await memory(page, cdp, browserCdp) });
    if (good !== (outcome === 'shown')) console.error(`drop ${k + 1}: ${files[0].name} was ${outcome}${error ? `: ${error}` : ''}`);
  }
  const seconds = (Date.now() - started) / 1000;

  console.log(`Page soak: ${DROPS} drops, good and bad alternating (${seconds.toFixed(0)} s; Chromium ${viewer.browser.version()}, SwiftShader, 320 x 200)\n`);
  console.log('| drop | file | outcome | on screen | terrains | WASM MB | heap MB | nodes | listeners | RSS MB |');
  console.log('| ---: | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |');
  for (const r of rows) {
    console.log(`| ${r.drop} | ${r.file} | ${r.outcome} | ${r.shown} | ${r.terrains} | ${r.wasmMB.toFixed(1)} | ${r.heapMB.toFixed(2)} | ${r.nodes} | ${r.listeners} | ${r.rssMB.toFixed(0)} |`);
  }

  // Back to its level: the same terrain on screen, the same memory as the first time it was
  // after the warm-up (every file dropped once: one-time costs such as the first RAW size
  // dialog or a decoder module loaded on first use are not growth).
  const warmUp = 2 * Math.max(GOOD.length, bad.length);
  const first = new Map();
  const findings = [];
  for (const r of rows.filter((row) => row.drop >= warmUp)) {
    const was = first.get(r.shown);
    if (!was) { first.set(r.shown, r); continue; }
    const heapGrowth = r.heapMB - was.heapMB;
    if (r.wasmMB > was.wasmMB) findings.push(`drop ${r.drop}: WASM ${was.wasmMB.toFixed(1)} -> ${r.wasmMB.toFixed(1)} MB with ${r.shown} again`);
    if (heapGrowth > HEAP_TOLERANCE_MB) findings.push(`drop ${r.drop}: heap +${heapGrowth.toFixed(2)} MB over the first time ${r.shown} was on screen`);
    if (r.listeners > was.listeners) findings.push(`drop ${r.drop}: ${r.listeners - was.listeners} more event listeners`);
    if (r.nodes > was.nodes + 50) findings.push(`drop ${r.drop}: ${r.nodes - was.nodes} more DOM nodes`);
  }
  for (const r of rows) if (r.terrains !== 1) findings.push(`drop ${r.drop}: the core holds ${r.terrains} terrains`);
  const wrong = rows.filter((r) => r.outcome.startsWith('??') || (r.drop > 0 && (r.drop % 2 === 1) !== (r.outcome === 'shown')));
  const good = rows.filter((r) => r.outcome === 'shown');
  const summary = (key, unit, digits) => {
    const values = rows.map((r) => r[key]);
    return `${key.replace(/MB$/, '')} ${Math.min(...values).toFixed(digits)}–${Math.max(...values).toFixed(digits)} ${unit}`;
  };
  console.log(`\n${good.length - 1} files shown, ${rows.length - good.length} refused; ${summary('wasmMB', 'MB', 1)}, ${summary('heapMB', 'MB', 2)}, `
    + `${summary('listeners', '', 0)}, ${summary('rssMB', 'MB', 0)} over the run`);
  const cycle = rows[Math.min(warmUp, rows.length - 1)];
  console.log(`last drop vs drop ${cycle.drop}: heap ${(rows.at(-1).heapMB - cycle.heapMB).toFixed(2)} MB, `
    + `WASM ${(rows.at(-1).wasmMB - cycle.wasmMB).toFixed(1)} MB, RSS ${(rows.at(-1).rssMB - cycle.rssMB).toFixed(0)} MB`);
  const pageProblems = problems.filter((p) => !/^console\.error: hexlod: /.test(p));
  const ok = findings.length === 0 && wrong.length === 0 && pageProblems.length === 0;
  console.log(`verdict: ${ok ? 'PASS: after every drop the page is back at its level' : 'FAIL'}`);
  for (const line of [...findings, ...wrong.map((r) => `drop ${r.drop}: ${r.file} ${r.outcome}`), ...pageProblems]) console.log(`  ${line}`);
  process.exitCode = ok ? 0 : 1;
} finally {
  await viewer.close();
}
