// Accessibility (WCAG 2.1 AA): axe-core finds no serious or critical violation in the page's
// states (opening, every panel folder open, measuring, help, an error); the HUD, status line,
// drop hint and attribution keep AA contrast over any ground; and a person with a keyboard alone
// opens a file, changes τ in the panel, turns the camera and measures a path, and hides,
// reorders and removes image layers in the layers list, seeing the focus at each step.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { decode } from 'fast-png';
import { startViewer, openPage, pageReady, projectDir, dropFiles, terrainShown, drawFrames, converged } from '../../lib/page_harness.js';
import { lookStraightDown } from '../../lib/draped_points.js';

let viewer;
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

const AXE = readFileSync(`${projectDir}node_modules/axe-core/axe.min.js`, 'utf8');

/** axe-core's serious and critical WCAG 2.1 A/AA violations on the page as it is. */
async function seriousViolations(page) {
  if (!await page.evaluate(() => typeof window.axe === 'object')) await page.evaluate(AXE); // evaluated, not a <script>: the page's CSP stays
  const result = await page.evaluate(() => window.axe.run(document, { runOnly: ['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa'] }));
  return result.violations.filter((v) => v.impact === 'serious' || v.impact === 'critical')
    .map((v) => `${v.id}: ${v.help} (${v.nodes.map((n) => n.target.join(' ')).slice(0, 3).join(', ')})`);
}

test('axe-core: no serious or critical violation on opening, with every folder open, measuring, in the help and with an error', async () => {
  const { page } = await openPage(viewer.browser, viewer.url, { width: 1100, height: 720 });
  await pageReady(page);
  assert.deepEqual(await seriousViolations(page), [], 'on opening');
  // Every folder of the panel open.
  await page.evaluate(() => {
    for (const title of document.querySelectorAll('#panel .lil-gui.lil-closed > .lil-title')) title.click();
  });
  await page.waitForTimeout(400);
  assert.deepEqual(await seriousViolations(page), [], 'every folder open');
  await page.getByRole('button', { name: 'Measure', exact: true }).click();
  await page.evaluate(() => { window.hexlod.measure.add(20000, 20000); window.hexlod.measure.add(60000, 50000); });
  assert.deepEqual(await seriousViolations(page), [], 'measuring');
  await page.keyboard.press('Escape');
  await page.keyboard.press('h');
  assert.equal(await page.locator('#help').isVisible(), true);
  assert.deepEqual(await seriousViolations(page), [], 'the help');
  await page.keyboard.press('Escape');
  await page.evaluate(() => window.hexlod.setSetting('tau', 99));
  assert.equal(await page.locator('#status.error').isVisible(), true);
  assert.deepEqual(await seriousViolations(page), [], 'an error in the status line');
  await page.close();
});

test('the HUD, status line, error, drop hint and attribution keep AA contrast (4.5:1) over black and over white ground', async () => {
  const { page } = await openPage(viewer.browser, viewer.url, { width: 1100, height: 720 });
  await pageReady(page);
  await page.evaluate(() => {
    document.getElementById('attribution').hidden = false;
    document.getElementById('attribution').textContent = '© someone';
  });
  const ratios = await page.evaluate(() => {
    const rgba = (text) => { const [r, g, b, a = 1] = text.match(/[\d.]+/g).map(Number); return [r, g, b, a]; };
    const luminance = ([r, g, b]) => {
      const c = (v) => { v /= 255; return v <= 0.03928 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4; };
      return 0.2126 * c(r) + 0.7152 * c(g) + 0.0722 * c(b);
    };
    const over = ([r, g, b, a], under) => [r * a + under[0] * (1 - a), g * a + under[1] * (1 - a), b * a + under[2] * (1 - a)];
    const ratio = (x, y) => { const [l1, l2] = [luminance(x), luminance(y)].sort((p, q) => q - p); return (l1 + 0.05) / (l2 + 0.05); };
    const out = {};
    const measure = (name, element) => {
      const style = getComputedStyle(element);
      const opacity = Number(style.opacity);
      const worst = [[0, 0, 0], [255, 255, 255]].map((ground) => {
        const background = over(rgba(style.backgroundColor), ground);
        const [r, g, b, a] = rgba(style.color);
        return ratio(over([r, g, b, a * opacity], background), background);
      });
      out[name] = Math.min(...worst);
    };
    const status = document.getElementById('status');
    status.textContent = 'a message';
    measure('status', status);
    status.classList.add('error');
    measure('error', status);
    measure('hud', document.getElementById('hud'));
    measure('drop hint', document.getElementById('drop-hint'));
    measure('attribution', document.getElementById('attribution'));
    return out;
  });
  for (const [name, value] of Object.entries(ratios)) assert.ok(value >= 4.5, `${name}: contrast ${value.toFixed(2)}:1`);
  await page.close();
});

