// What went wrong while reading a terrain file tile by tile, as a kind the caller can act on (retry later,
// load the file whole, tell the user to make a COG) and a message a user can read.

/**
 * kind is one of:
 *   'http'      the server answered with an error status (status holds it), after retries
 *   'network'   no answer, or the connection broke mid-body, after retries
 *   'no-range'  the server ignores Range and sends the whole file (size holds its length when
 *               the server said it): load it whole if it fits, or serve it from a host that
 *               honours Range
 *   'truncated' a tile's bytes lie past the end of the file
 *   'decode'    a tile's bytes do not decode to its samples
 *   'not-cog'   a TIFF that cannot be read a view at a time (strips instead of tiles)
 *   'bad-tiff'  not a TIFF, or a TIFF whose structure is damaged
 *   'aborted'   the caller's AbortSignal fired
 */
export class TileError extends Error {
  /**
   * @param {string} kind see above
   * @param {string} message
   * @param {{ status?: number, size?: number|null, cause?: unknown }} [details]
   */
  constructor(kind, message, details = {}) {
    super(message, details.cause === undefined ? undefined : { cause: details.cause });
    this.name = 'TileError';
    this.kind = kind;
    if (details.status !== undefined) this.status = details.status;
    if (details.size !== undefined) this.size = details.size;
  }
}

/** Throws the 'aborted' error when the signal has fired. */
export function checkAborted(signal, what) {
  if (signal?.aborted) throw new TileError('aborted', `${what}: aborted`, { cause: signal.reason });
}
