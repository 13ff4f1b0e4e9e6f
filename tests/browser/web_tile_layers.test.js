// Web map tiles on the terrain, in the page, by what a person sees: the Blue Marble cut into
// XYZ tiles by gdal2tiles (tests/fixtures/webtiles/) and served by a local tile server with
// latency (lib/tile_server.js) are draped by ?tiles= on the default terrain: GDAL's colours at
// known ground points, tiles asked for only where the view is, the attribution in the page's
// corner and in its own screenshots, the address keeping the layer beside an image file, and
// each fault (a missing tile, a server that refuses cross-origin reads, one that is down, a
// template without {z}) told once while what is drawn stays.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, outDir, FULL_RESOLUTION, projectDir } from '../../lib/page_harness.js';
import { startTileServer } from '../../lib/tile_server.js';
import { colourAt, coloursMatch, lookStraightDown, projectLonLat } from '../../lib/draped_points.js';
import { tileLonLatBounds } from '../../web/webtiles/web_mercator.js';

const POINTS = JSON.parse(readFileSync(new URL('../fixtures/webtiles/bmng_points.json', import.meta.url), 'utf8')).points
  .filter((p) => p.name !== 'Khumbu snow'); // one source pixel wide: the tiles blur it (the fixture's README)
const VIEW = 560;
let viewer, server;
before(async () => {
  [viewer, server] = await Promise.all([startViewer({ pixelRatio: 0.5 }),
    startTileServer(`${projectDir}tests/fixtures/webtiles/bmng`, { latencyMs: 20, capabilities: `${projectDir}tests/fixtures/webtiles/wmts_capabilities.xml` })]);
});
after(async () => { await viewer?.close(); await server?.close(); });

const spec = (origin = server.url) => `${origin}/{z}/{x}/{y}.png|zoom=3-7|attribution=NASA Blue Marble`;

/** Waits until the tile layers have nothing in flight for a few frames running, then draws. */
async function settled(page) {
  await page.waitForFunction(() => {
    const h = window.hexlod;
    h.requestRender();
    const tiles = h.imageLayers.filter((l) => l.kind === 'tiles' && l.visible); // hidden layers fetch nothing
    const quiet = tiles.every((l) => l.tiles.inFlight === 0 && l.tiles.resident > 0);
    h.quietChecks = quiet ? (h.quietChecks ?? 0) + 1 : 0;
    return h.quietChecks >= 5;
  }, null, { timeout: 120000, polling: 100 });
  for (let i = 0; i < 3; i++) await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
}

const status = (page) => page.evaluate(() => document.getElementById('status').textContent);

/** Types `text` into the panel's "add tiles" field and leaves it, as a person does. */
function typeTiles(page, text) {
  return page.evaluate((s) => {
    const field = [...document.querySelectorAll('#panel .lil-controller.lil-string')].find((c) => /add tiles/.test(c.textContent)).querySelector('input');
    field.value = s;
    field.dispatchEvent(new Event('input'));
    field.dispatchEvent(new Event('blur')); // typed and left: the field's value is taken
  }, text);
}

