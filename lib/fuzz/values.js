// Values that sit on the edges decoders get wrong: zero, one, off-by-one around powers of two,
// the limits of 16- and 32-bit fields, sizes just past the loaders' limit (32769^2 samples).

/** Whole numbers for sizes, counts, offsets (non-negative, up to 2^32 - 1). */
export const EDGE_UINTS = [
  0, 1, 2, 3, 7, 8, 15, 16, 17, 63, 64, 65, 127, 128, 255, 256, 257, 1023, 1024, 1201, 3601, 4095, 4096,
  16384, 16385, 32767, 32768, 32769, 46340, 46341, 65535, 65536, 65537, 1 << 20, 0x7ffffffe, 0x7fffffff,
  0x80000000, 0x80000001, 0xfffffffe, 0xffffffff,
];

/** A size near `n`: n itself, off by one or two, doubled, halved, or an edge value. */
export function nearSize(random, n) {
  return random.weighted([
    [4, n + random.pick([-2, -1, 1, 2])],
    [2, random.pick([n * 2, Math.floor(n / 2), n * 10, n * 1000])],
    [3, random.pick(EDGE_UINTS)],
    [1, random.int(0x100000000)],
  ]);
}

/** Number texts a text format might meet, good and bad. */
export const NUMBER_TEXTS = [
  '0', '-0', '1', '-1', '1.5', '-1.5', '1e999', '-1e999', '1e-999', 'NaN', 'nan', 'inf', '-inf', 'Infinity',
  '-Infinity', '3.5e38', '-3.5e38', '3.4028235e38', '1e38', '1e308', '2e308', '4294967296', '9007199254740993',
  '1e', '1e+', '.', '-', '+', '+1', '--1', '1..2', '1.2.3', '0x10', '1,5', '', '\u0661', '1_000', 'e5', '.5', '5.',
];

/** JSON values for a sidecar's fields: right types, wrong types, out of range. */
export const JSON_VALUES = [
  '0', '1', '-1', '1.5', '-0.5', '2', '87', '200', '1e999', '-1e999', '1e308', '4294967297', '9007199254740993',
  '65535', '65536', '32769', '1e-320', 'null', 'true', 'false', '"87"', '"NaN"', '""', '[]', '[87]', '{}',
  '"1e999"', '-9999', '1e38', '3.5e38',
];
