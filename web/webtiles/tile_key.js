// One number for a tile (z, x, y) of the Web Mercator pyramid: its index in the pyramid counted
// level by level, row by row. Exact up to zoom 26 (4^26 < 2^53), so per-frame maps and sets
// of tiles need no strings.

/** The key of tile (z, x, y); 0 <= x, y < 2^z. */
export function tileKey(z, x, y) {
  const n = 2 ** z;
  return (n * n - 1) / 3 + y * n + x;
}

/** The zoom, x and y of a key, written into `out` ([z, x, y]). */
export function tileOfKey(key, out = [0, 0, 0]) {
  let z = 0;
  while ((4 ** (z + 1) - 1) / 3 <= key) z++;
  const n = 2 ** z, rest = key - (n * n - 1) / 3;
  out[0] = z;
  out[1] = rest % n;
  out[2] = Math.floor(rest / n);
  return out;
}
