// Fetching a height field by URL within limits: a time limit without progress (no answer, or
// no new bytes, for that long), and a size cap checked against Content-Length before the body
// is read and again while it streams, so a wrong or absent length cannot get past it either.
// The caller's AbortSignal stops it at once (Cancel, or another file opened meanwhile).

const MB = 2 ** 20;

/** A limit of the load was reached (its time limit or size cap), not a fault of the server's. */
export class LimitError extends Error {}
const FIRST_CHUNK_BYTES = MB; // the buffer's start when the server gives no length; it doubles

/** A size in MB as the messages give it: whole above 10 MB, else one decimal. */
export const formatMB = (bytes) => (bytes >= 10 * MB ? String(Math.round(bytes / MB)) : String(Number((bytes / MB).toFixed(1))));

/**
 * Fetches `url` into one Uint8Array of exactly the body's size.
 * @param {string|URL} url
 * @param {{ signal: AbortSignal, timeoutMs: number, maxBytes: number,
 *   accept?: (response: Response) => boolean, onBytes?: (received: number, total: number|null) => void }} options
 *   signal: the load's (its reason is thrown when it aborts); timeoutMs: the longest wait for
 *   the answer and then for each piece of the body; maxBytes: the size cap; accept: looks at the
 *   answer before its body is read: false skips it (the result is null), or it throws why the
 *   answer is no use; onBytes: after every piece, with the length the server gave (or null)
 * @returns {Promise<Uint8Array|null>}
 * @throws {Error} whose message says what went wrong ("Failed to fetch", the accept function's),
 *   a LimitError ("no answer in 60 s", "5120 MB, more than the 1024 MB size cap"), or the
 *   signal's reason
 */
export async function fetchLimited(url, { signal, timeoutMs, maxBytes, accept = () => true, onBytes = null }) {
  const seconds = `${Number((timeoutMs / 1000).toFixed(1))} s`;
  let stalled = `no answer in ${seconds}`;
  const stall = new AbortController();
  let timer = setTimeout(() => stall.abort(), timeoutMs);
  const progressed = () => {
    clearTimeout(timer);
    timer = setTimeout(() => stall.abort(), timeoutMs);
  };
  let reader = null;
  try {
    const response = await fetch(url, { signal: AbortSignal.any([signal, stall.signal]) });
    stalled = `no data for ${seconds}`;
    progressed();
    // A refused answer (an error page, no JSON) is left to end by itself: cancelling a small
    // body would show as a failed request in the browser's log.
    if (!accept(response)) return null;
    const lengthHeader = response.headers.get('content-length');
    const declared = /^\s*\d+\s*$/.test(lengthHeader ?? '') ? Number(lengthHeader) : null;
    if (declared > maxBytes) {
      response.body?.cancel().catch(() => {}); // not a byte of it: the server sees the connection close
      throw new LimitError(`${formatMB(declared)} MB, more than the ${formatMB(maxBytes)} MB size cap`);
    }
    // The whole body in one buffer of the announced size (grown when the server said nothing or
    // too little), never a list of pieces joined at the end: the file is held once.
    let bytes = new Uint8Array(declared ?? Math.min(FIRST_CHUNK_BYTES, maxBytes));
    let received = 0;
    if (!response.body) return bytes.subarray(0, 0); // no body (HTTP 204): the loaders say "empty file"
    reader = response.body.getReader();
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      progressed();
      if (received + value.length > maxBytes) throw new LimitError(`more than the ${formatMB(maxBytes)} MB size cap`);
      if (received + value.length > bytes.length) {
        const grown = new Uint8Array(Math.min(Math.max(2 * bytes.length, received + value.length), maxBytes));
        grown.set(bytes.subarray(0, received));
        bytes = grown;
      }
      bytes.set(value, received);
      received += value.length;
      onBytes?.(received, declared);
    }
    return received === bytes.length ? bytes : bytes.slice(0, received);
  } catch (error) {
    if (signal.aborted) throw signal.reason;
    if (stall.signal.aborted) throw new LimitError(stalled);
    throw error;
  } finally {
    clearTimeout(timer);
    // Stops a download cut short (the size cap, a cancel, the time limit): the server sees the connection close.
    reader?.cancel().catch(() => {});
  }
}
