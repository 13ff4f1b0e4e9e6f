// The strips or tiles of a TIFF, checked before the field is allocated, as GDAL checks strip and
// tile sizes before it allocates: every block lies inside the file and decodes to exactly the
// bytes its geometry needs. Without that, a forged width or height reserves memory its data
// does not hold (WebAssembly memory never shrinks), and blocks too short or too long for the
// declared geometry load as garbage: the geotiff library pads a short block and ignores the
// rest of a long one.
//
// Uncompressed blocks prove their size by their byte counts, JPEG ones by their frame headers
// (the size every JPEG decoder, the library's or the browser's, produces). Other compressed
// ones are decoded once, keeping nothing where we can (LZW and deflate are only counted),
// before the decode proper.

import { getDecoder } from 'geotiff';
import { shown } from './shown.js';
import { inflatedLength } from './inflate.js';
import { lzwLength } from './tiff_lzw.js';
import { jpegFrame } from './tiff_jpeg_stream.js';

const STRIP_OFFSETS = 273, STRIP_BYTE_COUNTS = 279, TILE_OFFSETS = 324, TILE_BYTE_COUNTS = 325;

/**
 * The block layout of the first image, from its tags, each checked.
 * @param {import('geotiff').GeoTIFFImage} image
 * @param {ReturnType<typeof import('./tiff_directory.js').readDirectory>} directory the same
 *   directory as we read it (the block offsets and byte counts come from there)
 * @param {{ width: number, height: number }} size the image size, already checked
 * @param {(problem: string) => never} fail
 * @returns {Promise<{ tiled: boolean, blockWidth: number, blockHeight: number, bytesPerPixel: number,
 *   compression: number, offsets: number[], counts: number[], blocks: number,
 *   decoder: import('geotiff').BaseDecoder }>} blocks: how many blocks hold the first sample (the
 *   only one read); decoder: the library's for the file's compression and predictor
 */
export async function blockLayout(image, directory, { width, height }, fail) {
  const dir = image.fileDirectory;
  const tiled = image.isTiled;
  const kind = tiled ? 'tile' : 'strip';
  const positive = (tag, v) => {
    if (!Number.isInteger(v) || v <= 0) fail(`bad TIFF: ${tag} ${shown(v)} is not a positive whole number`);
    return v;
  };
  const blockWidth = tiled ? positive('TileWidth', await dir.loadValue('TileWidth')) : width;
  const rowsPerStrip = await dir.loadValue('RowsPerStrip');
  const blockHeight = tiled ? positive('TileLength', await dir.loadValue('TileLength'))
    : Math.min(height, rowsPerStrip === undefined ? height : positive('RowsPerStrip', rowsPerStrip));

  const bits = Array.from((await dir.loadValue('BitsPerSample')) ?? [1]);
  const planar = image.planarConfiguration;
  const pixelBits = planar === 2 ? bits[0] : bits.reduce((a, b) => a + b, 0);
  if (pixelBits % 8 !== 0) fail(`unsupported TIFF: ${pixelBits} bits a pixel is not a whole number of bytes`);
  // A decoder holds one block at a time: one beyond what a typed array holds is no block.
  if (blockWidth * blockHeight * (pixelBits / 8) > 2 ** 31 - 1) {
    fail(`bad TIFF: ${kind}s of ${blockWidth}x${blockHeight} samples are absurd (over 2 GB each)`);
  }

  const offsets = directory.values(tiled ? TILE_OFFSETS : STRIP_OFFSETS);
  const counts = directory.values(tiled ? TILE_BYTE_COUNTS : STRIP_BYTE_COUNTS);
  if (!offsets || !counts) fail(`bad TIFF: no ${kind} offsets`);
  const blocks = Math.ceil(width / blockWidth) * Math.ceil(height / blockHeight);
  if (offsets.length < blocks || counts.length < blocks) {
    fail(`bad TIFF: ${Math.min(offsets.length, counts.length)} ${kind}s listed, ${blocks} needed`);
  }
  const compression = (await dir.loadValue('Compression')) ?? 1;
  // The library undoes predictor 2 on samples of 8, 16 or 32 bits, all alike, and predictor 3
  // (floating point) on whole bytes; anything else it throws on while decoding, after the field
  // is allocated, or leaves as it is (garbage).
  const predictor = (await dir.loadValue('Predictor')) || 1;
  const alike = bits.every((b) => b === bits[0] && b % 8 === 0);
  if (![1, 2, 3].includes(predictor)) fail(`unsupported TIFF predictor ${shown(predictor)}`);
  if (predictor === 2 && !(alike && [8, 16, 32].includes(bits[0]))) fail(`unsupported TIFF: predictor 2 on ${bits.join('+')}-bit samples`);
  if (predictor === 3 && !(alike && ((await dir.loadValue('SampleFormat'))?.[0] ?? 1) === 3)) {
    fail('bad TIFF: predictor 3 is for floating-point samples');
  }
  // What the library's decoders (and ours, see tiff_lzw.js and tiff_deflate.js) need to know of a block.
  const decoderParameters = {
    tileWidth: blockWidth, tileHeight: blockHeight, planarConfiguration: planar, bitsPerSample: bits,
    predictor, bytesPerPixel: pixelBits / 8,
    samplesPerPixel: (await dir.loadValue('SamplesPerPixel')) ?? 1,
    JPEGTables: await dir.loadValue('JPEGTables'), LercParameters: await dir.loadValue('LercParameters'),
  };
  let decoder;
  try {
    decoder = await getDecoder(compression, decoderParameters);
  } catch (e) {
    fail(`unsupported TIFF compression ${compression} (${String(e?.message ?? e).split('\n')[0].slice(0, 80)})`);
  }
  return { tiled, blockWidth, blockHeight, bytesPerPixel: pixelBits / 8, compression, offsets, counts, blocks, decoder };
}

