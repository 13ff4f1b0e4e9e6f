// A JPEG-compressed TIFF block (Compression 7, TIFF Technical Note 2) as a complete JPEG stream
// that any JPEG decoder (the browser's) reads alone. A block is an "abbreviated" stream: its
// quantisation and Huffman tables may sit once in the JPEGTables tag (347), itself a stream of
// tables only (SOI, DQT/DHT..., EOI). Spliced together, SOI + tables + the block after its SOI,
// they make one interchange stream.
//
// Colour: a JFIF decoder takes three components to be YCbCr and converts them to RGB, which is
// right for Photometric YCbCr (6). A Photometric RGB (2) block holds RGB samples as they are;
// libtiff writes no marker saying so, so an Adobe APP14 marker with transform 0 ("no
// transform") goes in front, which decoders (libjpeg, the browsers') obey. One component is grey
// in every decoder.

const SOI = 0xd8, EOI = 0xd9, SOS = 0xda;
const STANDALONE = new Set([0x01, 0xd0, 0xd1, 0xd2, 0xd3, 0xd4, 0xd5, 0xd6, 0xd7, SOI, EOI]);
// Start-of-frame markers: C0..CF but DHT (C4), JPG (C8) and DAC (CC).
const isFrame = (marker) => marker >= 0xc0 && marker <= 0xcf && marker !== 0xc4 && marker !== 0xc8 && marker !== 0xcc;

/** APP14 "Adobe", version 100, no flags, transform 0: the components are stored as they are (RGB). */
const ADOBE_NO_TRANSFORM = Uint8Array.of(0xff, 0xee, 0, 14, 0x41, 0x64, 0x6f, 0x62, 0x65, 0, 100, 0, 0, 0, 0, 0);

/**
 * The marker segments of a stream up to and including its first SOS (after SOS comes entropy
 * data, not segments).
 * @param {Uint8Array} bytes
 * @returns {Generator<{ marker: number, at: number, length: number }>} at: the offset of the
 *   marker's 0xFF; length: the segment's length field (0 for standalone markers)
 * @throws {Error} on bytes that are no marker, or a segment running past the end
 */
export function* markerSegments(bytes) {
  let at = 0;
  while (at + 1 < bytes.length) {
    if (bytes[at] !== 0xff) throw new Error(`no JPEG marker at byte ${at}`);
    const marker = bytes[at + 1];
    if (marker === 0xff) { at++; continue; } // fill bytes before a marker
    if (STANDALONE.has(marker)) {
      yield { marker, at, length: 0 };
      at += 2;
      continue;
    }
    if (at + 4 > bytes.length) throw new Error(`JPEG marker ${marker.toString(16)} at byte ${at} is cut off`);
    const length = (bytes[at + 2] << 8) | bytes[at + 3];
    if (length < 2 || at + 2 + length > bytes.length) throw new Error(`JPEG segment ${marker.toString(16)} at byte ${at} runs past the end`);
    yield { marker, at, length };
    if (marker === SOS) return;
    at += 2 + length;
  }
}

/**
 * The complete stream of one block.
 * @param {Uint8Array|null|undefined} tables the JPEGTables tag's bytes (SOI ... EOI), or none
 * @param {Uint8Array} block the block's bytes, starting with its own SOI
 * @param {{ rgb?: boolean }} [options] rgb: the samples are RGB (Photometric 2), not YCbCr
 * @returns {Uint8Array} SOI, [APP14 Adobe transform 0], the tables' segments, the block after its SOI
 * @throws {Error} when the block or the tables do not start with SOI
 */
export function tiffJpegStream(tables, block, { rgb = false } = {}) {
  if (block[0] !== 0xff || block[1] !== SOI) throw new Error('the block does not start with a JPEG SOI marker');
  let middle = new Uint8Array(0);
  if (tables && tables.length > 0) {
    if (tables[0] !== 0xff || tables[1] !== SOI) throw new Error('JPEGTables does not start with a JPEG SOI marker');
    const end = tables.length >= 4 && tables[tables.length - 2] === 0xff && tables[tables.length - 1] === EOI ? tables.length - 2 : tables.length;
    middle = tables.subarray(2, end);
  }
  const head = rgb ? ADOBE_NO_TRANSFORM : new Uint8Array(0);
  const stream = new Uint8Array(2 + head.length + middle.length + block.length - 2);
  stream[0] = 0xff; stream[1] = SOI;
  stream.set(head, 2);
  stream.set(middle, 2 + head.length);
  stream.set(block.subarray(2), 2 + head.length + middle.length);
  return stream;
}

/**
 * The frame header (SOF) of a block: the size it decodes to, read without decoding it.
 * @param {Uint8Array} block
 * @returns {{ width: number, height: number, components: number } | null} null when no frame
 *   header comes before the scan
 * @throws {Error} on bytes that are no JPEG marker segments
 */
export function jpegFrame(block) {
  for (const { marker, at, length } of markerSegments(block)) {
    if (isFrame(marker)) {
      if (length < 8) throw new Error(`JPEG frame header at byte ${at} is too short`);
      const height = (block[at + 5] << 8) | block[at + 6], width = (block[at + 7] << 8) | block[at + 8];
      return { width, height, components: block[at + 9] };
    }
    if (marker === SOS) return null;
  }
  return null;
}
