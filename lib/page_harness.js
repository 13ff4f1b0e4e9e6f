// The page under test, shared by the browser tests and the page benchmarks: a Vite server on
// a free localhost port and Debian's Chromium driven by playwright-core (never a browser that
// a tool downloads).
import { createServer } from 'vite';
import { startStaticSite } from './static_site.js';
import { decode } from 'fast-png';
import { mkdirSync } from 'node:fs';
import { freePort, launchChromium } from './chromium.js';
import { crsFilesPlugin } from './crs_files_plugin.js';
import { fileURLToPath } from 'node:url';

export const projectDir = fileURLToPath(new URL('..', import.meta.url));
export const outDir = `${projectDir}tests/out`;

/**
 * The Vite dev server on a free port; returns { url, close() }. It serves the tree as it is when
 * a page asks: no file watching and no hot reload (`hmr: true` turns both on), so an edit
 * elsewhere in the work tree never reloads a page in the middle of a test.
 */
async function startDevServer({ hmr = false, examples = false } = {}) {
  const server = await createServer({
    // The examples are a user's pages: Vite's defaults, without the viewer page's Content-Security-Policy.
    configFile: examples ? false : `${projectDir}vite.config.js`,
    ...(examples ? { plugins: [crsFilesPlugin()], worker: { format: 'es' } } : {}),
    root: `${projectDir}${examples ? 'examples' : 'public'}`,
    // The examples import the package by its name, as in a user's project: here, its source.
    resolve: examples ? { alias: [{ find: /^hexlod\/element$/, replacement: `${projectDir}web/api/element.js` },
      { find: /^hexlod$/, replacement: `${projectDir}web/api/index.js` }] } : {},
    server: { port: await freePort(), strictPort: true, host: '127.0.0.1', ...(hmr ? {} : { hmr: false, watch: null }),
      ...(examples ? { fs: { allow: [projectDir] } } : {}) },
    // Its own dependency cache: another Vite server on this checkout's node_modules (the
    // viewer, a benchmark) re-optimising the shared one mid-test breaks lazy imports.
    cacheDir: `${outDir}/vite-cache`,
    logLevel: 'error',
  });
  await server.listen();
  const { port } = server.httpServer.address();
  return { url: `http://127.0.0.1:${port}/`, fixturesUrl: `/@fs${projectDir}tests/fixtures/`, close: () => server.close() };
}

/**
 * Starts the page and the browser; returns { url, fixturesUrl, browser, close() }.
 * `site: 'dev'` (default) is the Vite dev server; `site: 'built'` serves the production build in
 * dist/ (./build.sh site) from a plain static file server under the sub-path /hexlod/, as a
 * static host would, with the test fixtures under /fixtures/; `site: 'examples'` the pages of
 * examples/ on the dev server, `hexlod` imported from the source as from the package. `hmr`: the dev server watches
 * files and its client keeps a hot-reload connection, as for a developer. `chromiumArgs`: more
 * command-line flags for the browser. `pixelRatio`: the device pixels per CSS pixel of the pages
 * opened in it (0.5 for a test that judges what is drawn, not its fine detail: a quarter of the
 * pixels to draw on the CPU).
 */
export async function startViewer({ site = 'dev', hmr = false, chromiumArgs = [], pixelRatio = 1 } = {}) {
  const server = site === 'built' ? await startStaticSite() : await startDevServer({ hmr, examples: site === 'examples' });
  const browser = await launchChromium(undefined, chromiumArgs);
  // Pages open at `pixelRatio` device pixels per CSS pixel unless they ask otherwise: at 0.5 the
  // page lays out as on the screen it emulates while SwiftShader draws a quarter of the pixels.
  const newPage = browser.newPage.bind(browser);
  browser.newPage = (options = {}) => newPage({ deviceScaleFactor: pixelRatio, ...options });
  mkdirSync(outDir, { recursive: true });
  return {
    url: server.url,
    fixturesUrl: server.fixturesUrl,
    browser,
    async close() {
      await browser.close();
      await server.close();
    },
  };
}

/** Page options for a test that judges fine detail in a viewer started at a lower `pixelRatio`. */
export const FULL_RESOLUTION = { deviceScaleFactor: 1 };

