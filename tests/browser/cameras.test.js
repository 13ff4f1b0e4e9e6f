// The cameras as a person drives them: walking across the steepest slope of the default DEM
// never puts the eye under the drawn surface or the field, keys fly the fly camera, touch
// gestures orbit, pinch and pan, and the cursor readout names the ground under the pointer.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startViewer, openPage, outDir, drawFrames } from '../../lib/page_harness.js';

let viewer, page, problems;
before(async () => {
  viewer = await startViewer({ pixelRatio: 0.5 });
  ({ page, problems } = await openPage(viewer.browser, viewer.url, { width: 480, height: 300 }));
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
  assert.equal(await page.evaluate(() => window.hexlod.status), 'ready');
});
after(async () => { await viewer?.close(); });

/** Asks for frames until `n` more were drawn. */
const frames = (n) => drawFrames(page, n);

test('walking across the steepest slope of the DEM never goes under the drawn surface or the field', async () => {
  // The steepest place: the largest height difference between neighbouring samples.
  const start = await page.evaluate(() => {
    const h = window.hexlod;
    const terrain = h.terrainObject();
    let best = { slope: -1 };
    for (let i = 1; i < terrain.height - 1; i += 2) {
      for (let j = 1; j < terrain.width - 1; j += 2) {
        const x = j * terrain.spacingX, z = i * terrain.spacingY;
        const slope = Math.abs(terrain.heightAt(x, z - terrain.spacingY) - terrain.heightAt(x, z + terrain.spacingY)) / (2 * terrain.spacingY);
        if (slope > best.slope) best = { slope, x, z };
      }
    }
    return best;
  });
  assert.ok(start.slope > 1, `the steepest slope of the Himalaya is steep: ${start.slope}`);
  // A quarter of the pixels for the walk (no pixel is judged): SwiftShader's frame time follows
  // the triangles drawn, and at τ = 1 a smaller window needs fewer; the drawn surface is then
  // coarser, further from the field, which the eye must still keep above.
  await page.setViewportSize({ width: 240, height: 150 });
  // Walk north across it from 3 km south, at a fast pace, the mesh refining as it goes.
  await page.evaluate(({ x, z }) => {
    const h = window.hexlod;
    h.setSetting('camera', 'walk');
    const walk = h.rig.active;
    walk.position[0] = x;
    walk.position[2] = z + 3000;
    walk.yaw = 0;
    walk.pitch = 0;
    walk.settle();
  }, start);
  let below = [];
  for (let k = 0; k < 30; ++k) {
    await page.evaluate(() => window.hexlod.rig.active.move(0.1, { forward: 1, right: 0, up: 0 }, true));
    await frames(1);
    const check = await page.evaluate(() => {
      const h = window.hexlod;
      const terrain = h.terrainObject();
      const s = h.settings.exaggeration, eyeHeight = h.rig.active.eyeHeight;
      const [x, y, z] = h.eye;
      // The drawn surface now, and the four samples around the eye (the full-resolution field).
      const drawn = terrain.drawnHeightAt(x, z) * s;
      const j = Math.floor(x / terrain.spacingX), i = Math.floor(z / terrain.spacingY);
      let field = -Infinity;
      for (const [a, b] of [[0, 0], [1, 0], [0, 1], [1, 1]]) field = Math.max(field, terrain.heightAt((j + a) * terrain.spacingX, (i + b) * terrain.spacingY) * s);
      return { x, y, z, drawn, field, floor: Math.max(drawn, field) + eyeHeight, converged: h.converged };
    });
    if (check.y < check.floor - 1e-3) below.push(check);
    if (k === 15) await page.screenshot({ path: `${outDir}/cameras-walk.png` });
  }
  assert.deepEqual(below, [], 'the eye went under max(drawn surface, field) + eye height');
  const moved = await page.evaluate(() => window.hexlod.eye);
  assert.ok(moved[2] < start.z + 3000 - 1000, 'the walk went north');
  await page.setViewportSize({ width: 480, height: 300 });
});

