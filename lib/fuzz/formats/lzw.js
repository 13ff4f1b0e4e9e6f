// TIFF LZW encoding (TIFF 6.0 section 13, codes most significant bit first, with the early
// code-width change libtiff writes), to write LZW seeds and to recompress mutated data.

const CLEAR = 256, END = 257;

/** @returns {Uint8Array} the LZW codes of `input` */
export function lzwEncode(input) {
  const out = [];
  let buffer = 0, bits = 0, width = 9;
  const emit = (code) => {
    buffer = (buffer << width) | code;
    bits += width;
    while (bits >= 8) { out.push((buffer >>> (bits - 8)) & 255); bits -= 8; }
    buffer &= (1 << bits) - 1;
  };
  let codes = new Map(), next = 258, current = -1;
  emit(CLEAR);
  for (const byte of input) {
    if (current < 0) { current = byte; continue; }
    const known = codes.get(current * 256 + byte);
    if (known !== undefined) { current = known; continue; }
    emit(current);
    codes.set(current * 256 + byte, next++);
    // The decoder widens its codes one entry early; the encoder widens when the table fills.
    if (next === 512 || next === 1024 || next === 2048) width++;
    if (next === 4094) { emit(CLEAR); codes = new Map(); next = 258; width = 9; }
    current = byte;
  }
  if (current >= 0) emit(current);
  emit(END);
  if (bits > 0) out.push((buffer << (8 - bits)) & 255);
  return Uint8Array.from(out);
}
