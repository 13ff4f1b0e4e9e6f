// A world DEM as one Cloud-Optimized GeoTIFF, made on demand: an HTTP server whose one file is a
// BigTIFF of any size (by default 1,296,000 x 626,400 Int16 samples at 1″ from 180° W, 90° N,
// as published world COGs are), tiled 512 x 512 with overviews halving down to one tile. No byte
// of it is stored: the header, the image directories and the tile tables are laid out at start,
// and every byte a Range request asks for is computed (the tables' entries by arithmetic, a tile's
// samples from a smooth function of longitude and latitude), so a 1.6 TB file costs nothing and a
// test can count what a reader fetched. It answers Range requests only, with latency, and counts
// requests and body bytes.
//
// The layout is GDAL's COG order: the header, every directory (full resolution first), their
// out-of-line values, the tile tables (full resolution first), then the tiles, coarsest level
// first. Tiles are uncompressed, so a tile's offset and size follow from its index.
import { createServer } from 'node:http';

const TILE = 512;
const SAMPLE_BYTES = 2;
const TILE_BYTES = TILE * TILE * SAMPLE_BYTES;
const SHORT = 3, LONG = 4, LONG8 = 16, DOUBLE = 12;

/** The height of the virtual world at a longitude and latitude in degrees: smooth ridges, -500..4,500 m. */
export function worldHeight(lon, lat) {
  const rad = Math.PI / 180;
  return Math.round(2000 + 1500 * Math.sin(lon * rad * 40) * Math.cos(lat * rad * 30) + 1000 * Math.sin((lon + lat) * rad * 7));
}

/**
 * The file's layout: its levels and where everything lies.
 * @param {number} width full-resolution samples across
 * @param {number} height rows
 */
export function worldLayout(width = 1296000, height = 626400) {
  const levels = [];
  for (let w = width, h = height; ; w = Math.ceil(w / 2), h = Math.ceil(h / 2)) {
    levels.push({ width: w, height: h, across: Math.ceil(w / TILE), down: Math.ceil(h / TILE) });
    if (w <= TILE && h <= TILE) break;
  }
  const pixelDegrees = 360 / width;
  const directories = [];
  let at = 16;
  for (const [index, level] of levels.entries()) {
    const entries = index === 0 ? 16 : 13;
    directories.push({ at, entries });
    at += 8 + entries * 20 + 8;
  }
  const values = at; // out-of-line values of the first directory: pixel scale, tie point, geokeys
  at += 24 + 48 + 32;
  for (const level of levels) {
    level.tiles = level.across * level.down;
    level.offsetsAt = at;
    level.countsAt = at + level.tiles * 8;
    at += level.tiles * 16;
  }
  for (let i = levels.length - 1; i >= 0; i--) { // coarsest first, as GDAL writes them
    levels[i].dataAt = at;
    at += levels[i].tiles * TILE_BYTES;
  }
  return { width, height, levels, directories, values, tablesAt: levels[0].offsetsAt, dataAt: levels.at(-1).dataAt, size: at, pixelDegrees };
}

/** The bytes before the tile tables: header, directories, out-of-line values. */
function headBytes(layout) {
  const bytes = new Uint8Array(layout.tablesAt);
  const view = new DataView(bytes.buffer);
  bytes.set([0x49, 0x49, 43, 0, 8, 0, 0, 0]);
  view.setBigUint64(8, BigInt(layout.directories[0].at), true);
  const { values } = layout;
  view.setFloat64(values, layout.pixelDegrees, true);
  view.setFloat64(values + 8, layout.pixelDegrees, true);
  [0, 0, 0, -180, 90, 0].forEach((v, k) => view.setFloat64(values + 24 + k * 8, v, true));
  [1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326].forEach((v, k) => view.setUint16(values + 72 + k * 2, v, true));
  layout.levels.forEach((level, index) => {
    const { at, entries } = layout.directories[index];
    const fields = [
      [254, LONG, 1, index === 0 ? 0 : 1], [256, LONG, 1, level.width], [257, LONG, 1, level.height],
      [258, SHORT, 1, 16], [259, SHORT, 1, 1], [262, SHORT, 1, 1], [277, SHORT, 1, 1], [284, SHORT, 1, 1],
      // A one-tile table fits in its entry (8 bytes): the entry holds the value itself.
      [322, SHORT, 1, TILE], [323, SHORT, 1, TILE], [324, LONG8, level.tiles, level.tiles === 1 ? level.dataAt : level.offsetsAt],
      [325, LONG8, level.tiles, level.tiles === 1 ? TILE_BYTES : level.countsAt], [339, SHORT, 1, 2],
    ];
    if (index === 0) fields.push([33550, DOUBLE, 3, values], [33922, DOUBLE, 6, values + 24], [34735, SHORT, 16, values + 72]);
    if (fields.length !== entries) throw new Error('directory entries miscounted');
    view.setBigUint64(at, BigInt(entries), true);
    fields.forEach(([tag, type, count, value], k) => {
      const e = at + 8 + k * 20;
      view.setUint16(e, tag, true);
      view.setUint16(e + 2, type, true);
      view.setBigUint64(e + 4, BigInt(count), true);
      const inline = count === 1 && type !== DOUBLE;
      if (inline && type === SHORT) view.setUint16(e + 12, value, true);
      else if (inline && type === LONG) view.setUint32(e + 12, value, true);
      else view.setBigUint64(e + 12, BigInt(value), true); // a LONG8 count-1 value, or where the values lie
    });
    const next = index + 1 < layout.levels.length ? layout.directories[index + 1].at : 0;
    view.setBigUint64(at + 8 + entries * 20, BigInt(next), true);
  });
  return bytes;
}

