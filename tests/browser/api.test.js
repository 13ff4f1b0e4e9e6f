// The JS API in someone else's page (examples/, importing `hexlod` as a user's project does):
// createViewer's events in order, what it draws, two viewers on one page, the camera driven by
// the page's own buttons, bad arguments, <hexlod-viewer> with live attributes, prefers-reduced-
// motion, and dispose() giving back the WebAssembly memory, the GL context and the listeners.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { writeFileSync, rmSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, pixelStats, projectDir } from '../../lib/page_harness.js';

let viewer;
before(async () => { viewer = await startViewer({ site: 'examples', pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

// Counts the WebAssembly memories alive in the page: each instance's memory is registered, and
// told when it is collected. Set before the page's scripts run.
const COUNT_WASM_MEMORIES = () => {
  window.wasmMemories = { made: 0, collected: 0 };
  const registry = new FinalizationRegistry(() => { window.wasmMemories.collected += 1; });
  const watch = (result) => {
    const instance = result.instance ?? result;
    const memory = Object.values(instance.exports).find((e) => e instanceof WebAssembly.Memory);
    if (memory) { window.wasmMemories.made += 1; registry.register(memory, null); }
    return result;
  };
  for (const name of ['instantiate', 'instantiateStreaming']) {
    const original = WebAssembly[name];
    WebAssembly[name] = (...args) => original.apply(WebAssembly, args).then(watch);
  }
};

async function openExample(name, viewport = { width: 900, height: 560 }, init = null) {
  const page = await viewer.browser.newPage({ viewport });
  if (init) await page.addInitScript(init);
  const problems = [];
  page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
  page.on('console', (m) => { if (m.type() === 'error' || /WebGL contexts/.test(m.text())) problems.push(m.text()); });
  await page.goto(`${viewer.url}${name}.html`);
  await page.waitForFunction(() => window.viewer || window.viewers, null, { timeout: 120000 });
  return { page, problems };
}

/** A region's pixel statistics in a screenshot. */
const regionStats = async (page, selector) => pixelStats(await page.locator(selector).screenshot());

/** The share of a region's pixels that are clearly green (hypsometric lowlands; natural shading is rock and snow). */
async function greenShare(page, selector) {
  const { data, channels, width, height } = decode(await page.locator(selector).screenshot());
  let green = 0;
  for (let k = 0; k < data.length; k += channels) if (data[k + 1] > data[k] + 25 && data[k + 1] > data[k + 2]) green += 1;
  return green / (width * height);
}

test('createViewer: loaded comes before the first frame, the terrain is described, and the view draws it', async () => {
  const { page, problems } = await openExample('bare');
  const result = await page.evaluate(async () => {
    const element = document.createElement('div');
    element.style.height = '300px';
    document.body.append(element);
    const events = [];
    const second = await window.createViewer(element, { tau: 2, budgetMs: 8, ui: false,
      on: { loaded: (e) => events.push(['loaded', e.terrain?.name]), frame: (e) => { if (events.at(-1)?.[0] !== 'frame') events.push(['frame', e.triangles]); } } });
    await new Promise((resolve) => { const off = second.on('frame', (f) => { if (f.converged) { off(); resolve(); } }); });
    const out = { events, terrain: second.terrain, settings: { tau: second.settings.tau, budgetMs: second.settings.budgetMs } };
    second.dispose();
    element.remove();
    return out;
  });
  assert.deepEqual(result.events[0], ['loaded', 'globe_himalaya_2048.png']);
  assert.equal(result.events[1][0], 'frame');
  // Refined past the base mesh's few dozen triangles: how far an 8 ms budget gets depends on the machine.
  assert.ok(result.events[1][1] > 200, `the first frame after loading draws the mesh: ${result.events[1][1]} triangles`);
  assert.deepEqual(result.settings, { tau: 2, budgetMs: 8 });
  const t = result.terrain;
  assert.equal(t.width, 2048);
  assert.equal(t.height, 2048);
  assert.ok(t.maxHeight > 7000 && t.minHeight < 500, `Himalaya heights ${t.minHeight}..${t.maxHeight}`);
  assert.ok(t.centre && t.centre.lat > 20 && t.centre.lat < 40 && t.centre.lon > 75 && t.centre.lon < 95, JSON.stringify(t.centre));
  const stats = await regionStats(page, '#terrain');
  assert.ok(stats.colours > 200 && stats.luminanceStd > 10, `the bare viewer draws relief: ${JSON.stringify(stats)}`);
  assert.equal(await page.locator('#terrain #panel').isVisible(), false, 'ui: false has no panel');
  assert.deepEqual(problems, []);
  await page.close();
});

test('two viewers on one page: each draws its own settings, changes apply to one only, disposing one leaves the other', async () => {
  const { page, problems } = await openExample('two-viewers');
  const left = await regionStats(page, '#left #view'), right = await regionStats(page, '#right #view');
  assert.ok(left.colours > 150 && right.colours > 150, `both draw: ${left.colours} and ${right.colours} colours`);
  const [leftGreen, rightGreen] = [await greenShare(page, '#left #view'), await greenShare(page, '#right #view')];
  assert.ok(rightGreen > leftGreen + 0.2, `the hypsometric viewer is green where the natural one is rock: ${leftGreen} and ${rightGreen}`);
  const settings = await page.evaluate(() => {
    const [a, b] = window.viewers;
    a.set('exaggeration', 5);
    return [a.settings.exaggeration, b.settings.exaggeration, a.settings.tau, b.settings.tau];
  });
  assert.deepEqual(settings, [5, 2, 1, 2]);
  // Keys typed into one viewer are its own: the other's settings do not move.
  await page.locator('#left #view').click({ position: { x: 5, y: 300 } });
  await page.keyboard.press('o');
  assert.deepEqual(await page.evaluate(() => window.viewers.map((v) => v.settings.wireframe)), [true, false]);
  await page.evaluate(() => window.viewers[0].dispose());
  assert.equal(await page.locator('#left .hexlod').count(), 0, 'its elements are gone');
  const framesBefore = await page.evaluate(() => new Promise((resolve) => {
    let n = 0;
    const off = window.viewers[1].on('frame', () => { if (++n === 2) { off(); resolve(n); } });
    window.viewers[1].camera.flyTo({ position: [60000, 30000, 90000], target: [60000, 3000, 60000] }, { seconds: 0 });
  }));
  assert.equal(framesBefore, 2, 'the other viewer still draws');
  assert.deepEqual(problems, []);
  await page.close();
});

test('bad arguments: a clear TypeError or RangeError at once, and a refused file keeps the terrain', async () => {
  const { page } = await openExample('bare');
  const errors = await page.evaluate(async () => {
    const attempt = async (f) => { try { await f(); return 'no error'; } catch (e) { return `${e.name}: ${e.message}`; } };
    const v = window.viewer, el = document.createElement('div');
    return {
      notElement: await attempt(() => window.createViewer('#terrain')),
      options: await attempt(() => window.createViewer(el, 5)),
      tauType: await attempt(() => window.createViewer(el, { tau: '2' })),
      tauRange: await attempt(() => window.createViewer(el, { tau: 100 })),
      unknown: await attempt(() => window.createViewer(el, { colour: 'red' })),
      twice: await attempt(() => window.createViewer(document.getElementById('terrain'))),
      event: await attempt(() => v.on('click', () => {})),
      handler: await attempt(() => v.on('frame', 'draw')),
      fly: await attempt(() => v.camera.flyTo({ position: [0, 1], target: [0, 0, 0] })),
      flySeconds: await attempt(() => v.camera.flyTo({ position: [0, 1, 0], target: [0, 0, 0] }, { seconds: -1 })),
      open: await attempt(() => v.open(42)),
      set: await attempt(() => v.set('shading', 'neon')),
      missing: await attempt(() => v.open('/no/such/dem.tif')),
      name: v.terrain.name,
      shot: await attempt(() => v.screenshot({ scale: 7 })),
    };
  });
  assert.match(errors.notElement, /^TypeError: createViewer: the first argument must be an HTML element, not the string '#terrain'/);
  assert.match(errors.options, /^TypeError: createViewer: options must be an object/);
  assert.match(errors.tauType, /^TypeError: createViewer: tau must be a number, not the string '2'/);
  assert.match(errors.tauRange, /^RangeError: createViewer: tau=100 is not a number from 0.25 to 16/);
  assert.match(errors.unknown, /^TypeError: createViewer: unknown option 'colour'/);
  assert.match(errors.twice, /^TypeError: createViewer: this element already holds a viewer/);
  assert.match(errors.event, /^RangeError: viewer.on: unknown event 'click'/);
  assert.match(errors.handler, /^TypeError: viewer.on: the handler must be a function/);
  assert.match(errors.fly, /^RangeError: camera.flyTo: position must be three finite numbers/);
  assert.match(errors.flySeconds, /^RangeError: camera.flyTo: seconds must be a number from 0 to 600/);
  assert.match(errors.open, /^TypeError: viewer.open: give a URL string, a File or an array of Files, not number 42/);
  assert.match(errors.set, /^RangeError: viewer.set: shading must be one of natural, hypsometric/);
  assert.match(errors.missing, /^Error: .*dem\.tif/);
  assert.equal(errors.name, 'globe_himalaya_2048.png', 'the terrain stays');
  assert.match(errors.shot, /^RangeError: viewer.screenshot: scale must be 1, 2, 3 or 4/);
  await page.close();
});

test('the page\'s own buttons fly the camera there; with prefers-reduced-motion it goes at once', async () => {
  for (const reduced of [false, true]) {
    const { page, problems } = await openExample('camera-buttons');
    if (reduced) await page.emulateMedia({ reducedMotion: 'reduce' });
    const start = await page.evaluate(() => window.viewer.camera.get().position);
    await page.getByRole('button', { name: 'Overview' }).click();
    // Two frames after the click: a 2 s flight has barely left, a reduced-motion one has arrived.
    const early = await page.evaluate(() => new Promise((resolve) => {
      let n = 0;
      const off = window.viewer.on('frame', () => { if (++n === 2) { off(); resolve(window.viewer.camera.get().position); } });
    }));
    const goal = await page.evaluate(() => {
      const t = window.viewer.terrain, width = (t.width - 1) * t.spacingX, depth = (t.height - 1) * t.spacingY;
      return [width / 2, t.maxHeight * 6, depth * 1.1];
    });
    const distance = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    if (reduced) assert.ok(distance(early, goal) < 1, `reduced motion: there at once (${distance(early, goal)} m away)`);
    else assert.ok(distance(early, goal) > 0.5 * distance(start, goal), 'a flight takes its time');
    await page.waitForFunction((g) => {
      const p = window.viewer.camera.get().position;
      return Math.hypot(p[0] - g[0], p[1] - g[1], p[2] - g[2]) < 1;
    }, goal, { timeout: 60000 });
    // A click on the ground says where it is.
    await page.locator('#terrain #view').click({ position: { x: 450, y: 380 } });
    await page.waitForFunction(() => /\d m/.test(document.getElementById('where').textContent), null, { timeout: 30000 });
    assert.deepEqual(problems, []);
    await page.close();
  }
});

test('<hexlod-viewer>: attributes set its view and apply live; removing it disposes its viewer', async () => {
  const { page, problems } = await openExample('element');
  await page.waitForFunction(() => document.getElementById('terrain').viewer?.terrain);
  const before = await greenShare(page, '#terrain #view');
  assert.equal(await page.evaluate(() => document.getElementById('terrain').viewer.settings.exaggeration), 2);
  await page.evaluate(() => {
    const element = document.getElementById('terrain');
    element.setAttribute('shading', 'hypsometric');
    element.setAttribute('tau', '4');
    // The next frame drawn is drawn with the new shading.
    window.shadedFrame = new Promise((resolve) => {
      const stop = element.viewer.on('frame', () => { stop(); resolve(); });
    });
  });
  assert.deepEqual(await page.evaluate(() => {
    const s = document.getElementById('terrain').viewer.settings;
    return [s.shading, s.tau];
  }), ['hypsometric', 4]);
  await page.evaluate(() => window.shadedFrame);
  const after = await greenShare(page, '#terrain #view');
  assert.ok(after > before + 0.2, `the hypsometric colours show: green share ${before} → ${after}`);
  const refused = await page.evaluate(() => new Promise((resolve) => {
    const element = document.getElementById('terrain');
    element.addEventListener('hexlod-error', (e) => resolve(e.detail.message), { once: true });
    element.setAttribute('tau', 'lots');
  }));
  assert.match(refused, /tau=lots is not a number/);
  assert.equal(await page.evaluate(() => document.getElementById('terrain').viewer.settings.tau), 4, 'a refused value keeps the old one');
  await page.evaluate(() => document.getElementById('terrain').remove());
  await page.waitForFunction(() => !document.querySelector('.hexlod'));
  assert.deepEqual(problems, []);
  await page.close();
});

test('dispose() gives back the WebAssembly memory, the GL context and the page\'s listeners', async () => {
  const { page, problems } = await openExample('bare', { width: 600, height: 400 }, COUNT_WASM_MEMORIES);
  const cdp = await page.context().newCDPSession(page);
  // Twenty viewers made and disposed one after another: more than Chromium keeps GL contexts for
  // (16), so a context not given back would make it drop the oldest, with a warning.
  const figures = await page.evaluate(async () => {
    const element = document.createElement('div');
    element.style.height = '200px';
    document.body.append(element);
    let lost = 0;
    for (let k = 0; k < 20; ++k) {
      const v = await window.createViewer(element, { ui: false });
      const gl = v.canvas.getContext('webgl2');
      v.dispose();
      if (gl.isContextLost()) lost += 1;
    }
    return { lost, children: element.childElementCount };
  });
  assert.deepEqual(figures, { lost: 20, children: 0 });
  // The memories of the disposed viewers are collected (the page's own viewer keeps its one).
  let counts;
  for (let attempt = 0; attempt < 20; ++attempt) {
    await cdp.send('HeapProfiler.collectGarbage');
    counts = await page.evaluate(() => new Promise((resolve) => setTimeout(() => resolve({ ...window.wasmMemories }), 100)));
    if (counts.made - counts.collected === 1) break;
  }
  assert.equal(counts.made, 21);
  assert.equal(counts.made - counts.collected, 1, `WebAssembly memories alive after 20 disposed viewers: ${JSON.stringify(counts)}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the examples type-check against the package\'s declarations (tsc), and a wrong call does not', () => {
  const tsc = (args) => execFileSync(process.execPath, [`${projectDir}node_modules/typescript/bin/tsc`, ...args], { cwd: projectDir, encoding: 'utf8' });
  tsc(['-p', 'examples/tsconfig.json']);
  const wrong = `${projectDir}examples/wrong-call.js`;
  writeFileSync(wrong, "import { createViewer } from 'hexlod';\nawait createViewer(document.body, { tau: '2', shading: 'neon' });\n");
  try {
    assert.throws(() => tsc(['-p', 'examples/tsconfig.json']), (error) => /tau[\s\S]*shading|TS2322/.test(error.stdout));
  } finally {
    rmSync(wrong);
  }
});
