// The status line never hides what the HUD shows: after a refused file, its red message and the
// HUD (folded and unfolded) are both on screen and apart, at desktop, laptop and phone sizes.
// Checked by geometry (the boxes do not meet, both lie inside the window) and by pixels (no
// pixel of the message's red inside the HUD's box).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { decode } from 'fast-png';
import { startViewer, openPage, pageReady, dropFiles, converged } from '../../lib/page_harness.js';

const VIEWPORTS = [
  { width: 1280, height: 720 }, { width: 960, height: 540 }, { width: 390, height: 844 }, { width: 320, height: 568 },
];
// A long refusal, as a real one can be: the message wraps over several lines on a phone.
const BAD = { name: 'a_rather_long_name_for_a_survey_tile_that_is_not_a_height_field.png', bytes: new TextEncoder().encode('not a PNG at all') };
const STATUS_RED = [150, 24, 24]; // #status.error's background (public/style.css), over the terrain at 0.92
// Only boxes and the message's red are judged, not the terrain: a coarse mesh (τ = 8 px) at a
// 50 ms frame budget converges in a few of SwiftShader's frames and then draws no more, so the
// clicks and screenshots do not wait behind frames (at the default τ and 4 ms the 1280×720 page
// is still refining, a frame of seconds each, all through the test). Each window has a page of
// its own, opened at that size.
const QUERY = '?budget=50&tau=8';

const boxOf = (page, selector) => page.evaluate((s) => {
  const r = document.querySelector(s).getBoundingClientRect();
  return { left: r.left, top: r.top, right: r.right, bottom: r.bottom, width: r.width, height: r.height };
}, selector);
const meet = (a, b) => a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;

/** Pixels inside `box` of a screenshot whose colour is the error background's (within 12 a channel). */
function redPixels(png, box, scale) {
  const { width, data, channels } = png;
  let count = 0;
  for (let y = Math.ceil(box.top * scale); y < Math.floor(box.bottom * scale); y++) {
    for (let x = Math.ceil(box.left * scale); x < Math.floor(box.right * scale); x++) {
      const i = (y * width + x) * channels;
      if (STATUS_RED.every((c, k) => Math.abs(data[i + k] - c) <= 12)) count++;
    }
  }
  return count;
}

test('after a refused file, the status line and the HUD are both on screen and apart, phones included', async () => {
  const viewer = await startViewer({ pixelRatio: 0.5 });
  try {
    for (const viewport of VIEWPORTS) {
      const { page, problems } = await openPage(viewer.browser, `${viewer.url}${QUERY}`, viewport);
      await pageReady(page);
      await page.waitForFunction(() => /triangles/.test(document.getElementById('hud').textContent));
      await converged(page);
      await dropFiles(page, [BAD]);
      await page.waitForFunction(() => window.hexlod.error && document.getElementById('status').classList.contains('error'));
      const message = await page.evaluate(() => document.getElementById('status').textContent);
      assert.match(message, /not a PNG|signature/i, `${viewport.width}x${viewport.height}: ${message}`);

      for (const folded of [false, true]) {
        const isFolded = await page.evaluate(() => document.getElementById('hud').classList.contains('collapsed'));
        if (isFolded !== folded) await page.click('#hud .hud-toggle');
        const where = `${viewport.width}x${viewport.height}, HUD ${folded ? 'folded' : 'unfolded'}`;
        const [status, hud] = [await boxOf(page, '#status'), await boxOf(page, '#hud')];
        assert.ok(status.height > 0 && hud.height > 0, `${where}: both shown (${status.height}, ${hud.height} px tall)`);
        assert.ok(!meet(status, hud), `${where}: the status line ${JSON.stringify(status)} covers the HUD ${JSON.stringify(hud)}`);
        for (const [name, box] of [['status', status], ['HUD', hud]]) {
          assert.ok(box.left >= 0 && box.top >= 0 && box.right <= viewport.width && box.bottom <= viewport.height,
            `${where}: the ${name} ${JSON.stringify(box)} lies inside the window`);
        }
        const png = decode(await page.screenshot());
        const scale = png.width / viewport.width;
        assert.ok(redPixels(png, status, scale) > status.width * status.height * scale * scale * 0.3, `${where}: the message is drawn red`);
        assert.equal(redPixels(png, hud, scale), 0, `${where}: none of the message's red inside the HUD`);
        const text = await page.evaluate(() => document.getElementById('hud').innerText);
        assert.match(text, /triangles/, `${where}: the HUD still reads its triangle count`);
      }
      assert.deepEqual(problems.filter((p) => !/Failed to load resource|request failed/.test(p)), []);
      await page.close();
    }
  } finally {
    await viewer.close();
  }
});
