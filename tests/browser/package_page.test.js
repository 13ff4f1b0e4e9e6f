// The npm package in users' pages: the tarball installed into an empty folder
// (lib/packed_install.js). examples/element.html served by Vite with examples/vite.config.js:
// the <hexlod-viewer> draws the default terrain and reports it, and removing it gives its
// WebAssembly memory back. examples/import-map.html from a plain static server: no bundler.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { copyFileSync, existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { INSTALL_FLAGS, packAndInstall, run } from '../../lib/packed_install.js';
import { startFileServer } from '../../lib/static_site.js';
import { launchChromium, freePort } from '../../lib/chromium.js';
import { pixelStats } from '../../lib/page_harness.js';

const root = fileURLToPath(new URL('../../', import.meta.url));
let server, browser, url, files;

before(async () => {
  const { dir, pack } = await packAndInstall();
  // A user's Vite project of its own, with hexlod from the same tarball and the Vite version this
  // project uses (from npm's cache). Vite serves only files inside its project, as it would a
  // user's. The shared install stays without Vite.
  const site = join(dir, 'vite-page');
  mkdirSync(site, { recursive: true });
  if (!existsSync(join(site, 'node_modules/hexlod/package.json'))) {
    const version = JSON.parse(readFileSync(join(root, 'node_modules/vite/package.json'), 'utf8')).version;
    writeFileSync(join(site, 'package.json'), '{ "private": true, "type": "module" }\n');
    const installed = await run('npm', ['install', pack.tarball, `vite@${version}`, ...INSTALL_FLAGS], { cwd: site });
    if (installed.code !== 0) throw new Error(`npm install hexlod vite failed: ${installed.stderr}`);
  }
  const { createServer } = await import(pathToFileURL(join(site, 'node_modules/vite/dist/node/index.js')).href);
  for (const name of ['element.html', 'element.js', 'examples.css', 'vite.config.js']) copyFileSync(join(root, 'examples', name), join(site, name));
  server = await createServer({ configFile: join(site, 'vite.config.js'), root: site, cacheDir: join(site, '.vite'),
    server: { port: await freePort(), strictPort: true, host: '127.0.0.1', hmr: false, watch: null }, logLevel: 'error' });
  await server.listen();
  url = `http://127.0.0.1:${server.httpServer.address().port}/`;
  // The page without a bundler beside the install's node_modules, from a plain static server.
  for (const name of ['import-map.html', 'examples.css']) copyFileSync(join(root, 'examples', name), join(dir, name));
  files = await startFileServer({ mounts: [['/', `${dir}/`]] });
  browser = await launchChromium();
});
after(async () => {
  await browser?.close();
  await server?.close();
  await files?.close();
});

/** A page that records its errors and failed responses in `problems`. */
async function trackedPage() {
  const page = await browser.newPage({ viewport: { width: 800, height: 500 }, deviceScaleFactor: 0.5 });
  const problems = [];
  page.on('pageerror', (error) => problems.push(error.message));
  page.on('response', (response) => { if (response.status() >= 400) problems.push(`${response.status()} ${response.url()}`); });
  return { page, problems };
}

/** Waits for the page's viewer to report its terrain; on time-out, says what the page met. */
async function terrainShown(page, problems) {
  await page.waitForFunction(() => window.viewer?.terrain, null, { timeout: 180000 })
    .catch((error) => { throw new Error(`${error.message}; the page met: ${problems.join('; ') || 'nothing'}`); });
  return page.evaluate(() => window.viewer.terrain);
}

/** After a few frames the view shows relief, and the panel shows, styled. */
async function assertDrawsRelief(page) {
  await page.evaluate(() => new Promise((resolve) => { const off = window.viewer.on('frame', (f) => { if (f.frames > 3) { off(); resolve(); } }); }));
  const stats = pixelStats(await page.locator('#view').screenshot());
  assert.ok(stats.colours > 200 && stats.luminanceStd > 10 && stats.skyFraction < 0.5, `it draws relief: ${JSON.stringify(stats)}`);
  assert.equal(await page.locator('#panel .lil-title').first().isVisible(), true, 'the panel shows, styled');
}

test('a Vite page with <hexlod-viewer> from the installed package draws and reports its terrain; dispose() frees its memory', async () => {
  const { page, problems } = await trackedPage();
  await page.addInitScript(() => {
    window.wasmMemories = { made: 0, collected: 0 };
    const registry = new FinalizationRegistry(() => { window.wasmMemories.collected += 1; });
    for (const name of ['instantiate', 'instantiateStreaming']) {
      const original = WebAssembly[name];
      WebAssembly[name] = (...args) => original.apply(WebAssembly, args).then((result) => {
        const memory = Object.values((result.instance ?? result).exports).find((e) => e instanceof WebAssembly.Memory);
        if (memory) { window.wasmMemories.made += 1; registry.register(memory, null); }
        return result;
      });
    }
  });
  await page.goto(`${url}element.html`);
  const terrain = await terrainShown(page, problems);
  assert.equal(terrain.name, 'globe_himalaya_2048.png');
  assert.deepEqual([terrain.width, terrain.height, terrain.crs], [2048, 2048, 'EPSG:4326']);
  await assertDrawsRelief(page);
  await page.evaluate(() => { window.viewer = null; document.getElementById('terrain').remove(); }); // removing the element disposes its viewer
  const cdp = await page.context().newCDPSession(page);
  let counts;
  for (let attempt = 0; attempt < 20; ++attempt) {
    await cdp.send('HeapProfiler.collectGarbage');
    counts = await page.evaluate(() => new Promise((resolve) => setTimeout(() => resolve({ ...window.wasmMemories }), 100)));
    if (counts.made > 0 && counts.collected === counts.made) break;
  }
  assert.ok(counts.made === 1 && counts.collected === 1, `the core's memory is collected after dispose(): ${JSON.stringify(counts)}`);
  assert.equal(await page.locator('.hexlod').count(), 0);
  // A user's page serves no crs/CODE.json files (the viewer's own site does): a code's definition is then missing, said, not fatal.
  assert.deepEqual(problems.filter((p) => !p.endsWith('/favicon.ico') && !/^404 .*\/crs\/\d+\.json$/.test(p)), []);
  await page.close();
});

test('a plain page with an import map and no bundler loads the installed package from a static server and draws', async () => {
  const { page, problems } = await trackedPage();
  await page.goto(`${files.origin}/import-map.html`);
  assert.equal((await terrainShown(page, problems)).name, 'globe_himalaya_2048.png');
  await assertDrawsRelief(page);
  const loaded = await page.evaluate(() => performance.getEntriesByType('resource').map((e) => e.name));
  assert.ok(loaded.every((name) => !name.includes('/node_modules/') || name.includes('/node_modules/hexlod/library/')),
    'everything comes from the package\'s library, no other package');
  assert.deepEqual(problems.filter((p) => !/^404 .*\/crs\/\d+\.json$/.test(p)), []);
  await page.close();
});