test('?tiles= drapes web map tiles: GDAL\'s colours at ground points, tiles only where the view is, the attribution in the corner and the screenshot, the address keeps it', async () => {
  server.reset();
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1&tiles=${encodeURIComponent(spec())}`, { width: VIEW, height: VIEW }, FULL_RESOLUTION);
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });
  await lookStraightDown(page);
  await settled(page);
  const png = decode(await page.screenshot({ path: `${outDir}/webtiles-whole.png` }));
  const at = await projectLonLat(page, Object.fromEntries(POINTS.map((p) => [p.name, [p.lon, p.lat]])));
  for (const p of POINTS) {
    assert.ok(coloursMatch(colourAt(png, at[p.name]), p.z7.rgba.slice(0, 3), 16), `${p.name} at ${at[p.name]}: ${colourAt(png, at[p.name])}, GDAL's tiles have ${p.z7.rgba}`);
  }
  // The attribution in the corner, and the address keeps the layer.
  assert.equal(await page.evaluate(() => { const a = document.getElementById('attribution'); return a.hidden ? null : a.textContent; }), 'NASA Blue Marble');
  await page.waitForFunction((s) => new URL(location.href).searchParams.getAll('tiles').includes(s), spec(), { timeout: 10000 });

  // The page's own screenshot carries the attribution in its bottom right corner.
  const light = (image) => {
    let n = 0;
    for (let y = image.height - 14; y < image.height - 2; y++) {
      for (let x = image.width - 100; x < image.width - 2; x++) {
        const c = colourAt(image, [x, y]);
        if (c.every((v) => v > 170)) n++;
      }
    }
    return n;
  };
  const saved = async () => {
    const [download] = await Promise.all([page.waitForEvent('download'), page.evaluate(() => window.hexlod.screenshot(1))]);
    return decode(readFileSync(await download.path()));
  };
  const withCredit = await saved();
  await page.evaluate(() => window.hexlod.images.setVisible(window.hexlod.imageLayers[0].id, false));
  const withoutCredit = await saved();
  assert.ok(light(withCredit) > 4 * light(withoutCredit) + 50, `the credit's band: ${light(withCredit)} light pixels, ${light(withoutCredit)} without the layer`);
  await page.evaluate(() => window.hexlod.images.setVisible(window.hexlod.imageLayers[0].id, true));

  // Close over the Bay of Bengal: finer tiles there, and none far from the view.
  server.reset();
  const target = [89.5, 21.5];
  await page.evaluate(([lon, lat]) => {
    const h = window.hexlod, t = h.terrainObject(), orbit = h.rig.cameras.orbit;
    const W = 72.93333333333334, N = 37.916666666666664, step = (90 - W) / 2048;
    orbit.target[0] = ((lon - W) / step - 0.5) * t.spacingX; orbit.target[1] = 0; orbit.target[2] = ((N - lat) / step - 0.5) * t.spacingY;
    orbit.distance = 4e5;
    h.requestRender();
  }, target);
  await settled(page);
  const asked = server.tilesRequested().map((k) => k.split('/').map(Number));
  assert.ok(asked.some(([z]) => z === 7), `zoom 7 tiles asked for close up (${asked.map((t) => t.join('/')).join(' ')})`);
  const far = asked.filter(([z, x, y]) => {
    const [west, south, east, north] = tileLonLatBounds(z, x, y);
    return z > 4 && (east < target[0] - 4 || west > target[0] + 4 || north < target[1] - 4 || south > target[1] + 4);
  });
  assert.deepEqual(far, [], 'no tile finer than the base level far from the view');
  const close = decode(await page.screenshot({ path: `${outDir}/webtiles-close.png` }));
  const sea = (await projectLonLat(page, { sea: POINTS[0] && [POINTS[0].lon, POINTS[0].lat] })).sea;
  assert.ok(coloursMatch(colourAt(close, sea), POINTS[0].z7.rgba.slice(0, 3), 16), `close up, the sea: ${colourAt(close, sea)}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('faults keep what is drawn and say so once: missing tiles, a server that refuses cross-origin reads, one that is down, a template without {z}', async () => {
  server.reset();
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1&tiles=${encodeURIComponent(spec())}`, { width: 400, height: 400 }, FULL_RESOLUTION);
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });
  await lookStraightDown(page);
  await settled(page);
  const before = decode(await page.screenshot());
  const centre = (await projectLonLat(page, { c: [89.1, 31.8333] })).c; // Siling Co: above the status line
  const add = (text) => typeTiles(page, text);
  // A template without {z}: refused, no layer added.
  await add('http://127.0.0.1:1/{x}/{y}.png');
  assert.match(await status(page), /the tile template has no \{z\} \(the zoom\)/);
  assert.equal(await page.evaluate(() => window.hexlod.imageLayers.length), 1);
  // Each fault in a second layer of another origin's tiles: one message, the drawn tiles stay.
  for (const [fault, message] of [['missing', /HTTP 404 for http:\/\/127\.0\.0\.1:\d+\/\d+\/\d+\/\d+\.png/],
    ['no-cors', /answers but does not let this page read its tiles/], ['down', /cannot reach the tile server 127\.0\.0\.1:1 \(it is down, or the address is wrong\)/]]) {
    // A server that is down: a port nothing listens on.
    const broken = fault === 'down' ? { url: 'http://127.0.0.1:1', close: async () => {} }
      : await startTileServer(`${projectDir}tests/fixtures/webtiles/bmng`, { fault });
    try {
      await add(`http://127.0.0.1:${new URL(broken.url).port}/{z}/{x}/{y}.png|zoom=3-7`);
      await page.waitForFunction((source) => new RegExp(source).test(document.getElementById('status').textContent), message.source, { timeout: 60000 })
        .catch(async (error) => { throw new Error(`${fault}: the status says '${await status(page)}' (${error.message})`); });
      const layers = await page.evaluate(() => window.hexlod.imageLayers);
      assert.equal(layers.length, 2, fault);
      const now = decode(await page.screenshot());
      assert.ok(coloursMatch(colourAt(now, centre), colourAt(before, centre), 6), `${fault}: the tiles drawn before stay (${colourAt(now, centre)})`);
      await page.evaluate((id) => window.hexlod.images.remove(id), layers[1].id);
    } finally {
      await broken.close();
    }
  }
  assert.equal(await page.evaluate(() => window.hexlod.terrain.name), 'globe_himalaya_2048.png');
  // The browser reports the refused requests itself; nothing else may go wrong.
  assert.deepEqual(problems.filter((p) => !/request failed: http:\/\/127\.0\.0\.1|Failed to load resource|ERR_CONNECTION_REFUSED|CORS/.test(p)), []);
  await page.close();
});

