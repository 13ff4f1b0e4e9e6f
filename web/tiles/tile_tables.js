// The tile tables of a COG (TileOffsets and TileByteCounts of each image directory), read entry
// by entry as tiles are wanted, never whole. A world DEM at 1″ has 3.1 million full-resolution
// tiles: its two tables alone are 50 MB, which a viewer that reads them at open fetches before
// its first frame. Here only where each table lies is read at open (the directories, a few KB);
// an entry is then read through the header source, which fetches the aligned block around it
// once (header_source.js): one 16 KB block answers 2,048 neighbouring tiles of a BigTIFF.
//
// The directories are walked here, not taken from the geotiff library, which keeps where a
// table lies to itself and reads a big-endian table stored away from its directory as
// little-endian (see web/geo/tiff_directory.js).

const SHORT = 3, LONG = 4, LONG8 = 16;
const ENTRY_BYTES = { [SHORT]: 2, [LONG]: 4, [LONG8]: 8 };
const TILE_OFFSETS = 324, TILE_BYTE_COUNTS = 325;

/**
 * One table: `length` entries, each read on demand.
 * @typedef {{ length: number, get: (index: number) => Promise<number> }} LazyTable
 */

/**
 * Reads the header and walks the image directories to learn where each one's tile tables lie.
 * @param {{ fetch: (slices: {offset: number, length: number}[], signal?: AbortSignal) => Promise<ArrayBuffer[]> }} source
 *   the header source (blocks cached: the library has read these directories already)
 * @param {number} count how many directories to walk (the library's image count)
 * @param {(problem: string) => never} fail
 * @param {AbortSignal} [signal]
 * @returns {Promise<({ offsets: LazyTable, counts: LazyTable } | null)[]>} per directory, in the
 *   file's order; null for one without tile tables (a striped image)
 */
export async function readTileTables(source, count, fail, signal) {
  // Entries are read later without the open's signal: a table outlives the open that found it.
  const bytesAt = async (offset, length, abort) => new DataView((await source.fetch([{ offset, length }], abort))[0]);
  const directoryBytes = (offset, length) => bytesAt(offset, length, signal);
  const head = await directoryBytes(0, 16);
  const little = head.getUint8(0) === 0x49, big = head.getUint16(2, little) === 43;
  const u64 = (view, at) => {
    const value = view.getBigUint64(at, little);
    if (value > BigInt(Number.MAX_SAFE_INTEGER)) fail(`bad TIFF: an offset of ${value} bytes is past what a file can hold`);
    return Number(value);
  };
  const entryBytes = big ? 20 : 12;

  const tables = [];
  let ifd = big ? u64(head, 8) : head.getUint32(4, little);
  for (let index = 0; index < count; index++) {
    if (ifd === 0) fail(`bad TIFF: image directory ${index} is missing`);
    const counted = await directoryBytes(ifd, big ? 8 : 2);
    if (counted.byteLength < (big ? 8 : 2)) fail(`bad TIFF: image directory ${index} lies past the end of the file`);
    const entries = big ? u64(counted, 0) : counted.getUint16(0, little);
    const first = ifd + (big ? 8 : 2), length = entries * entryBytes + (big ? 8 : 4);
    const view = await directoryBytes(first, length);
    if (view.byteLength < length) fail(`bad TIFF: image directory ${index} runs past the end of the file`);
    const found = {};
    for (let e = 0; e < entries; e++) {
      const at = e * entryBytes;
      const tag = view.getUint16(at, little);
      if (tag !== TILE_OFFSETS && tag !== TILE_BYTE_COUNTS) continue;
      const type = view.getUint16(at + 2, little);
      const size = ENTRY_BYTES[type];
      if (!size) fail(`bad TIFF: tag ${tag} of image directory ${index} has field type ${type}, not SHORT, LONG or LONG8`);
      const n = big ? u64(view, at + 4) : view.getUint32(at + 4, little);
      const inline = n * size <= (big ? 8 : 4);
      const where = inline ? first + at + (big ? 12 : 8) : big ? u64(view, at + 12) : view.getUint32(at + 8, little);
      found[tag] = lazyTable(bytesAt, where, n, size, little);
    }
    tables.push(found[TILE_OFFSETS] && found[TILE_BYTE_COUNTS] ? { offsets: found[TILE_OFFSETS], counts: found[TILE_BYTE_COUNTS] } : null);
    ifd = big ? u64(view, entries * entryBytes) : view.getUint32(entries * entryBytes, little);
  }
  return tables;
}

/** `length` entries of `size` bytes from byte `where`, each read when first asked for. */
function lazyTable(bytesAt, where, length, size, little) {
  return {
    length,
    async get(index) {
      if (!(index >= 0 && index < length)) throw new RangeError(`tile table entry ${index} of ${length}`);
      const view = await bytesAt(where + index * size, size);
      if (view.byteLength < size) return NaN; // past the end: the caller says the file is truncated
      if (size === 2) return view.getUint16(0, little);
      if (size === 4) return view.getUint32(0, little);
      return Number(view.getBigUint64(0, little));
    },
  };
}
