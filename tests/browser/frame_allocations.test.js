// The page's frame path makes no garbage once warm, flown with the keys in three phases (fly,
// walk with contour lines and labels, fly with colour by level and outlines), over overlays, with V8's sampling
// heap profiler on through the DevTools protocol at a sampling interval so small that an object
// of 16 bytes or more is sampled with a probability above 0.98.
//
// What counts: every sample whose JS stack passes through the frame callback
// (FramePipeline.render in web/app/frame_pipeline.js), i.e. anything our frame path allocates,
// in our code or in a browser API it calls. What does not: allocations with no frame callback
// on their stack (the browser's own, this test's page.evaluate calls, the address bar's
// throttled writer), and the HUD's text, which a person reads and which is rewritten at most
// every 250 ms whatever the frame rate (a string cannot be rewritten in place).
//
// Boxed numbers: V8 keeps a double that code has not proven to stay a double (a local of code
// not yet optimised, an argument to a call that is not inlined) in a small engine object, not
// one our code creates and not one a page can avoid short of doing all its arithmetic in typed
// arrays. At SwiftShader's few frames a second, code called once a frame stays unoptimised, so
// these dominate the frame path (some 800 a frame). Their size is measured, not guessed: a
// second browser with the JIT off (--jitless, so nothing is optimised away) runs a loop that
// boxes a double per step, and the size of its samples is the boxed number's.
//
// Inside the core: WebAssembly without reference types cannot make a JavaScript object, and
// each of the core's imports (src/lod/frame_clock.h's clock among them) shows as a JS frame of
// its own when it allocates. A sample whose innermost frame is the JS-to-WebAssembly entry
// itself is the engine's own bookkeeping while the core runs (some 24-byte objects a frame
// here), reported apart.
//
// What remains besides them is the engine's own now and then: feedback and inline-cache
// objects, code tier-up, seen in functions with no allocating expression at all (a getter that
// returns a field), at a site that changes from run to run and at most a few tenths of a
// sample a frame. Garbage of ours is made at its site in every frame. So each phase is
// profiled in two windows one after the other, and a site fails when it allocates in half of the
// frames or more in both windows: garbage of ours is sampled in over 98 % of frames in each,
// while the engine's allocations come in bursts and stay far under half.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startViewer, openPage } from '../../lib/page_harness.js';
import { launchChromium } from '../../lib/chromium.js';

const FRAME_PATH = /\/web\/app\/frame_pipeline\.js/;
// [file, function]: allowed inside the frame path (see above).
const ALLOWED = [[/\/web\/ui\/hud\.js/, 'update']];
const PHASES = [
  { name: 'fly', camera: 'fly', levels: false },
  { name: 'walk with contour lines and labels', camera: 'walk', levels: false, contours: true },
  { name: 'fly, colour by level and outlines', camera: 'fly', levels: true },
];
const WARM_FRAMES = 20; // a phase's frames before profiling: its code has run and met its types
const WINDOW_FRAMES = 40; // frames of each of a phase's two profiled windows
const SITE_LIMIT = 0.5; // samples a frame at one site, in both windows, that fail
const TOTAL_LIMIT = 2; // samples a frame in all, in both windows, that fail (garbage spread over sites)
const SAMPLING = { samplingInterval: 4, includeObjectsCollectedByMajorGC: true, includeObjectsCollectedByMinorGC: true };
const MEASURED = 'measure=p:1300000,1000000;1450000,1100000;1460000,960000';

let viewer, page, cdp, boxedSize;
before(async () => {
  boxedSize = await boxedNumberSize();
  viewer = await startViewer({ pixelRatio: 0.5 });
  // With a measured line, and a GPX track and a KML of places (lines, a line aloft, a filled
  // polygon, markers and their names), so that all of them are drawn in every frame profiled.
  const overlays = ['everest_trek.gpx', 'everest_places.kml'].map((f) => `&overlay=${encodeURIComponent(`${viewer.fixturesUrl}overlays/${f}`)}`).join('');
  ({ page } = await openPage(viewer.browser, `${viewer.url}?${MEASURED}${overlays}`, { width: 240, height: 180 }));
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 180000 });
  await page.waitForFunction(() => window.hexlod.layers.overlays.length === 2, null, { timeout: 60000 });
  assert.equal(await page.evaluate(() => window.hexlod.status), 'ready');
  cdp = await page.context().newCDPSession(page);
  await cdp.send('HeapProfiler.enable');
});
after(async () => { await viewer?.close(); });

/** Samples of a sampling heap profile taken while `run()` runs, with their stacks (innermost frame first). */
async function profiled(session, run) {
  await session.send('HeapProfiler.collectGarbage');
  await session.send('HeapProfiler.startSampling', SAMPLING);
  await run();
  const { profile } = await session.send('HeapProfiler.stopSampling');
  const parents = new Map(), nodes = new Map();
  const visit = (node, parent) => {
    nodes.set(node.id, node);
    parents.set(node.id, parent);
    for (const child of node.children) visit(child, node);
  };
  visit(profile.head, null);
  return profile.samples.map((sample) => {
    const stack = [];
    for (let node = nodes.get(sample.nodeId); node; node = parents.get(node.id)) stack.push(node.callFrame);
    return { size: sample.size, stack };
  });
}

