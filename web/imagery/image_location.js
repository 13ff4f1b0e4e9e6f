// Where an image file lies on a field, before any of its pixels is decoded: its size (header),
// its georeference (a world file beside it wins over the GeoTIFF's own tags), its placement on
// the field (refused when it misses the field or is in another CRS) and the ground size of its
// pixels. The page (open_image.js, which then decodes into textures) and the command line
// (hexlod mesh --image, which only needs texture coordinates) take these steps here, so both
// place and refuse an image alike.

import { degreesToMetres, parseWorldFile } from '../geo/index.js';
import { readImageHeader, HEADER_BYTES } from './image_header.js';
import { placeImage } from './placement.js';
import { readTiffImage } from './image_tiff.js';
import { ImageError } from './image_error.js';

/**
 * @typedef {object} ImageLocation
 * @property {number} width pixels
 * @property {number} height
 * @property {import('../geo/georef.js').Georef|null} georef the one used (world file, else the file's own)
 * @property {import('./placement.js').Placement} placement
 * @property {number|null} metresPerPixel across, on the ground (null when stretched over a field without spacing)
 */

/**
 * The world file's georeference, or null without one.
 * @param {{ name: string, bytes: Uint8Array }|null} worldFile
 * @throws {ImageError} for a world file that is not one
 */
export function worldFileGeoref(worldFile) {
  return worldFile ? parseWorldFile(worldFile.bytes, (problem) => { throw new ImageError(worldFile.name, problem); }) : null;
}

/**
 * Places an image of known size on a field.
 * @param {{ width: number, height: number, spacingX: number, georef: object|null }} field
 * @param {{ name: string, width: number, height: number }} image
 * @param {object|null} worldGeoref from its world file
 * @param {object|null} ownGeoref from the image file itself (GeoTIFF tags)
 * @returns {ImageLocation}
 * @throws {ImageError} when the CRSs differ or the image misses the field
 */
export function locateImage(field, { name, width, height }, worldGeoref, ownGeoref = null) {
  const georef = worldGeoref ?? ownGeoref;
  const placement = placeImage(field, { name, width, height, georef });
  let metresPerPixel = null;
  if (placement.how !== 'stretched') {
    // An image that names no CRS is in the field's (placement.js).
    const geographic = georef.crs.epsg === null ? field.georef?.crs.geographic : georef.crs.geographic;
    metresPerPixel = geographic
      ? degreesToMetres(georef.dx, Math.abs(georef.dy), georef.y0 + (georef.dy * height) / 2).spacingX
      : georef.dx;
  } else if (field.spacingX > 0) {
    metresPerPixel = (field.spacingX * (field.width - 1)) / width;
  }
  return { width, height, georef, placement, metresPerPixel };
}

/**
 * Locates a whole image file held in memory (the command line reads files whole): PNG, JPEG and
 * WebP by their header alone; a GeoTIFF is checked block by block and its tags read, but no
 * pixel is decoded.
 * @param {{ name: string, bytes: Uint8Array }} image
 * @param {{ name: string, bytes: Uint8Array }|null} worldFile
 * @param {{ width: number, height: number, spacingX: number, georef: object|null }} field
 * @returns {Promise<ImageLocation & { format: string }>}
 * @throws {ImageError}
 */
export async function locateImageFile(image, worldFile, field) {
  const { name, bytes } = image;
  if (bytes.length === 0) throw new ImageError(name, 'empty file');
  const header = readImageHeader(bytes.subarray(0, HEADER_BYTES), name);
  const worldGeoref = worldFileGeoref(worldFile);
  if (header.format !== 'tiff') {
    return { format: header.format, ...locateImage(field, { name, width: header.width, height: header.height }, worldGeoref) };
  }
  let location = null;
  await readTiffImage(bytes, name, {
    begin: (width, height, georef) => {
      location = locateImage(field, { name, width, height }, worldGeoref, georef);
      return false; // its size and georeference are all that is needed: no band is decoded
    },
    onBand: () => {},
  });
  return { format: header.format, ...location };
}
