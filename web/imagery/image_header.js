// What kind of image a file is and its size, from its first bytes, before anything is decoded:
// the size decides whether it fits the GPU, and a person hears "too big" before the tab runs
// out of memory, not after. PNG, JPEG and WebP sizes come from the image-size package (made
// for exactly this, EXIF orientation included); TIFFs are read by image_tiff.js.

import { imageSize } from 'image-size';
import { hasTiffSignature } from '../geo/index.js';
import { ImageError } from './image_error.js';

/** Bytes read to find a PNG, JPEG or WebP's size: JPEG's frame header may follow long EXIF and ICC blocks. */
export const HEADER_BYTES = 1 << 20;

/**
 * @param {Uint8Array} head the file's first bytes (up to HEADER_BYTES; all of a small file)
 * @param {string} name for messages
 * @returns {{ format: 'png'|'jpeg'|'webp'|'tiff', width: number, height: number }|{ format: 'tiff' }}
 *   width and height as the image shows (rotated by its EXIF orientation); for a TIFF, only the format
 * @throws {ImageError} for anything else, or a header without a size
 */
export function readImageHeader(head, name) {
  if (hasTiffSignature(head)) return { format: 'tiff' };
  let info;
  try {
    info = imageSize(head);
  } catch (e) {
    throw new ImageError(name, `not an image hexlod can drape (${String(e?.message ?? e).slice(0, 80)}); PNG, JPEG, WebP and 8-bit GeoTIFF can`);
  }
  const format = { png: 'png', jpg: 'jpeg', webp: 'webp' }[info.type];
  if (!format) throw new ImageError(name, `a ${info.type?.toUpperCase() ?? 'unknown'} image cannot be draped; PNG, JPEG, WebP and 8-bit GeoTIFF can`);
  const turned = info.orientation >= 5 && info.orientation <= 8; // EXIF: rotated a quarter turn
  const width = turned ? info.height : info.width, height = turned ? info.width : info.height;
  if (!(width > 0) || !(height > 0)) throw new ImageError(name, `its header gives no size (${width} x ${height})`);
  return { format, width, height };
}
