// The paper's look (§7), rendered headless: fixed views compared with committed
// reference images within a tolerance, and colour statistics of known regions that fail when
// the sky, the shadows or the ground colours are missing. Small viewports: SwiftShader draws on
// the CPU. UPDATE_REFERENCES=1 writes the references instead of comparing (look at them
// before committing). Every rendered image is also written to tests/out/.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync, existsSync, mkdirSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, outDir, projectDir } from '../../lib/page_harness.js';

const SIZE = { width: 480, height: 270 };
const REFERENCES = `${projectDir}tests/fixtures/reference/`;
const UPDATE = process.env.UPDATE_REFERENCES === '1';
const fixture = (name) => `/@fs${projectDir}tests/fixtures/${name}`;
// A larger refinement budget per frame: the views converge in fewer (slow) frames.
const COMMON = 'tau=1&budget=40&exag=2';

/** The fixed views: the Himalaya at sunrise, the Grand Canyon from the rim, the Earth from high up. */
const VIEWS = {
  himalaya_sunrise: `?${COMMON}&sunaz=105&sunel=4&cam=orbit,1477858.625,8159.95,1117360.375,98996.587,0.4,0.3`,
  grand_canyon_rim: `?src=${encodeURIComponent(fixture('grandcanyon_512.png'))}&${COMMON}&sunaz=230&sunel=35`
    + '&cam=orbit,15000,3600,17000,9000,2.6,0.18',
  earth_from_high: `?src=${encodeURIComponent(fixture('shading/etopo5_global_540x270.png'))}&tau=1&budget=40&exag=2&sunaz=180&sunel=55`
    + '&cam=orbit,19976000,0,9978000,26000000,0,1.55',
};

let viewer;
before(async () => { viewer = await startViewer(); mkdirSync(REFERENCES, { recursive: true }); });
after(async () => { await viewer?.close(); });

