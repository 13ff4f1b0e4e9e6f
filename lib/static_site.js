// A plain static file server, as any static host serves files: by path, with their content
// type, nothing else; plus request handlers under given URL prefixes. Two users: the browser
// tests' production build (dist/ under the sub-path /hexlod/, to show that it needs no server
// root, and the test fixtures under /fixtures/), and `hexlod regress` from an installed package,
// which serves the built site with its height fields and EPSG files (lib/regress_browser.js).
import { createServer } from 'node:http';
import { existsSync, readFileSync, statSync } from 'node:fs';
import { extname, normalize, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const projectDir = fileURLToPath(new URL('..', import.meta.url));

export const SITE_PATH = '/hexlod/';
const TYPES = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css',
  '.wasm': 'application/wasm', '.json': 'application/json', '.png': 'image/png', '.svg': 'image/svg+xml' };

/** The file a URL path names under the mounts, or null (never outside them). */
function fileFor(mounts, pathname) {
  for (const [prefix, dir] of mounts) {
    if (!pathname.startsWith(prefix)) continue;
    let rest = decodeURIComponent(pathname.slice(prefix.length));
    if (rest === '' || rest.endsWith('/')) rest += 'index.html';
    const file = normalize(dir + rest);
    if (!file.startsWith(normalize(dir)) || file.includes(`${sep}..${sep}`)) return null;
    return existsSync(file) && statSync(file).isFile() ? file : null;
  }
  return null;
}

/**
 * Serves files on a free localhost port: `mounts` maps URL prefixes to folders (each ending in
 * `/`); `handlers` are connect-style middleware `(request, response, next)` tried first, each
 * under its URL prefix, which is taken off request.url as connect's `use(prefix, fn)` does.
 * @param {{ mounts: [string, string][], handlers?: [string, Function][] }} what
 * @returns {Promise<{ origin: string, close: () => Promise<void> }>}
 */
export async function startFileServer({ mounts, handlers = [] }) {
  const serveFile = (request, response) => {
    const file = fileFor(mounts, new URL(request.url, 'http://localhost').pathname);
    if (!file) {
      response.writeHead(404, { 'content-type': 'text/plain' });
      response.end('not found');
      return;
    }
    response.writeHead(200, { 'content-type': TYPES[extname(file)] ?? 'application/octet-stream' });
    response.end(readFileSync(file));
  };
  const server = createServer((request, response) => {
    const url = request.url;
    const next = (k) => {
      const [prefix, handler] = handlers[k] ?? [];
      if (!handler) { request.url = url; serveFile(request, response); return; }
      if (!url.startsWith(prefix)) { next(k + 1); return; }
      request.url = url.slice(prefix.length).replace(/^(?!\/)/, '/');
      handler(request, response, () => next(k + 1));
    };
    next(0);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return { origin: `http://127.0.0.1:${server.address().port}`,
    close: () => new Promise((resolve) => { server.closeAllConnections(); server.close(resolve); }) };
}

/** Serves dist/ on a free localhost port; returns { url, fixturesUrl, close() }. */
export async function startStaticSite() {
  if (!existsSync(`${projectDir}dist/index.html`)) {
    throw new Error('dist/ has no built site: run ./build.sh site (the test command builds it)');
  }
  const { origin, close } = await startFileServer({ mounts: [[SITE_PATH, `${projectDir}dist/`], ['/fixtures/', `${projectDir}tests/fixtures/`]] });
  return { url: `${origin}${SITE_PATH}`, fixturesUrl: '/fixtures/', close };
}
