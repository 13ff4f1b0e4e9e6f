// A plain static file server for the production build (dist/), as any static host serves it:
// files by path with their content type, nothing else. The site lives under a sub-path
// (/hexlod/) to show that it needs no server root; the test fixtures are under /fixtures/.
import { createServer } from 'node:http';
import { existsSync, readFileSync, statSync } from 'node:fs';
import { extname, normalize, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const projectDir = fileURLToPath(new URL('..', import.meta.url));

export const SITE_PATH = '/hexlod/';
const TYPES = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.css': 'text/css',
  '.wasm': 'application/wasm', '.json': 'application/json', '.png': 'image/png', '.svg': 'image/svg+xml' };
const MOUNTS = [[SITE_PATH, `${projectDir}dist/`], ['/fixtures/', `${projectDir}tests/fixtures/`]];

/** The file a URL path names under the mounts, or null (never outside them). */
function fileFor(pathname) {
  for (const [prefix, dir] of MOUNTS) {
    if (!pathname.startsWith(prefix)) continue;
    let rest = decodeURIComponent(pathname.slice(prefix.length));
    if (rest === '' || rest.endsWith('/')) rest += 'index.html';
    const file = normalize(dir + rest);
    if (!file.startsWith(normalize(dir)) || file.includes(`${sep}..${sep}`)) return null;
    return existsSync(file) && statSync(file).isFile() ? file : null;
  }
  return null;
}

/** Serves dist/ on a free localhost port; returns { url, fixturesUrl, close() }. */
export async function startStaticSite() {
  if (!existsSync(`${projectDir}dist/index.html`)) {
    throw new Error('dist/ has no built site: run ./build.sh site (the test command builds it)');
  }
  const server = createServer((request, response) => {
    const file = fileFor(new URL(request.url, 'http://localhost').pathname);
    if (!file) {
      response.writeHead(404, { 'content-type': 'text/plain' });
      response.end('not found');
      return;
    }
    response.writeHead(200, { 'content-type': TYPES[extname(file)] ?? 'application/octet-stream' });
    response.end(readFileSync(file));
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const origin = `http://127.0.0.1:${server.address().port}`;
  return { url: `${origin}${SITE_PATH}`, fixturesUrl: '/fixtures/',
    close: () => new Promise((resolve) => { server.closeAllConnections(); server.close(resolve); }) };
}
