// The first image directory of a TIFF (classic or BigTIFF, either byte order), walked before
// the geotiff library parses it. Two things the library gets wrong on a file it cannot trust:
// it makes an array of the count an entry claims before it reads any value (a count forged to
// 2^31 took gigabytes), and it reads an array stored away from its directory as little-endian
// whatever the file's byte order (the strip offsets of a valid big-endian file came out as
// 134217728 for 8). So every entry must fit in the file, as libtiff checks, and the entries
// the block check needs (offsets and byte counts) are read here, with where the directory and
// its values lie (no strip or tile shares a byte with them in a sound file).

/** Bytes a value of each TIFF field type takes (TIFF 6.0, and BigTIFF's 16 to 18). */
const FIELD_TYPE_BYTES = { 1: 1, 2: 1, 3: 2, 4: 4, 5: 8, 6: 1, 7: 1, 8: 2, 9: 4, 10: 8, 11: 4, 12: 8, 13: 4, 16: 8, 17: 8, 18: 8 };
const SHORT = 3, LONG = 4, LONG8 = 16;

/**
 * @param {Uint8Array} bytes a file with a TIFF or BigTIFF signature and at least 8 bytes
 * @param {(problem: string) => never} fail
 * @returns {{ values: (tag: number) => number[] | undefined,
 *   structureIn: (start: number, end: number) => string | null }} values: an entry's SHORT, LONG
 *   or LONG8 values as numbers, undefined when the directory has no such entry; structureIn:
 *   what of the directory lies in bytes [start, end), or null
 */
export function readDirectory(bytes, fail) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.length);
  const little = bytes[0] === 0x49, big = view.getUint16(2, little) === 43;
  const u64 = (p) => (p + 8 <= bytes.length ? Number(view.getBigUint64(p, little)) : Infinity);
  const ifd = big ? u64(8) : view.getUint32(4, little);
  const first = ifd + (big ? 8 : 2), entryBytes = big ? 20 : 12, inline = big ? 8 : 4;
  if (first > bytes.length) fail(`truncated: the image directory at byte ${ifd} lies past the end (${bytes.length} bytes)`);
  const entries = big ? u64(ifd) : view.getUint16(ifd, little);
  if (first + entries * entryBytes > bytes.length) {
    fail(`truncated: the image directory's ${entries} entries run past the end (${bytes.length} bytes)`);
  }

  const found = new Map(); // tag -> { type, count, at: where its values are }
  const structure = [['the image directory', ifd, first + entries * entryBytes + (big ? 8 : 4)]]; // [what, start, end)
  for (let i = 0; i < entries; i++) {
    const e = first + i * entryBytes;
    const tag = view.getUint16(e, little), type = view.getUint16(e + 2, little);
    const count = big ? u64(e + 4) : view.getUint32(e + 4, little);
    const size = (FIELD_TYPE_BYTES[type] ?? 0) * count; // an unknown type is the library's to refuse
    const at = size <= inline ? e + (big ? 12 : 8) : big ? u64(e + 12) : view.getUint32(e + 8, little);
    if (at + size > bytes.length) {
      fail(`bad TIFF: tag ${tag} holds ${count} values (${size} bytes from byte ${at}), past the end of the file (${bytes.length} bytes)`);
    }
    found.set(tag, { type, count, at });
    if (size > inline) structure.push([`the values of tag ${tag}`, at, at + size]);
  }

  const read = { [SHORT]: (p) => view.getUint16(p, little), [LONG]: (p) => view.getUint32(p, little), [LONG8]: u64 };
  return {
    values(tag) {
      const entry = found.get(tag);
      if (!entry || !read[entry.type]) return undefined;
      const size = FIELD_TYPE_BYTES[entry.type];
      return Array.from({ length: entry.count }, (_, k) => read[entry.type](entry.at + k * size));
    },
    structureIn(start, end) {
      const hit = structure.find(([, s, e]) => s < end && start < e);
      return hit ? `${hit[0]} (bytes ${hit[1]}..${hit[2] - 1})` : null;
    },
  };
}
