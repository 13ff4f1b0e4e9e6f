// The drop a GIS user makes: a DEM that places itself only by GDAL's .aux.xml (a 16-bit PNG in
// NAD83 / Conus Albers, tests/fixtures/crs/), an orthophoto PNG with its world file and .prj,
// and what GDAL and other tools leave beside them (.ovr overviews, an .md5 checksum, a stray
// world file, a hidden file): the terrain opens where the .aux.xml puts it, the image drapes in
// the .prj's CRS, and the status line names each skipped file and why. Dropped as files and as
// a folder (with a folder inside, read through the entries API), judged by the screenshot's
// pixels: each quadrant of the image shows its colour at its ground points, and the ground
// outside the image is as it was without it; the cursor's readout gives the point's latitude
// and longitude. A drop of nothing but sidecars keeps the terrain.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { decode, encode } from 'fast-png';
import { readFileSync } from 'node:fs';
import { startViewer, openPage, dropFiles, terrainShown, converged, outDir, FULL_RESOLUTION } from '../../lib/page_harness.js';
import { colourAt, coloursMatch, lookStraightDown, screenPoint } from '../../lib/draped_points.js';
import { useNodeCrsDefinitions } from '../../lib/crs_definitions.js';
import { crsOfEpsg, resolveCrs, toLonLat } from '../../web/geo/index.js';

let viewer;
// Half a device pixel per CSS pixel for the browser, but the page that judges ground points' colours is at full resolution.
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

const fixture = (path, as) => ({ name: as ?? path.split('/').pop(), bytes: new Uint8Array(readFileSync(new URL(`../fixtures/${path}`, import.meta.url))) });
const text = (name, content) => ({ name, bytes: new TextEncoder().encode(content) });

// The DEM: 207 x 200 samples of 100 m, its outer edges at x 1030700..1051400, y 1559100..1579100.
const DEM = 'jacksboro_5070_png.png';
const dem = () => [fixture(`crs/${DEM}`), fixture(`crs/${DEM}.aux.xml`)];
// Its CRS as GDAL wrote it into the .aux.xml: the orthophoto's .prj says the same.
const WKT_5070 = /<SRS[^>]*>([^<]*)<\/SRS>/.exec(readFileSync(new URL(`../fixtures/crs/${DEM}.aux.xml`, import.meta.url), 'utf8'))[1];

// The orthophoto: 64 x 64 pixels of four colours over the middle 14 km of the DEM.
const QUADRANTS = { nw: [220, 40, 40], ne: [40, 200, 60], sw: [40, 60, 220], se: [230, 210, 40] };
const IMAGE = { west: 1034000, north: 1576000, size: 14000, pixels: 64 };
function orthophoto() {
  const { pixels } = IMAGE, rgb = new Uint8Array(pixels * pixels * 3);
  for (let y = 0; y < pixels; y++) {
    for (let x = 0; x < pixels; x++) rgb.set(QUADRANTS[`${y < pixels / 2 ? 'n' : 's'}${x < pixels / 2 ? 'w' : 'e'}`], (y * pixels + x) * 3);
  }
  const step = IMAGE.size / pixels;
  return [
    { name: 'ortho.png', bytes: encode({ width: pixels, height: pixels, data: rgb, channels: 3 }) },
    text('ortho.pgw', `${step}\n0\n0\n${-step}\n${IMAGE.west + step / 2}\n${IMAGE.north - step / 2}\n`),
    text('ortho.prj', WKT_5070),
  ];
}
// Ground points (EPSG:5070 metres): each quadrant's centre, and two outside the image.
const POINTS = {
  nw: [1037500, 1572500], ne: [1044500, 1572500], sw: [1037500, 1565500], se: [1044500, 1565500],
  outsideNorth: [1041000, 1577700], outsideWest: [1032300, 1569000],
};
// GDAL's companions, which hold nothing to show.
const extras = () => [fixture('crs/jacksboro_5070.tif', `${DEM}.ovr`), text(`${DEM}.md5`, '0f343b0931126a20f133d67c2b018a3b  jacksboro_5070_png.png\n'),
  text('old.pgw', '1\n0\n0\n-1\n0\n0\n')];