/** Opens a view with the panel and HUD hidden, waits for the converged, fully blended mesh. */
async function openView(query) {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}${query}`, SIZE);
  await page.addStyleTag({ content: '#hud, #side, #drop-hint, #status { display: none !important; }' });
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
  assert.deepEqual(await page.evaluate(() => [window.hexlod.status, window.hexlod.error]), ['ready', null]);
  await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged; }, null,
    { timeout: 300000, polling: 200 });
  return { page, problems, shot: (name) => shoot(page, name) };
}

/** Draws a few more frames (blends end, settings apply) and returns the decoded screenshot. */
async function shoot(page, name) {
  await page.evaluate(() => { window.hexlod.until = window.hexlod.frames + 10; });
  await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.frames >= window.hexlod.until; }, null,
    { timeout: 120000, polling: 50 });
  const png = await page.screenshot({ path: `${outDir}/shading-${name}.png` });
  return Object.assign(decode(png), { png });
}

/** Mean and 99th percentile of the per-pixel largest channel difference. */
function difference(a, b) {
  assert.deepEqual([a.width, a.height], [b.width, b.height]);
  const histogram = new Uint32Array(256);
  let sum = 0;
  const n = a.width * a.height;
  for (let k = 0; k < n; ++k) {
    let d = 0;
    for (let c = 0; c < 3; ++c) d = Math.max(d, Math.abs(a.data[k * a.channels + c] - b.data[k * b.channels + c]));
    histogram[d] += 1;
    sum += d;
  }
  let seen = 0, p99 = 0;
  while (p99 < 255 && (seen += histogram[p99]) < 0.99 * n) p99 += 1;
  return { mean: sum / n, p99 };
}

/** Colour statistics of a region (fractions of the image: x0, y0, x1, y1). */
function region(image, [x0, y0, x1, y1], classify = {}) {
  const { width, height, data, channels } = image;
  const counts = Object.fromEntries(Object.keys(classify).map((k) => [k, 0]));
  let n = 0, r = 0, g = 0, b = 0, luma = 0;
  for (let y = Math.floor(y0 * height); y < Math.floor(y1 * height); ++y) {
    for (let x = Math.floor(x0 * width); x < Math.floor(x1 * width); ++x) {
      const k = (y * width + x) * channels;
      const p = [data[k], data[k + 1], data[k + 2]];
      r += p[0]; g += p[1]; b += p[2]; luma += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
      for (const [name, test] of Object.entries(classify)) if (test(...p)) counts[name] += 1;
      n += 1;
    }
  }
  const fractions = Object.fromEntries(Object.entries(counts).map(([k, v]) => [k, v / n]));
  return { r: r / n, g: g / n, b: b / n, luma: luma / n, ...fractions };
}

/** The fraction of a region's pixels whose luminance is at least `levels` lower in `b` than in `a`. */
function darkenedFraction(a, b, box, levels) {
  const la = (img, k) => 0.2126 * img.data[k] + 0.7152 * img.data[k + 1] + 0.0722 * img.data[k + 2];
  const [x0, y0, x1, y1] = box;
  let n = 0, darker = 0;
  for (let y = Math.floor(y0 * a.height); y < Math.floor(y1 * a.height); ++y) {
    for (let x = Math.floor(x0 * a.width); x < Math.floor(x1 * a.width); ++x) {
      const k = (y * a.width + x) * a.channels;
      if (la(a, k) - la(b, k) >= levels) darker += 1;
      n += 1;
    }
  }
  return darker / n;
}

/** Compares with the committed reference (or writes it with UPDATE_REFERENCES=1). */
function matchReference(name, image) {
  const file = `${REFERENCES}${name}.png`;
  if (UPDATE || !existsSync(file)) {
    assert.ok(UPDATE, `no reference ${file}: run with UPDATE_REFERENCES=1 and look at it`);
    writeFileSync(file, image.png);
    return;
  }
  const d = difference(image, decode(readFileSync(file)));
  // SwiftShader is deterministic; the budgeted refinement may end on a slightly different mesh.
  assert.ok(d.mean < 3 && d.p99 < 40, `${name} differs from its reference: mean ${d.mean.toFixed(2)}, p99 ${d.p99} levels`);
}

const isSnow = (r, g, b) => r > 200 && g > 200 && b > 200;
const isBlueSky = (r, g, b) => b > r + 15 && b >= g;
const isVegetation = (r, g, b) => g > r && g > b;
const isWarm = (r, g, b) => r > g && g > b && r - b > 25;
const isSea = (r, g, b) => b > r + 20 && b > 40;

test('the Himalaya at sunrise: a sky of the scattering model, long shadows, warm light, snow', async () => {
  const { page, problems, shot } = await openView(VIEWS.himalaya_sunrise);
  const image = await shot('himalaya_sunrise');
  matchReference('himalaya_sunrise', image);
  // The sky (top rows): blue, brighter towards the horizon, not the plain mode's clear colour.
  const top = region(image, [0, 0, 1, 0.08], { blue: isBlueSky });
  const nearHorizon = region(image, [0, 0.14, 1, 0.18]);
  assert.ok(top.blue > 0.9, `sky: ${JSON.stringify(top)}`);
  assert.ok(nearHorizon.luma > top.luma + 20, `the sky brightens towards the horizon: ${top.luma} -> ${nearHorizon.luma}`);
  // The terrain below: with the sun 4° up, long shadows cover much of it; without them the
  // same pixels are lit.
  const terrainBox = [0, 0.35, 1, 1];
  const withShadows = region(image, terrainBox);
  await page.evaluate(() => window.hexlod.setSetting('shadows', false));
  const unshadowed = await shot('himalaya_sunrise_no_shadows');
  const without = region(unshadowed, terrainBox);
  const darkened = darkenedFraction(unshadowed, image, terrainBox, 20);
  assert.ok(darkened > 0.05, `${(100 * darkened).toFixed(1)} % of the ground lies in shadow`);
  assert.ok(without.luma > withShadows.luma * 1.05, `shadows darken the ground: ${withShadows.luma} vs ${without.luma}`);
  // Sunrise light is warm: lit ground is redder than it is blue.
  const lit = region(image, terrainBox, { warm: (r, g, b) => r > b + 15 });
  assert.ok(lit.warm > 0.1, `warm light: ${JSON.stringify(lit)}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the Grand Canyon from the rim: banded rock on the walls, vegetation on the plateau, no snow', async () => {
  const { page, problems, shot } = await openView(VIEWS.grand_canyon_rim);
  const image = await shot('grand_canyon_rim');
  matchReference('grand_canyon_rim', image);
  const ground = region(image, [0, 0.3, 1, 1], { red: (r, g, b) => r > g + 8 && r > b + 15, vegetation: isVegetation, snow: isSnow });
  assert.ok(ground.red > 0.04, `red and buff rock: ${JSON.stringify(ground)}`);
  assert.ok(ground.vegetation > 0.1, `vegetation: ${JSON.stringify(ground)}`);
  assert.ok(ground.snow < 0.001, `no snow below 2400 m: ${JSON.stringify(ground)}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the Earth from high up: seas, land, snow of the ice caps, and the plain ground (here the deep sea) going on past the map', async () => {
  const { page, problems, shot } = await openView(VIEWS.earth_from_high);
  const image = await shot('earth_from_high');
  matchReference('earth_from_high', image);
  const all = region(image, [0, 0, 1, 1], { sea: isSea, vegetation: isVegetation, snow: isSnow, warm: isWarm });
  assert.ok(all.sea > 0.3, `seas: ${JSON.stringify(all)}`);
  assert.ok(all.vegetation + all.warm > 0.05, `land: ${JSON.stringify(all)}`);
  assert.ok(all.snow > 0.005, `ice: ${JSON.stringify(all)}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('analysis modes, mesh normals and a tiled normal texture', async () => {
  // Tiles of 512 texels: the 2048² field needs 5 x 5 of them; the picture must not change.
  const query = `?${COMMON}&cam=orbit,1477858.625,8159.95,1117360.375,98996.587,0.4,0.3`;
  const single = await openView(query);
  const natural = await single.shot('natural');
  // Lit from the field's normals, the core keeps none of its own (24 B a vertex).
  assert.equal(await single.page.evaluate(() => window.hexlod.streamNormals), false, 'no mesh normals while unused');
  const modes = {};
  for (const mode of ['hillshade', 'hypsometric', 'slope', 'plain']) {
    await single.page.evaluate((m) => window.hexlod.setSetting('shading', m), mode);
    modes[mode] = await single.shot(mode);
  }
  await single.page.evaluate(() => { window.hexlod.setSetting('shading', 'natural'); window.hexlod.setSetting('normals', 'mesh'); });
  const meshNormals = await single.shot('mesh_normals');
  assert.equal(await single.page.evaluate(() => window.hexlod.streamNormals), true, 'mesh normals rebuilt when drawn');
  assert.deepEqual(single.problems, []);
  await single.page.close();

  const terrainBox = [0, 0.4, 1, 1];
  const hill = region(modes.hillshade, terrainBox, { grey: (r, g, b) => r === g && g === b });
  assert.ok(hill.grey > 0.99, `hillshade is grey: ${JSON.stringify(hill)}`);
  const hyps = region(modes.hypsometric, terrainBox, { vegetation: isVegetation });
  assert.ok(hyps.vegetation > 0.05, `hypsometric tint: ${JSON.stringify(hyps)}`);
  const slope = region(modes.slope, terrainBox, { steep: (r, g, b) => r > g + 40 && r > b + 60, gentle: (r, g, b) => g > r && g > b });
  assert.ok(slope.steep > 0.01 && slope.gentle > 0.01, `slope classes: ${JSON.stringify(slope)}`);
  // The plain mode has no sky pass: its clear colour fills the sky.
  const plainSky = region(modes.plain, [0, 0, 1, 0.05]);
  assert.ok(Math.abs(plainSky.r - 158) < 3 && Math.abs(plainSky.b - 224) < 3, `plain sky ${JSON.stringify(plainSky)}`);
  for (const [mode, image] of Object.entries(modes)) {
    assert.ok(difference(image, natural).mean > 8, `the ${mode} mode looks different from the natural one`);
  }
  // Mesh normals light the same ground a little differently (coarser), but the same ground.
  const dm = difference(meshNormals, natural);
  assert.ok(dm.mean > 0.3 && dm.mean < 20, `mesh normals vs field normals: ${JSON.stringify(dm)}`);

  const tiled = await openView(`${query}&normaltile=512`);
  const tiledImage = await tiled.shot('natural_tiled');
  const layers = await tiled.page.evaluate(() => { const t = window.hexlod.fieldTextures.tiles; return t.tilesX * t.tilesZ; });
  assert.equal(layers, 25, 'the 2048² field in tiles of 512 texels');
  const dt = difference(tiledImage, natural);
  assert.ok(dt.mean < 0.5 && dt.p99 <= 8, `tiles change the picture: ${JSON.stringify(dt)} (${layers} tiles)`);
  assert.deepEqual(tiled.problems, []);
  await tiled.page.close();
});

test('the fragment stage discards nothing but no-data holes: the overhang is clamped in the vertex stage', () => {
  // The holes are a program variant of their own (nodata=holes), so every other draw keeps early depth testing.
  const holes = /#ifdef NODATA_HOLES[\s\S]*?#endif/g;
  for (const file of ['terrain.frag', 'ground_color.glsl', 'field_textures.glsl', 'scattering.glsl', 'tonemap.glsl']) {
    const source = readFileSync(`${projectDir}shaders/${file}`, 'utf8').replace(/\/\/.*$/gm, '');
    if (file === 'terrain.frag') assert.match(source.match(holes)?.[0] ?? '', /\bdiscard\b/, 'the holes variant discards');
    assert.doesNotMatch(source.replace(holes, ''), /\bdiscard\b/, `${file} discards fragments`);
  }
  assert.match(readFileSync(`${projectDir}shaders/terrain.vert`, 'utf8'), /p\.xz = clamp\(p\.xz, vec2\(0\.0\), uExtent\)/);
});
