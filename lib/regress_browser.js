// The page for `hexlod regress`, and headless Chromium (lib/chromium.js) through playwright-core,
// the same way the browser tests run the page. Which page depends on where hexlod runs:
//
// - In a checkout (src/ is there): Vite's dev server over the source, started from node_modules.
//   The page is plain ES modules, but it imports bare npm specifiers (gl-matrix, lil-gui, fflate,
//   geotiff and geotiff's own dependencies) and its shaders as `?raw` text modules; serving the
//   source ourselves would mean re-implementing both resolutions and keeping them in step with
//   every import someone adds, and serving a `vite build` output would test a build that may be
//   older than the source. Run programmatically, Vite starts in about a second.
// - In an installed package (no src/, no Vite: a development dependency): the built site, dist/,
//   which `npm pack` builds from the same source as the package's WebAssembly (prepack), served
//   by a plain static server. The EPSG files the page may fetch (crs/CODE.json) are answered from
//   the epsg-index and proj4-list packages, as the dev server answers them, so the package does
//   not carry the 34 MB of dist/crs/.
//
// The height fields and flights are served by a small middleware from wherever they are on
// disk, under /__regress/, by either server.
import { existsSync, readFileSync } from 'node:fs';
import { basename, dirname, extname, join } from 'node:path';
import { createHash } from 'node:crypto';
import { tmpdir } from 'node:os';
import { fileURLToPath } from 'node:url';
import { EnvironmentError, freePort, launchChromium } from './chromium.js';
import { startFileServer } from './static_site.js';
import { crsFilesMiddleware } from './crs_files_plugin.js';
import { inCheckout } from './node_core.js';

export const projectDir = fileURLToPath(new URL('..', import.meta.url));

/** Files the middleware may serve: /__regress/<id>/<kind>/<name> -> their bytes. */
class FileTable {
  constructor() { this.files = new Map(); }

  /**
   * Registers files under one id and kind (a height field with its sidecar, or a flight file);
   * returns the URL path of the first.
   * @param {{name: string, bytes: Uint8Array}[]} files
   */
  add(id, kind, files) {
    for (const { name, bytes } of files) this.files.set(`/${id}/${kind}/${name}`, { name, bytes });
    return `/__regress/${id}/${kind}/${encodeURIComponent(files[0].name)}`;
  }

  /** Registers a file on disk and, for a height field, its NAME.json sidecar beside it. */
  addPath(id, kind, path) {
    const files = [{ name: basename(path), bytes: readFileSync(path) }];
    const sidecar = join(dirname(path), `${basename(path, extname(path))}.json`);
    if (kind === 'dem' && extname(path).toLowerCase() !== '.json' && existsSync(sidecar)) {
      files.push({ name: basename(sidecar), bytes: readFileSync(sidecar) });
    }
    return this.add(id, kind, files);
  }

  middleware() {
    return (req, res) => {
      const file = this.files.get(decodeURIComponent(req.url.split('?')[0]));
      if (!file) {
        // Not ours (the page asks for a sidecar that may not exist): a plain 404, never Vite's HTML.
        res.statusCode = 404;
        res.setHeader('Content-Type', 'text/plain');
        res.end('not found');
        return;
      }
      res.setHeader('Content-Type', extname(file.name).toLowerCase() === '.json' ? 'application/json' : 'application/octet-stream');
      res.setHeader('Content-Length', file.bytes.length);
      res.setHeader('Cache-Control', 'no-store');
      res.end(file.bytes);
    };
  }
}

/**
 * Starts the page's server (see the top of this file) and Chromium (`chromium`: the program, else
 * lib/chromium.js finds one). Throws one-line EnvironmentErrors for a missing Chromium or server.
 * @param {{ chromium?: string, site?: 'source'|'built' }} [options] site: which page to serve
 *   (default: the source in a checkout, the built site in an installed package)
 * @returns {Promise<{files: FileTable, url: string, site: string, browser: object, close: () => Promise<void>}>}
 */
