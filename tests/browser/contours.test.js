// Contour lines over a real DEM (the Grand Canyon fixture), judged against the field itself:
// the levels' crossings of every sample edge (the field is linear along rows and columns, so
// these points are on the exact contours), projected with the page's camera, must have a line
// pixel within about 2 px, and line pixels away from every crossing must be rare; at device
// pixel ratio 1 and 2; the lines as wide far away as near; a phone-sized touch viewport; refused
// intervals keep the old one; a tiny one is widened with a message; the URL restores them.
// Line pixels are those the contours darken (the view drawn with them and without, labels
// hidden). Small viewports: SwiftShader draws on the CPU. Screenshots go to tests/out/.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { decode, encode } from 'fast-png';
import { writeFileSync } from 'node:fs';
import { startViewer, openPage, outDir, projectDir, FULL_RESOLUTION } from '../../lib/page_harness.js';

const SIZE = { width: 480, height: 300 };
const INTERVAL = 50;
const DEM = `/@fs${projectDir}tests/fixtures/grandcanyon_512.png`;
const CAMERA = 'cam=orbit,15000,1500,17000,14000,2.6,0.5';
// On the flat Earth: the crossings are projected, and their sight lines marched, on the plane.
const query = (extra = '') => `?src=${encodeURIComponent(DEM)}&tau=1&budget=40&exag=2&earth=flat&contours=1&cint=${INTERVAL}&${CAMERA}${extra}`;

let viewer;
// Pages at half a device pixel per CSS pixel unless a test names its own ratio.
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

