// The live LOD in the page: a short deterministic flight over the default terrain refines and
// coarsens the mesh every frame (the triangle count follows the view), uploads only what
// changed, raises no WebGL error, and the last frame shows terrain.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startViewer, openPage, outDir, pixelStats } from '../../lib/page_harness.js';

let viewer;
before(async () => { viewer = await startViewer({ pixelRatio: 0.5 }); });
after(async () => { await viewer?.close(); });

/** Moves the orbit camera in the page and waits until `frames` more frames were drawn. */
async function flyTo(page, { dx, dz, distance, yaw, pitch }, frames) {
  await page.evaluate(({ dx, dz, distance, yaw, pitch }) => {
    const { camera } = window.hexlod;
    camera.target[0] += dx;
    camera.target[2] += dz;
    camera.distance = distance;
    camera.yaw = yaw;
    camera.pitch = pitch;
    window.hexlod.flightStart = window.hexlod.frames;
    window.hexlod.requestRender();
  }, { dx, dz, distance, yaw, pitch });
  // Keep asking for frames: a converged, blended view stops drawing on its own.
  await page.waitForFunction((n) => {
    window.hexlod.requestRender();
    return window.hexlod.frames - window.hexlod.flightStart >= n;
  }, frames, { timeout: 120000, polling: 100 });
  return page.evaluate(() => ({ triangles: window.hexlod.triangles, uploadBytes: window.hexlod.uploadBytes,
    streamBytes: window.hexlod.streamBytes, glError: window.hexlod.glError() }));
}

test('a scripted flight changes the triangle count with the view, uploads only changes, and raises no WebGL error', async () => {
  // A 50 ms budget: SwiftShader draws about a frame a second, and at the default 4 ms the
  // default view takes some 160 frames to converge; the legs still change the mesh every frame.
  // A small window: SwiftShader's frame time follows the triangles drawn, which at τ = 1 a
  // smaller window needs fewer of; the picture is judged by its shares of sky and its colours.
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?budget=50`, { width: 400, height: 250 });
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 60000 });
  await page.waitForFunction(() => window.hexlod.status !== 'ready' || window.hexlod.converged, null, { timeout: 240000 });
  assert.equal(await page.evaluate(() => window.hexlod.status), 'ready');
  const start = await page.evaluate(() => ({ distance: window.hexlod.camera.distance, yaw: window.hexlod.camera.yaw,
    triangles: window.hexlod.triangles }));
  // In low over the mountains, turning, then far out: each leg a few frames.
  const legs = [
    { dx: 0, dz: -40000, distance: start.distance * 0.25, yaw: start.yaw, pitch: 0.25 },
    { dx: 20000, dz: -20000, distance: start.distance * 0.2, yaw: start.yaw + 0.6, pitch: 0.2 },
    { dx: 0, dz: 0, distance: start.distance * 8, yaw: start.yaw + 0.6, pitch: 0.8 },
  ];
  const seen = [];
  for (const leg of legs) {
    seen.push(await flyTo(page, leg, 12));
    if (leg !== legs[1]) continue;
    // Low over the mountains, mid-flight: the frame shows terrain.
    const png = await page.screenshot({ path: `${outDir}/viewer-flight.png` });
    const stats = pixelStats(png);
    assert.ok(stats.skyFraction < 0.4, `${(100 * stats.skyFraction).toFixed(0)} % of the frame is sky: no terrain in view`);
    assert.ok(stats.colours > 80, `only ${stats.colours} distinct colours: the terrain is not shaded`);
    assert.ok(stats.luminanceStd > 6, `luminance spread ${stats.luminanceStd.toFixed(1)}: a flat image`);
  }
  for (const frame of seen) assert.equal(frame.glError, 0, 'WebGL reported an error');
  const counts = seen.map((f) => f.triangles);
  assert.ok(new Set(counts).size === counts.length, `the triangle count should follow the view: ${counts}`);
  // Holding still far out: merges fade and complete, the view converges, then nothing changes
  // and nothing is uploaded.
  await page.waitForFunction(() => {
    window.hexlod.requestRender();
    return window.hexlod.converged;
  }, null, { timeout: 240000, polling: 200 });
  const still = await flyTo(page, legs[2], 3);
  assert.ok(still.triangles < Math.min(...counts), `flying far out should coarsen: ${counts}, then ${still.triangles}`);
  assert.equal(still.uploadBytes, 0, 'a converged view re-uploads nothing');
  assert.ok(still.streamBytes > 0);

  assert.deepEqual(problems, []);
  await page.close();
});
