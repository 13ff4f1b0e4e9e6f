// Sun shadows follow the terrain on screen when a bigger field replaces a smaller one: the
// shadow texture is made anew at the new field's size (it once kept the first field's buffer,
// so texImage2D failed with INVALID_OPERATION and every pixel of the new field was in shadow).
// Judged by what a person sees: with the sun low in the east and then in the west, shadows
// darken part of the sunlit slopes, not all of them.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, dropFiles, terrainShown, drawFrames, outDir, projectDir } from '../../lib/page_harness.js';

const SIZE = { width: 320, height: 200 };
const fixture = (name) => `${projectDir}tests/fixtures/${name}`;

let viewer;
before(async () => { viewer = await startViewer(); });
after(async () => { await viewer?.close(); });

/** The screenshot after the mesh converged and its blends ended, with the page's boxes hidden. */
async function shot(page, name) {
  await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged; }, null,
    { timeout: 240000, polling: 200 });
  await drawFrames(page, 10);
  return decode(await page.screenshot({ path: `${outDir}/sun-shadows-${name}.png` }));
}

/**
 * The share of the sunlit ground (warm pixels without shadows: lit rock) that the shadows
 * darken (luminance at least 12 lower).
 */
function shadowedShare(withShadows, without) {
  const a = withShadows.data, b = without.data, channels = without.channels;
  const luma = (d, k) => 0.2126 * d[k] + 0.7152 * d[k + 1] + 0.0722 * d[k + 2];
  let lit = 0, shadowed = 0;
  for (let k = 0; k < b.length; k += channels) {
    if (b[k] - b[k + 2] < 25) continue; // sky, haze and shade are not warm
    lit += 1;
    if (luma(b, k) - luma(a, k) >= 12) shadowed += 1;
  }
  return { lit, share: shadowed / Math.max(lit, 1) };
}

test('a bigger second field gets its own sun shadows: no GL error, shadows on part of the sunlit ground', async () => {
  const small = `/@fs${fixture('volcano_maungawhau.png')}`;
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?src=${encodeURIComponent(small)}&sunel=15&sunaz=90&budget=50`, SIZE); // converges in fewer of SwiftShader's slow frames
  await page.waitForFunction(() => window.hexlod?.status === 'ready', null, { timeout: 180000 });
  await page.evaluate(() => { for (const id of ['hud', 'side', 'drop-hint', 'status']) document.getElementById(id).style.display = 'none'; });
  assert.deepEqual(await page.evaluate(() => [window.hexlod.terrain.width, window.hexlod.terrain.height]), [87, 61]);
  await shot(page, 'volcano');

  await dropFiles(page, ['grandcanyon_512.png', 'grandcanyon_512.json'].map((name) => ({ name, bytes: readFileSync(fixture(name)) })));
  await terrainShown(page, 'grandcanyon_512.png');
  for (const azimuth of [90, 270]) {
    await page.evaluate((a) => { window.hexlod.setSetting('sunAzimuth', a); window.hexlod.setSetting('shadows', true); }, azimuth);
    const shadowed = await shot(page, `canyon-${azimuth}`);
    assert.equal(await page.evaluate(() => window.hexlod.glError()), 0, `no GL error with the sun at ${azimuth}°`);
    await page.evaluate(() => window.hexlod.setSetting('shadows', false));
    const { lit, share } = shadowedShare(shadowed, await shot(page, `canyon-${azimuth}-unshadowed`));
    assert.ok(lit > 400, `the sun at ${azimuth}° lights the canyon's slopes (${lit} px)`);
    // A texture that failed to take the new field's size leaves every pixel in shadow.
    assert.ok(share > 0.02 && share < 0.8, `sun at ${azimuth}°: shadows on part of the sunlit ground, not none nor all (${share.toFixed(2)})`);
  }
  assert.deepEqual(problems, []);
  await page.close();
});