/** Opens the view with the page's boxes hidden and waits for the converged mesh. */
async function openView(extra = '', options = {}, size = SIZE) {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}${query(extra)}`, size, options);
  await page.addStyleTag({ content: '#hud, #side, #drop-hint, #status, #intake, #panel { display: none !important; }' });
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
  assert.deepEqual(await page.evaluate(() => [window.hexlod.status, window.hexlod.error]), ['ready', null]);
  await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged; }, null,
    { timeout: 300000, polling: 200 });
  return { page, problems };
}

/**
 * Waits for a frame drawn after this call (settings apply) with the mesh still: converged and its
 * geomorph blends ended, where the page stops drawing and every later frame is the same picture.
 * Returns the decoded screenshot.
 */
async function shoot(page, name) {
  await page.evaluate(() => { window.hexlod.until = window.hexlod.frames + 1; });
  await page.waitForFunction(() => {
    const h = window.hexlod, shown = h.layers.ground;
    const still = h.frames >= h.until && h.converged && shown !== null && h.lod.frame >= shown.blendsEnd;
    if (!still) h.requestRender(); // no frame asked beyond the one waited for: it would be drawn during the screenshot
    return still;
  }, null, { timeout: 120000, polling: 50 });
  const png = await page.screenshot({ path: `${outDir}/contours-${name}.png` });
  return decode(png);
}

/** The field's heights (metres, through the core), the camera, and the drawing size in device pixels. */
const sceneOf = (page) => page.evaluate(() => {
  const h = window.hexlod, t = h.terrainObject(), camera = h.rig.active;
  const heights = new Float64Array(t.width * t.height);
  for (let r = 0; r < t.height; ++r) for (let c = 0; c < t.width; ++c) heights[r * t.width + c] = t.heightAt(c * t.spacingX, r * t.spacingY);
  // The doubles' bytes as base64: a quarter-million numbers as one string, not one JSON value each.
  const bytes = new Uint8Array(heights.buffer);
  let binary = '';
  for (let k = 0; k < bytes.length; k += 0x8000) binary += String.fromCharCode(...bytes.subarray(k, k + 0x8000));
  const canvas = document.getElementById('view');
  return { width: t.width, height: t.height, sx: t.spacingX, sz: t.spacingY, heights: btoa(binary), exag: h.settings.exaggeration,
    viewProjection: [...camera.viewProjection], eye: [...camera.position], pixelsX: canvas.width, pixelsY: canvas.height };
}).then((scene) => {
  return { ...scene, heights: new Float64Array(Uint8Array.from(Buffer.from(scene.heights, 'base64')).buffer) };
});

const luminance = (d, k) => 0.2126 * d[k] + 0.7152 * d[k + 1] + 0.0722 * d[k + 2];

/** Pixels the contours darkened: a mask of the image's size. */
function linePixels(on, off) {
  const mask = new Uint8Array(on.width * on.height);
  for (let p = 0; p < mask.length; ++p) {
    const k = p * on.channels;
    if (luminance(off.data, k) - luminance(on.data, k) > 12) mask[p] = 1;
  }
  return mask;
}

/**
 * Every crossing of a level with a sample edge (and with lines between them, `split` to a
 * cell), projected to the image (device pixels), with whether it is in sight from the eye and
 * how many pixels apart the lines are around it.
 */
function crossings(scene, interval, split = 4) {
  const { width, height, sx, sz, heights, exag, viewProjection: m, eye, pixelsX, pixelsY } = scene;
  const at = (c, r) => heights[r * width + c];
  const bilinear = (x, z) => {
    const fx = Math.min(Math.max(x / sx, 0), width - 1), fz = Math.min(Math.max(z / sz, 0), height - 1);
    const c = Math.min(Math.floor(fx), width - 2), r = Math.min(Math.floor(fz), height - 2), u = fx - c, v = fz - r;
    return (at(c, r) * (1 - u) + at(c + 1, r) * u) * (1 - v) + (at(c, r + 1) * (1 - u) + at(c + 1, r + 1) * u) * v;
  };
  const project = (x, y, z) => {
    const w = m[3] * x + m[7] * y + m[11] * z + m[15];
    if (!(w > 0)) return null;
    return [((m[0] * x + m[4] * y + m[8] * z + m[12]) / w + 1) * 0.5 * pixelsX, (1 - (m[1] * x + m[5] * y + m[9] * z + m[13]) / w) * 0.5 * pixelsY];
  };
  // Above the highest sample (a hair higher than rounding could lift a height) nothing hides a
  // point: the steps of a sight line up there are skipped, they could not find the ground.
  let top = -Infinity;
  for (let k = 0; k < heights.length; ++k) top = Math.max(top, heights[k]);
  top = top * exag + 1e-9 * Math.abs(top * exag) + 1e-6;
  const inSight = (x, y, z) => {
    const dx = x - eye[0], dy = y - eye[1], dz = z - eye[2], d = Math.hypot(dx, dy, dz);
    const steps = Math.ceil(Math.hypot(dx, dz) / (0.5 * Math.min(sx, sz)));
    const clear = top - eye[1] - 0.0005 * d; // the line is above `top` while dy * t > clear
    let first = 1;
    if (dy >= 0) { if (clear < 0) return true; } // rising from above the highest ground
    else if (clear < 0) first = Math.max(1, Math.floor((clear / dy) * steps) - 1); // t < clear / dy: above it
    for (let s = first; s < steps - 2; ++s) {
      const t = s / steps;
      if (bilinear(eye[0] + dx * t, eye[2] + dz * t) * exag > eye[1] + dy * t + 0.0005 * d) return false;
    }
    return true;
  };
  const out = [];
  // Heights at fractional sample positions (column u, row v): bilinear, as the field is.
  const field = (u, v) => bilinear(u * sx, v * sz);
  // A straight line from (u0, v0) to (u1, v1) inside one cell: the field is linear along it
  // when it runs along a row or a column, so a level crosses it at one exact point.
  const edge = (u0, v0, u1, v1) => {
    const h0 = field(u0, v0), h1 = field(u1, v1);
    const lo = Math.min(h0, h1), hi = Math.max(h0, h1);
    // Each level a hair above its value, as contours.glsl draws it: a sample on a level is below it.
    const shift = 1e-4 * interval;
    for (let level = Math.ceil((lo - shift) / interval) * interval; level + shift < hi; level += interval) {
      if (level + shift <= lo) continue;
      const t = (level + shift - h0) / (h1 - h0);
      const x = (u0 + (u1 - u0) * t) * sx, z = (v0 + (v1 - v0) * t) * sz, y = level * exag;
      const p = project(x, y, z);
      if (!p || p[0] < 3 || p[1] < 3 || p[0] > pixelsX - 3 || p[1] > pixelsY - 3) continue;
      // The screen gradient of the height from the cell's corners: the shader's fwidth.
      const c = Math.min(Math.floor(Math.min(u0, u1)), width - 2), r = Math.min(Math.floor(Math.min(v0, v1)), height - 2);
      const a = project(c * sx, at(c, r) * exag, r * sz), b = project((c + 1) * sx, at(c + 1, r) * exag, r * sz);
      const d = project(c * sx, at(c, r + 1) * exag, (r + 1) * sz);
      let spacing = 0;
      if (a && b && d) {
        const e1 = [b[0] - a[0], b[1] - a[1]], e2 = [d[0] - a[0], d[1] - a[1]];
        const dh1 = at(c + 1, r) - at(c, r), dh2 = at(c, r + 1) - at(c, r);
        const det = e1[0] * e2[1] - e1[1] * e2[0];
        if (Math.abs(det) > 1e-9) {
          const gx = (dh1 * e2[1] - dh2 * e1[1]) / det, gy = (e1[0] * dh2 - e2[0] * dh1) / det;
          spacing = interval / (Math.abs(gx) + Math.abs(gy) + 1e-12);
        }
      }
      out.push({ x: p[0], y: p[1], visible: inSight(x, y, z), spacing, distance: Math.hypot(x - eye[0], y - eye[1], z - eye[2]),
        level, onSampleEdge: Number.isInteger(u0) && Number.isInteger(v0) && (u0 === u1 || v0 === v1) });
    }
  };
  // Samples on a level (within a thousandth of the interval: whole-metre heights decoded from
  // 16 bits miss it by a millimetre): the line touches them, however flat the ground around.
  for (let r = 0; r < height; ++r) {
    for (let c = 0; c < width; ++c) {
      const h = at(c, r), level = Math.round(h / interval) * interval;
      if (Math.abs(h - level) >= 1e-3 * interval) continue;
      const p = project(c * sx, level * exag, r * sz);
      if (!p || p[0] < 3 || p[1] < 3 || p[0] > pixelsX - 3 || p[1] > pixelsY - 3) continue;
      out.push({ x: p[0], y: p[1], visible: inSight(c * sx, level * exag, r * sz), spacing: 0, distance: 0, level, onSampleEdge: false });
    }
  }
  // Sample rows and columns, and `split` - 1 lines between them: a cell can span several
  // pixels near the eye, and its contour runs between the crossings of its edges.
  for (let k = 0; k < split; ++k) {
    for (let r = 0; r + (k ? 1 : 0) < height; ++r) for (let c = 0; c + 1 < width; ++c) edge(c, r + k / split, c + 1, r + k / split);
    for (let r = 0; r + 1 < height; ++r) for (let c = 0; c + (k ? 1 : 0) < width; ++c) edge(c + k / split, r, c + k / split, r + 1);
  }
  return out;
}

/** A mask of the pixels within `radius` of any of the points. */
function near(points, w, h, radius) {
  const mask = new Uint8Array(w * h), r = Math.ceil(radius);
  for (const p of points) {
    for (let y = Math.max(0, Math.round(p.y) - r); y <= Math.min(h - 1, Math.round(p.y) + r); ++y) {
      for (let x = Math.max(0, Math.round(p.x) - r); x <= Math.min(w - 1, Math.round(p.x) + r); ++x) {
        if ((x + 0.5 - p.x) ** 2 + (y + 0.5 - p.y) ** 2 <= radius * radius) mask[y * w + x] = 1;
      }
    }
  }
  return mask;
}

/** Lines with contours on and off (labels hidden), the crossings, and the fractions judged. */
async function judge(page, name, pixelRatio, split = 4) {
  await page.evaluate(() => { window.hexlod.view.contourLabels = false; });
  const on = await shoot(page, `${name}-lines`);
  await page.evaluate(() => window.hexlod.setSetting('contours', false));
  const off = await shoot(page, `${name}-off`);
  await page.evaluate(() => { window.hexlod.setSetting('contours', true); window.hexlod.view.contourLabels = true; });
  await shoot(page, name); // with labels: to look at
  const scene = await sceneOf(page);
  assert.deepEqual([on.width, on.height], [scene.pixelsX, scene.pixelsY]);
  const lines = linePixels(on, off);
  const interval = await page.evaluate(() => window.hexlod.contours.interval);
  const all = crossings(scene, interval, split).filter((p) => p.visible);
  // Lines at least 10 px apart: closer ones fade out (contours.glsl), as they should.
  const judged = all.filter((p) => p.onSampleEdge && p.spacing >= 10 * pixelRatio);
  const hitRadius = 2 * pixelRatio + 0.5;
  let hits = 0;
  const { width: w, height: h } = on;
  for (const p of judged) {
    let hit = false;
    for (let y = Math.floor(p.y - hitRadius); y <= Math.ceil(p.y + hitRadius) && !hit; ++y) {
      for (let x = Math.floor(p.x - hitRadius); x <= Math.ceil(p.x + hitRadius); ++x) {
        if (x >= 0 && y >= 0 && x < w && y < h && lines[y * w + x] && (x + 0.5 - p.x) ** 2 + (y + 0.5 - p.y) ** 2 <= hitRadius ** 2) { hit = true; break; }
      }
    }
    hits += hit;
  }
  const nearAny = near(all, w, h, 3 * pixelRatio);
  let linesTotal = 0, stray = 0, covered = 0;
  const marked = Uint8Array.from(on.data);
  for (let k = 0; k < lines.length; ++k) {
    covered += nearAny[k];
    if (lines[k]) { linesTotal += 1; stray += !nearAny[k]; }
    if (lines[k] && !nearAny[k]) { marked[k * on.channels] = 255; marked[k * on.channels + 1] = 0; marked[k * on.channels + 2] = 0; }
  }
  writeFileSync(`${outDir}/contours-${name}-stray.png`, encode({ ...on, data: marked })); // line pixels away from every crossing in red
  return { interval, scene, lines, all, judged, hitShare: hits / judged.length, strayShare: stray / linesTotal, linesTotal, w, h,
    nearShare: covered / lines.length };
}

test('line pixels lie on the field\'s crossings of the levels, at device pixel ratio 1 and 2, as wide far away as near', async () => {
  for (const pixelRatio of [1, 2]) {
    const { page, problems } = await openView('', { deviceScaleFactor: pixelRatio });
    const r = await judge(page, `dpr${pixelRatio}`, pixelRatio);
    const summary = { pixelRatio, crossings: r.all.length, judged: r.judged.length, hit: r.hitShare.toFixed(3), stray: r.strayShare.toFixed(3),
      linePixels: r.linesTotal, nearCrossings: r.nearShare.toFixed(3) };
    console.log(JSON.stringify(summary));
    assert.ok(r.judged.length > 500, `enough crossings judged: ${r.judged.length}`);
    assert.ok(r.hitShare > 0.9, `${(100 * r.hitShare).toFixed(1)}% of the crossings have a line pixel within ${2 * pixelRatio + 0.5} px`);
    assert.ok(r.strayShare < 0.05, `${(100 * r.strayShare).toFixed(1)}% of the line pixels are away from every crossing`);
    // That means something only if much of the image is away from every crossing.
    assert.ok(r.nearShare < 0.7, `${(100 * r.nearShare).toFixed(1)}% of the image is near a crossing`);
    // Width: line pixels per pixel of contour length, near and far (split at the median distance).
    const distances = r.judged.map((p) => p.distance).sort((a, b) => a - b), median = distances[distances.length >> 1];
    const width = (group) => {
      const mask = near(group, r.w, r.h, 2.5 * pixelRatio);
      let pixels = 0;
      for (let k = 0; k < mask.length; ++k) pixels += mask[k] & r.lines[k];
      // Contour length: crossings come about one per sample edge; their spacing on screen along
      // the line is the length each stands for. Measured as the mask's area over its width.
      let area = 0;
      for (let k = 0; k < mask.length; ++k) area += mask[k];
      return pixels / (area / (5 * pixelRatio)); // line pixels across a band 5 px wide
    };
    const nearWidth = width(r.judged.filter((p) => p.distance < median)), farWidth = width(r.judged.filter((p) => p.distance >= median));
    console.log(JSON.stringify({ pixelRatio, nearWidth: nearWidth.toFixed(2), farWidth: farWidth.toFixed(2) }));
    assert.ok(nearWidth / farWidth > 0.6 && nearWidth / farWidth < 1.6, `line width near ${nearWidth.toFixed(2)} px, far ${farWidth.toFixed(2)} px`);
    const labels = await page.evaluate(() => window.hexlod.contours.labels);
    assert.ok(labels >= 3, `${labels} labels drawn`);
    assert.deepEqual(problems, []);
    await page.close();
  }
});

test('every sample depth is read exactly: u8, u16, i16 and f32 fields, lines on their crossings', async () => {
  // u16 again: the volcano's heights are whole metres, so many samples lie on a level.
  const formats = { u8: 'formats/jacksboro_8bit.png', i16: 'formats/everest_i16_strips.tif', f32: 'formats/canyon_terrain-rgb.png',
    u16: 'volcano_maungawhau.png' };
  for (const [type, file] of Object.entries(formats)) {
    const src = `/@fs${projectDir}tests/fixtures/${file}`;
    const { page, problems } = await openPage(viewer.browser, `${viewer.url}?src=${encodeURIComponent(src)}&tau=1&budget=40&earth=flat&contours=1&cint=auto`, SIZE, FULL_RESOLUTION);
    await page.addStyleTag({ content: '#hud, #side, #drop-hint, #status, #intake, #panel { display: none !important; }' });
    await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
    // Closer than the opening view, which shows the whole field small: lines far enough apart to judge.
    await page.evaluate(() => {
      const h = window.hexlod, t = h.terrainObject(), ex = (t.width - 1) * t.spacingX, ez = (t.height - 1) * t.spacingY;
      h.setSetting('camera', 'orbit');
      const orbit = h.rig.active;
      orbit.target.set([ex / 2, t.heightAt(ex / 2, ez / 2) * h.settings.exaggeration, ez / 2]);
      Object.assign(orbit, { distance: 0.45 * Math.max(ex, ez), yaw: 0.5, pitch: 0.9 });
      h.requestRender();
    });
    await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged; }, null, { timeout: 300000, polling: 200 });
    assert.equal(await page.evaluate(() => window.hexlod.terrainObject().sampleType), type, file);
    const r = await judge(page, `type-${type}`, 1);
    console.log(JSON.stringify({ type, interval: r.interval, judged: r.judged.length, hit: r.hitShare.toFixed(3), stray: r.strayShare.toFixed(3) }));
    assert.ok(r.judged.length > 100, `${type}: enough crossings judged: ${r.judged.length}`);
    assert.ok(r.hitShare > 0.9, `${type}: ${(100 * r.hitShare).toFixed(1)}% of the crossings have a line pixel within 2.5 px`);
    assert.ok(r.strayShare < 0.05, `${type}: ${(100 * r.strayShare).toFixed(1)}% of the line pixels are away from every crossing`);
    assert.deepEqual(problems, []);
    await page.close();
  }
});

test('refused intervals keep the old one with a message; a tiny one is widened and says so; the URL keeps them', async () => {
  const { page, problems } = await openView();
  await page.addStyleTag({ content: '#status { display: block !important; }' });
  const state = () => page.evaluate(() => ({ interval: window.hexlod.settings.contourInterval, status: document.getElementById('status').textContent,
    error: document.getElementById('status').classList.contains('error'), contours: { ...window.hexlod.contours } }));
  assert.deepEqual(await page.evaluate(() => [window.hexlod.settings.contours, window.hexlod.settings.contourInterval]), [true, INTERVAL]);
  for (const bad of ['0', '-5', 'abc']) {
    assert.equal(await page.evaluate((v) => window.hexlod.setSetting('contourInterval', v), bad), false, `${bad} refused`);
    const s = await state();
    assert.equal(s.interval, INTERVAL, `${bad}: the old interval is kept`);
    assert.ok(s.error && /contour interval/.test(s.status) && s.status.includes(bad), `${bad}: ${s.status}`);
  }
  assert.equal(await page.evaluate(() => window.hexlod.setSetting('contourInterval', '0.01')), true);
  const tiny = await state();
  assert.equal(tiny.interval, 0.01);
  assert.equal(tiny.contours.widened, true);
  assert.equal(tiny.contours.interval, 5);
  assert.match(tiny.status, /widened to 5 m/);
  assert.equal(tiny.error, false);
  await shoot(page, 'widened');
  assert.equal(await page.evaluate(() => window.hexlod.setSetting('contourInterval', 'auto')), true);
  const auto = await state();
  assert.deepEqual([auto.contours.interval, auto.contours.widened, auto.status], [50, false, '']);
  await page.evaluate(() => window.hexlod.setSetting('contourInterval', '25'));
  await shoot(page, 'interval-25'); // a frame notes the view for the address bar
  await page.evaluate(() => window.hexlod.flushUrl());
  const search = new URLSearchParams(await page.evaluate(() => location.search));
  assert.deepEqual([search.get('contours'), search.get('cint')], ['true', '25']);
  // That address opens the same contours.
  const { page: again } = await openPage(viewer.browser, await page.evaluate(() => location.href), SIZE);
  await again.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
  assert.deepEqual(await again.evaluate(() => [window.hexlod.settings.contours, window.hexlod.settings.contourInterval, window.hexlod.contours.interval]),
    [true, 25, 25]);
  await again.close();
  assert.deepEqual(problems, []);
  await page.close();
});

test('a phone-sized touch viewport draws the contours and their labels', async () => {
  const { page, problems } = await openView('', { hasTouch: true, isMobile: true, deviceScaleFactor: 2 }, { width: 390, height: 844 });
  const image = await shoot(page, 'phone');
  await page.evaluate(() => window.hexlod.setSetting('contours', false));
  const off = await shoot(page, 'phone-off');
  const lines = linePixels(image, off);
  const share = lines.reduce((a, b) => a + b, 0) / lines.length;
  const labels = await page.evaluate(() => window.hexlod.contours.labels);
  assert.ok(share > 0.01, `${(100 * share).toFixed(1)}% of the phone's pixels are contour lines or labels`);
  assert.ok(labels >= 2, `${labels} labels`);
  assert.deepEqual(problems, []);
  await page.close();
});


test('a streamed terrain (a COG by ?src=) draws its contours from the mesh and says so', async () => {
  const cog = `/@fs${projectDir}tests/fixtures/cog/himalaya_1024_i16.tif`;
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?src=${encodeURIComponent(cog)}&budget=50&tau=3&contours=1`, SIZE);
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
  await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged && window.hexlod.tiles?.settled; }, null,
    { timeout: 300000, polling: 200 });
  await shoot(page, 'streamed');
  const s = await page.evaluate(() => ({ tiled: window.hexlod.terrainObject().tiled, contours: { ...window.hexlod.contours },
    status: document.getElementById('status').textContent, glError: window.hexlod.glError() }));
  assert.equal(s.tiled, true);
  assert.deepEqual([s.contours.source, s.contours.labels, s.contours.textureBytes, s.glError], ['mesh', 0, 0, 0]);
  assert.match(s.status, /streamed terrain follow the drawn mesh/);
  assert.deepEqual(problems, []);
  await page.close();
});