// What the status line says of them, in any order (a folder's files come sorted by name).
const SKIPPED = [`${DEM}.ovr (GeoTIFF overviews)`, `${DEM}.md5 (checksum)`,
  'old.pgw (a world file of no image here: ortho.png\'s is named ortho.pgw or ortho.pngw or ortho.wld)'];

/** The page's view straight down on the DEM, and the screen pixels of POINTS on its ground. */
async function view(page, label) {
  await lookStraightDown(page, 30000);
  await converged(page); // the same mesh for the same view: the ground outside the image is comparable
  for (let i = 0; i < 4; i++) await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
  const png = decode(await page.screenshot({ path: `${outDir}/gis-drop-${label}.png` }));
  const placed = await page.evaluate((points) => {
    const h = window.hexlod, t = h.terrainObject(), g = h.layers.ground.field.georef;
    const ground = {};
    for (const [name, [x, y]] of Object.entries(points)) {
      const gx = ((x - g.x0) / g.dx) * t.spacingX, gz = ((y - g.y0) / g.dy) * t.spacingY;
      ground[name] = h.drawnPoint(gx, h.rig.world.ground(gx, gz), gz);
    }
    return { m: Array.from(h.camera.viewProjection), ground, width: innerWidth, height: innerHeight };
  }, POINTS);
  const at = Object.fromEntries(Object.entries(placed.ground).map(([name, p]) => [name, screenPoint(placed.m, p, placed.width, placed.height)]));
  return { png, at };
}

const status = (page) => page.evaluate(() => ({ text: document.getElementById('status').textContent,
  error: document.getElementById('status').classList.contains('error') }));

/** The drop's outcome: the terrain where the .aux.xml put it, the image in its quadrants, the rest skipped. */
async function assertDraped(page, bare, label) {
  await terrainShown(page, DEM);
  await page.waitForFunction(() => window.hexlod.image !== null && !window.hexlod.loading, null, { timeout: 60000 });
  const { terrain, image, crs } = await page.evaluate(() => ({ terrain: window.hexlod.terrain.name, image: window.hexlod.image,
    crs: window.hexlod.layers.ground.field.georef.crs.label }));
  assert.deepEqual([terrain, crs, image.name, image.how], [DEM, 'EPSG:5070', 'ortho.png', 'georeferenced']);
  // 14 km square of a 20.7 x 19.9 km field of sample centres.
  assert.ok(Math.abs(image.coverage - (14000 * 14000) / (20600 * 19900)) < 0.01, `the image covers ${image.coverage} of the field`);
  // The .prj names the image's CRS: nothing is assumed; everything else is skipped by name.
  const said = await status(page);
  assert.ok(!said.error && said.text.startsWith('skipped ') && SKIPPED.every((s) => said.text.includes(s)) &&
    said.text.length === 'skipped '.length + SKIPPED.join(', ').length, `${label}: ${said.text}`);
  const { png, at } = await view(page, label);
  for (const [quadrant, colour] of Object.entries(QUADRANTS)) {
    assert.ok(coloursMatch(colourAt(png, at[quadrant]), colour, 16), `${label}: ${quadrant} at ${at[quadrant]}: ${colourAt(png, at[quadrant])}, the image has ${colour}`);
  }
  for (const outside of ['outsideNorth', 'outsideWest']) {
    assert.ok(coloursMatch(colourAt(png, at[outside]), colourAt(bare.png, bare.at[outside]), 8),
      `${label}: outside the image at ${at[outside]} the ground is as it was: ${colourAt(png, at[outside])} vs ${colourAt(bare.png, bare.at[outside])}`);
  }
}

