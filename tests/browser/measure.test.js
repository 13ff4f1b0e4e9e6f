// The measuring tool as a person uses it: turn it on, click points on the terrain, read the
// profile chart and its figures (checked against web/measure/ run on its own in the page), see
// the line on the ground (and in a screenshot), hover the chart, export CSV and PNG, share the
// address and get the same line back; in the orbit, fly and walk cameras (a drag still moves
// them); an area; a phone's touch; and the cursor's real coordinates for georeferenced fields.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, pageReady, drawFrames, outDir, projectDir, FULL_RESOLUTION } from '../../lib/page_harness.js';

let viewer;
// Half a device pixel per CSS pixel but for the path, whose chart and ground line are judged by
// their pixels.
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

const DESKTOP = { width: 640, height: 480 };
// The default terrain at a 50 ms frame budget, for the cases that stay on one view: SwiftShader
// draws a frame in a second or more, and at the default 4 ms the page refines for some 160
// frames, all through a test, each click, frame and screenshot waiting behind them. At 50 ms it
// converges in a few frames to the same mesh and then draws only when asked.
const quick = '?budget=50';
const lib = (file) => `/@fs${projectDir}web/measure/${file}`;

/** The first pixel of `candidates` where the canvas is on top and the ray meets the ground. */
const groundPixels = (page, candidates, count) => page.evaluate(([list, n]) => {
  const found = [];
  for (const [x, y] of list) {
    if (document.elementFromPoint(x, y)?.id !== 'view') continue;
    if (window.hexlod.measure.pick(x, y) && !found.some(([a, b]) => Math.hypot(a - x, b - y) < 40)) found.push([x, y]);
    if (found.length === n) break;
  }
  return found;
}, [candidates, count]);

/** Candidate pixels in rows from y0 to y1 across the view. */
function grid(width, y0, y1) {
  const list = [];
  for (let y = y0; y <= y1; y += 12) for (let x = 60; x < width - 60; x += 37) list.push([x, y]);
  return list;
}

/** Where ground points [x, z] (local metres) are on screen, CSS pixels, with the current camera. */
const project = (page, points) => page.evaluate((pts) => {
  const h = window.hexlod, c = h.rig.active, m = c.viewProjection, t = h.terrainObject(), s = h.settings.exaggeration;
  const canvas = document.getElementById('view');
  return pts.map(([gx, gz]) => {
    const [x, y, z] = h.drawnPoint(gx, t.heightAt(gx, gz) * s, gz);
    const cx = m[0] * x + m[4] * y + m[8] * z + m[12], cy = m[1] * x + m[5] * y + m[9] * z + m[13];
    const w = m[3] * x + m[7] * y + m[11] * z + m[15];
    return [((cx / w + 1) / 2) * canvas.clientWidth, ((1 - cy / w) / 2) * canvas.clientHeight];
  });
}, points);

/** Pixels within `r` of (x, y) that differ between two decoded screenshots by more than 60 (sum of RGB). */
function changedNear(a, b, [x, y], r = 7) {
  let count = 0;
  for (let py = Math.round(y - r); py <= y + r; py++) {
    for (let px = Math.round(x - r); px <= x + r; px++) {
      if (px < 0 || py < 0 || px >= a.width || py >= a.height) continue;
      const k = (py * a.width + px) * a.channels;
      if (Math.abs(a.data[k] - b.data[k]) + Math.abs(a.data[k + 1] - b.data[k + 1]) + Math.abs(a.data[k + 2] - b.data[k + 2]) > 60) count++;
    }
  }
  return count;
}

/** Clicks like a person: press, release, and a pause longer than a double click. */
async function clickAt(page, [x, y]) {
  await page.mouse.click(x, y);
  await page.waitForTimeout(550);
}

