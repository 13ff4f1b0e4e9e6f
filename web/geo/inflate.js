// zlib streams (PNG IDAT, deflate TIFF blocks), inflated chunk by chunk into the caller's hands.
//
// The platform's DecompressionStream (native zlib, in browsers and Node) does the work while it
// can: it is two to three times faster than inflating in JavaScript, and a compressed file is
// inflated twice, once to count its bytes before memory is reserved for it (a header can claim
// any size; only the data can show it, and WebAssembly memory never shrinks), once to decode.
// When the native stream fails (corrupt or truncated data, a bad checksum), fflate's streaming
// inflater goes on from where it stopped and says why: what is accepted, and why a file is
// refused, are fflate's on every platform.

import { Unzlib } from 'fflate';

/** Compressed bytes handed to fflate per call: bounds its output per call and the time between pauses. */
const SLICE = 64 * 1024;

/**
 * Inflates a zlib stream, handing every inflated byte to onChunk once, in order.
 * @param {Uint8Array[]} parts the stream in pieces (e.g. views of consecutive IDAT chunks)
 * @param {(chunk: Uint8Array) => boolean} onChunk takes the next inflated bytes; returns false
 *   to stop (enough seen, or a problem found in them)
 * @param {() => Promise<void>} [pace] called between slices of work
 * @returns {Promise<string|null>} what is wrong with the data ("zlib: ..."), or null when the
 *   stream ended (complete or cut short: the caller counts what it got) or onChunk stopped it
 */
export async function inflate(parts, onChunk, pace = async () => {}) {
  let delivered = 0;
  const take = (chunk) => { delivered += chunk.length; return onChunk(chunk); };
  if (typeof DecompressionStream === 'function' && await inflateNatively(parts, take, pace)) return null;

  // fflate from the start, skipping the bytes the native stream delivered.
  let skip = delivered, stopped = false;
  const inflater = new Unzlib((chunk) => {
    if (stopped) return;
    if (skip >= chunk.length) { skip -= chunk.length; return; }
    stopped = !take(chunk.subarray(skip));
    skip = 0;
  });
  try {
    for (const part of parts) {
      for (let p = 0; p < part.length && !stopped; p += SLICE) {
        inflater.push(part.subarray(p, p + SLICE), false);
        await pace();
      }
    }
    if (!stopped) inflater.push(new Uint8Array(0), true);
  } catch (e) {
    if (!isInflateError(e)) throw e;
    // Running out of input is truncation, not corruption. With a valid 2-byte header,
    // 'invalid zlib data' can only mean the stream is shorter than its 4-byte checksum.
    if (!/^(unexpected EOF|invalid zlib data)$/.test(e.message)) return `zlib: ${e.message}`;
  }
  return null;
}

/**
 * How many bytes a zlib stream inflates to, counted without keeping any, up to `enough`.
 * @param {Uint8Array[]} parts
 * @param {number} enough
 * @param {() => Promise<void>} [pace]
 * @returns {Promise<{ length: number, error: string|null }>} length: at least `enough` when the
 *   stream holds that many; error as for inflate()
 */
export async function inflatedLength(parts, enough, pace) {
  let length = 0;
  const error = await inflate(parts, (chunk) => (length += chunk.length) < enough, pace);
  return { length, error };
}

/**
 * Through DecompressionStream; true when it ended cleanly (checksum included) or onChunk
 * stopped it, false when it failed (fflate then takes over).
 */
async function inflateNatively(parts, take, pace) {
  const stream = new DecompressionStream('deflate');
  const writer = stream.writable.getWriter(), reader = stream.readable.getReader();
  // Writes resolve as the inflater takes the input; they fail once reading stops early.
  (async () => {
    for (const part of parts) await writer.write(part);
    await writer.close();
  })().catch(() => {});
  try {
    for (;;) {
      const { value, done } = await reader.read();
      if (done || !take(value)) return true;
      await pace();
    }
  } catch {
    return false;
  } finally {
    reader.cancel().catch(() => {});
  }
}

/** fflate throws plain Errors carrying a numeric `code`. */
export function isInflateError(e) {
  return e instanceof Error && typeof e.code === 'number';
}