test('the fly camera moves with the keys, faster when higher, and the cursor readout names the ground', async () => {
  await page.evaluate(() => window.hexlod.setSetting('camera', 'fly'));
  const fly = () => page.evaluate(() => ({ p: Array.from(window.hexlod.rig.active.position), yaw: window.hexlod.rig.active.yaw,
    speed: window.hexlod.rig.active.speed(false) }));
  const before = await fly();
  await page.keyboard.down('KeyW');
  await frames(4);
  await page.keyboard.up('KeyW');
  const after = await fly();
  const forward = [-Math.sin(before.yaw), -Math.cos(before.yaw)];
  const moved = (after.p[0] - before.p[0]) * forward[0] + (after.p[2] - before.p[2]) * forward[1];
  assert.ok(moved > 0, `W flies forward: ${moved} m`);
  const higher = await page.evaluate(() => {
    const cam = window.hexlod.rig.active;
    cam.position[1] += 20000;
    return cam.speed(false);
  });
  assert.ok(higher > 2 * after.speed, `speed follows altitude: ${after.speed} then ${higher} m/s`);

  // Back to the orbit view; the readout at the canvas centre is the field under that pixel.
  await page.evaluate(() => { window.hexlod.setSetting('camera', 'orbit'); window.hexlod.rig.cameras.orbit.pitch = 0.5; });
  await frames(2);
  await page.mouse.move(240, 150);
  await page.mouse.move(241, 151);
  await page.waitForFunction(() => window.hexlod.cursor !== null, null, { timeout: 10000 });
  const readout = await page.evaluate(() => {
    const h = window.hexlod;
    const { x, z, height } = h.cursor;
    const cam = h.rig.active;
    const m = cam.viewProjection, p = [...h.drawnPoint(x, height * h.settings.exaggeration, z), 1];
    const clip = [0, 1, 2, 3].map((r) => m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r] * p[3]);
    return { height, field: h.terrainObject().heightAt(x, z), px: (clip[0] / clip[3] + 1) * 240, py: (1 - clip[1] / clip[3]) * 150,
      text: document.getElementById('hud').textContent };
  });
  assert.ok(Math.abs(readout.height - readout.field) < 1e-3, `height ${readout.height} is the field's ${readout.field}`);
  assert.ok(Math.hypot(readout.px - 241, readout.py - 151) < 2, `the point lies under the pointer: ${readout.px}, ${readout.py}`);
  assert.match(readout.text, new RegExp(`height ${readout.height.toFixed(1)} m  slope \\d+\\.\\d°`));
});

test('a double click orbits around the ground under the pointer, from any camera', async () => {
  await page.evaluate(() => window.hexlod.setSetting('camera', 'fly'));
  await frames(2);
  // One move, past the readout's 50 ms interval: the readout is of exactly the clicked pixel.
  await page.evaluate(() => { window.hexlod.cursor = null; });
  await page.waitForTimeout(60);
  await page.mouse.move(301, 201);
  await page.waitForFunction(() => window.hexlod.cursor !== null, null, { timeout: 10000 });
  const under = await page.evaluate(() => ({ ...window.hexlod.cursor }));
  await page.mouse.dblclick(301, 201);
  await frames(2);
  const orbit = await page.evaluate(() => ({ mode: window.hexlod.camera.mode, target: Array.from(window.hexlod.rig.cameras.orbit.target),
    exaggeration: window.hexlod.settings.exaggeration }));
  assert.equal(orbit.mode, 'orbit');
  const [x, y, z] = orbit.target;
  assert.ok(Math.hypot(x - under.x, z - under.z) < 1e-6 * Math.hypot(under.x, under.z) + 1,
    `the orbit's target ${x}, ${z} is the ground under the pointer ${under.x}, ${under.z}`);
  assert.ok(Math.abs(y - under.height * orbit.exaggeration) < 1, `at its height: ${y} against ${under.height}`);
});

test('touch: one finger orbits, pinch zooms, two fingers pan', async () => {
  const orbit = () => page.evaluate(() => { const c = window.hexlod.rig.cameras.orbit; return { yaw: c.yaw, distance: c.distance, target: Array.from(c.target) }; });
  const touch = (type, id, x, y) => page.dispatchEvent('#view', type, { pointerType: 'touch', pointerId: id, clientX: x, clientY: y, isPrimary: id === 1, bubbles: true });
  const a = await orbit();
  await touch('pointerdown', 1, 200, 150);
  await touch('pointermove', 1, 260, 150);
  await touch('pointerup', 1, 260, 150);
  const b = await orbit();
  assert.ok(Math.abs(b.yaw - a.yaw) > 0.1, 'one finger orbits');
  await touch('pointerdown', 1, 200, 150);
  await touch('pointerdown', 2, 280, 150);
  await touch('pointermove', 2, 360, 150); // spread grows: zoom in
  const c = await orbit();
  assert.ok(c.distance < b.distance * 0.8, `pinch zooms in: ${b.distance} then ${c.distance}`);
  await touch('pointermove', 1, 200, 100);
  await touch('pointermove', 2, 360, 100); // both move up: pan
  await touch('pointerup', 1, 200, 100);
  await touch('pointerup', 2, 360, 100);
  const d = await orbit();
  assert.ok(Math.hypot(d.target[0] - c.target[0], d.target[2] - c.target[2]) > 1, 'two fingers pan');
  assert.deepEqual(problems, []);
});