/**
 * Opens a page that records console errors, page errors and failed requests in `problems`.
 * `options`: more of Playwright's page options (deviceScaleFactor, hasTouch, isMobile).
 */
export async function openPage(browser, url, viewport = { width: 960, height: 600 }, options = {}) {
  const page = await browser.newPage({ viewport, ...options });
  // The page's Content-Security-Policy refuses the <style> element of Playwright's addStyleTag;
  // a test's own styles (hiding the page's boxes) go in as a constructed stylesheet, which
  // script may add under the policy.
  const addStyleTag = page.addStyleTag.bind(page);
  page.addStyleTag = (options) => (options.content === undefined ? addStyleTag(options) : page.evaluate((css) => {
    const sheet = new CSSStyleSheet();
    sheet.replaceSync(css);
    document.adoptedStyleSheets = [...document.adoptedStyleSheets, sheet];
  }, options.content));
  const problems = [];
  page.on('console', (message) => {
    if (message.type() === 'error') problems.push(`console.error: ${message.text()}`);
  });
  page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
  page.on('requestfailed', (request) => problems.push(`request failed: ${request.url()}`));
  await page.goto(url);
  return { page, problems };
}

/** The renderer's clear colour (web/render/renderer.js SKY_COLOR) as 8-bit RGB. */
const SKY_RGB = [158, 189, 224];

/**
 * Colour statistics of a PNG screenshot: distinct quantised colours, luminance spread, and the
 * fractions of pixels that are the sky (clear) colour, snow white, and warm ground or rock.
 */
export function pixelStats(png) {
  const image = decode(png);
  const { data, channels } = image;
  const colours = new Set();
  let sum = 0, sumSq = 0, n = 0, sky = 0, snow = 0, ground = 0;
  for (let k = 0; k < data.length; k += channels * 7) {
    const r = data[k], g = data[k + 1], b = data[k + 2];
    colours.add(((r >> 3) << 10) | ((g >> 3) << 5) | (b >> 3));
    if (Math.abs(r - SKY_RGB[0]) + Math.abs(g - SKY_RGB[1]) + Math.abs(b - SKY_RGB[2]) < 12) sky += 1;
    else if (r > 215 && g > 215 && b > 215) snow += 1;        // lit snow of the high peaks
    else if (r >= g && g >= b && r - b > 12) ground += 1;      // warm rock and dry ground
    const y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    sum += y; sumSq += y * y; n += 1;
  }
  const mean = sum / n;
  return { colours: colours.size, luminanceStd: Math.sqrt(sumSq / n - mean * mean), skyFraction: sky / n,
    snowFraction: snow / n, groundFraction: ground / n };
}

/** Asks the page for frames until it has drawn `n` more. */
export async function drawFrames(page, n) {
  await page.evaluate(() => { window.hexlod.mark = window.hexlod.frames; });
  await page.waitForFunction((k) => { window.hexlod.requestRender(); return window.hexlod.frames - window.hexlod.mark >= k; },
    n, { timeout: 120000, polling: 30 });
}

/** Resolves once the page has drawn a frame asked for after this call. */
export function nextFrame(page) {
  return page.evaluate(() => new Promise((resolve) => {
    const start = window.hexlod.frames;
    window.hexlod.requestRender();
    const poll = () => (window.hexlod.frames > start ? resolve() : requestAnimationFrame(poll));
    poll();
  }));
}

/**
 * What a person sees of the terrain: the share of the window where the terrain shows (the
 * terrain's pixels, drawn alone in one colour with view.terrainMask, outside the page's boxes:
 * HUD, panel, file bar, status line), and the distinct colours and luminance spread of those
 * pixels as drawn. Independent of the sky's and the plain ground's colours past the field.
 * @returns {Promise<{coverage: number, colours: number, luminanceStd: number, skyOnly: boolean}>}
 */