/** What has the focus: its tag, name and whether a focus ring shows (an outline or a ring of shadow). */
const focused = (page) => page.evaluate(() => {
  const e = document.activeElement;
  const style = getComputedStyle(e);
  const label = e.getAttribute('aria-label') ?? e.closest('.lil-controller')?.querySelector('.lil-name')?.textContent ?? e.textContent;
  return { tag: e.tagName, label: (label ?? '').trim().slice(0, 40), layer: e.closest('[data-layer-id]')?.dataset.layerId ?? null,
    ring: (style.outlineStyle !== 'none' && parseFloat(style.outlineWidth) > 0) || style.boxShadow !== 'none' };
});

async function tabTo(page, matches, limit = 80) {
  for (let k = 0; k < limit; ++k) {
    await page.keyboard.press('Tab');
    const f = await focused(page);
    if (f.tag === 'BODY') continue; // past the last control the focus goes to the browser's own bar
    assert.ok(f.ring, `the focus shows on ${f.tag} '${f.label}'`);
    if (matches(f)) return f;
  }
  throw new Error('not reached with Tab');
}

test('keyboard alone: open a file, set τ in the panel, turn the camera, measure a path; the focus shows at every step', async () => {
  const { page, problems } = await openPage(viewer.browser, viewer.url, { width: 1100, height: 720 });
  await pageReady(page);
  // Open file… with Enter, then the file chooser.
  await tabTo(page, (f) => f.label.startsWith('Open file'));
  // Headless Chromium opens no chooser window; Enter must reach the file input, whose files are then set as a chooser would.
  await page.evaluate(() => document.getElementById('file-input').addEventListener('click', () => { window.chooserAsked = true; }, { once: true }));
  await page.keyboard.press('Enter');
  assert.equal(await page.evaluate(() => window.chooserAsked), true, 'Enter on "Open file…" asks for the file chooser');
  await page.setInputFiles('#file-input', [`${projectDir}tests/fixtures/volcano_maungawhau.png`, `${projectDir}tests/fixtures/volcano_maungawhau.json`]);
  await page.waitForFunction(() => window.hexlod.terrain?.name === 'volcano_maungawhau.png' && !window.hexlod.loading, null, { timeout: 60000 });
  // τ in the panel: its number field, typed.
  await tabTo(page, (f) => f.tag === 'INPUT' && f.label.startsWith('error τ'));
  await page.keyboard.press('Control+a');
  await page.keyboard.type('3');
  await page.keyboard.press('Enter');
  assert.equal(await page.evaluate(() => window.hexlod.settings.tau), 3);
  // The camera: the orbit turns while an arrow key is held.
  await page.evaluate(() => document.activeElement.blur());
  const yaw = await page.evaluate(() => window.hexlod.rig.cameras.orbit.yaw);
  await page.keyboard.down('ArrowLeft');
  await page.waitForFunction((y) => Math.abs(window.hexlod.rig.cameras.orbit.yaw - y) > 0.2, yaw, { timeout: 30000 });
  await page.keyboard.up('ArrowLeft');
  // Measure: the button by Tab and Enter, points with Space at the view's centre, Enter ends.
  await tabTo(page, (f) => f.label === 'Measure');
  await page.keyboard.press('Enter');
  assert.equal(await page.locator('#measure-button').getAttribute('aria-pressed'), 'true');
  await page.evaluate(() => document.activeElement.blur());
  await page.keyboard.press('Space');
  await page.keyboard.down('ArrowRight');
  await page.waitForFunction((y) => Math.abs(window.hexlod.rig.cameras.orbit.yaw - y) > 0.3, await page.evaluate(() => window.hexlod.rig.cameras.orbit.yaw), { timeout: 30000 });
  await page.keyboard.up('ArrowRight');
  await page.keyboard.down('ArrowUp'); // closer: the centre moves over other ground
  await page.waitForTimeout(300);
  await page.keyboard.up('ArrowUp');
  await page.keyboard.press('Space');
  await page.keyboard.press('Enter');
  const result = await page.evaluate(() => ({ points: window.hexlod.measure.points.length, finished: window.hexlod.measure.finished }));
  assert.deepEqual(result, { points: 2, finished: true });
  assert.match(await page.locator('#measure-summary').textContent(), /\d+ m/);
  await page.keyboard.press('Escape');
  assert.equal(await page.evaluate(() => window.hexlod.measure.points.length), 0);
  assert.deepEqual(problems, []);
  await page.close();
});