export async function startBrowser({ chromium: chromiumPath, site = inCheckout() ? 'source' : 'built' } = {}) {
  const browser = await launchChromium(chromiumPath); // first: a missing Chromium is the likelier mistake
  const files = new FileTable();
  let server;
  try {
    server = site === 'source' ? await startDevServer(files) : await startBuiltSite(files);
  } catch (error) {
    await browser.close();
    throw error instanceof EnvironmentError ? error : new EnvironmentError(`the page's server did not start: ${String(error.message).split('\n')[0]}`);
  }
  return {
    files,
    url: server.url,
    site,
    browser,
    async close() {
      await browser.close().catch(() => {});
      await server.close();
    },
  };
}

/** Vite's dev server over the source, with the /__regress/ files. */
async function startDevServer(files) {
  let createServer;
  try {
    ({ createServer } = await import('vite'));
  } catch {
    throw new EnvironmentError('in a checkout hexlod regress serves the page from source with Vite, a development dependency, which is not installed: run npm ci');
  }
  let server;
  try {
    server = await createServer({
      configFile: join(projectDir, 'vite.config.js'),
      root: join(projectDir, 'public'),
      // A cache of its own per checkout, so parallel runs elsewhere never share a half-written one.
      cacheDir: join(tmpdir(), `hexlod-regress-vite-${createHash('sha1').update(projectDir).digest('hex').slice(0, 12)}`),
      // Pre-bundle the npm imports up front: a dependency discovered mid-run makes Vite reload the page.
      optimizeDeps: { include: ['gl-matrix', 'lil-gui', 'fflate', 'geotiff'] },
      server: { port: await freePort(), strictPort: true, host: '127.0.0.1', hmr: false, watch: null },
      logLevel: 'error',
      plugins: [{ name: 'hexlod-regress-files', configureServer: (s) => { s.middlewares.use('/__regress', files.middleware()); } }],
    });
    await server.listen();
  } catch (error) {
    throw new EnvironmentError(`the page's dev server (Vite) did not start: ${String(error.message).split('\n')[0]}`);
  }
  return { url: `http://127.0.0.1:${server.httpServer.address().port}/`, close: () => server.close() };
}

/** The built site, dist/, with the /__regress/ files and crs/CODE.json from the packages. */
async function startBuiltSite(files) {
  const dist = join(projectDir, 'dist/');
  if (!existsSync(join(dist, 'index.html'))) {
    throw new EnvironmentError(inCheckout()
      ? `${dist} has no built site: run ./build.sh site`
      : `this hexlod package has no built page (${dist}index.html): reinstall it (npm install hexlod)`);
  }
  const { origin, close } = await startFileServer({ mounts: [['/', dist]],
    handlers: [['/__regress', files.middleware()], ['/', crsFilesMiddleware()]] });
  return { url: `${origin}/`, close };
}

/**
 * Flies one flight in a new page: captures the pixels of `captures` and the figures of every frame.
 * A browser that dies on the way throws EnvironmentError; a page that fails throws Error.
 * @param {{id: string|number, demFiles: {name: string, bytes: Uint8Array}[], flightPath: string, flight: object,
 *   layerFiles?: Array<import('./image_files.js').ImageFiles|null>, overlayFiles?: Array<{name: string, bytes: Uint8Array}>,
 *   trackFile?: {name: string, bytes: Uint8Array}|null}} job layerFiles: each image layer's files (null for a
 *   layer of another kind), in the flight's order; overlayFiles: its overlays'; trackFile: its track's
 * @returns {Promise<{stats: object[], images: Map<number, {width, height, rgb: Uint8Array}>, problems: string[]}>}
 */
