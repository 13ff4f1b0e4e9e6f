// The page for `hexlod regress`: Vite's dev server started from node_modules, and Debian's
// Chromium through playwright-core, the same way the browser tests run the page.
//
// Why Vite and not a static server of our own: the page is plain ES modules, but it imports
// bare npm specifiers (gl-matrix, lil-gui, fflate, geotiff and geotiff's own dependencies) and
// its shaders as `?raw` text modules; serving the source ourselves would mean re-implementing
// both resolutions and keeping them in step with every import someone adds, and serving a
// `vite build` output would test a build that may be older than the source. Vite is already in
// the lockfile (`./hexlod.sh view` serves with it), and run programmatically it starts in about
// a second. The height fields and flights are served by a small middleware from wherever they
// are on disk, under /__regress/.
import { existsSync, readFileSync } from 'node:fs';
import { basename, dirname, extname, join } from 'node:path';
import { createHash } from 'node:crypto';
import { tmpdir } from 'node:os';
import { fileURLToPath } from 'node:url';
import { DEFAULT_CHROMIUM, freePort, launchChromium } from './chromium.js';

export const projectDir = fileURLToPath(new URL('..', import.meta.url));
export { DEFAULT_CHROMIUM };

/** Files the middleware may serve: /__regress/<id>/<kind>/<name> -> absolute path. */
class FileTable {
  constructor() { this.files = new Map(); }

  /** Registers a file (and, for a height field, its NAME.json sidecar); returns its URL path. */
  add(id, kind, path) {
    const name = basename(path);
    this.files.set(`/${id}/${kind}/${name}`, path);
    if (kind === 'dem') {
      const sidecar = join(dirname(path), `${basename(path, extname(path))}.json`);
      if (extname(path).toLowerCase() !== '.json' && existsSync(sidecar)) this.files.set(`/${id}/${kind}/${basename(sidecar)}`, sidecar);
    }
    return `/__regress/${id}/${kind}/${encodeURIComponent(name)}`;
  }

  middleware() {
    return (req, res, next) => {
      const path = this.files.get(decodeURIComponent(req.url.split('?')[0]));
      if (!path) {
        // Not ours (the page asks for a sidecar that may not exist): a plain 404, never Vite's HTML.
        res.statusCode = 404;
        res.setHeader('Content-Type', 'text/plain');
        res.end('not found');
        return;
      }
      const bytes = readFileSync(path);
      res.setHeader('Content-Type', extname(path).toLowerCase() === '.json' ? 'application/json' : 'application/octet-stream');
      res.setHeader('Content-Length', bytes.length);
      res.setHeader('Cache-Control', 'no-store');
      res.end(bytes);
    };
  }
}

/**
 * Starts the dev server and Chromium. Throws one-line errors for a missing Chromium.
 * @returns {Promise<{files: FileTable, url: string, browser: object, close: () => Promise<void>}>}
 */
export async function startBrowser({ chromium: chromiumPath = process.env.CHROMIUM_PATH || DEFAULT_CHROMIUM } = {}) {
  const browser = await launchChromium(chromiumPath); // first: a missing Chromium is the likelier mistake
  const { createServer } = await import('vite');
  const files = new FileTable();
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
    await browser.close();
    throw error;
  }
  const { port } = server.httpServer.address();
  return {
    files,
    url: `http://127.0.0.1:${port}/`,
    browser,
    async close() {
      await browser.close().catch(() => {});
      await server.close();
    },
  };
}

/**
 * Flies one flight in a new page: captures the pixels of `captures` and the figures of every frame.
 * @returns {Promise<{stats: object[], images: Map<number, {width, height, rgb: Uint8Array}>, problems: string[]}>}
 */
export async function flyInPage(session, { id, demPath, flightPath, flight, timeoutMs = 300000 }) {
  const dem = session.files.add(id, 'dem', demPath);
  const flightUrl = session.files.add(id, 'flight', flightPath);
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
    await page.goto(`${session.url}?src=${encodeURIComponent(dem)}&flight=${encodeURIComponent(flightUrl)}`);
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
  } finally {
    await page.close();
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
