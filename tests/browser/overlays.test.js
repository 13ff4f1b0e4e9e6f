// A hiker's files on the terrain, as a person uses them: a GPX track of the Everest Base Camp
// trek and a KML of places (made with GDAL from the real Everest DEM's coordinates, tests/
// fixtures/overlays/) dropped onto the terrain on screen, then the DEM after them, and the other
// way round; judged by the screenshot's pixels (the track's colour along its projected line and
// nowhere else) and by geometry (the line where GDAL puts the vertices). Then what a person does
// with it: hover for its name, click it for its profile and the CSV of every vertex, fly along
// it; every broken file refused with a message, the terrain and the other overlays kept; and
// ?overlay= in the address bar.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, pageReady, dropFiles, terrainShown, converged, outDir } from '../../lib/page_harness.js';
import { screenPoint } from '../../lib/draped_points.js';

let viewer;
before(async () => { viewer = await startViewer(); });
after(async () => { await viewer?.close(); });

const fixture = (path) => ({ name: path.split('/').pop(), bytes: new Uint8Array(readFileSync(new URL(`../fixtures/${path}`, import.meta.url))) });
const expected = JSON.parse(readFileSync(new URL('../fixtures/overlays/expected.json', import.meta.url), 'utf8'));
const DEM = 'measure/everest_utm45.tif';
const TRACK_RGB = [255, 61, 139]; // the first overlay's colour (web/app/overlay_stage.js OVERLAY_COLORS)
const BARE = '#hud, #side, #drop-hint, #status, #attribution, #bottom-bar { display: none !important; }';
const VIEW = { width: 640, height: 400 };

const status = (page) => page.evaluate(() => ({ text: document.getElementById('status').textContent, error: document.getElementById('status').classList.contains('error') }));
const overlayCount = (page) => page.evaluate(() => window.hexlod.layers.overlays.length);
const frames = async (page, n) => {
  for (let i = 0; i < n; i++) await page.evaluate(() => new Promise((r) => { window.hexlod.requestRender(); requestAnimationFrame(() => r()); }));
};

/** Straight down on the track's middle from `distance` metres, north up. */
async function overTrack(page, distance) {
  await page.evaluate((distance) => {
    const h = window.hexlod, segments = h.layers.overlays[0].geometry.segments, orbit = h.rig.cameras.orbit;
    let x0 = Infinity, x1 = -Infinity, z0 = Infinity, z1 = -Infinity;
    for (let k = 0; k < segments.length; k += 3) {
      x0 = Math.min(x0, segments[k]); x1 = Math.max(x1, segments[k]); z0 = Math.min(z0, segments[k + 2]); z1 = Math.max(z1, segments[k + 2]);
    }
    h.setSetting('camera', 'orbit');
    orbit.target.set([(x0 + x1) / 2, 0, (z0 + z1) / 2]);
    Object.assign(orbit, { yaw: 0, pitch: 1.55, distance });
    h.requestRender();
  }, distance);
  await converged(page);
  await frames(page, 3);
}

/** The track's drawn segments and the markers, projected to the screen (CSS pixels). */
function projected(page) {
  return page.evaluate(() => {
    const h = window.hexlod, vs = h.settings.exaggeration, m = Array.from(h.camera.viewProjection);
    const layer = h.layers.overlays[0], g = layer.geometry;
    // Each point where it is drawn (on the curved Earth too), its height exaggerated.
    const lift = (a) => Array.from({ length: a.length / 3 }, (_, k) => h.drawnPoint(a[3 * k], a[3 * k + 1] * vs, a[3 * k + 2])).flat();
    return { m, segments: lift(g.segments), markers: lift(g.markers), width: innerWidth, height: innerHeight };
  });
}

/** Distance from pixel p to the projected polyline's segments. */
function distanceTo(p, lines) {
  let d = Infinity;
  for (const [a, b] of lines) {
    const ex = b[0] - a[0], ey = b[1] - a[1], len2 = ex * ex + ey * ey;
    const t = len2 > 0 ? Math.max(0, Math.min(1, ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / len2)) : 0;
    d = Math.min(d, Math.hypot(a[0] + ex * t - p[0], a[1] + ey * t - p[1]));
  }
  return d;
}