export async function flyInPage(session, { id, demFiles, layerFiles = [], overlayFiles = [], trackFile = null, flightPath, flight, timeoutMs = 300000 }) {
  if (!session.browser.isConnected()) throw new EnvironmentError('the browser closed during the run');
  const dem = session.files.add(id, 'dem', demFiles);
  const flightUrl = session.files.addPath(id, 'flight', flightPath);
  // The images by URL parameters, as the height field: the page then looks for no world file itself.
  let imageQuery = '';
  layerFiles.forEach((files, k) => {
    if (!files) return;
    imageQuery += `&image${k}=${encodeURIComponent(session.files.add(id, `image${k}`, [files.image]))}`;
    if (files.worldFile) imageQuery += `&world${k}=${encodeURIComponent(session.files.add(id, `world${k}`, [files.worldFile]))}`;
  });
  // Its overlays and its track likewise.
  overlayFiles.forEach((file, k) => { imageQuery += `&overlay${k}=${encodeURIComponent(session.files.add(id, `overlay${k}`, [file]))}`; });
  if (trackFile) imageQuery += `&track=${encodeURIComponent(session.files.add(id, 'track', [trackFile]))}`;
  const [w, h] = flight.viewport;
  const page = await session.browser.newPage({ viewport: { width: w, height: h }, deviceScaleFactor: flight.dpr });
  const problems = [];
  page.on('console', (m) => {
    // The page asks for a NAME.json sidecar beside every height field; a missing one is no problem.
    const sidecar404 = /\/__regress\/.*\.json$/.test(m.location()?.url ?? '') && /status of 404/.test(m.text());
    if (m.type() === 'error' && !sidecar404) problems.push(`console.error: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.setDefaultTimeout(timeoutMs);
  try {
    await page.goto(`${session.url}?src=${encodeURIComponent(dem)}&flight=${encodeURIComponent(flightUrl)}${imageQuery}`);
    await page.waitForFunction(() => window.hexlod && (window.hexlod.status === 'error' || window.hexlod.flight), null, { timeout: timeoutMs });
    const start = await withTimeout(page.evaluate(async () => {
      try {
        return { ok: await window.hexlod.flight.ready };
      } catch (error) {
        return { error: window.hexlod.error ?? error.message };
      }
    }), timeoutMs, 'loading the terrain').catch((error) => ({ error: error.message }));
    if (start.error) throw new Error(`the page did not start the flight: ${start.error}`);
    const images = new Map();
    for (const frame of flight.captures) {
      const { pixels } = await withTimeout(page.evaluate((n) => window.hexlod.flight.frame(n, { pixels: true }), frame), timeoutMs, `frame ${frame}`);
      images.set(frame, toRgb(pixels));
    }
    await withTimeout(page.evaluate((n) => window.hexlod.flight.frame(n), flight.frames - 1), timeoutMs, `frame ${flight.frames - 1}`);
    const stats = await page.evaluate(() => window.hexlod.flight.stats());
    return { stats, images, problems };
  } catch (error) {
    if (!session.browser.isConnected() || /Target (page, context or browser )?(has been )?closed|crashed/i.test(error.message)) {
      throw new EnvironmentError(`the browser closed or crashed during the flight: ${String(error.message).split('\n')[0]}`);
    }
    throw error;
  } finally {
    await page.close().catch(() => {});
  }
}

/** `promise`, or an error naming `what` after `ms` milliseconds (page.evaluate has no timeout of its own). */
function withTimeout(promise, ms, what) {
  let timer;
  const timeout = new Promise((_, reject) => { timer = setTimeout(() => reject(new Error(`${what}: no answer from the page in ${ms / 1000} s`)), ms); });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

/** RGBA rows bottom first (readPixels) -> RGB rows top first. */
function toRgb({ width, height, base64 }) {
  const rgba = Buffer.from(base64, 'base64');
  const rgb = new Uint8Array(width * height * 3);
  for (let y = 0; y < height; y++) {
    const from = (height - 1 - y) * width * 4, to = y * width * 3;
    for (let x = 0; x < width; x++) {
      rgb[to + 3 * x] = rgba[from + 4 * x];
      rgb[to + 3 * x + 1] = rgba[from + 4 * x + 1];
      rgb[to + 3 * x + 2] = rgba[from + 4 * x + 2];
    }
  }
  return { width, height, rgb };
}
