// Calls into the geotiff library on a file nobody should trust: whatever it throws (a TypeError
// on a tag of the wrong type, a RangeError past the end of a buffer) is that file's problem, and
// reaches the caller as the reader's own error, saying what was being read. Shared by the
// height-field and the draped-image readers.

/**
 * @param {(problem: string) => never} fail throws the reader's own error for a problem
 * @param {Function} OwnError that error's class: thrown as it is
 * @returns {<T>(what: string, step: () => Promise<T>|T) => Promise<T>}
 */
export function libraryGuard(fail, OwnError) {
  return async (what, step) => {
    try {
      return await step();
    } catch (e) {
      if (e instanceof OwnError) throw e;
      fail(`${what}: ${String(e?.message ?? e).split('\n')[0].slice(0, 160)}`);
    }
  };
}

/** The file's bytes as the ArrayBuffer the library reads: its own buffer when it holds the file alone. */
export function fileBuffer(bytes) {
  return bytes.byteOffset === 0 && bytes.length === bytes.buffer.byteLength ? bytes.buffer : bytes.slice().buffer;
}
