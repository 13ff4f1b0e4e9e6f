// The image formats hexlod drapes, one row each. A row says how a file is recognised (its
// extensions and first bytes), whether it is always an image or the drop's other files decide
// (a PNG or a TIFF may be heights: drop_roles.js), how its size is read before decoding
// (image-size's type name; null: its band reader reads it) and how it is decoded: by the browser
// (createImageBitmap, whole) or by a band reader of ours, row bands straight to the GPU
// (open_image.js). A new format the browser decodes is one row here; one it does not, a band
// reader beside image_tiff.js and its row.
import { hasTiffSignature } from '../geo/index.js';
import { hasPngSignature } from '../loaders/png.js';
import { readTiffImage } from './image_tiff.js';

const startsWith = (head, bytes) => bytes.every((b, i) => head[i] === b);
const ascii = (head, from, to) => String.fromCharCode(...head.subarray(from, to));

/**
 * @typedef {object} ImageFormat
 * @property {string} format
 * @property {string} label for messages
 * @property {string[]} extensions lower case, without the dot
 * @property {(head: Uint8Array) => boolean} signature whether the first bytes are of this format
 * @property {boolean} alwaysImage false when the file may also be a height field
 * @property {string|null} sizeType image-size's name of the format, whose header gives the size
 * @property {Function|null} readBands null: the browser decodes it; else (bytes, name, { begin,
 *   onBand, pace, decodeJpeg }) as image_tiff.js readTiffImage
 */

/** @type {ImageFormat[]} */
export const IMAGE_FORMATS = [
  { format: 'png', label: 'PNG', extensions: ['png'], signature: hasPngSignature, alwaysImage: false, sizeType: 'png', readBands: null },
  { format: 'jpeg', label: 'JPEG', extensions: ['jpg', 'jpeg'], signature: (head) => startsWith(head, [0xff, 0xd8, 0xff]),
    alwaysImage: true, sizeType: 'jpg', readBands: null },
  { format: 'webp', label: 'WebP', extensions: ['webp'], alwaysImage: true, sizeType: 'webp', readBands: null,
    signature: (head) => head.length >= 12 && ascii(head, 0, 4) === 'RIFF' && ascii(head, 8, 12) === 'WEBP' },
  { format: 'tiff', label: '8-bit GeoTIFF', extensions: ['tif', 'tiff'], signature: hasTiffSignature, alwaysImage: false,
    sizeType: null, readBands: readTiffImage },
];

/** "PNG, JPEG, WebP and 8-bit GeoTIFF" */
export const DRAPED_FORMATS = `${IMAGE_FORMATS.slice(0, -1).map((f) => f.label).join(', ')} and ${IMAGE_FORMATS.at(-1).label}`;

/** The row of a file that is always an image, by its extension or its first bytes, or undefined. */
export const alwaysImageFormat = (extension, head) =>
  IMAGE_FORMATS.find((f) => f.alwaysImage && (f.extensions.includes(extension) || f.signature(head)));

/** The row of format `format` (a row's `format`). */
export const imageFormat = (format) => IMAGE_FORMATS.find((f) => f.format === format);
