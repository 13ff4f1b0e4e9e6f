// The journeys a person takes, judged by what they see: the terrain on screen (its share of the
// window, its colours), the camera above the ground, and a refined mesh (triangles at τ = 1).
// Open the page; drop every format and the real DEMs; pick a file; ?src=; R after moving away;
// switch cameras after a drop; change the exaggeration after a drop; fields of odd shapes and
// heights. Screenshots go to tests/out/journey-*.png.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, outDir, projectDir, terrainCoverage, pageReady, dropFiles, terrainShown,
  converged, eyeClearance, nextFrame, FULL_RESOLUTION } from '../../lib/page_harness.js';

const FIXTURES = `${projectDir}tests/fixtures/`;
const VIEWPORT = { width: 960, height: 540 };
const read = (path) => ({ name: path.split('/').pop(), bytes: readFileSync(FIXTURES + path) });

let viewer;
// Pages at half a device pixel per CSS pixel: the layout of the window they emulate, a quarter of
// the pixels for SwiftShader to draw; the opening view, the phone and the odd fields are judged at
// full resolution.
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

/**
 * Asserts that the terrain is seen as a person would want: converged at τ = 1 with at least
 * `minTriangles`, over at least `minCoverage` of the window, in many colours, the eye above
 * the ground. Saves the screenshot as tests/out/journey-<label>.png.
 */
async function assertSeen(page, label, { minCoverage = 0.15, maxCoverage = 1, minTriangles = 3000, minSpread = 4, minColours = 30 } = {}) {
  await converged(page);
  const triangles = await page.evaluate(() => window.hexlod.triangles);
  assert.ok(triangles >= minTriangles, `${label}: ${triangles} triangles after convergence (at least ${minTriangles})`);
  const seen = await terrainCoverage(page);
  await page.screenshot({ path: `${outDir}/journey-${label}.png` });
  assert.ok(!seen.skyOnly, `${label}: the terrain is on screen`);
  assert.ok(seen.coverage >= minCoverage, `${label}: the terrain covers ${(100 * seen.coverage).toFixed(1)} % of the view`);
  assert.ok(seen.coverage <= maxCoverage, `${label}: the terrain covers ${(100 * seen.coverage).toFixed(1)} % of the view, no sky above it`);
  assert.ok(seen.colours >= minColours && seen.luminanceStd >= minSpread, `${label}: the terrain is shaded, not one colour (${JSON.stringify(seen)})`);
  const clearance = await eyeClearance(page);
  assert.ok(clearance === null || clearance > 0, `${label}: the eye is ${clearance} m above the ground`);
  return { triangles, ...seen };
}

/** The real DEMs and one file of every format fixture (RAW asks its size: files.test.js). */
function dropSets() {
  const sets = [['grandcanyon_512.png', 'grandcanyon_512.json'], ['jacksboro_fault.png', 'jacksboro_fault.json'],
    ['volcano_maungawhau.png', 'volcano_maungawhau.json'], ['grandcanyon_512.f32', 'grandcanyon_512.json']];
  const manifest = JSON.parse(readFileSync(`${FIXTURES}formats/manifest.json`, 'utf8'));
  for (const entry of manifest) if (!entry.options) sets.push(entry.files.map((name) => `formats/${name}`));
  return [...sets.map((paths) => paths.map(read)), [everestHgt()]];
}

/**
 * An SRTM tile (1201² big-endian int16 metres, 3" spacing from the latitude in its name) of
 * Everest: the default terrain's 120 x 120 samples around its highest point, resampled
 * bilinearly to 3" (SRTM has no small form to commit).
 */