/**
 * Checks every block of the first sample: inside the file, clear of the directory, and decoding
 * to the bytes its geometry needs (a strip at the bottom may hold only the image's remaining
 * rows, or a whole strip). Nothing is allocated but one block at a time for codecs that cannot
 * be counted.
 * @param {import('geotiff').GeoTIFFImage} image
 * @param {Awaited<ReturnType<typeof blockLayout>>} layout
 * @param {ReturnType<typeof import('./tiff_directory.js').readDirectory>} directory
 * @param {Uint8Array} bytes the file
 * @param {(problem: string) => never} fail
 * @param {(fraction: number) => Promise<void>} pace
 */
export async function checkBlocks(image, layout, directory, bytes, fail, pace) {
  const { tiled, blockWidth, blockHeight, bytesPerPixel, compression, offsets, counts, blocks } = layout;
  const height = image.getHeight();
  const kind = tiled ? 'tile' : 'strip';
  const slices = [];
  for (let i = 0; i < blocks; i++) {
    const offset = offsets[i], count = counts[i];
    if (offset + count > bytes.length) fail(`truncated: ${kind} ${i} ends at byte ${offset + count}, the file has ${bytes.length}`);
    // A block cut short whose byte count was kept would read the directory as samples.
    const shared = count > 0 && directory.structureIn(offset, offset + count);
    if (shared) fail(`bad TIFF: ${kind} ${i} (bytes ${offset}..${offset + count - 1}) overlaps ${shared}`);
    slices.push(bytes.subarray(offset, offset + count));
  }

  const measure = measurer(layout);
  const full = blockWidth * blockHeight * bytesPerPixel;
  for (let i = 0; i < blocks; i++) {
    if (slices[i].length === 0) continue; // an empty block: the reader fills it with no-data
    const rows = tiled ? blockHeight : Math.min(blockHeight, height - i * blockHeight);
    const needed = blockWidth * rows * bytesPerPixel;
    let length;
    try {
      length = await measure(slices[i], full);
    } catch (e) {
      fail(`corrupt ${kind} ${i} (${String(e?.message ?? e).split('\n')[0].slice(0, 120)})`);
    }
    if (length !== needed && length !== full) {
      const counted = compression === 1 ? `holds ${length}` : `decodes to ${length > full ? `more than ${full}` : length}`;
      fail(`bad TIFF: ${kind} ${i} ${counted} bytes, but its ${blockWidth}x${rows} samples need ${needed} ` +
        `(is the ${tiled ? 'tile' : 'image'} size right?)`);
    }
    await pace((i + 1) / blocks);
  }
}

