// The production build (dist/, ./build.sh site) served by a plain static file server under a
// sub-path (/hexlod/), as a static host would: the default terrain opens and shows, its CRS
// defined by the site's own EPSG files, a dropped
// file and a ?src= file open framed, R resets the view; a satellite image drapes, dropped or by
// ?image=; a COG by ?src= streams, its tiles decoded by the bundled workers; contours and a
// measured path come from the address. Judged by pixels and geometry.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { startViewer, openPage, FULL_RESOLUTION, outDir, projectDir, terrainCoverage, pageReady, dropFiles, terrainShown,
  converged, eyeClearance, nextFrame } from '../../lib/page_harness.js';
import { BLUE_MARBLE_POINTS as POINTS, colourAt, coloursMatch, lookStraightDown, projectLonLat } from '../../lib/draped_points.js';
import { decode } from 'fast-png';
import { startRangeServer } from '../../lib/range_server.js';

const FIXTURES = `${projectDir}tests/fixtures/`;
const read = (name) => ({ name, bytes: readFileSync(FIXTURES + name) });
// Pages that wait for a converged mesh open at a 50 ms frame budget: SwiftShader draws a frame
// in a second or more, and at the default 4 ms the default view refines for some 160 frames.
// The converged mesh is the same. (The draped image is judged from a few frames after the page
// is ready, not converged: there the default budget's coarser mesh draws faster.)
const QUICK = 'budget=50';
let site;
// Half a device pixel per CSS pixel but for the draped image's colours and the streamed tiles,
// which are judged at full resolution.
before(async () => { site = await startViewer({ site: 'built', pixelRatio: 0.5 }); });
after(async () => { await site?.close(); });

/** The terrain on screen over `minCoverage` of the view, shaded, the eye above it. */
async function assertShown(page, label, minCoverage) {
  const seen = await terrainCoverage(page);
  await page.screenshot({ path: `${outDir}/built-${label}.png` });
  assert.ok(seen.coverage >= minCoverage && seen.colours >= 30, `${label}: terrain over ${(100 * seen.coverage).toFixed(1)} % (${JSON.stringify(seen)})`);
  const clearance = await eyeClearance(page); // null: the eye is off the field
  assert.ok(clearance === null || clearance > 0, `${label}: the eye is ${clearance} m above the ground`);
}

test('the built site under /hexlod/ opens the default terrain; a drop, R and ?src= work', async () => {
  assert.match(site.url, /\/hexlod\/$/);
  const { page, problems } = await openPage(site.browser, `${site.url}?${QUICK}`, { width: 960, height: 540 });
  await pageReady(page);
  const state = await page.evaluate(() => ({ status: window.hexlod.status, error: window.hexlod.error, terrain: window.hexlod.terrain }));
  assert.equal(state.status, 'ready', state.error);
  assert.equal(state.error, null);
  assert.deepEqual([state.terrain.name, state.terrain.width, state.terrain.height], ['globe_himalaya_2048.png', 2048, 2048]);
  // The EPSG definitions are files of the site, one per code, fetched when a file names a code:
  // the default terrain's EPSG:4326 came from crs/4326.json beside the page.
  const crs = await page.evaluate(async () => ({ terrain: window.hexlod.layers.ground.field.georef.crs,
    lv95: await (await fetch('crs/2056.json')).json() }));
  assert.deepEqual([crs.terrain.name, crs.terrain.geographic, crs.terrain.proj4], ['WGS 84', true, '+proj=longlat +datum=WGS84 +no_defs']);
  assert.deepEqual([crs.lv95.name, /\+towgs84=674\.374/.test(crs.lv95.proj4)], ['CH1903+ / LV95', true]);
  await page.waitForFunction(() => window.hexlod.triangles > 10000, null, { timeout: 120000 });
  await assertShown(page, 'default', 0.6);

  await dropFiles(page, [read('volcano_maungawhau.png'), read('volcano_maungawhau.json')]);
  await terrainShown(page, 'volcano_maungawhau.png');
  await converged(page);
  assert.ok(await page.evaluate(() => window.hexlod.triangles) > 3000, 'the dropped volcano refines');
  await assertShown(page, 'drop-volcano', 0.15);
  await page.evaluate(() => { window.hexlod.rig.cameras.orbit.target[2] -= 5000; });
  await nextFrame(page);
  await page.keyboard.press('r');
  await assertShown(page, 'reset-volcano', 0.15);
  assert.deepEqual(problems, []);
  await page.close();

  // ?src= also asks for NAME.json beside the file; a static host answers 404 when there is none.
  const opened = await openPage(site.browser, 'about:blank', { width: 960, height: 540 });
  const missing = [];
  opened.page.on('response', (response) => { if (response.status() >= 400) missing.push(new URL(response.url()).pathname); });
  await opened.page.goto(`${site.url}?${QUICK}&src=${encodeURIComponent('/fixtures/formats/canyon_u16_tiled_deflate.tif')}`);
  await pageReady(opened.page);
  assert.equal(await opened.page.evaluate(() => window.hexlod.terrain.name), 'canyon_u16_tiled_deflate.tif');
  await converged(opened.page);
  await assertShown(opened.page, 'src-canyon', 0.15);
  assert.deepEqual(missing, ['/fixtures/formats/canyon_u16_tiled_deflate.json'], 'only the optional sidecar is missing');
  // A TIFF by ?src= is first opened to stream; this host ignores Range, so the reader cut its
  // first answer short (a failed request to the browser) and the file was loaded whole.
  assert.equal(await opened.page.evaluate(() => window.hexlod.terrain.tiled), false);
  assert.deepEqual(opened.problems.filter((p) => !/status of 404/.test(p) && !/^request failed: .*canyon_u16_tiled_deflate\.tif$/.test(p)), []);
  await opened.page.close();
});

