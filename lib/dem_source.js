// Where a height field comes from for a command: a file on disk or an http(s) URL, read whole
// with its NAME.json sidecar beside it when there is one (as the page's ?src= does). A URL is
// fetched with a time limit and a size cap, and every failure is one line naming the URL.
import { createHash } from 'node:crypto';
import { basename, dirname, extname, resolve } from 'node:path';
import { readInputs } from './cli_common.js';

export const URL_TIMEOUT_MS = 60000;    // no answer (or no more bytes) for this long: give up
export const URL_MAX_BYTES = 2 ** 30;   // 1 GiB: larger height fields do not fit the core's memory anyway

/** True when `text` is a URL (scheme://...) rather than a path. */
export const isUrl = (text) => /^[a-z][a-z0-9+.-]*:\/\//i.test(text);

/**
 * A height field named in a flight file (`dem`, relative to the flight) or on the command line:
 * an absolute path, or the URL as it is. Throws for a URL of a scheme other than http(s).
 */
export function resolveDem(text, baseDir) {
  if (!isUrl(text)) return resolve(baseDir, text);
  const scheme = text.slice(0, text.indexOf(':')).toLowerCase();
  if (scheme !== 'http' && scheme !== 'https') throw new Error(`${text}: only http and https URLs can be read, not ${scheme}:`);
  return text;
}

/** The file name at the end of a URL's path (decoded), e.g. 'n27e086.hgt'. */
export function urlFileName(url) {
  const path = new URL(url).pathname;
  const name = decodeURIComponent(path.slice(path.lastIndexOf('/') + 1));
  return name || 'heightfield';
}

/** Reads a response body, refusing one larger than `maxBytes`; `timer` is reset per chunk. */
async function readCapped(response, url, maxBytes, timer) {
  const declared = Number(response.headers.get('content-length'));
  if (Number.isFinite(declared) && declared > maxBytes) {
    throw new Error(`${url}: ${Math.round(declared / 2 ** 20)} MB, more than the ${Math.round(maxBytes / 2 ** 20)} MB a height field may have`);
  }
  const chunks = [];
  let total = 0;
  for await (const chunk of response.body) {
    timer.refresh();
    total += chunk.length;
    if (total > maxBytes) throw new Error(`${url}: more than the ${Math.round(maxBytes / 2 ** 20)} MB a height field may have`);
    chunks.push(chunk);
  }
  return new Uint8Array(Buffer.concat(chunks, total));
}

/**
 * Fetches a URL's bytes; null for a 404 when `optional`. One-line errors: HTTP status, no
 * connection, no answer within the time limit, too large.
 */
export async function fetchBytes(url, { optional = false, timeoutMs = URL_TIMEOUT_MS, maxBytes = URL_MAX_BYTES } = {}) {
  const controller = new AbortController();
  const timer = setTimeout(() => controller.abort(), timeoutMs);
  try {
    const response = await fetch(url, { signal: controller.signal, redirect: 'follow' });
    if (optional && response.status === 404) {
      await response.body?.cancel();
      return null;
    }
    if (!response.ok) {
      await response.body?.cancel();
      throw new Error(`${url}: the server answered HTTP ${response.status}${response.statusText ? ` ${response.statusText}` : ''}`);
    }
    return await readCapped(response, url, maxBytes, timer);
  } catch (error) {
    if (error.name === 'AbortError') throw new Error(`${url}: no answer from the server in ${timeoutMs / 1000} s`);
    if (error.message.startsWith(url)) throw error;
    const cause = error.cause?.code ?? error.cause?.message ?? error.message;
    throw new Error(`${url}: could not be read (${cause})`);
  } finally {
    clearTimeout(timer);
  }
}

/**
 * A height field's files ([{name, bytes}], the field first, then its sidecar if any) and a
 * fingerprint of its bytes, from a path or a URL.
 * @returns {Promise<{files: {name: string, bytes: Uint8Array}[], name: string, size: number, sha256: string}>}
 */
export async function readDem(source) {
  let files;
  if (isUrl(source)) {
    const name = urlFileName(source);
    files = [{ name, bytes: await fetchBytes(source) }];
    if (extname(name).toLowerCase() !== '.json') {
      const sidecarName = `${basename(name, extname(name))}.json`;
      const sidecar = await fetchBytes(new URL(sidecarName, source).href, { optional: true });
      if (sidecar) files.push({ name: sidecarName, bytes: sidecar });
    }
  } else {
    files = readInputs(source);
  }
  const hash = createHash('sha256');
  for (const file of files) hash.update(file.bytes);
  return { files, name: files[0].name, size: files[0].bytes.length, sha256: hash.digest('hex') };
}

/** The folder a path source sits in, or null for a URL. */
export const sourceDir = (source) => (isUrl(source) ? null : dirname(source));
