// Byte ranges of a file that is not all here: a URL read by HTTP Range requests, or a Blob or
// File read by slice (a dropped file is never read whole). Both count what they fetched, so
// tests and the HUD can show how little of a large file a view needed.

import { TileError, checkAborted } from './tile_error.js';

/**
 * @typedef {object} RangeReader
 * @property {(offset: number, length: number, signal?: AbortSignal) => Promise<Uint8Array>} read
 *   bytes [offset, offset + length), fewer where the file ends before (none past its end)
 * @property {number|null} size the file's length in bytes, once known (null before the first
 *   answer of a server)
 * @property {{ requests: number, bytes: number }} stats requests made (every try counts) and
 *   body bytes received
 * @property {string} name for messages
 */

/**
 * @param {string} url
 * @param {{ retries?: number, backoffMs?: number, fetch?: typeof fetch }} [options] retries:
 *   further tries after a failed one (an error status or a broken connection); backoffMs: the
 *   wait before the first retry, doubled before each next one
 * @returns {RangeReader}
 */
export function urlReader(url, { retries = 3, backoffMs = 250, fetch: fetchFn = globalThis.fetch } = {}) {
  const reader = {
    name: url,
    size: null,
    stats: { requests: 0, bytes: 0 },
    async read(offset, length, signal) {
      if (length <= 0) return new Uint8Array(0);
      for (let attempt = 0; ; attempt++) {
        try {
          return await readOnce(offset, length, signal);
        } catch (e) {
          if (!e.transient) throw e;
          if (attempt >= retries) {
            const tries = attempt + 1;
            throw new TileError(e.kind, `${url}: ${e.message} (${tries} ${tries === 1 ? 'try' : 'tries'})`, { status: e.status, cause: e.cause });
          }
          await pause(backoffMs * 2 ** attempt, signal, url);
        }
      }
    },
  };

  async function readOnce(offset, length, signal) {
    checkAborted(signal, url);
    // Our own controller: a body we do not want (a whole file sent for a range) is cut off here.
    const controller = new AbortController();
    const forward = () => controller.abort(signal.reason);
    signal?.addEventListener('abort', forward, { once: true });
    reader.stats.requests++;
    try {
      let response;
      try {
        response = await fetchFn(url, { headers: { Range: `bytes=${offset}-${offset + length - 1}` }, signal: controller.signal });
      } catch (e) {
        checkAborted(signal, url);
        throw transient('network', `no answer (${e?.cause?.code ?? e?.message ?? e})`, e);
      }
      if (response.status === 200) {
        // The whole file is on its way: stop it before it arrives, and say how big it is.
        controller.abort();
        const declared = Number(response.headers.get('content-length'));
        const size = Number.isFinite(declared) && response.headers.has('content-length') ? declared : null;
        if (size !== null) reader.size = size;
        throw new TileError('no-range', `${url}: the server ignores Range requests and sends the whole file` +
          `${size === null ? '' : ` (${size} bytes)`}; load it whole, or serve it from a host that honours Range`, { size });
      }
      if (response.status === 416) { // the range starts at or past the end
        controller.abort();
        noteTotal(response.headers.get('content-range'));
        return new Uint8Array(0);
      }
      if (response.status !== 206) {
        controller.abort();
        const error = transient('http', `HTTP ${response.status} ${response.statusText}`.trim());
        error.status = response.status;
        throw error;
      }
      const range = /^bytes (\d+)-(\d+)\/(\d+|\*)$/.exec(response.headers.get('content-range') ?? '');
      if (!range || Number(range[1]) !== offset) {
        controller.abort();
        throw new TileError('http', `${url}: the server answered bytes ${offset}.. with "${response.headers.get('content-range')}"`);
      }
      noteTotal(range[0]);
      let body;
      try {
        body = new Uint8Array(await response.arrayBuffer());
      } catch (e) {
        checkAborted(signal, url);
        throw transient('network', `connection lost while reading bytes ${offset}..${offset + length - 1}`, e);
      }
      reader.stats.bytes += body.length;
      return body.length > length ? body.subarray(0, length) : body;
    } finally {
      signal?.removeEventListener('abort', forward);
    }
  }

  /** The file's length from a Content-Range header ("bytes a-b/size", or "bytes \*\/size" for a range past the end). */
  function noteTotal(header) {
    const total = /\/(\d+)$/.exec(header ?? '');
    if (total) reader.size = Number(total[1]);
  }
  return reader;
}

/**
 * @param {Blob} blob a File or any Blob; read by slice, one range at a time
 * @returns {RangeReader}
 */
export function blobReader(blob) {
  const name = blob.name ?? 'blob';
  return {
    name,
    size: blob.size,
    stats: { requests: 0, bytes: 0 },
    async read(offset, length, signal) {
      checkAborted(signal, name);
      this.stats.requests++;
      const bytes = new Uint8Array(await blob.slice(offset, offset + Math.max(0, length)).arrayBuffer());
      this.stats.bytes += bytes.length;
      checkAborted(signal, name);
      return bytes;
    },
  };
}

/** A failure worth another try. */
function transient(kind, message, cause) {
  const error = new Error(message, { cause });
  error.kind = kind;
  error.transient = true;
  return error;
}

function pause(ms, signal, what) {
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => { signal?.removeEventListener('abort', stop); resolve(); }, ms);
    const stop = () => { clearTimeout(timer); reject(new TileError('aborted', `${what}: aborted`, { cause: signal.reason })); };
    signal?.addEventListener('abort', stop, { once: true });
  });
}
