// A web map tile server for the tests of web/webtiles/: serves a folder of {z}/{x}/{y}.png
// tiles (gdal2tiles --xyz writes them so) as XYZ, as WMTS REST (an address ending in
// /{TileMatrix}/{TileRow}/{TileCol}.png) and as WMTS KVP (GetTile), with a GetCapabilities
// document whose addresses name this server. It logs every request, so a test can check which
// tiles were asked for, and it can be made to fail the ways real servers do:
//   'missing'   every tile answers 404
//   'no-cors'   answers without Access-Control-Allow-Origin (a browser refuses to read them)
//   'down'      the port is closed: connections are refused
//   'slow'      every answer waits slowMs
//   'not-image' tiles answer 200 with an HTML page
import { createServer } from 'node:http';
import { existsSync, readFileSync, statSync } from 'node:fs';
import { join } from 'node:path';

/** The host the capabilities fixture names; served documents name the server instead. */
export const FIXTURE_HOST = 'http://tiles.example.test';
export const TILE_FAULTS = [null, 'missing', 'no-cors', 'down', 'slow', 'not-image'];

/**
 * @param {string} root the folder of {z}/{x}/{y}.png
 * @param {object} [options]
 * @param {number} [options.latencyMs] wait before each answer
 * @param {number} [options.slowMs] the wait of the 'slow' fault
 * @param {string|null} [options.capabilities] path of a WMTS capabilities document to serve at /wmts
 * @param {string|null} [options.fault] one of TILE_FAULTS (setFault changes it)
 * @param {number[]} [options.missingZooms] zooms whose tiles all answer 404 (a service that lacks them)
 * @returns {Promise<{ url: string, options: object, log: { path: string, tile: string|null, status: number, mode: string }[],
 *   tilesRequested: () => string[], setFault: (fault: string|null) => Promise<void>, reset: () => void, close: () => Promise<void> }>}
 *   url: the origin (no trailing slash); log: every request (tile: 'z/x/y' or null); tilesRequested: the tiles asked for, in order
 */
export async function startTileServer(root, options = {}) {
  const settings = { latencyMs: 0, slowMs: 2000, capabilities: null, fault: null, missingZooms: [], ...options };
  const log = [];
  let url = '';

  const server = createServer(async (request, response) => {
    const address = new URL(request.url, 'http://localhost');
    const tile = tileOf(address);
    const entry = { path: address.pathname + address.search, tile: tile ? tile.join('/') : null, status: 0,
      mode: request.headers['sec-fetch-mode'] ?? '' };
    log.push(entry);
    const wait = settings.latencyMs + (settings.fault === 'slow' ? settings.slowMs : 0);
    if (wait > 0) await new Promise((resolve) => setTimeout(resolve, wait));
    const headers = settings.fault === 'no-cors' ? {} : { 'access-control-allow-origin': '*' };
    const answer = (status, type, body) => {
      entry.status = status;
      if (response.destroyed) return;
      response.writeHead(status, { ...headers, 'content-type': type, 'content-length': body.length });
      response.end(body);
    };
    const isCapabilities = address.pathname === '/wmts' && (address.searchParams.get('REQUEST') ?? address.searchParams.get('request') ?? '')
      .toLowerCase() === 'getcapabilities';
    if (isCapabilities && settings.capabilities) {
      return answer(200, 'application/xml', Buffer.from(readFileSync(settings.capabilities, 'utf8').replaceAll(FIXTURE_HOST, url)));
    }
    if (!tile) return answer(404, 'text/plain', Buffer.from('not found'));
    if (settings.fault === 'missing' || settings.missingZooms.includes(tile[0])) return answer(404, 'text/plain', Buffer.from('tile not found'));
    if (settings.fault === 'not-image') return answer(200, 'text/html', Buffer.from('<!doctype html><title>Error</title><p>No tile here.</p>'));
    const file = join(root, String(tile[0]), String(tile[1]), `${tile[2]}.png`);
    if (!existsSync(file) || !statSync(file).isFile()) return answer(404, 'text/plain', Buffer.from('tile not found'));
    return answer(200, 'image/png', readFileSync(file));
  });

  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const port = server.address().port;
  url = `http://127.0.0.1:${port}`;
  let listening = true;

  const stop = () => new Promise((resolve) => {
    listening = false;
    server.closeAllConnections();
    server.close(() => resolve());
  });
  const start = () => new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(port, '127.0.0.1', () => { server.off('error', reject); listening = true; resolve(); });
  });

  return {
    url,
    options: settings,
    log,
    tilesRequested: () => log.filter((e) => e.tile !== null).map((e) => e.tile),
    /** Switches the fault; 'down' closes the port, and any other opens it again (the same port). */
    async setFault(fault) {
      if (!TILE_FAULTS.includes(fault)) throw new Error(`unknown tile server fault '${fault}' (${TILE_FAULTS.join(', ')})`);
      settings.fault = fault;
      if (fault === 'down' && listening) await stop();
      if (fault !== 'down' && !listening) await start();
    },
    reset: () => { log.length = 0; },
    close: async () => { if (listening) await stop(); },
  };
}

/** [z, x, y] of a tile address (XYZ, WMTS REST or KVP), or null. */
function tileOf(address) {
  const xyz = /^\/(\d+)\/(\d+)\/(\d+)\.png$/.exec(address.pathname);
  if (xyz) return [Number(xyz[1]), Number(xyz[2]), Number(xyz[3])];
  // WMTS REST: .../{TileMatrix}/{TileRow}/{TileCol}.png, the matrix named by its zoom.
  const rest = /^\/wmts\/.*\/(?:[^/]*?)(\d+)\/(\d+)\/(\d+)\.png$/.exec(address.pathname);
  if (rest) return [Number(rest[1]), Number(rest[3]), Number(rest[2])];
  if (address.pathname === '/wmts') {
    const q = (name) => address.searchParams.get(name) ?? address.searchParams.get(name.toLowerCase());
    if ((q('REQUEST') ?? '').toLowerCase() !== 'gettile') return null;
    const z = /(\d+)$/.exec(q('TILEMATRIX') ?? '')?.[1];
    const row = q('TILEROW'), col = q('TILECOL');
    if (z !== undefined && /^\d+$/.test(row ?? '') && /^\d+$/.test(col ?? '')) return [Number(z), Number(col), Number(row)];
  }
  return null;
}