const toolState = (page) => page.evaluate(() => {
  const r = window.hexlod.measure.result;
  return { active: r.active, kind: r.kind, points: r.points.map((p) => [...p]), finished: r.finished, error: r.error,
    summary: r.profile && { ...r.profile.summary }, samples: r.profile?.samples.distance.length ?? 0,
    clipped: r.profile?.clipped ?? null, area: r.area && { ...r.area } };
});

const summaryText = (page) => page.evaluate(() => Object.fromEntries([...document.querySelectorAll('#measure-summary dt')]
  .map((dt) => [dt.textContent, dt.nextElementSibling.textContent])));

test('a path: chart, figures, the line on the ground, hover, CSV and PNG, the address and a reload', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}${quick}`, DESKTOP, FULL_RESOLUTION);
  await pageReady(page);
  await page.keyboard.press('m');
  assert.equal(await page.isVisible('#measure'), true, 'M shows the measuring panel');
  const pixels = await groundPixels(page, grid(DESKTOP.width, 100, 130), 3);
  assert.equal(pixels.length, 3, 'three ground pixels above the panel');
  for (const p of pixels) await clickAt(page, p);
  await page.keyboard.press('Enter');
  await drawFrames(page, 2);
  const state = await toolState(page);
  assert.equal(state.points.length, 3);
  assert.equal(state.finished, true);
  assert.ok(state.samples > 50, `${state.samples} samples along the path`);

  // The figures against the library run on its own in the page.
  const independent = await page.evaluate(async ([profileUrl, samplerUrl, unitsUrl, points]) => {
    const { computeProfile } = await import(profileUrl);
    const { fieldSampler } = await import(samplerUrl);
    const { formatLength } = await import(unitsUrl);
    const p = computeProfile(points, fieldSampler(window.hexlod.terrainObject(), window.hexlod.layers.ground.field.georef ?? null));
    return { summary: { ...p.summary }, length: formatLength(p.summary.length), length3d: formatLength(p.summary.length3d) };
  }, [lib('profile.js'), lib('field_sampler.js'), lib('units.js'), state.points]);
  for (const key of ['length', 'length3d', 'gain', 'loss', 'min', 'max', 'meanSlope', 'steepestSlope']) {
    assert.ok(Math.abs(independent.summary[key] - state.summary[key]) < 1e-6 * Math.max(1, Math.abs(state.summary[key])), key);
  }
  const shown = await summaryText(page);
  assert.equal(shown.length, independent.length);
  assert.equal(shown['3D length'], independent.length3d);
  assert.equal(shown.gain, `${Math.round(state.summary.gain).toLocaleString('en')} m`);
  assert.equal(shown.max, `${Math.round(state.summary.max).toLocaleString('en')} m`);
  assert.equal(shown.steepest, `${state.summary.steepestSlope.toFixed(1)}°`);

  // The chart: its axis and a plotted curve.
  const chart = await page.evaluate(() => {
    const c = document.getElementById('profile-chart'), d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let curve = 0, axis = 0, text = 0;
    for (let k = 0; k < d.length; k += 4) {
      const [r, g, b] = [d[k], d[k + 1], d[k + 2]];
      if (r > 220 && g > 170 && b < 90) curve++;
      else if (Math.abs(r - 154) < 12 && Math.abs(g - 166) < 12 && Math.abs(b - 184) < 12) axis++;
      else if (r > 180 && g > 180 && b > 180) text++;
    }
    return { curve, axis, text, width: c.width, height: c.height };
  });
  assert.ok(chart.curve > chart.width * 0.5, `curve pixels ${chart.curve}`);
  assert.ok(chart.axis > chart.height * 0.5, `axis pixels ${chart.axis}`);
  assert.ok(chart.text > 50, `label pixels ${chart.text}`);

  // The line on the ground: pixels change near every clicked point and segment middle when it is drawn.
  const withLine = decode(await page.screenshot({ path: `${outDir}/measure-path.png` }));
  await page.evaluate(() => { window.hexlod.measure.overlay.setLine(null, []); window.hexlod.requestRender(); });
  await drawFrames(page, 1);
  const without = decode(await page.screenshot());
  await page.evaluate(() => window.hexlod.measure.update());
  await drawFrames(page, 1);
  const middles = state.points.slice(1).map((p, k) => [(p[0] + state.points[k][0]) / 2, (p[1] + state.points[k][1]) / 2]);
  const onScreen = await project(page, [...state.points, ...middles]);
  for (const [k, at] of onScreen.entries()) {
    const changed = changedNear(withLine, without, at);
    assert.ok(changed > 8, `the line shows near point ${k} (${at.map(Math.round)}): ${changed} pixels`);
  }
  // And in the page's screenshot (renderer.draw into a framebuffer).
  const [shot] = await Promise.all([page.waitForEvent('download'), page.evaluate(() => window.hexlod.screenshot(1))]);
  const png = decode(readFileSync(await shot.path()));
  let yellow = 0;
  for (let k = 0; k < png.data.length; k += png.channels) if (png.data[k] > 220 && png.data[k + 1] > 170 && png.data[k + 2] < 90) yellow++;
  assert.ok(yellow > 40, `the line in the screenshot: ${yellow} pixels`);

  // Hover: the chart's middle marks a sample on the terrain and says its height.
  const box = await page.locator('#profile-chart').boundingBox();
  await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
  await drawFrames(page, 1);
  const hover = await page.evaluate(() => ({ on: window.hexlod.measure.overlay.hoverOn, at: [...window.hexlod.measure.overlay.hover].slice(0, 3),
    text: document.getElementById('measure-hover').textContent }));
  assert.equal(hover.on, true);
  assert.match(hover.text, /height [\d,]+ m/);
  assert.match(hover.text, /° N .*° E/, 'the hovered point in latitude and longitude');
  const hovered = decode(await page.screenshot({ path: `${outDir}/measure-hover.png` }));
  const [marker] = await project(page, [[hover.at[0], hover.at[2]]]);
  assert.ok(changedNear(hovered, without, marker, 9) > 20, 'a marker at the hovered point');

  // CSV: the summary, the columns with latitude and longitude, a row per sample.
  const [csvDownload] = await Promise.all([page.waitForEvent('download'), page.click('#measure-csv')]);
  const csv = readFileSync(await csvDownload.path(), 'utf8');
  const lines = csv.trim().split('\n');
  const header = lines.find((l) => !l.startsWith('#')).split(',');
  assert.deepEqual(header, ['distance_m', 'x_m', 'z_m', 'lon', 'lat', 'height_m']);
  const rows = lines.filter((l) => !l.startsWith('#')).slice(1).map((l) => l.split(',').map(Number));
  assert.equal(rows.length, state.samples);
  assert.equal(rows[0][0], 0);
  assert.ok(Math.abs(rows.at(-1)[0] - state.summary.length) < 0.01);
  assert.ok(rows.every((r) => r[4] > 20 && r[4] < 38 && r[3] > 72 && r[3] < 90), 'lat, lon in the Himalaya');
  assert.ok(Math.abs(Math.max(...rows.map((r) => r[5])) - state.summary.max) < 0.01);
  assert.match(csv, /^# length_m /m);

  // PNG of the chart.
  const [pngDownload] = await Promise.all([page.waitForEvent('download'), page.click('#measure-png')]);
  const chartPng = readFileSync(await pngDownload.path());
  assert.deepEqual([...chartPng.subarray(0, 4)], [0x89, 0x50, 0x4e, 0x47]);
  assert.equal(decode(chartPng).width, chart.width);

  // The address carries the line; opening it restores it.
  await page.evaluate(() => window.hexlod.flushUrl());
  const href = await page.evaluate(() => location.href);
  assert.match(href, /[?&]measure=p:-?\d+(\.\d+)?,-?\d+(\.\d+)?;/);
  const second = await openPage(viewer.browser, href, DESKTOP, FULL_RESOLUTION);
  await pageReady(second.page);
  await drawFrames(second.page, 1);
  const restored = await toolState(second.page);
  assert.equal(restored.active, true);
  assert.equal(restored.kind, 'path');
  restored.points.forEach((p, k) => assert.ok(Math.hypot(p[0] - state.points[k][0], p[1] - state.points[k][1]) < 1, `point ${k}`));
  assert.ok(Math.abs(restored.summary.length - state.summary.length) < 3);
  await second.page.screenshot({ path: `${outDir}/measure-restored.png` });
  assert.deepEqual([...problems, ...second.problems], []);
  await second.page.close();
  await page.close();
});

test('orbit, fly and walk: a click adds a point, a drag moves the camera; an area', async () => {
  // At the default budget: the cameras move all through this test, so it never waits for a
  // converged mesh, and at 50 ms it ran slower (103 s → 276 s in one run).
  const { page, problems } = await openPage(viewer.browser, viewer.url, DESKTOP);
  await pageReady(page);
  await page.keyboard.press('m');
  await page.click('#measure-fold'); // the panel to its title bar: more terrain to click on
  for (const [key, mode] of [['1', 'orbit'], ['2', 'fly'], ['3', 'walk']]) {
    await page.keyboard.press(key);
    await drawFrames(page, 2);
    const before = await page.evaluate(() => ({ mode: window.hexlod.rig.mode, yaw: window.hexlod.rig.active.yaw, points: window.hexlod.measure.points.length }));
    assert.equal(before.mode, mode);
    const [pixel] = await groundPixels(page, grid(DESKTOP.width, 110, 380), 1);
    assert.ok(pixel, `ground in view in the ${mode} camera`);
    await page.mouse.move(pixel[0], pixel[1]);
    await page.mouse.down();
    await page.mouse.move(pixel[0] + 40, pixel[1] + 10, { steps: 4 });
    await page.mouse.up();
    await page.waitForTimeout(550);
    const dragged = await page.evaluate(() => ({ yaw: window.hexlod.rig.active.yaw, points: window.hexlod.measure.points.length }));
    assert.notEqual(dragged.yaw, before.yaw, `a drag turns the ${mode} camera`);
    assert.equal(dragged.points, before.points, `a drag adds no point in the ${mode} camera`);
    await drawFrames(page, 2);
    const [target] = await groundPixels(page, grid(DESKTOP.width, 110, 380), 1);
    await clickAt(page, target);
    assert.equal(await page.evaluate(() => window.hexlod.measure.points.length), before.points + 1, `a click adds a point in the ${mode} camera`);
    await page.screenshot({ path: `${outDir}/measure-${mode}.png` });
  }
  // A click off the terrain (the sky of the walk) adds nothing.
  const sky = await page.evaluate(() => {
    for (let y = 80; y < 300; y += 10) for (let x = 40; x < 600; x += 40) {
      if (document.elementFromPoint(x, y)?.id === 'view' && !window.hexlod.measure.pick(x, y)) return [x, y];
    }
    return null;
  });
  if (sky) {
    const count = await page.evaluate(() => window.hexlod.measure.points.length);
    await clickAt(page, sky);
    assert.equal(await page.evaluate(() => window.hexlod.measure.points.length), count, 'a click on the sky adds nothing');
  }

  // An area in the orbit camera: its figures against measurePolygon on its own.
  await page.keyboard.press('r');
  await page.keyboard.press('Escape');
  await page.click('#measure-area');
  await drawFrames(page, 2);
  // Corners far apart (the panel folded meanwhile): left and right above, the middle below.
  const half = (x0, x1, y0, y1) => grid(DESKTOP.width, y0, y1).filter(([x]) => x >= x0 && x < x1);
  const corners = [...await groundPixels(page, half(60, 260, 110, 150), 1), ...await groundPixels(page, half(380, 600, 110, 150), 1),
    ...await groundPixels(page, half(220, 420, 280, 330), 1)];
  assert.equal(corners.length, 3);
  for (const p of corners) await clickAt(page, p);
  await page.keyboard.press('Enter');
  await page.click('#measure-fold');
  await drawFrames(page, 2);
  const area = await toolState(page);
  assert.equal(area.kind, 'area');
  assert.equal(area.points.length, 3);
  const independent = await page.evaluate(async ([areaUrl, samplerUrl, points]) => {
    const { measurePolygon } = await import(areaUrl);
    const { fieldSampler } = await import(samplerUrl);
    return { ...measurePolygon(points, fieldSampler(window.hexlod.terrainObject(), window.hexlod.layers.ground.field.georef ?? null)) };
  }, [lib('polygon_area.js'), lib('field_sampler.js'), area.points]);
  for (const key of ['planimetric', 'surface', 'perimeter', 'perimeter3d']) {
    assert.ok(Math.abs(independent[key] - area.area[key]) <= 1e-9 * independent[key], key);
  }
  assert.ok(area.area.surface > area.area.planimetric);
  const shown = await summaryText(page);
  assert.match(shown['area (map)'], /^[\d,.]+ km²$/);
  assert.equal(shown['area (map)'], `${(independent.planimetric / 1e6).toLocaleString('en', { maximumFractionDigits: independent.planimetric < 1e8 ? 2 : 0 })} km²`);
  assert.match(shown.perimeter, /km$/);
  await page.evaluate(() => window.hexlod.flushUrl());
  assert.match(await page.evaluate(() => location.search), /measure=a:/);
  await page.screenshot({ path: `${outDir}/measure-area.png` });
  assert.deepEqual(problems, []);
  await page.close();
});

test('a phone: taps add points, the panel leaves most of the view', async () => {
  const page = await viewer.browser.newPage({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true, deviceScaleFactor: 1 });
  const problems = [];
  page.on('pageerror', (error) => problems.push(error.message));
  await page.goto(`${viewer.url}${quick}`);
  await pageReady(page);
  await page.tap('#measure-button'); // as a person on a phone turns the tool on
  assert.equal(await page.evaluate(() => window.hexlod.measure.active), true);
  const taps = await groundPixels(page, grid(390, 200, 420), 3);
  assert.equal(taps.length, 3);
  for (const [x, y] of taps) {
    await page.touchscreen.tap(x, y);
    await page.waitForTimeout(600);
  }
  await page.tap('#measure-done');
  await drawFrames(page, 2);
  const state = await toolState(page);
  assert.equal(state.points.length, 3);
  assert.equal(state.finished, true);
  assert.ok(state.summary.length > 0);
  const panel = await page.locator('#measure').boundingBox();
  assert.ok(panel.height < 844 * 0.5, `the panel is ${panel.height} px tall`);
  assert.ok(panel.width <= 390);
  await page.screenshot({ path: `${outDir}/measure-phone.png` });
  await page.tap('#measure-fold');
  const folded = await page.locator('#measure').boundingBox();
  assert.ok(folded.height < 50, `folded: ${folded.height} px`);
  assert.deepEqual(problems, []);
  await page.close();
});

/** Moves the mouse over ground and returns the HUD's cursor readout. */
async function cursorPlace(page) {
  const [pixel] = await groundPixels(page, grid(480, 110, 200), 1);
  await page.mouse.move(pixel[0], pixel[1]);
  await page.waitForTimeout(100);
  await page.mouse.move(pixel[0] + 3, pixel[1] + 2);
  await page.waitForFunction(() => window.hexlod.cursor, null, { timeout: 10000 });
  return page.evaluate(() => ({ place: window.hexlod.cursor.place, hud: document.querySelector('#hud').textContent }));
}

test('the cursor in real coordinates: a UTM GeoTIFF, the geographic default, a plain file; bad and clipped lines', async () => {
  const size = { width: 480, height: 320 };
  const utm = await openPage(viewer.browser, `${viewer.url}?src=${viewer.fixturesUrl}measure/everest_utm45.tif`, size);
  await pageReady(utm.page);
  const a = await cursorPlace(utm.page);
  assert.match(a.place, /^E \d{3} \d{3} m N \d \d{3} \d{3} m \(EPSG:32645\) · \d+\.\d{4}° N \d+\.\d{4}° E$/);
  assert.ok(a.hud.includes(a.place), 'the HUD shows it');
  // Its profile CSV has eastings and northings too.
  await utm.page.evaluate(() => window.hexlod.measure.restore({ kind: 'path', points: [[20000, 20000], [60000, 50000]] }));
  const [csvDownload] = await Promise.all([utm.page.waitForEvent('download'), utm.page.click('#measure-csv')]);
  const csv = readFileSync(await csvDownload.path(), 'utf8');
  assert.match(csv, /^distance_m,x_m,z_m,easting_m,northing_m,lon,lat,height_m$/m);
  assert.match(csv, /^# crs EPSG:32645$/m);
  assert.deepEqual(utm.problems, []);
  await utm.page.close();

  const plain = await openPage(viewer.browser, `${viewer.url}?src=${viewer.fixturesUrl}volcano_maungawhau.png`, size);
  await pageReady(plain.page);
  assert.equal((await cursorPlace(plain.page)).place, 'local metres (no CRS)');
  // A new cell size keeps the line on the same samples: its points and length scale with the ground.
  const scaled = await plain.page.evaluate(() => {
    const h = window.hexlod, t = h.terrainObject(), x = t.spacingX;
    h.measure.restore({ kind: 'path', points: [[10 * x, 10 * x], [40 * x, 30 * x]] });
    const before = h.measure.result.profile.summary.length;
    h.setSetting('cellSize', 2 * x);
    return { ratio: h.measure.result.profile.summary.length / before, first: h.measure.points[0].map((v) => v / x) };
  });
  assert.ok(Math.abs(scaled.ratio - 2) < 1e-9, `length x${scaled.ratio}`);
  assert.deepEqual(scaled.first, [20, 20]);
  await plain.page.close();

  // A bad line gets the page's message and no measurement; a line partly off the field is clipped with a note.
  const bad = await openPage(viewer.browser, `${viewer.url}?measure=p:1,2`, size);
  await pageReady(bad.page);
  assert.match(await bad.page.textContent('#status'), /measure=p:1,2: a path needs at least 2 points.*\(defaults used\)/);
  assert.equal(await bad.page.evaluate(() => window.hexlod.measure.active), false);
  await bad.page.close();
  const clipped = await openPage(viewer.browser, `${viewer.url}?measure=p:-200000,900000;400000,900000`, size);
  await pageReady(clipped.page);
  const state = await toolState(clipped.page);
  assert.match(state.clipped, /outside the field/);
  assert.match(await clipped.page.textContent('#measure-note'), /^Clipped: 200(\.0)? km of 600(\.0)? km lay outside/);
  // 400 km of the map at row z = 900 km, on the WGS 84 ellipsoid there (a geographic grid's
  // metres are its centre row's): N(lat) cos(lat) per radian of longitude, by the test's formula.
  const onEllipsoid = await clipped.page.evaluate(() => {
    const h = window.hexlod, g = h.layers.ground.field.georef, t = h.terrainObject(), rad = Math.PI / 180;
    const lat = (g.y0 + (900000 / t.spacingY) * g.dy) * rad, e2 = (1 / 298.257223563) * (2 - 1 / 298.257223563);
    const n = 6378137 / Math.sqrt(1 - e2 * Math.sin(lat) ** 2);
    return (400000 / t.spacingX) * Math.abs(g.dx) * rad * n * Math.cos(lat);
  });
  assert.ok(Math.abs(state.summary.length - onEllipsoid) < 1, `${state.summary.length} m, on the ellipsoid ${onEllipsoid} m`);
  await clipped.page.close();
});