test('the built site drapes a dropped satellite image by its world file, and ?image= opens one', async () => {
  const image = [read('imagery/bmng_himalaya_4arcmin.jpg'), read('imagery/bmng_himalaya_4arcmin.jgw')];
  const imageUrl = '/fixtures/imagery/bmng_himalaya_4arcmin.jpg';
  for (const how of ['drop', '?image=']) {
    const { page, problems } = await openPage(site.browser, how === 'drop' ? site.url : `${site.url}?image=${encodeURIComponent(imageUrl)}`, { width: 640, height: 640 }, FULL_RESOLUTION);
    await pageReady(page);
    if (how === 'drop') await dropFiles(page, image);
    await page.waitForFunction(() => window.hexlod.image !== null, null, { timeout: 60000 });
    assert.equal(await page.evaluate(() => window.hexlod.image.coverage), 1, how);
    await lookStraightDown(page);
    await nextFrame(page);
    await nextFrame(page);
    const png = decode(await page.screenshot({ path: `${outDir}/built-image-${how === 'drop' ? 'drop' : 'url'}.png` }));
    const at = await projectLonLat(page, POINTS);
    for (const [name, [, , expected]] of Object.entries(POINTS)) {
      assert.ok(coloursMatch(colourAt(png, at[name]), expected, 24), `${how}: ${name} at ${at[name]} is ${colourAt(png, at[name])}, the image has ${expected}`);
    }
    assert.deepEqual(problems, [], how);
    await page.close();
  }
});

test('the built site streams a COG by ?src=, its tiles decoded by the bundled workers', async () => {
  const cogs = await startRangeServer(`${FIXTURES}cog`, { latencyMs: 20 });
  try {
    const url = `${cogs.url}/himalaya_1024_i16.tif`;
    const { page, problems } = await openPage(site.browser, `${site.url}?budget=50&tau=3&src=${encodeURIComponent(url)}`, { width: 480, height: 300 }, FULL_RESOLUTION);
    await pageReady(page);
    const terrain = await page.evaluate(() => window.hexlod.terrain);
    assert.deepEqual([terrain?.name, terrain?.width, terrain?.tiled], ['himalaya_1024_i16.tif', 1024, true],
      await page.evaluate(() => window.hexlod.error));
    await page.waitForFunction(() => window.hexlod.converged && window.hexlod.tiles?.settled, null, { timeout: 120000 });
    const stream = await page.evaluate(() => window.hexlod.tiles);
    assert.ok(stream.tilesIn > 0 && stream.bytesFetched < stream.fileBytes, JSON.stringify(stream));
    await assertShown(page, 'src-cog', 0.2);
    // Tile requests the view left are aborted: the browser logs them as failed.
    assert.deepEqual(problems.filter((p) => p !== `request failed: ${url}`), []);
    await page.close();
  } finally {
    await cogs.close();
  }
});

