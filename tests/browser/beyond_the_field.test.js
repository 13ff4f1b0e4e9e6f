// Past the field's edges the Earth goes on: where no terrain is drawn below the horizon, the
// sky pass draws plain ground at the field's lowest height under the same atmosphere, up to the
// horizon (shaders/sky.frag). On a phone the default view looks down past the far edge: that
// band was black; now it is hazy ground, and the sky stays above the horizon.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { decode } from 'fast-png';
import { startViewer, openPage, pageReady, nextFrame, outDir } from '../../lib/page_harness.js';

let viewer;
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

/**
 * Where the horizon straight ahead lies on the screen (0 at the top, 1 at the bottom): on the
 * plane the level far away, on the curved Earth the sea-level sphere's, its dip below the level
 * of the eye (in the drawn frame: web/cameras/on_the_earth.js).
 */
const horizonAt = (page) => page.evaluate(() => {
  const c = window.hexlod.camera, m = c.viewProjection, p = c.drawnPosition, up = c.drawnUp;
  const f = [0, 1, 2].map((k) => c.drawnTarget[k] - p[k]);
  const along = f[0] * up[0] + f[1] * up[1] + f[2] * up[2];
  const level = f.map((v, k) => v - along * up[k]), length = Math.hypot(...level);
  const radius = c.earth.radius, dip = c.earth.kind === 0 ? 0 : Math.acos(radius / (radius + Math.max(c.position[1], 0)));
  const d = level.map((v, k) => (v / length) * Math.cos(dip) - up[k] * Math.sin(dip));
  const q = [0, 1, 2].map((k) => p[k] + d[k] * 1e7).concat(1);
  const [, y, , w] = [0, 1, 2, 3].map((r) => m[r] * q[0] + m[4 + r] * q[1] + m[8 + r] * q[2] + m[12 + r] * q[3]);
  return (1 - y / w) / 2;
});

/**
 * Luminance (0-255) of each pixel of the view, -1 where the page's boxes (file bar, panel, HUD,
 * status, drop hint) cover it or, with `belowHorizon`, above the horizon.
 */
async function viewLuminance(page, { belowHorizon = false } = {}) {
  await nextFrame(page);
  const shot = decode(await page.screenshot());
  const scale = shot.width / (await page.evaluate(() => innerWidth));
  const boxes = await page.evaluate((scale) => [...document.querySelectorAll('#side, #bottom-bar, #drop-hint')]
    .map((e) => e.getBoundingClientRect()).filter((r) => r.width > 0 && r.height > 0)
    .map((r) => [r.left * scale, r.top * scale, r.right * scale, r.bottom * scale]), scale);
  const top = belowHorizon ? Math.ceil((await horizonAt(page)) * shot.height) + 2 : 0;
  const { width, height, data, channels } = shot;
  const luminance = new Float32Array(width * height).fill(-1);
  for (let y = Math.max(top, 0); y < height; y++) {
    for (let x = 0; x < width; x++) {
      if (boxes.some(([l, t, r, b]) => x >= l && x < r && y >= t && y < b)) continue;
      const k = (y * width + x) * channels;
      luminance[y * width + x] = 0.2126 * data[k] + 0.7152 * data[k + 1] + 0.0722 * data[k + 2];
    }
  }
  return { width, height, luminance };
}

/** The share of the pixels seen that are near black. */
function darkShare({ luminance }) {
  let dark = 0, seen = 0;
  for (const l of luminance) if (l >= 0) { seen++; if (l < 30) dark++; }
  return dark / seen;
}

test('a phone\'s view of the default terrain: no black below the horizon past the far edge, drawn or with the terrain hidden', async () => {
  const { page, problems } = await openPage(viewer.browser, viewer.url, { width: 390, height: 844 });
  await pageReady(page);
  await page.waitForFunction(() => window.hexlod.triangles > 5000, null, { timeout: 120000 });
  await page.screenshot({ path: `${outDir}/beyond-the-field-phone.png` });
  // Above the horizon, seen from hundreds of kilometres up, the sky is rightly dark.
  const drawn = await viewLuminance(page, { belowHorizon: true });
  assert.ok(darkShare(drawn) < 0.002, `${(100 * darkShare(drawn)).toFixed(2)} % of the phone's view below the horizon is black`);
  // The background alone (the terrain hidden): plain ground everywhere below the horizon.
  await page.evaluate(() => { window.hexlod.view.hideTerrain = true; });
  const background = await viewLuminance(page, { belowHorizon: true });
  await page.evaluate(() => { window.hexlod.view.hideTerrain = false; });
  assert.ok(darkShare(background) < 0.002, `${(100 * darkShare(background)).toFixed(2)} % of the background below the horizon is black`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('looking out from the field\'s edge: ground to the horizon, the sky above it, none of it black', async () => {
  // The orbit's target on the south edge, 120 km away, pitched 0.15 rad down: the horizon is in view.
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?cam=orbit,826000,300,1850000,120000,0,0.15`, { width: 390, height: 844 });
  await pageReady(page);
  const horizon = await horizonAt(page);
  assert.ok(horizon > 0.05 && horizon < 0.6, `the horizon is in view (${horizon})`);
  await page.evaluate(() => { window.hexlod.view.hideTerrain = true; });
  const { width, height, luminance } = await viewLuminance(page);
  // Each row's mean: the sky's rows above the horizon, the plain ground's below.
  const rows = Array.from({ length: height }, (_, y) => {
    let sum = 0, n = 0;
    for (let x = 0; x < width; x++) if (luminance[y * width + x] >= 0) { sum += luminance[y * width + x]; n++; }
    return n ? sum / n : null;
  });
  const known = rows.filter((v) => v !== null);
  assert.ok(Math.min(...known) > 30, `every row shows sky or ground (darkest row ${Math.min(...known).toFixed(0)})`);
  // The ground is not the sky: the rows just below the horizon and at the bottom differ from the rows above.
  // Plain ground below the horizon, not the sky's haze: greener than blue near the eye, where
  // the sky above the horizon is bluer than green (the sky alone drew haze there).
  const shot = decode(await page.screenshot());
  const meanColour = (from, to) => {
    const sum = [0, 0, 0];
    let n = 0;
    for (let y = Math.round(from * shot.height); y < to * shot.height; y++) {
      for (let x = 0; x < shot.width; x++) {
        if (luminance[y * width + x] < 0) continue;
        for (let c = 0; c < 3; c++) sum[c] += shot.data[(y * shot.width + x) * shot.channels + c];
        n++;
      }
    }
    return sum.map((v) => v / n);
  };
  const ground = meanColour(0.82, 0.9), sky = meanColour(Math.max(0, horizon - 0.08), horizon - 0.02);
  assert.ok(ground[1] > ground[2] + 3, `the ground below is greener than blue: ${ground.map(Math.round)}`);
  assert.ok(sky[2] > sky[1], `the sky above is bluer than green: ${sky.map(Math.round)}`);
  await page.close();
  assert.deepEqual(problems, []);
});