function everestHgt() {
  const png = decode(readFileSync(`${projectDir}public/terrain/globe_himalaya_2048.png`)); // 0..8752 m as 0..65535
  const at = (x, y) => (png.data[y * 2048 + x] / 65535) * 8752;
  let peak = 0;
  for (let k = 1; k < png.data.length; ++k) if (png.data[k] > png.data[peak]) peak = k;
  const side = 1201, across = 120, x0 = (peak % 2048) - across / 2, y0 = Math.floor(peak / 2048) - across / 2;
  const bytes = new Uint8Array(side * side * 2), view = new DataView(bytes.buffer);
  for (let y = 0; y < side; y++) {
    for (let x = 0; x < side; x++) {
      const fx = x0 + (x * across) / (side - 1), fy = y0 + (y * across) / (side - 1);
      const ix = Math.min(Math.floor(fx), 2046), iy = Math.min(Math.floor(fy), 2046), tx = fx - ix, ty = fy - iy;
      const h = (at(ix, iy) * (1 - tx) + at(ix + 1, iy) * tx) * (1 - ty) + (at(ix, iy + 1) * (1 - tx) + at(ix + 1, iy + 1) * tx) * ty;
      view.setInt16(2 * (y * side + x), Math.round(h), false);
    }
  }
  return { name: 'N27E086.hgt', bytes };
}


// The pages run at a 50 ms frame budget: SwiftShader draws about a frame a second, and at the
// default 4 ms the default view takes some 160 frames to converge. Convergence is the same.
// At half a device pixel per CSS pixel, τ = 0.5 device pixels is the 1 CSS pixel a person at a
// full-resolution screen gets: the same mesh, a quarter of the pixels.
const quick = (query = '') => `${fullResolution()}&tau=0.5${query ? `&${query}` : ''}`;
// The pages judged at full resolution (one device pixel per CSS pixel), at the default τ.
const fullResolution = () => `${viewer.url}?budget=50`;
test('the page opens on the default terrain over at least 75 % of a 1280×720 view; panel and HUD fold', async () => {
  const { page, problems } = await openPage(viewer.browser, fullResolution(), { width: 1280, height: 720 }, FULL_RESOLUTION);
  await pageReady(page);
  await page.waitForFunction(() => window.hexlod.triangles > 20000, null, { timeout: 120000 });
  const seen = await terrainCoverage(page);
  await page.screenshot({ path: `${outDir}/journey-default-1280.png` });
  assert.ok(seen.coverage >= 0.75, `the terrain shows over ${(100 * seen.coverage).toFixed(1)} % of the canvas`);
  assert.ok(seen.colours >= 100, `shaded relief, ${seen.colours} colours`);
  assert.ok((await eyeClearance(page)) > 0, 'the eye is above the ground');

  // The HUD folds and unfolds (button or I); the panel's title folds it.
  const hudHeight = () => page.evaluate(() => document.getElementById('hud').getBoundingClientRect().height);
  const folded = await hudHeight();
  await page.click('#hud .hud-toggle');
  const unfolded = await hudHeight();
  assert.ok(unfolded > 3 * folded, `the HUD unfolds (${folded} -> ${unfolded} px)`);
  assert.match(await page.textContent('#hud'), /hexagons: [\d,]+ full/);
  await page.keyboard.press('i');
  assert.equal(await hudHeight(), folded, 'I folds it again');
  const panelHeight = () => page.evaluate(() => document.querySelector('#panel .lil-root').getBoundingClientRect().height);
  const open = await panelHeight();
  await page.click('#panel .lil-gui.lil-root > .lil-title');
  // lil-gui folds on its next animation frame, which waits for a terrain frame in progress.
  await page.waitForFunction((open) => document.querySelector('#panel .lil-root').getBoundingClientRect().height < open / 3, open, { timeout: 20000 })
    .catch(async () => assert.fail(`the panel folds to its title (${open} -> ${await panelHeight()} px)`));
  const bare = await terrainCoverage(page);
  assert.ok(bare.coverage > seen.coverage, 'with the panel folded more terrain shows');
  assert.deepEqual(problems, []);
  await page.close();

  // A phone: panel and HUD start folded.
  const phone = await openPage(viewer.browser, fullResolution(), { width: 390, height: 844 }, FULL_RESOLUTION);
  await pageReady(phone.page);
  const layout = await phone.page.evaluate(() => ({
    panelClosed: document.querySelector('#panel .lil-gui.lil-root').classList.contains('lil-closed'),
    hudFolded: document.getElementById('hud').classList.contains('collapsed') }));
  assert.deepEqual(layout, { panelClosed: true, hudFolded: true });
  await phone.page.waitForFunction(() => window.hexlod.triangles > 5000, null, { timeout: 120000 });
  const phoneSeen = await terrainCoverage(phone.page);
  await phone.page.screenshot({ path: `${outDir}/journey-default-phone.png` });
  assert.ok(phoneSeen.coverage >= 0.5, `the terrain shows over ${(100 * phoneSeen.coverage).toFixed(1)} % of a phone`);
  await phone.page.close();
});

