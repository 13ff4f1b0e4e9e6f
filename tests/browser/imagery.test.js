// A real satellite image (NASA Blue Marble, tests/fixtures/imagery/) draped on the default
// terrain by its world file, judged by pixels: known ground points (a sea, a desert, a plain)
// are projected to the screen and the colour there is the image's; the same view with the image
// cut into small tiles (?imagetile=64) and opened by ?image= draws the same pixels; a refused
// image (another CRS) keeps the one on screen. Then the journeys: both drop orders, half an
// image over the field, bad images, a lost context, Remove, and a photo PNG alone.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { decode, encode } from 'fast-png';
import { readFileSync } from 'node:fs';
import { startViewer, openPage, dropFiles, terrainShown, outDir, FULL_RESOLUTION } from '../../lib/page_harness.js';
import { BLUE_MARBLE_POINTS as POINTS, colourAt, coloursMatch, lookStraightDown, projectLonLat } from '../../lib/draped_points.js';

// One browser and server for the file.
let viewer;
// Half a device pixel per CSS pixel but where colours at ground points are judged.
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

// The draped view's window: the whole field from straight above, the image's 256 pixels over
// some 400 of the screen's, so each colour judged is the image's own pixel magnified, not a blend
// of its neighbours. (SwiftShader draws on the CPU: at 800 x 800 each frame cost twice as much.)
const VIEW = 560;

/** Opens the page, drapes the Blue Marble crop unlit from straight above, and returns the screenshot and the points' pixels. */
async function drapedView(query = '') {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1${query}`, { width: VIEW, height: VIEW }, FULL_RESOLUTION);
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });
  // ?image= drapes it before the page is ready; else it is draped here.
  const draped = await page.evaluate(async (base) => {
    const get = async (name) => ({ name, blob: await (await fetch(base + name)).blob() });
    const d = window.hexlod.images.current
      ?? await window.hexlod.images.drape(await get('bmng_himalaya_4arcmin.jpg'), { worldFile: await get('bmng_himalaya_4arcmin.jgw'), prj: null, auxXml: null });
    return d && { width: d.width, height: d.height, coverage: d.placement.coverage };
  }, `${viewer.fixturesUrl}imagery/`);
  await lookStraightDown(page);
  for (let i = 0; i < 4; i++) await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
  const png = decode(await page.screenshot());
  const pixels = await projectLonLat(page, POINTS);
  return { page, problems, png, draped, pixels };
}


test('a satellite image placed by its world file shows its colours at known ground points, tiled or not', async () => {
  const whole = await drapedView();
  assert.deepEqual(whole.draped, { width: 256, height: 257, coverage: 1 });
  for (const [name, [, , expected]] of Object.entries(POINTS)) {
    const at = whole.pixels[name], got = colourAt(whole.png, at);
    assert.ok(at[0] > 0 && at[0] < VIEW && at[1] > 0 && at[1] < VIEW, `${name} is on screen at ${at}`);
    assert.ok(coloursMatch(got, expected, 24), `${name} at ${at}: ${got}, the image has ${expected}`);
  }
  assert.deepEqual(whole.problems, []);

  // Cut into 64-pixel tiles with aprons and an overview, opened by ?image= with its world file
  // found beside it: the same picture, and the address keeps the image.
  const imageUrl = `${viewer.fixturesUrl}imagery/bmng_himalaya_4arcmin.jpg`;
  const tiled = await drapedView(`&imagetile=64&image=${encodeURIComponent(imageUrl)}`);
  assert.deepEqual(tiled.draped, { width: 256, height: 257, coverage: 1 });
  await tiled.page.waitForFunction((url) => new URL(location.href).searchParams.get('image') === url, imageUrl, { timeout: 10000 });
  let differing = 0, largest = 0;
  for (let i = 0; i < whole.png.data.length; i += whole.png.channels) {
    const d = Math.max(...[0, 1, 2].map((k) => Math.abs(whole.png.data[i + k] - tiled.png.data[i + k])));
    if (d > 8) differing++;
    largest = Math.max(largest, d);
  }
  assert.ok(differing / (VIEW * VIEW) < 0.01, `${(100 * differing / (VIEW * VIEW)).toFixed(2)} % of pixels differ by more than 8 (largest ${largest})`);

  // An image in another CRS is refused by name; the Blue Marble stays.
  const refused = await tiled.page.evaluate(async (base) => {
    const blob = await (await fetch(`${base}haiti_rgb_5m_tiled_deflate.tif`)).blob();
    await window.hexlod.images.drape({ name: 'haiti.tif', blob }, null);
    return { status: document.getElementById('status').textContent, still: window.hexlod.images.current?.name };
  }, `${viewer.fixturesUrl}imagery/`);
  assert.match(refused.status, /^haiti\.tif: it lies outside the terrain/);
  assert.equal(refused.still, 'bmng_himalaya_4arcmin.jpg');
  await whole.page.close();
  await tiled.page.close();
});

const fixture = (path) => ({ name: path.split('/').pop(), bytes: new Uint8Array(readFileSync(new URL(`../fixtures/${path}`, import.meta.url))) });

test('dropped with its DEM in either order, the image drapes it; a new DEM alone takes the image away', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1`, { width: 640, height: 400 });
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });
  const dem = fixture('formats/everest_i16_strips.tif');
  const image = [fixture('imagery/bmng_everest_4arcmin.jpg'), fixture('imagery/bmng_everest_4arcmin.jgw')];
  for (const files of [[dem, ...image], [...image.reverse(), dem]]) {
    await dropFiles(page, files);
    await terrainShown(page, 'everest_i16_strips.tif');
    await page.waitForFunction(() => window.hexlod.images.current !== null, null, { timeout: 60000 });
    const draped = await page.evaluate(() => ({ name: window.hexlod.images.current.name, coverage: window.hexlod.images.current.placement.coverage }));
    assert.equal(draped.name, 'bmng_everest_4arcmin.jpg');
    assert.ok(draped.coverage > 0.99, `the image covers the Everest field (${draped.coverage})`);
  }
  // The HUD lists the layers over the terrain as the layer list has them.
  const layerLines = () => page.evaluate(() => {
    const lines = document.querySelector('#hud .hud-image');
    return lines.hidden ? null : lines.textContent;
  });
  assert.match(await layerLines(), /^image bmng_everest_4arcmin\.jpg {2}\d+ × \d+ px, [\d.]+ m\/px, covers 100 % of the field$/);
  await dropFiles(page, [fixture('formats/everest_16bit.png')]);
  await terrainShown(page, 'everest_16bit.png');
  assert.equal(await page.evaluate(() => window.hexlod.images.current), null, 'the old image went with the old ground');
  assert.equal(await layerLines(), null, 'and its line in the HUD');
  assert.deepEqual(problems, []);
  await page.close();
});