// A sparse file (GDAL SPARSE_OK) may leave blocks empty: they are no-data. Its declared size is
// then proven only where blocks hold data, so the field is the data's extent (the smallest
// rectangle of blocks around every block that holds data), and that extent must be mostly data:
// a file of a few real blocks spread over a huge declared raster would otherwise reserve memory
// thousands of times its size and fill it by interpolating from almost nothing.
export const SPARSE_MIN_SHARE = 1 / 16; // the least share of the extent's blocks that must hold data

/**
 * The part of the raster the field is made of: all of it, unless empty blocks of a sparse file
 * lie around the data.
 * @param {Awaited<ReturnType<typeof blockLayout>>} layout
 * @param {{ width: number, height: number }} size the image size
 * @param {(problem: string) => never} fail
 * @returns {{ x: number, y: number, width: number, height: number, cropped: boolean }} in samples
 */
export function dataExtent({ tiled, blockWidth, blockHeight, counts, blocks }, { width, height }, fail) {
  const kind = tiled ? 'tile' : 'strip';
  const across = Math.ceil(width / blockWidth);
  let minX = Infinity, minY = Infinity, maxX = -1, maxY = -1, withData = 0;
  for (let i = 0; i < blocks; i++) {
    if (counts[i] === 0) continue;
    const bx = i % across, by = Math.floor(i / across);
    minX = Math.min(minX, bx); maxX = Math.max(maxX, bx); minY = Math.min(minY, by); maxY = Math.max(maxY, by);
    withData++;
  }
  if (withData === 0) fail(`every ${kind} is empty (a sparse file with no data): nothing to show`);
  const inExtent = (maxX - minX + 1) * (maxY - minY + 1);
  if (withData < inExtent * SPARSE_MIN_SHARE) {
    fail(`too sparse to open: only ${withData} of the ${inExtent} ${kind}s around its data hold samples ` +
      `(at least 1 in ${Math.round(1 / SPARSE_MIN_SHARE)} must); cut the area you need with gdal_translate -srcwin`);
  }
  const x = minX * blockWidth, y = minY * blockHeight;
  const extent = {
    x, y, width: Math.min(width, (maxX + 1) * blockWidth) - x, height: Math.min(height, (maxY + 1) * blockHeight) - y,
  };
  return { ...extent, cropped: extent.width !== width || extent.height !== height };
}

/**
 * A function (block bytes, full block size) -> bytes the block decodes to, counted up to just
 * past the full size (anything more is too long in any case).
 */
export function measurer({ compression, decoder }) {
  if (compression === 1) return (block) => block.length;
  if (compression === 5) return (block, full) => lzwLength(block, full + 1);
  if (compression === 8 || compression === 32946) {
    return async (block, full) => {
      const { length, error } = await inflatedLength([block], full + 1);
      if (error) throw new Error(error);
      return length;
    };
  }
  if (compression === 7) {
    // Decoding every block here would double the cost of the slowest codec for nothing the
    // header does not say; damaged entropy data fails the decode proper, block by block.
    return (block) => {
      const frame = jpegFrame(block);
      if (!frame) throw new Error('no JPEG frame header');
      return frame.width * frame.height * frame.components;
    };
  }
  // Any other codec the library knows: decode the block (one at a time) and measure it.
  return async (block) => (await decoder.decodeBlock(block.slice().buffer)).byteLength;
}

/**
 * Block geometry for our decoders (LZW, deflate) when the library's own readRasters asks for it
 * (its registry of decoders is global); strips never taller than the image.
 */
export async function decoderParametersOf(dir) {
  const tiled = dir.hasTag('TileOffsets');
  const imageHeight = await dir.loadValue('ImageLength');
  const bits = Array.from(await dir.loadValue('BitsPerSample') ?? [1]);
  const planar = (await dir.loadValue('PlanarConfiguration')) ?? 1;
  return {
    tileWidth: await dir.loadValue(tiled ? 'TileWidth' : 'ImageWidth'),
    tileHeight: tiled ? await dir.loadValue('TileLength')
      : Math.min(imageHeight, (await dir.loadValue('RowsPerStrip')) || imageHeight),
    planarConfiguration: planar,
    bitsPerSample: bits,
    predictor: (await dir.loadValue('Predictor')) || 1,
    bytesPerPixel: Math.ceil((planar === 2 ? bits[0] : bits.reduce((a, b) => a + b, 0)) / 8),
  };
}
