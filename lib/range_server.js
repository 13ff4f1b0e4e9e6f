// A small static file server for the streaming tests and benchmarks: serves the files of one
// folder with HTTP Range support (or, like some hosts, without it), with a delay per request,
// paths that answer 404, and connections that break after some bytes, counting the requests
// and body bytes of every path so a test can check how much a reader fetched. Any origin may
// read it (a page under test lives on another port), Range and Content-Range included.
import { createServer } from 'node:http';
import { createReadStream, existsSync, statSync } from 'node:fs';
import { join, normalize, sep } from 'node:path';

/**
 * @param {string} root the folder served (nothing outside it)
 * @param {object} [options] all can be changed later through server.options
 * @param {boolean} [options.range] honour Range requests (206); false answers 200 with the whole file
 * @param {number} [options.latencyMs] wait before each answer, as a distant server would
 * @param {Record<string, number>|string[]} [options.failPaths] paths answered 404: an array
 *   always, an object for that many requests each (then served)
 * @param {number|null} [options.dropAfterBytes] break the connection after that many body bytes of each answer
 * @returns {Promise<{ url: string, options: object, stats: (path: string) => { requests: number, bytes: number },
 *   reset: () => void, close: () => Promise<void> }>} url: the origin, without a trailing slash;
 *   stats: requests and body bytes sent of a path ('/name.tif'), zero for one never asked for
 */
export async function startRangeServer(root, options = {}) {
  const settings = { range: true, latencyMs: 0, failPaths: {}, dropAfterBytes: null, ...options };
  const counts = new Map();
  const failures = new Map(); // path -> 404s answered so far
  const base = normalize(root + sep);

  const server = createServer(async (request, response) => {
    response.setHeader('access-control-allow-origin', '*');
    response.setHeader('access-control-expose-headers', 'content-range, content-length, accept-ranges');
    if (request.method === 'OPTIONS') { // a browser's preflight for a Range request: not counted
      response.writeHead(204, { 'access-control-allow-headers': 'range', 'access-control-allow-methods': 'GET, HEAD' });
      response.end();
      return;
    }
    const path = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    const count = counts.get(path) ?? { requests: 0, bytes: 0 };
    counts.set(path, count);
    count.requests++;
    if (settings.latencyMs > 0) await new Promise((resolve) => setTimeout(resolve, settings.latencyMs));

    const file = normalize(join(base, path));
    const failing = Array.isArray(settings.failPaths) ? settings.failPaths.includes(path)
      : (failures.get(path) ?? 0) < (settings.failPaths[path] ?? 0);
    if (failing) failures.set(path, (failures.get(path) ?? 0) + 1);
    if (failing || !file.startsWith(base) || !existsSync(file) || !statSync(file).isFile()) {
      response.writeHead(404, { 'content-type': 'text/plain' });
      response.end('not found');
      return;
    }
    const size = statSync(file).size;
    let start = 0, end = size - 1, status = 200;
    const headers = { 'content-type': 'application/octet-stream', 'accept-ranges': settings.range ? 'bytes' : 'none' };
    const asked = settings.range && /^bytes=(\d*)-(\d*)$/.exec(request.headers.range ?? '');
    if (asked && (asked[1] !== '' || asked[2] !== '')) {
      if (asked[1] === '') { // a suffix: the last n bytes
        start = Math.max(0, size - Number(asked[2]));
      } else {
        start = Number(asked[1]);
        if (asked[2] !== '') end = Math.min(end, Number(asked[2]));
      }
      if (start >= size || start > end) {
        response.writeHead(416, { 'content-range': `bytes */${size}` });
        response.end();
        return;
      }
      status = 206;
      headers['content-range'] = `bytes ${start}-${end}/${size}`;
    }
    headers['content-length'] = String(end - start + 1);
    response.writeHead(status, headers);
    if (request.method === 'HEAD') { response.end(); return; }

    const limit = settings.dropAfterBytes ?? Infinity;
    let sent = 0;
    const stream = createReadStream(file, { start, end });
    stream.on('data', (chunk) => {
      const part = sent + chunk.length > limit ? chunk.subarray(0, limit - sent) : chunk;
      sent += part.length;
      count.bytes += part.length;
      // Only as fast as the client takes it: a client that cuts an answer off early then
      // leaves most of the file unsent, as it would over a real network.
      if (part.length > 0 && !response.write(part)) {
        stream.pause();
        response.once('drain', () => stream.resume());
      }
      if (sent >= limit) {
        stream.destroy();
        // The connection breaks with the answer half sent (once what was written has gone out).
        response.write('', () => response.socket?.destroy());
      }
    });
    stream.on('end', () => response.end());
    // A client that hangs up (a reader cutting off a whole-file answer) stops the reading.
    response.on('close', () => stream.destroy());
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return {
    url: `http://127.0.0.1:${server.address().port}`,
    options: settings,
    stats: (path) => ({ ...(counts.get(path) ?? { requests: 0, bytes: 0 }) }),
    reset: () => { counts.clear(); failures.clear(); },
    close: () => new Promise((resolve) => { server.closeAllConnections(); server.close(() => resolve()); }),
  };
}