/** A JPEG (JFIF) whose header announces `width` x `height` pixels, and holds nothing else. */
function jpegHeader(width, height) {
  return Uint8Array.from([0xff, 0xd8, 0xff, 0xe0, 0, 16, 0x4a, 0x46, 0x49, 0x46, 0, 1, 1, 0, 0, 1, 0, 1, 0, 0, 0xff, 0xc0, 0, 17, 8, height >> 8, height & 255, width >> 8, width & 255, 3,
    1, 0x22, 0, 2, 0x11, 1, 3, 0x11, 1, 0xff, 0xd9]);
}

const text = (name, content) => ({ name, bytes: new TextEncoder().encode(content) });

test('half over the field, bad images refused while it stays, back after a lost context, removed, and a photo PNG alone', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1`, { width: 700, height: 700 }, FULL_RESOLUTION);
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });
  await lookStraightDown(page);
  const shot = async (label) => {
    for (let i = 0; i < 3; i++) await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
    return decode(await page.screenshot(label ? { path: `${outDir}/imagery-${label}.png` } : {}));
  };
  // The image moved half the field west by its world file: its Bay of Bengal and Ganges plain
  // land in the field's west half; the east half keeps the procedural ground.
  const shift = (90 - 72.93333333333334) / 2;
  const at = await projectLonLat(page, { sea: [89.5 - shift, 21.0333], plain: [84.9667 - shift, 25.6333], east: [86.5, 30.5], eastSouth: [88, 24] });
  const bare = await shot();
  const jpeg = fixture('imagery/bmng_himalaya_4arcmin.jpg');
  const shifted = text('bmng_himalaya_4arcmin.jgw', `0.0666666666666667\n0\n0\n-0.0666666666666667\n${72.9666666666667 - shift}\n37.9\n`);
  await dropFiles(page, [jpeg, shifted]);
  await page.waitForFunction(() => window.hexlod.image !== null, null, { timeout: 60000 });
  const image = await page.evaluate(() => window.hexlod.image);
  assert.ok(Math.abs(image.coverage - 0.5) < 0.01, `half the field under the image (${image.coverage})`);
  assert.match(image.hud, /^image bmng_himalaya_4arcmin\.jpg {2}256 × 257 px, 64\d\d m\/px, covers 50 % of the field$/);
  assert.ok(await page.isVisible('#hud .hud-image'), 'the HUD shows the image line');
  const half = await shot('half');
  assert.ok(coloursMatch(colourAt(half, at.sea), POINTS['Bay of Bengal'][2], 24), `the sea at ${at.sea}: ${colourAt(half, at.sea)}`);
  assert.ok(coloursMatch(colourAt(half, at.plain), POINTS['Ganges plain'][2], 24), `the plain at ${at.plain}: ${colourAt(half, at.plain)}`);
  for (const p of [at.east, at.eastSouth]) assert.ok(coloursMatch(colourAt(half, p), colourAt(bare, p), 6), `outside the image at ${p}: the ground as before`);

  // Bad input: each refused by name; the terrain and the image stay.
  const bad = [
    [[{ name: 'broken.jpg', bytes: fixture('imagery/bmng_himalaya_4arcmin.jpg').bytes.subarray(0, 700) }], /^broken\.jpg: /],
    [[{ name: 'huge.jpg', bytes: jpegHeader(60000, 60000) }], /^huge\.jpg: 60000 × 60000 pixels \(3600 Mpx\) is more than the browser can decode at once/],
    [[jpeg, text('bmng_himalaya_4arcmin.jgw', '0.0666666666666667\n0\n0\n-0.0666666666666667\n-140\n-60\n')], /^bmng_himalaya_4arcmin\.jpg: it lies outside the terrain/],
    [[jpeg, text('bmng_himalaya_4arcmin.jgw', 'this is\nnot a\nworld file\n')], /^bmng_himalaya_4arcmin\.jgw: /],
    [[jpeg, text('bmng_himalaya_4arcmin.jgw', '0\n0\n0\n-0.0666666666666667\n72\n37\n')], /^bmng_himalaya_4arcmin\.jgw: /],
  ];
  for (const [files, message] of bad) {
    await dropFiles(page, files);
    await page.waitForFunction(() => !window.hexlod.loading, null, { timeout: 60000 });
    const after = await page.evaluate(() => ({ status: document.getElementById('status').textContent, error: document.getElementById('status').classList.contains('error'),
      image: window.hexlod.image?.coverage, terrain: window.hexlod.terrain.name }));
    assert.match(after.status, message);
    assert.match(after.status, /\(bmng_himalaya_4arcmin\.jpg stays\)$/);
    assert.ok(after.error, 'shown as an error');
    assert.deepEqual([after.terrain, Math.abs(after.image - 0.5) < 0.01], ['globe_himalaya_2048.png', true], files[0].name);
  }
  assert.ok(coloursMatch(colourAt(await shot(), at.sea), POINTS['Bay of Bengal'][2], 24), 'the image is still on screen');

  // A lost graphics context takes the textures; the image comes back with it.
  await page.evaluate(() => {
    window.loseContext = document.getElementById('view').getContext('webgl2').getExtension('WEBGL_lose_context');
    window.loseContext.loseContext();
  });
  await page.waitForFunction(() => window.hexlod.contextLost, null, { timeout: 30000 });
  await page.evaluate(() => window.loseContext.restoreContext());
  await page.waitForFunction(() => window.hexlod.contextRestores === 1 && !window.hexlod.contextLost, null, { timeout: 60000 });
  await page.waitForFunction(() => window.hexlod.image !== null, null, { timeout: 60000 });
  const restored = await shot();
  assert.ok(coloursMatch(colourAt(restored, at.sea), POINTS['Bay of Bengal'][2], 24), `after the lost context, the sea: ${colourAt(restored, at.sea)}`);

  // Opacity 0 shows the ground under it; lit, the sun shades it: a low sun darkens it.
  await page.evaluate(() => window.hexlod.setSetting('imageOpacity', 0));
  const clear = await shot();
  for (const p of [at.sea, at.plain]) assert.ok(coloursMatch(colourAt(clear, p), colourAt(bare, p), 6), `opacity 0: the ground at ${p}`);
  const brightness = (png) => colourAt(png, at.plain).reduce((a, b) => a + b, 0);
  const sun = await page.evaluate(() => window.hexlod.settings.sunElevation);
  await page.evaluate(() => { const h = window.hexlod; h.setSetting('imageOpacity', 1); h.setSetting('imageUnlit', false); h.setSetting('sunElevation', 60); });
  const high = brightness(await shot());
  await page.evaluate(() => window.hexlod.setSetting('sunElevation', 6));
  const low = brightness(await shot('lit-low-sun'));
  assert.ok(low < 0.8 * high, `lit, a low sun darkens the image: ${low} against ${high}`);
  await page.evaluate((sun) => { const h = window.hexlod; h.setSetting('imageUnlit', true); h.setSetting('sunElevation', sun); }, sun);

  // The panel's "remove layer": the ground as before the image.
  await page.evaluate(() => [...document.querySelectorAll('#panel button')].find((b) => b.textContent.trim() === 'remove layer').click());
  await page.waitForFunction(() => window.hexlod.image === null, null, { timeout: 10000 });
  assert.ok(!(await page.isVisible('#hud .hud-image')), 'no image line');
  const removed = await shot();
  for (const p of [at.sea, at.plain]) assert.ok(coloursMatch(colourAt(removed, p), colourAt(bare, p), 6), `removed: the ground at ${p} as before`);

  // A colour PNG alone whose colours are no heights (a photo, a scanned map) is draped, stretched.
  const width = 64, height = 64, rgb = new Uint8Array(width * height * 3);
  for (let i = 0; i < width * height; i++) rgb.set([20 + (i % width) / 2, 160, 90], i * 3);
  await dropFiles(page, [{ name: 'scan.png', bytes: encode({ width, height, data: rgb, channels: 3 }) }]);
  await page.waitForFunction(() => window.hexlod.image !== null, null, { timeout: 60000 });
  const photo = await page.evaluate(() => ({ how: window.hexlod.image.how, terrain: window.hexlod.terrain.name, status: document.getElementById('status').textContent }));
  assert.deepEqual([photo.how, photo.terrain], ['stretched', 'globe_himalaya_2048.png']);
  assert.match(photo.status, /^scan\.png: .*stretched over the whole field/);
  const centre = await projectLonLat(page, { c: [(72.93333333333334 + 90) / 2, (20.85 + 37.916666666666664) / 2] });
  assert.ok(coloursMatch(colourAt(await shot('photo'), centre.c), [36, 160, 90], 12), 'the photo at the field centre');
  assert.deepEqual(problems, []);
  await page.close();
});

test('an overlay in the layer list is drawn over the terrain, listed in the HUD, made again after a lost context, and gone when removed', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1`, { width: 400, height: 300 }, FULL_RESOLUTION);
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });
  // A square of magenta in the middle of the view, over the terrain (a kind of layer the page
  // does not know: the renderer and the HUD take it from the list alone).
  const magentaAt = async () => {
    await page.evaluate(() => new Promise((resolve) => { window.hexlod.requestRender(); requestAnimationFrame(() => requestAnimationFrame(resolve)); }));
    const image = decode(await page.screenshot({ clip: { x: 190, y: 140, width: 20, height: 20 } }));
    const c = image.channels, [r, g, b] = [image.data[10 * 20 * c + 10 * c], image.data[10 * 20 * c + 10 * c + 1], image.data[10 * 20 * c + 10 * c + 2]];
    return r > 240 && g < 15 && b > 240;
  };
  assert.equal(await magentaAt(), false);
  await page.evaluate(() => {
    const overlay = {
      description: 'overlay test square', made: 0,
      draw(gl, camera, width, height) {
        gl.enable(gl.SCISSOR_TEST);
        gl.scissor(Math.round(width / 2) - 20, Math.round(height / 2) - 20, 40, 40);
        gl.clearColor(1, 0, 1, 1);
        gl.clear(gl.COLOR_BUFFER_BIT);
        gl.disable(gl.SCISSOR_TEST);
      },
      createGlObjects() { overlay.made++; },
    };
    window.hexlod.layers.overlays.push(overlay);
    window.hexlod.layers.changed('overlays');
  });
  assert.equal(await magentaAt(), true, 'drawn');
  assert.equal(await page.evaluate(() => document.querySelector('#hud .hud-image').textContent), 'overlay test square');
  await page.evaluate(() => {
    window.loseContext = document.getElementById('view').getContext('webgl2').getExtension('WEBGL_lose_context');
    window.loseContext.loseContext();
  });
  await page.waitForFunction(() => window.hexlod.contextLost);
  await page.evaluate(() => window.loseContext.restoreContext());
  await page.waitForFunction(() => !window.hexlod.contextLost && window.hexlod.layers.overlays[0].made === 1);
  assert.equal(await magentaAt(), true, 'drawn again after the context came back');
  await page.evaluate(() => {
    window.hexlod.layers.overlays.length = 0;
    window.hexlod.layers.changed('overlays');
  });
  assert.equal(await magentaAt(), false, 'gone');
  assert.equal(await page.evaluate(() => document.querySelector('#hud .hud-image').hidden), true);
  assert.deepEqual(problems, []);
  await page.close();
});
