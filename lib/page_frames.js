// What the page benchmarks share: a page opened bare (no HUD, panel or hints over the view) and
// converged, and one frame drawn after a setting changed, with the frame's figures (the
// frame log of web/app/frame_pipeline.js: cpuMs, drawMs, lodMs, streamMs).
import { parseArgs } from 'node:util';
import { openPage, pageReady } from './page_harness.js';

/** Opens `url` with nothing over the terrain and waits until the mesh converged. */
export async function openConvergedView(browser, url, viewport) {
  const opened = await openPage(browser, url, viewport);
  const { page } = opened;
  await page.addStyleTag({ content: '#hud,#side,#drop-hint,#status{display:none !important}' });
  await page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 120000 });
  await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged; }, null, { timeout: 300000, polling: 200 });
  return opened;
}

/** Sets `key` to `value` as the panel would, draws one frame and returns its frame log entry. */
export function frameWithSetting(page, key, value) {
  return page.evaluate(([k, v]) => new Promise((resolve) => {
    const h = window.hexlod;
    h.setSetting(k, v);
    h.frameLog = [];
    h.recordFrames = true;
    const want = h.frames + 1;
    const wait = () => (h.frames >= want ? resolve(h.frameLog.at(-1)) : requestAnimationFrame(wait));
    h.requestRender();
    requestAnimationFrame(wait);
  }), [key, value]);
}

/** Draws `n` frames one after another, each asked for when the last has ended; their figures (cpuMs, drawMs). */
export function drawBlock(page, n) {
  return page.evaluate((count) => new Promise((resolve) => {
    const h = window.hexlod;
    h.frameLog = [];
    h.recordFrames = true;
    const next = () => {
      if (h.frameLog.length >= count) {
        h.recordFrames = false;
        resolve(h.frameLog.map(({ cpuMs, drawMs }) => ({ cpuMs, drawMs })));
        return;
      }
      const want = h.frames + 1;
      h.requestRender();
      const wait = () => (h.frames >= want ? next() : requestAnimationFrame(wait));
      requestAnimationFrame(wait);
    };
    next();
  }), n);
}

/**
 * The page on the default terrain with `query`, its overlays hidden (they are not what is
 * measured), waiting for the GPU after each frame (?timing=1), at a fixed oblique view over the
 * middle of the terrain, converged, so that no refinement competes with what is timed.
 * Returns the page, its problems and a description of the view.
 */
export async function obliqueTimedPage(viewer, query, { width, height }) {
  const { page, problems } = await openPage(viewer.browser, `${viewer.url}?test=1&timing=1&budget=40${query}`, { width, height });
  await page.addStyleTag({ content: '#hud,#side,#drop-hint,#status{display:none !important}' });
  await pageReady(page);
  const distanceKm = await page.evaluate(() => {
    const { camera, rig } = window.hexlod;
    camera.target[0] = rig.world.extentX / 2;
    camera.target[2] = rig.world.extentZ / 2;
    camera.distance = 0.6 * rig.world.extentX;
    camera.yaw = 0.5;
    camera.pitch = 0.45;
    return camera.distance / 1000;
  });
  await page.waitForFunction(() => { window.hexlod.requestRender(); return window.hexlod.converged; }, null, { timeout: 600000, polling: 500 });
  const triangles = await page.evaluate(() => window.hexlod.triangles);
  return { page, problems, view: `${width} × ${height}, oblique view from ${distanceKm.toFixed(0)} km (pitch 0.45 rad), converged: ${triangles.toLocaleString('en')} triangles` };
}

/** The page benchmarks' options: --viewport WxH (default 640x360), --runs N (3), --frames N (20). */
export function pageBenchOptions() {
  const { values } = parseArgs({ options: { viewport: { type: 'string' }, runs: { type: 'string' }, frames: { type: 'string' } } });
  const [width, height] = (values.viewport ?? '640x360').split('x').map(Number);
  return { width, height, runs: Number(values.runs ?? 3), frames: Number(values.frames ?? 20) };
}

/** The median of a list of numbers (the upper one of an even count). */
export const median = (v) => [...v].sort((a, b) => a - b)[v.length >> 1];

/** Milliseconds as a benchmark prints them: one decimal below 10. */
export const formatMs = (v) => `${v < 10 ? v.toFixed(1) : Math.round(v).toLocaleString('en')} ms`;