test('a GPX dropped on the terrain on screen, then its DEM: the track lies on the ground where GDAL puts it, its colour along it and nowhere else', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1&budget=50`, VIEW);
  await pageReady(page);
  // Alone, onto the default terrain (EPSG:4326, which covers Everest): drawn there at once.
  await dropFiles(page, [fixture('overlays/everest_trek.gpx')]);
  await page.waitForFunction(() => window.hexlod.layers.overlays.length === 1, null, { timeout: 60000 });
  assert.match((await status(page)).text, /^everest_trek\.gpx: 2 lines, 4 points drawn$/);
  // Then the DEM: the overlay stays and is placed again, on the UTM grid.
  await dropFiles(page, [fixture(DEM)]);
  await terrainShown(page, 'everest_utm45.tif');
  const first = await page.evaluate(() => Array.from(window.hexlod.layers.overlays[0].geometry.segments.subarray(0, 3)));
  const lukla = expected.track.vertices[0];
  assert.ok(Math.abs(first[0] - lukla.column * 1000) < 0.05 && Math.abs(first[2] - lukla.row * 1000) < 0.05, `first vertex at ${first}`);
  assert.match(await page.evaluate(() => document.getElementById('hud').textContent), /overlay: everest_trek\.gpx \(GPX, 2 lines, 4 points\)/);

  await page.addStyleTag({ content: BARE });
  await overTrack(page, 70000);
  const shown = decode(await page.screenshot({ path: `${outDir}/overlays-track.png` }));
  const geometry = await projected(page);
  await page.evaluate(() => { const h = window.hexlod; h.overlays.setStyle(h.layers.overlays[0], { visible: false }); });
  await frames(page, 3);
  const hidden = decode(await page.screenshot({ path: `${outDir}/overlays-hidden.png` }));

  const s = geometry.segments, lines = [];
  for (let k = 0; k < s.length; k += 6) {
    lines.push([screenPoint(geometry.m, s.slice(k, k + 3), geometry.width, geometry.height), screenPoint(geometry.m, s.slice(k + 3, k + 6), geometry.width, geometry.height)]);
  }
  const markers = [];
  for (let k = 0; k < geometry.markers.length; k += 3) markers.push(screenPoint(geometry.m, geometry.markers.slice(k, k + 3), geometry.width, geometry.height));
  const px = (img, [x, y]) => { const i = (y * img.width + x) * img.channels; return [img.data[i], img.data[i + 1], img.data[i + 2]]; };
  const isTrack = (c) => Math.abs(c[0] - TRACK_RGB[0]) < 40 && Math.abs(c[1] - TRACK_RGB[1]) < 50 && Math.abs(c[2] - TRACK_RGB[2]) < 50;
  // Along the line: the track's colour within 2 pixels of every point 8 pixels apart, and never without the overlay.
  let along = 0, found = 0, foundHidden = 0;
  for (const [a, b] of lines) {
    const steps = Math.max(1, Math.floor(Math.hypot(b[0] - a[0], b[1] - a[1]) / 8));
    for (let i = 0; i < steps; i++) {
      const p = [Math.round(a[0] + ((b[0] - a[0]) * i) / steps), Math.round(a[1] + ((b[1] - a[1]) * i) / steps)];
      if (p[0] < 3 || p[1] < 3 || p[0] >= shown.width - 3 || p[1] >= shown.height - 3) continue;
      along++;
      let hit = false, hitHidden = false;
      for (let dy = -2; dy <= 2; dy++) for (let dx = -2; dx <= 2; dx++) {
        hit ||= isTrack(px(shown, [p[0] + dx, p[1] + dy]));
        hitHidden ||= isTrack(px(hidden, [p[0] + dx, p[1] + dy]));
      }
      found += hit ? 1 : 0;
      foundHidden += hitHidden ? 1 : 0;
    }
  }
  assert.ok(along > 30, `${along} points along the track on screen`);
  assert.ok(found / along > 0.97, `the track's colour at ${found} of ${along} points along it`);
  assert.equal(foundHidden, 0, 'none of it without the overlay');
  // Elsewhere: away from the line, the markers and their names, the view is as it was without it.
  let away = 0, changed = 0;
  for (let y = 0; y < shown.height; y += 2) {
    for (let x = 0; x < shown.width; x += 2) {
      const nearMarker = markers.some(([mx, my]) => x > mx - 12 && x < mx + 260 && Math.abs(y - my) < 14);
      if (nearMarker || distanceTo([x, y], lines) < 8) continue;
      away++;
      const a = px(shown, [x, y]), b = px(hidden, [x, y]);
      if (Math.abs(a[0] - b[0]) + Math.abs(a[1] - b[1]) + Math.abs(a[2] - b[2]) > 24) changed++;
    }
  }
  assert.ok(away > 20000);
  assert.ok(changed / away < 0.002, `${changed} of ${away} pixels away from the overlay changed`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the DEM first, then a KML and a GeoJSON: lines aloft with a curtain, polygons filled on the ground, names beside the markers', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1&budget=50`, VIEW);
  await pageReady(page);
  await dropFiles(page, [fixture(DEM)]);
  await terrainShown(page, 'everest_utm45.tif');
  await dropFiles(page, [fixture('overlays/everest_places.kml'), fixture('overlays/everest_features.geojson')]);
  await page.waitForFunction(() => window.hexlod.layers.overlays.length === 2, null, { timeout: 60000 });
  const kml = await page.evaluate(() => {
    const layer = window.hexlod.layers.overlays.find((l) => l.name === 'everest_places.kml'), g = layer.geometry;
    return { order: window.hexlod.layers.overlays.map((l) => l.name), aloft: Array.from(g.segments).filter((v, k) => k % 3 === 1 && v === 9500).length, curtain: g.curtain.length, fill: layer.fill !== null, names: g.markerNames };
  });
  assert.deepEqual(kml.order, ['everest_places.kml', 'everest_features.geojson'], 'in the order they came');
  // A straight line at one altitude: drawn as one segment from Lukla to Everest, 9500 m up.
  assert.equal(kml.aloft, 2, 'the flight line at its 9500 m, as its altitudeMode says');
  assert.equal(kml.curtain, 0, 'no curtain until asked');
  assert.ok(kml.fill, 'the base camp polygon is filled');
  assert.deepEqual(kml.names.slice(0, 5), ['Mount Everest', 'Lhotse', 'Makalu', 'Cho Oyu', 'Ama Dablam']);
  await page.evaluate(() => { const h = window.hexlod; h.overlays.setAltitude(h.layers.overlays[0], { curtain: true }); });
  assert.equal(await page.evaluate(() => window.hexlod.layers.overlays[0].geometry.curtain.length), 18, 'two triangles down to the ground');
  // The Sagarmatha core polygon of the GeoJSON, filled: straight down on its middle, the ground
  // there takes the overlay's colour, and its hole does not.
  await page.addStyleTag({ content: BARE });
  const at = await page.evaluate(() => {
    const h = window.hexlod, layer = h.layers.overlays[1], poly = layer.placed.features.find((f) => f.feature.name === 'Sagarmatha core');
    const [outer, hole] = poly.paths, mid = (p) => [(Math.min(...p.x) + Math.max(...p.x)) / 2, (Math.min(...p.z) + Math.max(...p.z)) / 2];
    h.overlays.setStyle(h.layers.overlays[0], { visible: false });
    const orbit = h.rig.cameras.orbit, [hx, hz] = mid(hole);
    orbit.target.set([hx, 0, hz]);
    Object.assign(orbit, { yaw: 0, pitch: 1.55, distance: 30000 });
    return { inside: [hx, (Math.min(...outer.z) + Math.min(...hole.z)) / 2], hole: [hx, hz] };
  });
  await converged(page);
  await frames(page, 3);
  const withFill = decode(await page.screenshot({ path: `${outDir}/overlays-fill.png` }));
  await page.evaluate(() => { const h = window.hexlod; h.overlays.setStyle(h.layers.overlays[1], { visible: false }); });
  await frames(page, 3);
  const without = decode(await page.screenshot());
  const screen = await page.evaluate((points) => {
    const h = window.hexlod, m = Array.from(h.camera.viewProjection), vs = h.settings.exaggeration;
    return points.map(([x, z]) => [...h.drawnPoint(x, h.rig.world.ground(x, z), z), m, vs]);
  }, [at.inside, at.hole]);
  const [inside, hole] = screen.map(([x, y, z, m]) => screenPoint(m, [x, y, z], VIEW.width, VIEW.height));
  const rgb = (img, [x, y]) => { const i = (y * img.width + x) * img.channels; return [img.data[i], img.data[i + 1], img.data[i + 2]]; };
  const shift = (p) => { const a = rgb(withFill, p), b = rgb(without, p); return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; };
  // The GeoJSON's colour is the second of the palette, cyan (#2fd4ff): blue rises well above red.
  const [dr, dg, db] = shift(inside);
  assert.ok(db > 20 && dg > 10 && db - dr > 30, `inside the polygon the ground turns towards cyan: ${shift(inside)}`);
  assert.ok(shift(hole).every((d) => Math.abs(d) < 6), `the hole is not filled: ${shift(hole)}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('hover names a track, a click shows its profile with the recorded elevations and times, its CSV has every vertex; fly along it', async () => {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1&budget=50`, VIEW);
  await pageReady(page);
  await dropFiles(page, [fixture(DEM), fixture('overlays/everest_trek.gpx')]);
  await terrainShown(page, 'everest_utm45.tif');
  await page.waitForFunction(() => window.hexlod.layers.overlays.length === 1, null, { timeout: 60000 });
  await page.addStyleTag({ content: '#side, #drop-hint, #hud { display: none !important; }' });
  await overTrack(page, 70000);
  // A point of the track half way along it, on the screen.
  const [x, y] = await page.evaluate(() => {
    const h = window.hexlod, g = h.layers.overlays[0].geometry, k = 6 * Math.floor(g.segments.length / 12), m = h.camera.viewProjection;
    const p = h.drawnPoint(g.segments[k], g.segments[k + 1] * h.settings.exaggeration, g.segments[k + 2]);
    const w = m[3] * p[0] + m[7] * p[1] + m[11] * p[2] + m[15];
    return [((m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12]) / w * 0.5 + 0.5) * innerWidth, (0.5 - (m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13]) / w * 0.5) * innerHeight];
  });
  await page.mouse.move(x + 1, y + 1);
  await page.mouse.move(x, y, { steps: 3 });
  await page.waitForFunction(() => !document.getElementById('overlay-tip').hidden, null, { timeout: 10000 });
  assert.match(await page.textContent('#overlay-tip'), /^Everest Base Camp trek.*everest_trek\.gpx · click for its profile$/s);
  await page.mouse.click(x, y);
  await page.waitForFunction(() => !document.getElementById('measure').hidden, null, { timeout: 10000 });
  assert.equal(await page.textContent('#measure-title'), 'Track: Everest Base Camp trek');
  const summary = await page.$$eval('#measure-summary > div', (items) => Object.fromEntries(items.map((d) => [d.querySelector('dt').textContent, d.querySelector('dd').textContent])));
  assert.match(summary.length, /^43\.\d km$/);
  assert.match(summary['recorded gain'], /^3,\d{3} m$/);
  assert.equal(summary.time, '10 h 08 min');
  assert.match(summary['moving speed'], /^4\.\d km\/h$/);
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#measure-csv')]);
  const csv = readFileSync(await download.path(), 'utf8').split('\n').filter((l) => l && !l.startsWith('#'));
  const header = csv[0].split(',');
  assert.deepEqual(header.slice(-3), ['gps_elevation_m', 'time', 'vertex']);
  assert.equal(csv.slice(1).filter((l) => l.split(',').at(-1) !== '').length, expected.track.points, 'every vertex a row');
  await page.screenshot({ path: `${outDir}/overlays-profile.png` });

  // Fly along: the fly camera over the track, moving along it; the walk camera on it.
  await page.evaluate(() => { const h = window.hexlod; h.tracks.flyAlong(h.layers.overlays[0]); });
  assert.equal(await page.evaluate(() => window.hexlod.rig.mode), 'fly');
  await frames(page, 4);
  const a = await page.evaluate(() => ({ p: Array.from(window.hexlod.rig.active.position), progress: window.hexlod.rig.follow.progress }));
  await frames(page, 6);
  const b = await page.evaluate(() => ({ p: Array.from(window.hexlod.rig.active.position), progress: window.hexlod.rig.follow.progress }));
  assert.ok(b.progress > a.progress, `it moves on: ${a.progress} -> ${b.progress}`);
  const offTrack = await page.evaluate((p) => {
    const path = window.hexlod.layers.overlays[0].placed.features[0].paths[0];
    let d = Infinity;
    for (let k = 0; k < path.x.length; k++) d = Math.min(d, Math.hypot(path.x[k] - p[0], path.z[k] - p[2]));
    return d;
  }, b.p);
  assert.ok(offTrack < 200, `the eye is over the track (${offTrack.toFixed(0)} m from a vertex)`);
  await page.evaluate(() => window.hexlod.setSetting('camera', 'walk'));
  await frames(page, 3);
  const walk = await page.evaluate(() => { const h = window.hexlod, c = h.rig.active; return { mode: c.mode, clearance: c.position[1] - h.rig.world.floor(c.position[0], c.position[2]) }; });
  assert.equal(walk.mode, 'walk');
  assert.ok(Math.abs(walk.clearance - 2) < 1e-6, 'walking the track at eye height');
  await page.evaluate(() => window.hexlod.tracks.stop());
  assert.equal(await page.evaluate(() => window.hexlod.rig.follow), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('every broken file is refused with its message; the terrain and the other overlays stay; ?overlay= opens and stays in the address', async () => {
  const src = `${viewer.fixturesUrl}${DEM}`, overlay = `${viewer.fixturesUrl}overlays/everest_places.kmz`;
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1&src=${encodeURIComponent(src)}&overlay=${encodeURIComponent(overlay)}`, VIEW);
  await pageReady(page);
  await page.waitForFunction(() => window.hexlod.layers.overlays.length === 1, null, { timeout: 60000 });
  assert.equal(await page.evaluate(() => window.hexlod.layers.overlays[0].overlay.format), 'KMZ');
  await page.waitForFunction(() => new URLSearchParams(location.search).getAll('overlay').length === 1, null, { timeout: 10000 });
  const faults = [
    ['overlays/bad_empty.gpx', /^bad_empty\.gpx: the file is empty$/],
    ['overlays/bad_malformed.gpx', /^bad_malformed\.gpx: malformed XML: /],
    ['overlays/bad_malformed.geojson', /^bad_malformed\.geojson: malformed JSON at line 1: /],
    ['overlays/bad_no_kml.kmz', /^bad_no_kml\.kmz: a KMZ without a KML document inside/],
    ['overlays/bad_projected.geojson', /are not WGS 84 longitude and latitude/],
  ];
  for (const [file, pattern] of faults) {
    await dropFiles(page, [fixture(file)]);
    await page.waitForFunction(() => document.getElementById('status').classList.contains('error'), null, { timeout: 30000 });
    const said = await status(page);
    assert.match(said.text, pattern, file);
    assert.equal(await overlayCount(page), 1, `${file}: the other overlay stays`);
    assert.equal(await page.evaluate(() => window.hexlod.terrain.name), 'everest_utm45.tif');
    await page.evaluate(() => { document.getElementById('status').textContent = ''; document.getElementById('status').classList.remove('error'); });
  }
  // A track entirely off the terrain: kept, counted, not drawn in the void.
  await dropFiles(page, [fixture('overlays/off_terrain_alps.gpx')]);
  await page.waitForFunction(() => window.hexlod.layers.overlays.length === 2, null, { timeout: 30000 });
  assert.match((await status(page)).text, /off_terrain_alps\.gpx: every feature \(1\) lies off the terrain on screen/);
  assert.equal(await page.evaluate(() => window.hexlod.layers.overlays[1].geometry.segments.length), 0);
  assert.match(await page.evaluate(() => document.getElementById('hud').textContent), /overlay: off_terrain_alps\.gpx \(GPX, 1 line\) \(entirely off the terrain\)/);
  // Removed from the legend: the address bar forgets nothing it should keep.
  await page.evaluate(() => { const h = window.hexlod; h.overlays.remove(h.layers.overlays[1]); });
  assert.equal(await overlayCount(page), 1);
  assert.deepEqual(problems, []);
  await page.close();
});
