// The geotiff library's source interface over a range reader, for the header and the image
// directories only. The library asks for them in many small reads (1 KB for the header, each
// directory, each array of tile offsets); a COG keeps all of them together at the start of the
// file, so reading whole aligned blocks, kept once read, answers them in one or two requests
// instead of a dozen round trips. Tiles are read apart from this (cog_source.js), byte-exact.

export const HEADER_BLOCK_BYTES = 16384;

/**
 * @param {import('./range_reader.js').RangeReader} reader
 * @param {number} [blockBytes]
 * @returns {{ fetch: (slices: { offset: number, length: number }[], signal?: AbortSignal) => Promise<ArrayBuffer[]>,
 *   readonly fileSize: number|null }} what GeoTIFF.fromSource needs
 */
export function headerSource(reader, blockBytes = HEADER_BLOCK_BYTES) {
  const blocks = new Map(); // block index -> Promise<Uint8Array> (shorter than blockBytes at the end of the file)

  /** Fetches the blocks first..last not yet asked for, each run of them in one read. */
  function request(first, last, signal) {
    for (let b = first; b <= last; b++) {
      if (blocks.has(b)) continue;
      let end = b;
      while (end < last && !blocks.has(end + 1)) end++;
      const run = reader.read(b * blockBytes, (end - b + 1) * blockBytes, signal);
      for (let k = b; k <= end; k++) {
        const start = (k - b) * blockBytes;
        blocks.set(k, run.then((bytes) => bytes.subarray(start, start + blockBytes)));
      }
      // A failed read must not stay in the cache: the next request tries again.
      run.catch(() => { for (let k = b; k <= end; k++) blocks.delete(k); });
      b = end;
    }
  }

  async function slice({ offset, length }, signal) {
    const first = Math.floor(offset / blockBytes), last = Math.floor((offset + length - 1) / blockBytes);
    request(first, last, signal);
    const parts = await Promise.all(Array.from({ length: last - first + 1 }, (_, i) => blocks.get(first + i)));
    const out = new Uint8Array(length);
    let filled = 0;
    for (let i = 0; i < parts.length; i++) {
      const blockStart = (first + i) * blockBytes;
      const from = Math.max(offset, blockStart) - blockStart;
      const part = parts[i].subarray(from, Math.min(parts[i].length, offset + length - blockStart));
      out.set(part, filled);
      filled += part.length;
      if (parts[i].length < blockBytes) break; // the end of the file
    }
    if (filled < length) pastEnd = true;
    return filled === length ? out.buffer : out.slice(0, filled).buffer;
  }

  let pastEnd = false;
  return {
    fetch: (slices, signal) => Promise.all(slices.map((s) => slice(s, signal))),
    get fileSize() { return reader.size; },
    /** Whether a read asked for bytes past the end of the file (a truncated file's directories). */
    get pastEnd() { return pastEnd; },
  };
}