test('the built site draws contour lines and a measured path from the address, and both leave the picture when turned off', async () => {
  const line = 'measure=p:1300000,1000000;1450000,1100000;1460000,960000';
  const { page, problems } = await openPage(site.browser, `${site.url}?${QUICK}&contours=1&cint=250&${line}`, { width: 640, height: 400 });
  await pageReady(page);
  await page.click('#measure-fold'); // the panel folds to its bar, as on a small screen, and the line is in view
  await converged(page);
  const shown = await page.evaluate(() => {
    const h = window.hexlod, r = h.measure.result;
    return { contours: { ...h.contours }, points: r.points.length, length: r.profile?.summary.length ?? 0 };
  });
  assert.equal(shown.contours.on, true);
  assert.equal(shown.contours.interval, 250);
  assert.ok(shown.contours.labels > 0, `labels drawn: ${JSON.stringify(shown.contours)}`);
  assert.equal(shown.points, 3);
  assert.ok(shown.length > 150000 && shown.length < 400000, `the path is ${shown.length} m long`);
  const both = decode(await page.screenshot({ path: `${outDir}/built-measure-contours.png` }));
  // The same view with contours off, then with the line hidden: each takes pixels away.
  await page.evaluate(() => { window.hexlod.setSetting('contours', false); });
  await nextFrame(page);
  await nextFrame(page);
  const noContours = decode(await page.screenshot());
  await page.evaluate(() => { window.hexlod.measure.overlay.setLine(null, []); window.hexlod.requestRender(); });
  await nextFrame(page);
  await nextFrame(page);
  const neither = decode(await page.screenshot());
  const differing = (a, b) => {
    let n = 0;
    for (let k = 0; k < a.data.length; k += a.channels) {
      if (Math.abs(a.data[k] - b.data[k]) + Math.abs(a.data[k + 1] - b.data[k + 1]) + Math.abs(a.data[k + 2] - b.data[k + 2]) > 60) n++;
    }
    return n / (a.width * a.height);
  };
  const contourShare = differing(both, noContours), lineShare = differing(noContours, neither);
  assert.ok(contourShare > 0.01 && contourShare < 0.35, `contour lines change ${(100 * contourShare).toFixed(2)} % of the view`);
  assert.ok(lineShare > 0.001 && lineShare < 0.1, `the measured line changes ${(100 * lineShare).toFixed(2)} % of the view`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the built site draws a GPX dropped on the default terrain and a KMZ from ?overlay=, on the ground, in their colours', async () => {
  const files = await startRangeServer(`${FIXTURES}overlays`);
  try {
    const kmz = `${files.url}/everest_places.kmz`;
    const { page, problems } = await openPage(site.browser, `${site.url}?${QUICK}&overlay=${encodeURIComponent(kmz)}`, { width: 640, height: 400 }, FULL_RESOLUTION);
    await pageReady(page);
    await page.waitForFunction(() => window.hexlod.layers.overlays.length === 1, null, { timeout: 60000 });
    await dropFiles(page, [{ ...read('overlays/everest_trek.gpx'), name: 'everest_trek.gpx' }]);
    await page.waitForFunction(() => window.hexlod.layers.overlays.length === 2, null, { timeout: 60000 });
    assert.deepEqual(await page.evaluate(() => window.hexlod.layers.overlays.map((l) => [l.name, l.overlay.format, l.color])),
      [['everest_places.kmz', 'KMZ', '#ff3d8b'], ['everest_trek.gpx', 'GPX', '#2fd4ff']]);
    await page.addStyleTag({ content: '#hud,#side,#drop-hint,#status,#bottom-bar{display:none !important}' });
    // Straight down on the trek, 80 km up.
    await page.evaluate(() => {
      const h = window.hexlod, s = h.layers.overlays[1].geometry.segments, orbit = h.rig.cameras.orbit;
      h.setSetting('camera', 'orbit');
      orbit.target.set([s[0], 0, s[2]]);
      Object.assign(orbit, { yaw: 0, pitch: 1.55, distance: 80000 });
      h.requestRender();
    });
    await converged(page);
    for (let i = 0; i < 3; i++) await nextFrame(page);
    const png = decode(await page.screenshot({ path: `${outDir}/built-overlays.png` }));
    const count = (rgb) => {
      let n = 0;
      for (let k = 0; k < png.data.length; k += png.channels) {
        if (Math.abs(png.data[k] - rgb[0]) < 40 && Math.abs(png.data[k + 1] - rgb[1]) < 40 && Math.abs(png.data[k + 2] - rgb[2]) < 40) n++;
      }
      return n;
    };
    assert.ok(count([47, 212, 255]) > 300, `the trek in cyan: ${count([47, 212, 255])} pixels`);
    assert.ok(count([255, 61, 139]) > 100, `the places in pink: ${count([255, 61, 139])} pixels`);
    assert.deepEqual(problems, []);
    await page.close();
  } finally {
    await files.close();
  }
});
