// 8-bit GeoTIFF images to drape: RGB or RGBA, grey (black or white is zero), palette, and YCbCr
// JPEG, in strips or tiles, uncompressed, deflate, LZW or JPEG. Read in bands of whole block
// rows, each handed on as RGBA and dropped: the image is never held whole in JavaScript. Every
// block is checked against its geometry first (tiff_blocks.js), so a forged size reserves
// nothing. GDAL's no-data value (tag 42113) on every colour sample makes a pixel transparent,
// as GDAL shows the black or white collar of a warped orthophoto.
// JPEG blocks of grey, RGB and YCbCr images go to a JPEG decoder given by the caller (the
// browser's, tiff_jpeg_band.js) where there is one; a band it fails on, and every other image,
// is read by the geotiff library.

import { readDirectory, blockLayout, checkBlocks, georefOfTiff, hasTiffSignature, shown, libraryGuard, fileBuffer,
  openTiffBuffer } from '../geo/index.js';
import { ImageError } from './image_error.js';
import { decodeJpegBand } from './tiff_jpeg_band.js';

const PHOTOMETRIC = { 0: 'grey (white is zero)', 1: 'grey', 2: 'RGB', 3: 'palette', 6: 'YCbCr' };
const JPEG = 7;
/** Rows of a band: whole block rows, about this many pixels, so that one-row strips are not read one by one. */
const BAND_PIXELS = 1 << 21;

/**
 * @param {Uint8Array} bytes the file
 * @param {string} name for messages
 * @param {object} options
 * @param {(width: number, height: number, georef: import('../geo/georef.js').Georef|null) => void|false|Promise<void|false>} options.begin
 *   called once, after the file has proven its size and before the first band (the caller
 *   checks that it fits and lies on the field, and reserves textures), and awaited; returning
 *   false stops there, with no band decoded (a caller that needs only the size and georeference)
 * @param {(y: number, rows: number, rgba: Uint8Array) => void | Promise<void>} options.onBand
 *   rows y..y+rows-1 as RGBA, width * rows * 4 bytes (the array is the caller's to keep or drop)
 * @param {(fraction: number) => Promise<void>} [options.pace] between slices of work
 * @param {import('./tiff_jpeg_band.js').JpegDecoder|null} [options.decodeJpeg] decodes the blocks
 *   of a JPEG-compressed grey, RGB or YCbCr image (the library does without it)
 * @returns {Promise<{ width: number, height: number, georef: import('../geo/georef.js').Georef|null,
 *   kind: string, nodata: number|null }>}
 * @throws {ImageError}
 */