test('every format and real DEM dropped on the page opens framed and refines', async () => {
  const { page, problems } = await openPage(viewer.browser, quick(), VIEWPORT);
  await pageReady(page);
  const figures = [];
  for (const files of dropSets()) {
    await dropFiles(page, files);
    await terrainShown(page, files[0].name);
    const { width, height } = await page.evaluate(() => window.hexlod.terrain);
    // "A few thousand" triangles; a small field seen whole needs fewer at τ = 1 (the whole Earth
    // at 14 km a sample, 240 x 120, and the 192² canyon converge to 1,300-1,500): a 50th of its samples.
    const minTriangles = Math.min(2000, Math.round((width * height) / 50));
    // The whole field in view, seen obliquely, beside the open panel; its far side fades into
    // the haze (counted only where it differs from the sky): a 2:1 field fills an eighth.
    figures.push({ name: files[0].name, ...await assertSeen(page, `drop-${files[0].name}`, { minTriangles, minCoverage: 0.12 }) });
  }
  assert.ok(figures.length >= 18, `${figures.length} files dropped`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a picked file and a ?src= file open framed; R brings the view back after moving away', async () => {
  const { page, problems } = await openPage(viewer.browser, quick(), VIEWPORT);
  await pageReady(page);
  await page.setInputFiles('#file-input', [`${FIXTURES}grandcanyon_512.png`, `${FIXTURES}grandcanyon_512.json`]);
  await terrainShown(page, 'grandcanyon_512.png');
  await assertSeen(page, 'picked-grandcanyon', { minTriangles: 5000 });
  const pose = () => page.evaluate(() => {
    const { target, distance, yaw, pitch } = window.hexlod.rig.cameras.orbit;
    return { target: Array.from(target), distance, yaw, pitch, mode: window.hexlod.camera.mode };
  });
  const framed = await pose();

  // Move away: into the sky, looking at nothing; R frames the terrain again.
  await page.evaluate(() => {
    const orbit = window.hexlod.rig.cameras.orbit;
    orbit.target[0] += 1e6;
    orbit.pitch = 0.02;
    window.hexlod.requestRender();
  });
  await nextFrame(page);
  assert.ok((await terrainCoverage(page)).coverage < 0.02, 'moved away: nothing of the terrain in view');
  await page.keyboard.press('r');
  assert.deepEqual(await pose(), framed, 'R frames the terrain as the drop did');
  await assertSeen(page, 'reset-grandcanyon', { minTriangles: 5000 });
  assert.deepEqual(problems, []);
  await page.close();

  const src = `${viewer.fixturesUrl}formats/everest_i16_strips.tif`;
  const opened = await openPage(viewer.browser, quick(`src=${encodeURIComponent(src)}`), VIEWPORT);
  await pageReady(opened.page);
  const { name, error } = await opened.page.evaluate(() => ({ name: window.hexlod.terrain.name, error: window.hexlod.error }));
  assert.equal(name, 'everest_i16_strips.tif', `?src= opened ${name}: ${error}`);
  await assertSeen(opened.page, 'src-everest', { minTriangles: 3000 });
  assert.deepEqual(opened.problems, []);
  await opened.page.close();
});

test('after a drop: orbit → fly → walk → orbit, and a new exaggeration, keep the terrain in view', async () => {
  const { page, problems } = await openPage(viewer.browser, quick(), VIEWPORT);
  await pageReady(page);
  await dropFiles(page, [read('jacksboro_fault.png'), read('jacksboro_fault.json')]);
  await terrainShown(page, 'jacksboro_fault.png');
  await assertSeen(page, 'cameras-dropped', { minTriangles: 2000 });
  for (const key of ['2', '3', '1']) {
    await page.keyboard.press(key);
    await nextFrame(page);
    const mode = await page.evaluate(() => window.hexlod.camera.mode);
    assert.equal(mode, { 2: 'fly', 3: 'walk', 1: 'orbit' }[key]);
    // Walking puts the eye at eye height on the ground, seeing little of a 30 km field at τ = 1,
    // and looking ahead at the landscape: the sky above the horizon is in view, not only the
    // ground at the walker's feet.
    await assertSeen(page, `cameras-${mode}`, { minCoverage: mode === 'walk' ? 0.1 : 0.2, minTriangles: mode === 'walk' ? 500 : 2000,
      maxCoverage: mode === 'walk' ? 0.9 : 1 });
  }
  for (const exaggeration of [10, 1]) {
    await page.evaluate((value) => window.hexlod.setSetting('exaggeration', value), exaggeration);
    // The camera may back away from taller hills: fewer triangles, but the terrain in view.
    await assertSeen(page, `exaggeration-${exaggeration}`, { minTriangles: 300 });
  }
  assert.deepEqual(problems, []);
  await page.close();
});

/** A .f32 field and its sidecar, made here: width x height samples of heightOf(i, j) metres. */
function madeField(name, width, height, spacing, heightOf) {
  const heights = new Float32Array(width * height);
  for (let i = 0; i < height; ++i) for (let j = 0; j < width; ++j) heights[i * width + j] = heightOf(i, j);
  return [{ name: `${name}.f32`, bytes: new Uint8Array(heights.buffer) },
    { name: `${name}.json`, bytes: Buffer.from(JSON.stringify({ width, height, cell_size_m: spacing })) }];
}

test('odd fields open framed: under the sea, above 4000 m, flat, a spike, 2×2, a profile, a thin strip, 0.5 m lidar', async () => {
  // At full resolution: the colour counts that tell shading from one flat colour are those of
  // this window's pixels.
  const { page, problems } = await openPage(viewer.browser, fullResolution(), VIEWPORT, FULL_RESOLUTION);
  await pageReady(page);
  const wave = (low, high, period) => (i, j) => low + (high - low) * (0.5 + 0.25 * Math.sin(i / period) + 0.25 * Math.cos(j / (0.7 * period)));
  // The least coverage is what the whole field in view can fill: a spike 8 times higher than
  // its field is wide leaves the ground small; a profile or a strip is a thin ribbon. The least
  // triangle count is what τ = 1 asks: a flat field needs its base mesh only.
  const cases = [
    // [name, width, height, spacing m, heights m, least coverage, least triangles]
    ['seafloor', 160, 120, 500, wave(-7500, -3200, 11), 0.15, 3000],
    ['plateau', 160, 120, 90, wave(4200, 5600, 11), 0.15, 3000],
    ['flat', 64, 64, 30, () => 1200, 0.15, 2],
    ['spike', 101, 101, 10, (i, j) => (i === 50 && j === 50 ? 900 : 100), 0.02, 100],
    ['tiny', 2, 2, 30, (i, j) => 100 + 20 * i + 10 * j, 0.08, 2],
    ['profile', 1, 600, 10, (i) => 300 + 80 * Math.sin(i / 40), 0.001, 100],
    ['strip', 2000, 6, 5, (i, j) => 50 + 30 * Math.sin(j / 60), 0.001, 100],
    ['lidar', 400, 300, 0.5, wave(380, 420, 19), 0.15, 3000],
  ];
  for (const [name, width, height, spacing, heightOf, minCoverage, minTriangles] of cases) {
    const files = madeField(name, width, height, spacing, heightOf);
    await dropFiles(page, files);
    await terrainShown(page, files[0].name);
    // A plane (flat ground, the 2x2 field) is evenly lit: only the ground's noise varies it.
    // A ribbon (the profile, the strip) covers few pixels, so fewer colours. The sea floor is
    // drawn as water, lit as a level surface: its colours come from the depth and the haze.
    const plane = name === 'flat' || name === 'tiny', ribbon = name === 'profile' || name === 'strip', water = name === 'seafloor';
    await assertSeen(page, `odd-${name}`, { minCoverage, minTriangles, minSpread: plane ? 0.5 : 4, minColours: plane || ribbon || water ? 10 : 30 });
  }
  assert.deepEqual(problems, []);
  await page.close();
});
