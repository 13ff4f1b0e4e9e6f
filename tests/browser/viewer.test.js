// The page as a user opens it: the default terrain appears, drawn with WebGL2, with no errors.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { decode } from 'fast-png';
import { startViewer, openPage, outDir, pixelStats, skyFromTop, nextFrame } from '../../lib/page_harness.js';

let viewer;
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

// The default view, converged, in a small window: the first test judges it, the last draws it
// both ways. SwiftShader's frame time follows the triangles drawn, which at τ = 1 a smaller
// window needs fewer of; the picture's shares (snow, ground, sky) are those of any size.
let defaultView;
async function openDefaultView() {
  if (defaultView) return defaultView;
  // From scratch the default view needs about 170 updates of the default 4 ms: 3 s on a GPU at
  // 60 frames a second, minutes on SwiftShader's one or two frames a second. A 40 ms budget
  // reaches the same converged mesh in a few frames.
  defaultView = await openPage(viewer.browser, `${viewer.url}?budget=40`, { width: 480, height: 300 });
  const { page } = defaultView;
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 60000 });
  await page.waitForFunction(() => window.hexlod.status !== 'ready' || window.hexlod.converged, null, { timeout: 240000 });
  return defaultView;
}

test('the default view refines a real terrain until converged, not one flat colour, and logs no errors', async () => {
  const { page, problems } = await openDefaultView();
  const state = await page.evaluate(() => {
    const { status, error, terrain, triangles, mesh } = window.hexlod;
    return { status, error, terrain, triangles, mesh };
  });
  assert.equal(state.status, 'ready', `page status: ${state.error}`);
  assert.equal(state.terrain.name, 'globe_himalaya_2048.png');
  assert.deepEqual([state.terrain.width, state.terrain.height], [2048, 2048]);
  assert.ok(state.terrain.maxHeight > 8000, 'Everest is in the default terrain');
  assert.ok(state.triangles > 20000, `only ${state.triangles} triangles drawn`);
  assert.ok(state.mesh.cells > 1000, 'the hexagon mesh refined');
  assert.equal(await page.locator('#status').isVisible(), false,
    `the status box still reads "${await page.locator('#status').textContent()}" once the terrain is drawn`);

  const png = await page.screenshot({ path: `${outDir}/viewer-default.png` });
  const stats = pixelStats(png);
  assert.ok(stats.colours > 200, `only ${stats.colours} distinct colours: the terrain is not drawn`);
  assert.ok(stats.luminanceStd > 12, `luminance spread ${stats.luminanceStd.toFixed(1)}: a flat image`);
  // The opening view shows the Himalaya: snow on the peaks, rock and ground, sky above them.
  assert.ok(stats.snowFraction > 0.003, `${(100 * stats.snowFraction).toFixed(2)} % snow: no high peaks in view`);
  // On the curved Earth the far ground lies lower, under more haze: 6 to 7 % of warm rock here.
  assert.ok(stats.groundFraction > 0.05, `${(100 * stats.groundFraction).toFixed(1)} % ground colours`);
  const sky = skyFromTop(png); // the scattering model's sky, not a clear colour
  assert.ok(sky > 0.02 && sky < 0.5, `${(100 * sky).toFixed(1)} % sky`);
  assert.deepEqual(problems, []);
});

test('a person\'s page (no automation) publishes no test API and still draws the terrain', async () => {
  const page = await viewer.browser.newPage({ viewport: { width: 640, height: 400 } });
  const problems = [];
  page.on('pageerror', (error) => problems.push(error.message));
  // As a browser that no automation tool drives reports itself.
  await page.addInitScript(() => Object.defineProperty(Navigator.prototype, 'webdriver', { get: () => false }));
  await page.goto(viewer.url);
  // The HUD's summary line counts the triangles drawn, as a person reads it.
  await page.waitForFunction(() => {
    const m = /([\d,]+) triangles/.exec(document.getElementById('hud')?.textContent ?? '');
    return m && Number(m[1].replaceAll(',', '')) > 10000;
  }, null, { timeout: 120000 });
  assert.equal(await page.evaluate(() => typeof window.hexlod), 'undefined', 'window.hexlod is for tests only');
  const stats = pixelStats(await page.screenshot({ path: `${outDir}/viewer-person.png` }));
  assert.ok(stats.colours > 200 && stats.luminanceStd > 12, `the terrain is drawn: ${JSON.stringify(stats)}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the paper\'s fans, drawn straight from the mesh\'s fan table, give the triangle list\'s picture', async () => {
  // The fans layout uploads HexMesh's own fan table (a cell's vertices are stored there and
  // nowhere else); the list is written by the stream from it. Same mesh, same pixels.
  const { page, problems } = await openDefaultView();
  // Only the terrain: the HUD's figures (fps, times) change from frame to frame.
  await page.addStyleTag({ content: '#hud, #side, #drop-hint, #status { display: none !important; }' });
  await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged; }, null,
    { timeout: 240000, polling: 200 });
  for (let k = 0; k < 10; ++k) await nextFrame(page); // every blend (8 frames) has ended
  const draw = async (layout) => {
    await page.evaluate((l) => window.hexlod.setLayout(l), layout);
    await nextFrame(page);
    const triangles = await page.evaluate(() => window.hexlod.triangles);
    const png = await page.screenshot({ path: `${outDir}/viewer-layout-${layout}.png` });
    return { triangles, png, image: decode(png) };
  };
  const list = await draw('triangles'), fans = await draw('fans'), listAgain = await draw('triangles');
  const differing = (a, b) => {
    let count = 0;
    for (let k = 0; k < a.data.length; k += a.channels) {
      const d = Math.abs(a.data[k] - b.data[k]) + Math.abs(a.data[k + 1] - b.data[k + 1]) + Math.abs(a.data[k + 2] - b.data[k + 2]);
      if (d > 24) count += 1;
    }
    return count / (a.width * a.height);
  };
  assert.equal(differing(list.image, listAgain.image), 0, 'the view did not hold still between the layouts');
  assert.equal(fans.triangles, list.triangles);
  const stats = pixelStats(fans.png);
  assert.ok(stats.colours > 200 && stats.luminanceStd > 12, `the fans draw the terrain: ${JSON.stringify(stats)}`);
  const share = differing(list.image, fans.image);
  assert.ok(share < 0.002, `${(100 * share).toFixed(2)} % of the pixels differ between fans and list`);
  assert.deepEqual(problems, []);
  await page.close();
});