/** One tile's samples as the file stores them (little-endian Int16, rows north to south). */
export function worldTile(layout, levelIndex, tx, ty, heights = worldHeight) {
  const level = layout.levels[levelIndex];
  const degrees = 360 / level.width; // square samples, as at full resolution (the last row may run short)
  const bytes = new Uint8Array(TILE_BYTES);
  const view = new DataView(bytes.buffer);
  for (let row = 0; row < TILE; row++) {
    const lat = 90 - (ty * TILE + row + 0.5) * degrees;
    for (let col = 0; col < TILE; col++) {
      const lon = -180 + (tx * TILE + col + 0.5) * degrees;
      view.setInt16((row * TILE + col) * 2, heights(lon, lat), true);
    }
  }
  return bytes;
}

/** The file's bytes [start, end), computed. */
function fileBytes(layout, head, start, end, tileCache, heights) {
  const out = new Uint8Array(end - start);
  for (let p = start; p < end;) {
    if (p < layout.tablesAt) {
      const stop = Math.min(end, layout.tablesAt);
      out.set(head.subarray(p, stop), p - start);
      p = stop;
    } else if (p < layout.dataAt) {
      // One table entry (8 bytes, little-endian), written whole then cut to the range.
      const level = layout.levels.find((l) => p >= l.offsetsAt && p < l.offsetsAt + l.tiles * 16);
      const inCounts = p >= level.countsAt;
      const index = Math.floor((p - (inCounts ? level.countsAt : level.offsetsAt)) / 8);
      const entryAt = (inCounts ? level.countsAt : level.offsetsAt) + index * 8;
      const entry = new Uint8Array(8);
      new DataView(entry.buffer).setBigUint64(0, BigInt(inCounts ? TILE_BYTES : level.dataAt + index * TILE_BYTES), true);
      const stop = Math.min(end, entryAt + 8);
      out.set(entry.subarray(p - entryAt, stop - entryAt), p - start);
      p = stop;
    } else {
      const levelIndex = layout.levels.findIndex((l) => p >= l.dataAt && p < l.dataAt + l.tiles * TILE_BYTES);
      const level = layout.levels[levelIndex];
      const index = Math.floor((p - level.dataAt) / TILE_BYTES), tileAt = level.dataAt + index * TILE_BYTES;
      const key = `${levelIndex}:${index}`;
      let tile = tileCache.get(key);
      if (!tile) {
        tile = worldTile(layout, levelIndex, index % level.across, Math.floor(index / level.across), heights);
        tileCache.set(key, tile);
        if (tileCache.size > 64) tileCache.delete(tileCache.keys().next().value);
      }
      const stop = Math.min(end, tileAt + TILE_BYTES);
      out.set(tile.subarray(p - tileAt, stop - tileAt), p - start);
      p = stop;
    }
  }
  return out;
}

/**
 * Serves the virtual world at /world.tif.
 * @param {{ width?: number, height?: number, latencyMs?: number, heights?: (lon: number, lat: number) => number }} [options]
 *   heights: metres (rounded to Int16) at a sample's centre; worldHeight unless given
 * @returns {Promise<{ url: string, layout: ReturnType<typeof worldLayout>,
 *   stats: () => { requests: number, bytes: number }, reset: () => void, close: () => Promise<void> }>}
 *   url: the file's address
 */
export async function startWorldCogServer({ width, height, latencyMs = 0, heights = worldHeight } = {}) {
  const layout = worldLayout(width, height);
  const head = headBytes(layout);
  const tileCache = new Map();
  const stats = { requests: 0, bytes: 0 };
  const server = createServer(async (request, response) => {
    response.setHeader('access-control-allow-origin', '*');
    response.setHeader('access-control-expose-headers', 'content-range, content-length, accept-ranges');
    if (request.method === 'OPTIONS') {
      response.writeHead(204, { 'access-control-allow-headers': 'range', 'access-control-allow-methods': 'GET, HEAD' });
      response.end();
      return;
    }
    if (new URL(request.url, 'http://localhost').pathname !== '/world.tif') {
      response.writeHead(404).end();
      return;
    }
    stats.requests++;
    if (latencyMs > 0) await new Promise((resolve) => setTimeout(resolve, latencyMs));
    const range = /^bytes=(\d+)-(\d*)$/.exec(request.headers.range ?? '');
    if (!range) { // the whole file is never sent: 1.6 TB
      response.writeHead(416, { 'content-range': `bytes */${layout.size}` }).end();
      return;
    }
    const start = Number(range[1]);
    const end = Math.min(layout.size, range[2] === '' ? layout.size : Number(range[2]) + 1, start + 64 * 2 ** 20);
    if (start >= layout.size) {
      response.writeHead(416, { 'content-range': `bytes */${layout.size}` }).end();
      return;
    }
    const body = fileBytes(layout, head, start, end, tileCache, heights);
    stats.bytes += body.length;
    response.writeHead(206, { 'content-range': `bytes ${start}-${end - 1}/${layout.size}`, 'content-length': body.length,
      'accept-ranges': 'bytes', 'content-type': 'image/tiff' });
    response.end(body);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const origin = `http://127.0.0.1:${server.address().port}`;
  return {
    url: `${origin}/world.tif`, layout,
    stats: () => ({ ...stats }),
    reset: () => { stats.requests = 0; stats.bytes = 0; },
    close: () => new Promise((resolve) => { server.closeAllConnections?.(); server.close(() => resolve()); }),
  };
}
