// GeoTIFF height fields through the `geotiff` library (its directory parsing, and strips or
// tiles in none, deflate, LZW and the other codecs it knows, with predictors). Every block is
// checked against its geometry before the field is allocated (tiff_blocks.js), then decoded
// one at a time straight into the caller's samples (tiff_raster.js): the full raster is never
// held twice.
//
// Sample types: int16 -> i16, uint16 -> u16, uint8 -> u8 (exact); float32 -> f32 (exact);
// int32/uint32 and float64 -> f32 (exact for integer heights up to 2^24 = 16 777 216, i.e.
// metres, decimetres or centimetres of any terrain; float64 keeps ~7 significant digits).
// Spacing comes from the geotransform: metres (or feet) for projected grids, degrees for
// geographic ones (EPSG:4326 and friends), turned into metres at the raster's mid latitude.

import { HeightfieldError, DEFAULT_MAX_SAMPLES, checkSize } from './common.js';
import { hasTiffSignature, parseNodata, sampleTypeOf, spacingOf, readDirectory, libraryGuard, fileBuffer, openTiffBuffer, blockLayout,
  checkBlocks, dataExtent, readBlocks, georefOfTiff, shiftGeoref, heightScaling } from '../geo/index.js';
import { SampleSink, pacer } from './pacing.js';



/**
 * @returns {Promise<{ width, height, sampleType, samples, nodata: number|null, spacingX: number|null,
 *   spacingY: number|null, geographic: boolean, heightScale: number, heightOffset: number }>}
 *   spacing in metres, null when the file has no geotransform; metres = raw x heightScale +
 *   heightOffset (GDAL's scale and offset, tiff_fields.js heightScaling)
 */
export async function decodeGeoTiff(bytes, name, allocate, options = {}) {
  const { fail, guard, image, directory, width, height, format, bits, sampleType } = await openGeoTiff(bytes, name, options);
  const dir = image.fileDirectory;
  const nodata = parseNodata(await guard('bad TIFF no-data tag (42113)', () => dir.loadValue('GDAL_NODATA')), fail);
  const scaling = heightScaling(await guard('bad TIFF metadata tag (42112)', () => image.getGDALMetadata(0)), fail);

  // Every strip or tile must hold what its geometry needs before memory is reserved.
  const layout = await guard('bad TIFF layout', () => blockLayout(image, directory, { width, height }, fail));
  await guard('bad TIFF image data', () => checkBlocks(image, layout, directory, bytes, fail, pacer(options.onCheckProgress)));

  const extent = dataExtent(layout, { width, height }, fail);
  const geo = spacingOf(image, extent.y + extent.height / 2);
  const sink = new SampleSink(allocate, sampleType, extent.width, extent.height, options);
  await guard('corrupt image data', () => readBlocks(image, layout, bytes, sink, extent, { format, bits, nodata }));
  if (sampleType === 'f32') rejectInfinities(sink.samples, extent.width, fail);
  const cropped = extent.cropped ? { column: extent.x, row: extent.y, width, height } : null;
  const georef = shiftGeoref(georefOfTiff(image), extent.x, extent.y);
  return { width: extent.width, height: extent.height, sampleType, samples: sink.samples, nodata, cropped, georef, ...scaling, ...geo };
}

/**
 * The first image's size and sample type, checked, and where it lies: what a mosaic needs of a
 * tile before any tile is decoded (mosaic.js). Reads the directory, not the samples.
 * @returns {Promise<{ width: number, height: number, sampleType: string, georef: import('../geo/georef.js').Georef|null }>}
 */
export async function probeGeoTiff(bytes, name, options = {}) {
  const { width, height, sampleType, image } = await openGeoTiff(bytes, name, options);
  return { width, height, sampleType, georef: georefOfTiff(image) };
}

/** Opens a TIFF as far as its first image's size and sample type, refusing what we cannot decode. */
async function openGeoTiff(bytes, name, options) {
  const fail = (problem) => { throw new HeightfieldError(name, problem); };
  if (bytes.length < 8) fail(bytes.length === 0 ? 'empty file' : `truncated: ${bytes.length} bytes, no TIFF header`);
  if (!hasTiffSignature(bytes)) fail('not a TIFF file (bad signature)');
  const directory = readDirectory(bytes, fail);

  // Every call into the library goes through the guard (tiff_library.js).
  const guard = libraryGuard(fail, HeightfieldError);
  const buffer = fileBuffer(bytes);
  const image = await guard('bad TIFF structure', async () => (await openTiffBuffer(buffer)).getImage(0));
  const dir = image.fileDirectory;
  const [width, height] = await guard('bad TIFF image size', () => Promise.all([dir.loadValue('ImageWidth'), dir.loadValue('ImageLength')]));
  if (width === undefined || height === undefined) fail('bad TIFF: image size missing');
  checkSize(name, width, height, options.maxSamples ?? DEFAULT_MAX_SAMPLES);
  const [format, bits] = await guard('bad TIFF sample type', async () =>
    [(await dir.loadValue('SampleFormat'))?.[0] ?? 1, (await dir.loadValue('BitsPerSample'))?.[0] ?? 1]);
  const sampleType = sampleTypeOf(format, bits);
  if (!sampleType) fail(`unsupported TIFF sample type: ${['', 'unsigned', 'signed', 'float'][format] ?? `format ${format}`} ${bits}-bit`);
  return { fail, guard, image, directory, width, height, format, bits, sampleType };
}




function rejectInfinities(samples, width, fail) {
  for (let i = 0; i < samples.length; i++) {
    if (samples[i] === Infinity || samples[i] === -Infinity) {
      fail(`sample at row ${Math.floor(i / width)}, column ${i % width} is ${samples[i]} (expected finite metres or nodata)`);
    }
  }
}
