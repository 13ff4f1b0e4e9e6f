// Opening an image to drape, from its file (and its sidecars) to textures on the GPU:
//   header -> size and kind -> the tiling and whether it fits (before decoding) -> the
//   georeference (world file, .aux.xml or GeoTIFF tags) and CRS (the file's, .aux.xml or .prj)
//   -> its place on the field (image_location.js, shared
//   with the command line; refused when it misses it or is in another CRS) -> decode (the
//   browser's, or the format's band reader: image_formats.js) into the textures.
// Nothing of the image shown before is touched: the new one fills textures of its own, which
// take the old one's place only when it is whole; a failure (a corrupt band) drops the
// half-made textures and the old image stays on screen.

import { readImageHeader, HEADER_BYTES } from './image_header.js';
import { planImageTiling } from './image_tiling.js';
import { readImageSidecars, imageGeoref, locateImage } from './image_location.js';
import { imageFormat } from './image_formats.js';
import { ImageError } from './image_error.js';
import { browserJpegDecoder } from './browser_jpeg.js';
import { CRS_SIDECAR_BYTES } from '../geo/index.js';

/**
 * @typedef {object} DrapedImage
 * @property {string} name
 * @property {number} width pixels
 * @property {number} height
 * @property {import('./placement.js').Placement} placement
 * @property {number|null} metresPerPixel across, on the ground (null when stretched over a field without spacing)
 * @property {number} gpuBytes
 * @property {string|null} note what the status line should say (stretched, CRS assumed, a sidecar not used)
 */

/**
 * @param {{ name: string, blob: Blob }} image the image file
 * @param {{ worldFile?: {name: string, blob: Blob}|null, prj?: {name: string, blob: Blob}|null,
 *   auxXml?: {name: string, blob: Blob}|null }|null} sidecars the world file places it (over the
 *   .aux.xml's geotransform and its own tags); the .aux.xml or the .prj give its CRS when it names none
 * @param {{ width: number, height: number, spacingX: number, spacingY: number, georef: object|null }} field
 * @param {object} gpu the textures (render/shading/image_textures.js): limits(), begin(tiling),
 *   uploadBitmap(bitmap), uploadBand(y, rows, rgba), finish(), abort()
 * @param {{ budgetBytes?: number, pace?: (fraction: number) => Promise<void>, decodeBitmap?: (blob: Blob) => Promise<ImageBitmap>,
 *   decodeJpeg?: import('./tiff_jpeg_band.js').JpegDecoder|null }} [options] decodeJpeg: for the blocks of
 *   JPEG-compressed GeoTIFFs, the browser's where it has one (null: the geotiff library's)
 * @returns {Promise<DrapedImage>}
 * @throws {ImageError}
 */
export async function openImage(image, sidecars, field, gpu, options = {}) {
  const { name, blob } = image;
  if (blob.size === 0) throw new ImageError(name, 'empty file');
  const head = new Uint8Array(await blob.slice(0, HEADER_BYTES).arrayBuffer());
  const header = readImageHeader(head, name);
  const read = await readImageSidecars(await sidecarBytes(sidecars));
  const limits = { ...gpu.limits(), budgetBytes: options.budgetBytes, name };

  const { readBands } = imageFormat(header.format);
  if (readBands) {
    const bytes = new Uint8Array(await blob.arrayBuffer());
    let location = null, tiling = null, begun = false;
    try {
      await readBands(bytes, name, {
        pace: options.pace,
        decodeJpeg: options.decodeJpeg === undefined ? browserJpegDecoder() : options.decodeJpeg,
        begin: async (width, height, georef) => {
          tiling = planImageTiling(width, height, { ...limits, wholeDecode: false });
          location = locateImage(field, { name, width, height }, await imageGeoref(read, georef, name));
          gpu.begin(tiling);
          begun = true;
        },
        onBand: (y, rows, rgba) => gpu.uploadBand(y, rows, rgba),
      });
      gpu.finish();
      return described(name, location, tiling);
    } catch (error) {
      if (begun) gpu.abort();
      throw error;
    }
  }

  const tiling = planImageTiling(header.width, header.height, { ...limits, wholeDecode: true });
  const location = locateImage(field, { name, width: header.width, height: header.height }, await imageGeoref(read, null, name));
  let bitmap;
  try {
    bitmap = await (options.decodeBitmap ?? decodeBitmap)(blob);
  } catch (e) {
    throw new ImageError(name, `the browser cannot decode it (${String(e?.message ?? e).split('\n')[0].slice(0, 100)})`);
  }
  try {
    if (bitmap.width !== header.width || bitmap.height !== header.height) {
      throw new ImageError(name, `its header says ${header.width} × ${header.height} but it decodes to ${bitmap.width} × ${bitmap.height}`);
    }
    gpu.begin(tiling);
    await gpu.uploadBitmap(bitmap);
  } catch (error) {
    gpu.abort();
    throw error instanceof ImageError ? error : new ImageError(name, `could not be put on the GPU (${String(error?.message ?? error).slice(0, 100)})`);
  } finally {
    bitmap.close?.();
  }
  return described(name, location, tiling);
}

/** The browser's decoder, off the main thread, with the image's EXIF orientation applied. */
function decodeBitmap(blob) {
  return createImageBitmap(blob, { imageOrientation: 'from-image', premultiplyAlpha: 'none', colorSpaceConversion: 'default' });
}

function described(name, { width, height, placement, metresPerPixel, notes }, tiling) {
  const note = [placement.note, ...notes].filter(Boolean).join('; ') || null;
  return { name, width, height, placement, metresPerPixel, gpuBytes: tiling.gpuBytes, note };
}

/**
 * The sidecars' files as bytes ({ name, blob } -> { name, bytes }); a .prj or .aux.xml no
 * further than a byte past what its reader takes, which then says it is too big.
 */
async function sidecarBytes(sidecars) {
  const read = async (file, limit) => file && { name: file.name, bytes: new Uint8Array(await file.blob.slice(0, Math.min(file.blob.size, limit + 1)).arrayBuffer()) };
  return { worldFile: await read(sidecars?.worldFile ?? null, Infinity), prj: await read(sidecars?.prj ?? null, CRS_SIDECAR_BYTES),
    auxXml: await read(sidecars?.auxXml ?? null, CRS_SIDECAR_BYTES) };
}