test('an image file and web map tiles as layers of one terrain: the address keeps both in their order, and a reload gives them back', async () => {
  const imageUrl = `${viewer.fixturesUrl}imagery/bmng_himalaya_4arcmin.jpg`;
  const query = `?test=1&tiles=${encodeURIComponent(spec())}&image=${encodeURIComponent(imageUrl)}`;
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}${query}`, { width: 400, height: 300 }, FULL_RESOLUTION);
  await page.waitForFunction(() => window.hexlod?.status === 'ready' && window.hexlod.imageLayers.length === 2, null, { timeout: 240000 });
  assert.deepEqual(await page.evaluate(() => window.hexlod.imageLayers.map((l) => l.kind)), ['tiles', 'image'], 'in the address\'s order, bottom first');
  const order = () => page.evaluate(() => [...new URL(location.href).searchParams.keys()].filter((k) => k === 'tiles' || k === 'image'));
  await page.waitForFunction(() => new URL(location.href).searchParams.has('tiles'), null, { timeout: 10000 });
  assert.deepEqual(await order(), ['tiles', 'image']);
  // The tiles over the image: the address follows, and a reload of it keeps the order.
  await page.evaluate(() => window.hexlod.images.move(window.hexlod.imageLayers[0].id, 1));
  await page.waitForFunction(() => [...new URL(location.href).searchParams.keys()].filter((k) => k === 'tiles' || k === 'image')[0] === 'image', null, { timeout: 10000 });
  const address = await page.evaluate(() => location.href);
  const again = await openPage(viewer.browser, address, { width: 400, height: 300 }, FULL_RESOLUTION);
  await again.page.waitForFunction(() => window.hexlod?.status === 'ready' && window.hexlod.imageLayers.length === 2, null, { timeout: 240000 });
  assert.deepEqual(await again.page.evaluate(() => window.hexlod.imageLayers.map((l) => [l.kind, l.url])),
    [['image', imageUrl], ['tiles', spec()]]);
  assert.deepEqual([...problems, ...again.problems], []);
  await again.page.close();
  await page.close();
});

test('a WMTS service\'s address in the panel adds its layers in Web Mercator, the first shown, and says which it could not use', async () => {
  server.reset();
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1`, { width: VIEW, height: VIEW }, FULL_RESOLUTION);
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });
  await lookStraightDown(page);
  await typeTiles(page, `${server.url}/wmts`);
  await page.waitForFunction(() => window.hexlod.imageLayers.length === 2, null, { timeout: 60000 });
  const layers = await page.evaluate(() => window.hexlod.imageLayers.map(({ name, visible, url }) => ({ name, visible, url })));
  assert.deepEqual(layers.map((l) => [l.name, l.visible]), [['Blue Marble (REST)', true], ['Blue Marble (KVP)', false]]);
  assert.match(await status(page), /^hexlod test tiles: 2 layers added \(Blue Marble \(REST\), Blue Marble \(KVP\)\), the first shown; not in Web Mercator: bmng_geographic, nepal_local$/);
  await settled(page);
  const png = decode(await page.screenshot({ path: `${outDir}/webtiles-wmts.png` }));
  const at = await projectLonLat(page, Object.fromEntries(POINTS.map((p) => [p.name, [p.lon, p.lat]])));
  // The status line (its message names the layers) covers the south of the view.
  const statusTop = await page.evaluate(() => document.getElementById('status').getBoundingClientRect().top);
  const seen = POINTS.filter((p) => at[p.name][1] < statusTop);
  assert.ok(seen.length >= 3, `${seen.length} points above the status line`);
  for (const p of seen) {
    assert.ok(coloursMatch(colourAt(png, at[p.name]), p.z7.rgba.slice(0, 3), 16), `WMTS: ${p.name} at ${at[p.name]}: ${colourAt(png, at[p.name])}`);
  }
  // The address keeps each layer as a template: a reload needs no capabilities document.
  assert.ok(layers.every((l) => /\{z\}|\{TileMatrix\}|TILEMATRIX=\{z\}/i.test(l.url) || l.url.includes('{')), layers.map((l) => l.url).join(' '));
  assert.ok(server.log.some((e) => /GetCapabilities/i.test(e.path)), 'the capabilities were asked for');
  assert.deepEqual(problems, []);
  await page.close();
});
