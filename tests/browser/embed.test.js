// The built site in an <iframe> of a host page that cannot bundle: the host drives it with
// postMessage commands (web/app/embed_messages.js) and hears its events.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startViewer, pixelStats } from '../../lib/page_harness.js';
import { startFileServer } from '../../lib/static_site.js';

// The host is a page of another origin (another port): the frame and the host share nothing but
// messages. (Chromium refuses a local frame in about:blank, a public page.)
let viewer, host;
before(async () => {
  viewer = await startViewer({ site: 'built', pixelRatio: 0.5 });
  host = await startFileServer({ mounts: [], handlers: [['/host', (request, response) => {
    response.writeHead(200, { 'content-type': 'text/html; charset=utf-8' });
    response.end('<!doctype html><title>host</title><body></body>');
  }]] });
});
after(async () => { await viewer?.close(); await host?.close(); });

test('a host page drives the embedded viewer by postMessage: loaded event, terrain, settings, camera, screenshot, bad commands', { timeout: 180000 }, async () => {
  const page = await viewer.browser.newPage({ viewport: { width: 900, height: 600 } });
  const problems = [];
  page.on('pageerror', (error) => problems.push(error.message));
  await page.goto(`${host.origin}/host`);
  const events = await page.evaluate((src) => new Promise((resolve) => {
    window.heard = [];
    window.addEventListener('message', (e) => {
      if (e.data?.hexlod === 'event') window.heard.push([e.data.type, e.data.detail?.terrain?.name ?? e.data.detail?.message]);
      if (e.data?.hexlod === 'event' && e.data.type === 'loaded') resolve(window.heard);
    });
    // The host's whole client: a command, and the reply with its id.
    let next = 0;
    window.ask = (command, ...args) => new Promise((answer) => {
      const id = ++next;
      const listen = (e) => { if (e.data?.hexlod === 'reply' && e.data.id === id) { window.removeEventListener('message', listen); answer(e.data); } };
      window.addEventListener('message', listen);
      document.querySelector('iframe').contentWindow.postMessage({ hexlod: command, id, args }, '*');
    });
    const frame = Object.assign(document.createElement('iframe'), { src, title: 'terrain viewer' });
    frame.style.cssText = 'width: 800px; height: 500px; border: 0';
    document.body.append(frame);
  }), `${viewer.url}?ui=0`);
  assert.deepEqual(events[0], ['loaded', 'globe_himalaya_2048.png']);
  const answers = await page.evaluate(async () => {
    const ask = window.ask;
    const terrain = await ask('terrain');
    const set = await ask('set', 'tau', 3);
    const badValue = await ask('set', 'tau', 99);
    const unknown = await ask('explode');
    const flown = await ask('flyTo', { position: [800000, 40000, 1200000], target: [800000, 3000, 900000] }, { seconds: 0.5 });
    const camera = await ask('camera');
    const shot = await ask('screenshot', { scale: 1 });
    const bytes = new Uint8Array(await shot.result.arrayBuffer());
    return { terrain: terrain.result, tau: set.result, badValue: badValue.error, unknown: unknown.error, flown: flown.result,
      camera: camera.result, png: Array.from(bytes) };
  });
  assert.deepEqual([answers.terrain.width, answers.terrain.height, answers.terrain.crs], [2048, 2048, 'EPSG:4326']);
  assert.equal(answers.tau, 3);
  assert.match(answers.badValue, /^RangeError: viewer.set: tau=99 is not a number from 0.25 to 16/);
  assert.match(answers.unknown, /^RangeError: unknown command 'explode'/);
  assert.equal(answers.flown, true);
  assert.ok(Math.hypot(answers.camera.position[0] - 800000, answers.camera.position[1] - 40000, answers.camera.position[2] - 1200000) < 1,
    `the camera is where it was sent: ${answers.camera.position}`);
  // The screenshot the host got is the hazy terrain below a dark sky: many colours, light and dark.
  const shot = pixelStats(Buffer.from(answers.png));
  assert.ok(shot.colours > 80 && shot.luminanceStd > 25, `the terrain in the host's screenshot: ${JSON.stringify(shot)}`);
  // ?ui=0: the terrain alone.
  const panelShown = await page.frames()[1].evaluate(() => getComputedStyle(document.getElementById('side')).display !== 'none');
  assert.equal(panelShown, false);
  assert.deepEqual(problems, []);
  await page.close();
});