test('a GIS drop: the DEM placed by its .aux.xml, the orthophoto by its world file in its .prj\'s CRS, the rest skipped by name; as files and as a folder', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1`, { width: 600, height: 600 }, FULL_RESOLUTION);
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 240000 });

  // The DEM alone first: the ground without the image, for the points outside it.
  await dropFiles(page, dem());
  await terrainShown(page, DEM);
  assert.deepEqual(await page.evaluate(() => { const g = window.hexlod.layers.ground.field.georef; return [g.crs.label, g.crs.name, g.from, g.x0, g.y0]; }),
    ['EPSG:5070', 'NAD83 / Conus Albers', '.aux.xml', 1030750, 1579050]);
  const bare = await view(page, 'bare');
  for (const quadrant of Object.keys(QUADRANTS)) {
    assert.ok(!coloursMatch(colourAt(bare.png, bare.at[quadrant]), QUADRANTS[quadrant], 40), `no ${quadrant} colour before the image`);
  }

  // Everything at once, as files.
  await dropFiles(page, [...extras(), ...orthophoto(), ...dem()]);
  await assertDraped(page, bare, 'files');

  // The readout under the pointer: Conus Albers metres and their latitude and longitude, as
  // proj4 gives them in Node from the same definition (4 decimals: within 1e-4 degrees).
  const { at } = await view(page, 'cursor');
  await page.mouse.move(at.ne[0] - 3, at.ne[1] - 2);
  await page.mouse.move(at.ne[0], at.ne[1]);
  await page.waitForFunction(() => window.hexlod.cursor?.place?.includes('EPSG:5070'), null, { timeout: 10000 });
  const place = await page.evaluate(() => window.hexlod.cursor.place);
  const m = /^E (1 0\d\d \d{3}) m N (1 5\d\d \d{3}) m \(EPSG:5070\) · (\d+\.\d{4})° N (\d+\.\d{4})° W$/.exec(place);
  assert.ok(m, place);
  useNodeCrsDefinitions();
  const [lon, lat] = toLonLat(await resolveCrs(crsOfEpsg(5070)))(Number(m[1].replace(/ /g, '')), Number(m[2].replace(/ /g, '')));
  assert.ok(Math.abs(lat - Number(m[3])) < 1e-4 && Math.abs(-lon - Number(m[4])) < 1e-4, `${place}: Node has ${lat}, ${lon}`);
  assert.ok(Math.abs(Number(m[1].replace(/ /g, '')) - POINTS.ne[0]) < 500, `${place}: near the NE quadrant's centre`);

  // Another terrain, then the same files as a dropped folder: survey/ holds the DEM and GDAL's
  // files, survey/ortho/ the image's; the browser gives a folder's entries in batches.
  await dropFiles(page, [fixture('formats/everest_16bit.png')]);
  await terrainShown(page, 'everest_16bit.png');
  const folder = { name: 'survey', files: [...dem(), ...extras(), text('.DS_Store', 'Bud1')], folders: [{ name: 'ortho', files: orthophoto(), folders: [] }] };
  const encoded = (f) => ({ ...f, files: f.files.map(({ name, bytes }) => ({ name, data: Buffer.from(bytes).toString('base64') })), folders: f.folders.map(encoded) });
  await page.evaluate((tree) => {
    const file = ({ name, data }) => new File([Uint8Array.from(atob(data), (c) => c.charCodeAt(0))], name);
    const entryOf = (node) => {
      const children = [...node.files.map((f) => ({ isFile: true, isDirectory: false, name: f.name, file: (ok) => ok(file(f)) })), ...node.folders.map(entryOf)];
      return { isFile: false, isDirectory: true, name: node.name, createReader() {
        let batch = 0; // two batches, then the empty one that ends the folder
        return { readEntries: (ok) => setTimeout(() => ok(batch++ === 0 ? children.slice(0, 3) : batch === 2 ? children.slice(3) : []), 0) };
      } };
    };
    const transfer = { files: [], items: [{ kind: 'file', webkitGetAsEntry: () => entryOf(tree) }] };
    const event = new DragEvent('drop', { bubbles: true, cancelable: true });
    Object.defineProperty(event, 'dataTransfer', { value: transfer });
    window.dispatchEvent(event);
  }, encoded(folder));
  await assertDraped(page, bare, 'folder');

  // Only sidecars and metadata: nothing to open, said by name; the terrain and image stay.
  await dropFiles(page, [...extras().slice(0, 2), text('ortho.prj', WKT_5070)]);
  await page.waitForFunction(() => !window.hexlod.loading, null, { timeout: 60000 });
  const refused = await status(page);
  assert.match(refused.text, /^jacksboro_5070_png\.png\.ovr: GeoTIFF overviews: nothing here to open/);
  assert.ok(refused.error);
  assert.deepEqual(await page.evaluate(() => [window.hexlod.terrain.name, window.hexlod.image?.name]), [DEM, 'ortho.png']);
  assert.deepEqual(problems, []);
  await page.close();
});
