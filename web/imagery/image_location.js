// Where an image file lies on a field, before any of its pixels is decoded: its size (header),
// its georeference (a world file beside it wins over an .aux.xml's geotransform, which wins over
// the GeoTIFF's own tags), its CRS (the file's own, else its .aux.xml's or .prj's), its
// placement on the field (refused when it misses the field or is in another CRS) and the ground
// size of its pixels. The page (open_image.js, which then decodes into textures) and the command
// line (hexlod mesh --image, which only needs texture coordinates) take these steps here, so
// both place and refuse an image alike.

import { degreesToMetres, metresPerUnit, parseWorldFile, readCrsSidecars, withSidecarCrs, resolveGeoref } from '../geo/index.js';
import { readImageHeader, HEADER_BYTES } from './image_header.js';
import { placeImage } from './placement.js';
import { readTiffImage } from './image_tiff.js';
import { ImageError } from './image_error.js';

/**
 * @typedef {object} ImageLocation
 * @property {number} width pixels
 * @property {number} height
 * @property {import('../geo/georef.js').Georef|null} georef the one used (world file, else .aux.xml, else the file's own)
 * @property {import('./placement.js').Placement} placement
 * @property {number|null} metresPerPixel across, on the ground (null when stretched over a field without spacing)
 * @property {string[]} notes what the sidecars could not give, each naming its file
 */

/**
 * @typedef {{ name: string, bytes: Uint8Array }} NamedBytes
 * @typedef {{ worldFile: NamedBytes|null, prj: NamedBytes|null, auxXml: NamedBytes|null }} ImageSidecars
 */

/**
 * The world file's georeference, or null without one.
 * @param {NamedBytes|null} worldFile
 * @throws {ImageError} for a world file that is not one
 */
export function worldFileGeoref(worldFile) {
  return worldFile ? parseWorldFile(worldFile.bytes, (problem) => { throw new ImageError(worldFile.name, problem); }) : null;
}

/**
 * What an image's sidecars say, read before the image: the world file (a bad one refuses the
 * image, as it would place it wrongly), the .prj and .aux.xml (a bad one is a note).
 * @param {Partial<ImageSidecars>|null} sidecars
 * @returns {Promise<{ worldGeoref: object|null, crs: object|null, auxGeoref: object|null, notes: string[] }>}
 * @throws {ImageError} for a world file that is not one
 */
export async function readImageSidecars(sidecars) {
  const { worldFile = null, prj = null, auxXml = null } = sidecars ?? {};
  const worldGeoref = worldFileGeoref(worldFile);
  const { crs, georef: auxGeoref, notes } = await readCrsSidecars({ prj, auxXml });
  return { worldGeoref, crs, auxGeoref, notes };
}

/**
 * The georeference an image is placed by: its world file's, else its .aux.xml's, else its own
 * (GeoTIFF tags); in its own CRS when it names one, else the sidecars'; the CRS resolved.
 * @param {Awaited<ReturnType<typeof readImageSidecars>>} read
 * @param {object|null} ownGeoref
 * @param {string} name the image's, for notes
 * @returns {Promise<{ georef: object|null, notes: string[] }>}
 */
export async function imageGeoref(read, ownGeoref, name) {
  const chosen = read.worldGeoref ?? read.auxGeoref ?? ownGeoref ?? null;
  const { georef, note } = withSidecarCrs(chosen, read.crs, name);
  return { georef: await resolveGeoref(georef), notes: note ? [...read.notes, note] : read.notes };
}

/**
 * Places an image of known size on a field.
 * @param {{ width: number, height: number, spacingX: number, georef: object|null }} field
 * @param {{ name: string, width: number, height: number }} image
 * @param {{ georef: object|null, notes?: string[] }} located from imageGeoref: the georeference (CRS resolved)
 * @returns {ImageLocation}
 * @throws {ImageError} when the CRSs differ or the image misses the field
 */
export function locateImage(field, { name, width, height }, { georef, notes = [] }) {
  const placement = placeImage(field, { name, width, height, georef });
  let metresPerPixel = null;
  if (placement.how !== 'stretched') {
    // An image that names no CRS is in the field's (placement.js).
    const crs = georef.crs.epsg === null && georef.crs.proj4 === null ? field.georef?.crs : georef.crs;
    metresPerPixel = crs?.geographic
      ? degreesToMetres(georef.dx, Math.abs(georef.dy), georef.y0 + (georef.dy * height) / 2).spacingX
      : georef.dx * metresPerUnit(crs);
  } else if (field.spacingX > 0) {
    metresPerPixel = (field.spacingX * (field.width - 1)) / width;
  }
  return { width, height, georef, placement, metresPerPixel, notes };
}

/**
 * Locates a whole image file held in memory (the command line reads files whole): PNG, JPEG and
 * WebP by their header alone; a GeoTIFF is checked block by block and its tags read, but no
 * pixel is decoded.
 * @param {NamedBytes} image
 * @param {Partial<ImageSidecars>|null} sidecars its world file, .prj and .aux.xml (each may be null)
 * @param {{ width: number, height: number, spacingX: number, georef: object|null }} field
 * @returns {Promise<ImageLocation & { format: string }>}
 * @throws {ImageError}
 */
export async function locateImageFile(image, sidecars, field) {
  const { name, bytes } = image;
  if (bytes.length === 0) throw new ImageError(name, 'empty file');
  const header = readImageHeader(bytes.subarray(0, HEADER_BYTES), name);
  const read = await readImageSidecars(sidecars);
  if (header.format !== 'tiff') {
    const located = await imageGeoref(read, null, name);
    return { format: header.format, ...locateImage(field, { name, width: header.width, height: header.height }, located) };
  }
  let location = null;
  await readTiffImage(bytes, name, {
    begin: async (width, height, georef) => {
      location = locateImage(field, { name, width, height }, await imageGeoref(read, georef, name));
      return false; // its size and georeference are all that is needed: no band is decoded
    },
    onBand: () => {},
  });
  return { format: header.format, ...location };
}