export async function readTiffImage(bytes, name, { begin, onBand, pace = async () => {}, decodeJpeg = null }) {
  const fail = (problem) => { throw new ImageError(name, problem); };
  const guard = libraryGuard(fail, ImageError);
  if (!hasTiffSignature(bytes)) fail('not a TIFF file (bad signature)');
  const directory = readDirectory(bytes, fail);
  const buffer = fileBuffer(bytes);
  const image = await guard('bad TIFF structure', async () => (await openTiffBuffer(buffer)).getImage(0));
  const dir = image.fileDirectory;
  const tag = (key) => guard(`bad TIFF tag ${key}`, () => dir.loadValue(key));
  const [width, height] = [await tag('ImageWidth'), await tag('ImageLength')];
  for (const [what, v] of [['width', width], ['height', height]]) {
    if (!Number.isInteger(v) || v <= 0) fail(`bad TIFF: ${what} ${shown(v)} is not a positive whole number`);
  }
  const bits = Array.from((await tag('BitsPerSample')) ?? [1]);
  const samplesPerPixel = (await tag('SamplesPerPixel')) ?? 1;
  const photometric = await tag('PhotometricInterpretation');
  const compression = (await tag('Compression')) ?? 1;
  const kind = PHOTOMETRIC[photometric];
  if (!kind) fail(`unsupported TIFF image: photometric interpretation ${shown(photometric)} (RGB, grey, palette or YCbCr JPEG can be draped)`);
  if (!bits.every((b) => b === 8)) fail(`unsupported TIFF image: ${bits.join('+')}-bit samples (8-bit images can be draped; a height field is dropped on its own)`);
  if (photometric === 6 && compression !== JPEG) fail('unsupported TIFF image: YCbCr without JPEG compression');
  if (photometric === 3 && !(await tag('ColorMap'))) fail('bad TIFF: a palette image without its colour map');
  if ((photometric === 2 || photometric === 6) && samplesPerPixel < 3) fail(`bad TIFF: an ${kind} image with ${samplesPerPixel} samples a pixel`);
  if ((await tag('PlanarConfiguration') ?? 1) !== 1) fail('unsupported TIFF image: colour planes stored apart (write it pixel-interleaved, e.g. gdal_translate -co INTERLEAVE=PIXEL)');

  const layout = await guard('bad TIFF layout', () => blockLayout(image, directory, { width, height }, fail));
  await guard('bad TIFF image data', () => checkBlocks(image, layout, directory, bytes, fail, pace));
  const nodata = parseImageNodata(await tag('GDAL_NODATA'));
  const georef = georefOfTiff(image);
  // What a JPEG decoder makes of the components is the image's colour: grey from one, RGB from
  // three (with the stream marked RGB or YCbCr); four (RGBA, CMYK) and white-is-zero it is not.
  const jpeg = decodeJpeg && compression === JPEG
    && ((photometric === 1 && samplesPerPixel === 1) || ((photometric === 2 || photometric === 6) && samplesPerPixel === 3))
    ? { bytes, width, height, layout, tables: (await tag('JPEGTables')) ?? null, rgb: photometric === 2 } : null;
  if ((await begin(width, height, georef)) === false) return { width, height, georef, kind, nodata };

  const bandRows = Math.min(height, layout.blockHeight * Math.max(1, Math.round(BAND_PIXELS / width / layout.blockHeight)));
  for (let y = 0; y < height; y += bandRows) {
    const rows = Math.min(bandRows, height - y);
    let rgba = null;
    if (jpeg) {
      try {
        rgba = maskNodata(await decodeJpegBand(jpeg, y, rows, decodeJpeg), nodata);
      } catch {
        rgba = null; // the library may still read what this decoder would not; if not, its error says why
      }
    }
    if (!rgba) {
      const raster = await guard('corrupt image data', () =>
        image.readRGB({ window: [0, y, width, y + rows], interleave: true, enableAlpha: true }));
      rgba = toRgba(raster, raster.length / (width * rows), nodata);
    }
    await onBand(y, rows, rgba);
    await pace((y + rows) / height);
  }
  return { width, height, georef, kind, nodata };
}

/** RGB or RGBA samples as RGBA, no-data masked. */
function toRgba(raster, channels, nodata) {
  const pixels = raster.length / channels;
  const rgba = new Uint8Array(pixels * 4);
  for (let i = 0, j = 0; i < raster.length; i += channels, j += 4) {
    rgba[j] = raster[i]; rgba[j + 1] = raster[i + 1]; rgba[j + 2] = raster[i + 2];
    rgba[j + 3] = channels >= 4 ? raster[i + 3] : 255;
  }
  return maskNodata(rgba, nodata);
}

/** Makes the pixels whose colour samples all equal the no-data value transparent, in place; returns rgba. */
function maskNodata(rgba, nodata) {
  if (nodata === null) return rgba;
  for (let j = 0; j < rgba.length; j += 4) {
    if (rgba[j] === nodata && rgba[j + 1] === nodata && rgba[j + 2] === nodata) rgba[j + 3] = 0;
  }
  return rgba;
}

/** GDAL's no-data text as an 8-bit value, or null (none, or a value no 8-bit sample can hold). */
function parseImageNodata(value) {
  if (typeof value !== 'string') return null;
  const v = Number(value.replace(/\0+$/, '').trim());
  return Number.isInteger(v) && v >= 0 && v <= 255 ? v : null;
}