/** Mean absolute difference of two screenshots' colours, 0–255, left of the panel and clear of the HUD and status lines. */
function meanDifference(a, b) {
  let sum = 0, n = 0;
  for (let y = Math.round(a.height * 0.15); y < a.height * 0.8; ++y) {
    for (let x = Math.round(a.width * 0.05); x < a.width * 0.7; ++x) {
      const i = (y * a.width + x) * a.channels;
      for (let c = 0; c < 3; ++c) sum += Math.abs(a.data[i + c] - b.data[i + c]);
      n += 3;
    }
  }
  return sum / n;
}

test('keyboard alone in the layers list: hide and show a layer, move it up, remove it; the focus stays on the layer it acted on', async () => {
  const { page, problems } = await openPage(viewer.browser, viewer.url, { width: 1100, height: 720 });
  await pageReady(page);
  const fixture = (name) => ({ name, bytes: new Uint8Array(readFileSync(`${projectDir}tests/fixtures/reprojection/${name}`)) });
  await dropFiles(page, [fixture('himalaya_utm45_2500m.tif')]);
  await terrainShown(page, 'himalaya_utm45_2500m.tif');
  await lookStraightDown(page, 9e5);
  const shot = async () => { await converged(page); await drawFrames(page, 3); return decode(await page.screenshot()); };
  const bare = await shot();
  for (const [k, name] of ['bmng_himalaya_4326.tif', 'bmng_himalaya_3857.tif'].entries()) {
    await dropFiles(page, [fixture(name)]);
    await page.waitForFunction((n) => window.hexlod.imageLayers.length === n, k + 1, { timeout: 60000 });
  }
  const layers = () => page.evaluate(() => window.hexlod.imageLayers.map((l) => ({ id: String(l.id), visible: l.visible })));
  const [bottom, top] = (await layers()).map((l) => l.id);
  assert.ok(meanDifference(await shot(), bare) > 20, 'the images cover the ground');
  await page.evaluate(() => document.activeElement.blur());

  // The layers' folder opened by its title, then the top layer's visibility, with Space.
  await tabTo(page, (f) => f.label.startsWith('Image layers'));
  if (await page.evaluate(() => document.activeElement.getAttribute('aria-expanded')) === 'false') await page.keyboard.press('Enter');
  const checkbox = (layer) => (f) => f.tag === 'INPUT' && f.label === 'visible' && f.layer === layer;
  await tabTo(page, checkbox(top));
  await page.keyboard.press('Space');
  assert.deepEqual(await layers(), [{ id: bottom, visible: true }, { id: top, visible: false }]);
  const after = await focused(page);
  assert.ok(checkbox(top)(after) && after.ring, `the focus stays on the hidden layer's checkbox (${JSON.stringify(after)})`);
  await tabTo(page, checkbox(bottom));
  await page.keyboard.press('Space');
  assert.ok(meanDifference(await shot(), bare) < 2, 'both hidden: the bare ground');
  await page.keyboard.press('Space');
  assert.ok(meanDifference(await shot(), bare) > 20, 'the bottom layer shown again');

  // The bottom layer moved up with Enter: it lies on top, and the focus is still on its button.
  await tabTo(page, (f) => f.label === 'move up' && f.layer === bottom);
  await page.keyboard.press('Enter');
  assert.deepEqual((await layers()).map((l) => l.id), [top, bottom]);
  const moved = await focused(page);
  assert.ok(moved.label === 'move up' && moved.layer === bottom && moved.ring, `the focus follows the moved layer (${JSON.stringify(moved)})`);

  // Removed with Enter: one layer left, and the focus on the row now in its place.
  await tabTo(page, (f) => f.label === 'remove layer' && f.layer === bottom);
  await page.keyboard.press('Enter');
  assert.deepEqual(await layers(), [{ id: top, visible: false }]);
  const left = await focused(page);
  assert.ok(left.layer === top && left.ring, `the focus moves to the remaining layer's row (${JSON.stringify(left)})`);
  assert.ok(meanDifference(await shot(), bare) < 2, 'the remaining layer is hidden: the bare ground');
  assert.deepEqual(problems, []);
  await page.close();
});