export async function terrainCoverage(page) {
  await nextFrame(page);
  const shown = decode(await page.screenshot());
  await page.evaluate(() => { window.hexlod.view.terrainMask = true; });
  await nextFrame(page);
  const mask = decode(await page.screenshot());
  await page.evaluate(() => { window.hexlod.view.terrainMask = false; });
  await nextFrame(page);
  const { width, height, channels } = shown;
  // The boxes in CSS pixels, scaled to the screenshot's device pixels.
  const boxes = await page.evaluate((shotWidth) => {
    const scale = shotWidth / window.innerWidth;
    return [...document.querySelectorAll('#hud, #intake, #panel .lil-root, #status, #help')]
      .map((e) => e.getBoundingClientRect()).filter((r) => r.width > 0 && r.height > 0)
      .map((r) => [r.left * scale, r.top * scale, r.right * scale, r.bottom * scale]);
  }, width);
  const colours = new Set();
  let terrain = 0, sum = 0, sumSq = 0;
  for (let y = 0; y < height; ++y) {
    for (let x = 0; x < width; ++x) {
      if (boxes.some(([l, t, r, b]) => x >= l && x < r && y >= t && y < b)) continue;
      const k = (y * width + x) * channels;
      const m = mask.data;
      // Magenta, or magenta blended with the black around it: the terrain, its antialiased edges included.
      if (!(m[k] > 16 && m[k + 2] > 16 && 4 * m[k + 1] < Math.min(m[k], m[k + 2]))) continue;
      const a = shown.data;
      terrain += 1;
      colours.add(((a[k] >> 3) << 10) | ((a[k + 1] >> 3) << 5) | (a[k + 2] >> 3));
      const l = 0.2126 * a[k] + 0.7152 * a[k + 1] + 0.0722 * a[k + 2];
      sum += l;
      sumSq += l * l;
    }
  }
  const mean = terrain ? sum / terrain : 0;
  return { coverage: terrain / (width * height), colours: colours.size,
    luminanceStd: terrain ? Math.sqrt(Math.max(sumSq / terrain - mean * mean, 0)) : 0, skyOnly: terrain === 0 };
}

/** Waits for the page's first terrain (or its error). */
export const pageReady = (page) =>
  page.waitForFunction(() => window.hexlod && window.hexlod.status !== 'loading', null, { timeout: 180000 });

/** Drops files on the page the way a browser does: a drop event carrying a DataTransfer. */
export async function dropFiles(page, files) {
  const payload = files.map(({ name, bytes }) => ({ name, data: Buffer.from(bytes).toString('base64') }));
  await page.evaluate((list) => {
    const transfer = new DataTransfer();
    for (const { name, data } of list) {
      transfer.items.add(new File([Uint8Array.from(atob(data), (c) => c.charCodeAt(0))], name));
    }
    window.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
  }, payload);
}

/** Waits until the terrain named `name` is on screen and nothing is loading; fails with the page's error. */
export async function terrainShown(page, name) {
  await page.waitForFunction((n) => !window.hexlod.loading && (window.hexlod.terrain?.name === n || window.hexlod.error),
    name, { timeout: 180000 });
  const { shown, error } = await page.evaluate(() => ({ shown: window.hexlod.terrain?.name, error: window.hexlod.error }));
  if (shown !== name) throw new Error(`${name} did not open: ${error}`);
}

/** Waits until the mesh has converged for the current camera. */
export const converged = (page) => page.waitForFunction(() => window.hexlod.converged, null, { timeout: 240000 });

/**
 * The camera as a person would judge it: the eye's height above the highest samples around it
 * (negative: inside the ground), when it is over the field, else null.
 */
export const eyeClearance = (page) => page.evaluate(() => {
  const { rig } = window.hexlod, eye = rig.active.position, world = rig.world;
  const over = eye[0] >= 0 && eye[2] >= 0 && eye[0] <= world.extentX && eye[2] <= world.extentZ;
  return over ? eye[1] - world.ground(eye[0], eye[2]) : null;
});
/**
 * The fraction of a PNG screenshot that is sky drawn by the scattering model (the page's sky,
 * not a clear colour): in each column, the run of blue pixels (blue above red and green) from
 * the top edge down to the first pixel that is not. Blue-grey shadows and haze on the terrain
 * below do not count.
 */
export function skyFromTop(png) {
  const { width, height, data, channels } = decode(png);
  let sky = 0;
  for (let x = 0; x < width; ++x) {
    for (let y = 0; y < height; ++y) {
      const k = (y * width + x) * channels;
      if (!(data[k + 2] > data[k] + 10 && data[k + 2] >= data[k + 1])) break;
      sky += 1;
    }
  }
  return sky / (width * height);
}