/** The sampled size of a boxed double, from a browser with the JIT off running a loop that boxes one a step. */
async function boxedNumberSize() {
  const browser = await launchChromium(undefined, ['--js-flags=--jitless']);
  try {
    const calibration = await browser.newPage();
    await calibration.setContent('<script>function box() { let s = 0.5; for (let i = 0; i < 20000; i++) s = s * 1.0000001 + 0.25; return s; }</script>');
    const session = await calibration.context().newCDPSession(calibration);
    await session.send('HeapProfiler.enable');
    const samples = (await profiled(session, () => calibration.evaluate(() => window.box())))
      .filter((s) => s.stack[0].functionName === 'box');
    const sizes = new Map();
    for (const { size } of samples) sizes.set(size, (sizes.get(size) ?? 0) + 1);
    const [size, count] = [...sizes].sort((a, b) => b[1] - a[1])[0] ?? [0, 0];
    // 20,000 boxes of 12 to 32 bytes sampled every 4 bytes: tens of thousands of samples, all of one size.
    assert.ok(count > 10000 && count > 0.99 * samples.length, `boxed numbers sampled by size: ${JSON.stringify([...sizes])}`);
    return size;
  } finally {
    await browser.close();
  }
}

/** Sets a phase's camera and views. */
const enter = (phase) => page.evaluate(({ camera, levels, contours = false }) => {
  const h = window.hexlod;
  h.setSetting('camera', camera);
  h.setSetting('colorByLevel', levels);
  h.setSetting('wireframe', levels);
  h.setSetting('contours', contours);
  const c = h.rig.active;
  c.yaw = 0.3;
  c.pitch = -0.2;
}, phase);

/** Flies with W held until `frames` more frames were drawn; returns how many were. */
async function fly(frames) {
  const start = await page.evaluate(() => { window.hexlod.mark = window.hexlod.frames; return window.hexlod.frames; });
  await page.keyboard.down('w');
  await page.waitForFunction((n) => window.hexlod.frames - window.hexlod.mark >= n, frames, { timeout: 600000, polling: 100 });
  await page.keyboard.up('w');
  return (await page.evaluate(() => window.hexlod.frames)) - start;
}

const where = (frame) => `${frame.functionName || '(anonymous)'} ${frame.url.replace(/^.*\/web\//, 'web/')}:${frame.lineNumber + 1}`;

/** One window's frame-path samples sorted: HUD text, boxed numbers, the engine's inside the core, and the rest (garbage) by site. */
function sorted(samples) {
  const allowed = (s) => s.stack.some((f) => ALLOWED.some(([file, fn]) => file.test(f.url) && f.functionName === fn));
  const kind = (s) => (allowed(s) ? 'hud' : s.size === boxedSize ? 'numbers'
    : /^js-to-wasm/.test(s.stack[0].functionName) ? 'engine' : 'garbage');
  const counts = { hud: 0, numbers: 0, engine: 0, garbage: 0 };
  // Where: the innermost frame of ours (web/) of each sample of garbage.
  const sites = new Map();
  for (const s of samples) {
    if (!s.stack.some((f) => FRAME_PATH.test(f.url))) continue;
    const k = kind(s);
    counts[k] += 1;
    if (k !== 'garbage') continue;
    const ours = s.stack.find((f) => /\/web\//.test(f.url)) ?? s.stack[0];
    const key = `${s.size} B in ${where(ours)} <- ${s.stack.filter((f) => /\/web\//.test(f.url)).slice(1, 3).map(where).join(' <- ')}`;
    sites.set(key, (sites.get(key) ?? 0) + 1);
  }
  return { all: samples.length, ...counts, sites };
}

test('flying with fly, walk with contours, and colour by level, the frame path allocates nothing once warm', async () => {
  const failures = [];
  for (const phase of PHASES) {
    await enter(phase);
    await fly(WARM_FRAMES);
    const windows = [];
    for (let w = 0; w < 2; w++) {
      let frames = 0;
      const samples = await profiled(cdp, async () => { frames = await fly(WINDOW_FRAMES); });
      assert.ok(frames >= WINDOW_FRAMES, `${frames} frames drawn`);
      assert.ok(samples.length > 0, 'the profiler sampled something (the browser allocates all the time)');
      windows.push({ frames, ...sorted(samples) });
    }
    const perFrame = (n, frames) => (n / frames).toFixed(2);
    for (const [w, r] of windows.entries()) {
      console.log(`${phase.name}, window ${w + 1}: ${r.all} samples, over ${r.frames} frames in the frame path ` +
        `${perFrame(r.hud, r.frames)} a frame the HUD's text, ${perFrame(r.numbers, r.frames)} boxed numbers (${boxedSize} B), ` +
        `${perFrame(r.engine, r.frames)} the engine's inside the core, ${perFrame(r.garbage, r.frames)} other`);
      const report = [...r.sites].sort((a, b) => b[1] - a[1]).slice(0, 12).map(([site, n]) => `${n} x ${site}`).join('\n');
      if (report) console.log(report);
    }
    const [a, b] = windows;
    for (const [site, n] of a.sites) {
      const m = b.sites.get(site) ?? 0;
      if (n >= SITE_LIMIT * a.frames && m >= SITE_LIMIT * b.frames) failures.push(`${phase.name}: ${n} and ${m} samples of ${site}`);
    }
    if (a.garbage >= TOTAL_LIMIT * a.frames && b.garbage >= TOTAL_LIMIT * b.frames) {
      failures.push(`${phase.name}: ${a.garbage} and ${b.garbage} samples in all`);
    }
  }
  assert.deepEqual(failures, [], 'the frame path allocates in every frame');
});
