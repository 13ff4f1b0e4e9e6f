// What kind of image a file is and its size, from its first bytes, before anything is decoded:
// the size decides whether it fits the GPU, and a person hears "too big" before the tab runs
// out of memory, not after. The sizes of the formats the browser decodes come from the
// image-size package (made for exactly this, EXIF orientation included); a format with a band
// reader of ours (TIFF) is sized by it (image_formats.js).

import { imageSize } from 'image-size';
import { IMAGE_FORMATS, DRAPED_FORMATS } from './image_formats.js';
import { ImageError } from './image_error.js';

/** Bytes read to find a PNG, JPEG or WebP's size: JPEG's frame header may follow long EXIF and ICC blocks. */
export const HEADER_BYTES = 1 << 20;

/**
 * @param {Uint8Array} head the file's first bytes (up to HEADER_BYTES; all of a small file)
 * @param {string} name for messages
 * @returns {{ format: string, width: number, height: number }|{ format: string }} a row's format
 *   of image_formats.js; width and height as the image shows (rotated by its EXIF orientation);
 *   for a format read by bands, only the format
 * @throws {ImageError} for anything else, or a header without a size
 */
export function readImageHeader(head, name) {
  const banded = IMAGE_FORMATS.find((f) => f.readBands && f.signature(head));
  if (banded) return { format: banded.format };
  let info;
  try {
    info = imageSize(head);
  } catch (e) {
    throw new ImageError(name, `not an image hexlod can drape (${String(e?.message ?? e).slice(0, 80)}); ${DRAPED_FORMATS} can`);
  }
  const format = IMAGE_FORMATS.find((f) => f.sizeType !== null && f.sizeType === info.type)?.format;
  if (!format) throw new ImageError(name, `a ${info.type?.toUpperCase() ?? 'unknown'} image cannot be draped; ${DRAPED_FORMATS} can`);
  const turned = info.orientation >= 5 && info.orientation <= 8; // EXIF: rotated a quarter turn
  const width = turned ? info.height : info.width, height = turned ? info.width : info.height;
  if (!(width > 0) || !(height > 0)) throw new ImageError(name, `its header gives no size (${width} x ${height})`);
  return { format, width, height };
}
