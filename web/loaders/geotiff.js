// GeoTIFF height fields through the `geotiff` library (strips or tiles; none, deflate, LZW and
// the other codecs it knows; predictors). It reads a band of rows at a time into a small
// array that is copied into the caller's samples, so the full raster is never held twice.
//
// Sample types: int16 -> i16, uint16 -> u16, uint8 -> u8 (exact); float32 -> f32 (exact);
// int32/uint32 and float64 -> f32 (exact for integer heights up to 2^24 = 16 777 216, i.e.
// metres, decimetres or centimetres of any terrain; float64 keeps ~7 significant digits).
// Spacing comes from the geotransform: metres (or feet) for projected grids, degrees for
// geographic ones (EPSG:4326 and friends), turned into metres at the raster's mid latitude.

import { fromArrayBuffer, addDecoder } from 'geotiff';
import { HeightfieldError, DEFAULT_MAX_SAMPLES, checkSize, degreesToMetres } from './common.js';
import { SampleSink } from './pacing.js';
import { TiffLzwDecoder, lzwParameters } from './tiff_lzw.js';

// Compression 5 (LZW) through our bounded decoder (see tiff_lzw.js); not in a worker.
addDecoder(5, async () => TiffLzwDecoder, lzwParameters, false);

/** Rows decoded per read, at most (a band is cut to whole strips or tiles). */
const BAND_SAMPLES = 1 << 21;
const GEOGRAPHIC_MODEL = 2; // GTModelTypeGeoKey: 1 projected, 2 geographic
const LINEAR_UNITS_M = { 9001: 1, 9002: 0.3048, 9003: 0.3048006096012192 }; // EPSG unit codes

/** True when bytes start with a TIFF or BigTIFF header. */
export function hasTiffSignature(bytes) {
  return bytes.length >= 4 && ((bytes[0] === 0x49 && bytes[1] === 0x49 && (bytes[2] === 0x2a || bytes[2] === 0x2b) && bytes[3] === 0) ||
    (bytes[0] === 0x4d && bytes[1] === 0x4d && bytes[2] === 0 && (bytes[3] === 0x2a || bytes[3] === 0x2b)));
}

/**
 * @returns {Promise<{ width, height, sampleType, samples, nodata: number|null, spacingX: number|null,
 *   spacingY: number|null, geographic: boolean }>} spacing in metres, null when the file has no
 *   geotransform
 */
export async function decodeGeoTiff(bytes, name, allocate, options = {}) {
  const fail = (problem) => { throw new HeightfieldError(name, problem); };
  if (bytes.length < 8) fail(bytes.length === 0 ? 'empty file' : `truncated: ${bytes.length} bytes, no TIFF header`);
  if (!hasTiffSignature(bytes)) fail('not a TIFF file (bad signature)');
  const ifd = firstDirectoryOffset(bytes);
  if (ifd + 2 > bytes.length) fail(`truncated: the image directory at byte ${ifd} lies past the end (${bytes.length} bytes)`);

  // Any failure inside the library on a damaged file is that file's problem.
  const guard = async (what, step) => {
    try {
      return await step();
    } catch (e) {
      if (e instanceof HeightfieldError) throw e;
      fail(`${what}: ${String(e?.message ?? e).split('\n')[0].slice(0, 160)}`);
    }
  };
  const buffer = bytes.byteOffset === 0 && bytes.length === bytes.buffer.byteLength
    ? bytes.buffer : bytes.slice().buffer;
  const image = await guard('bad TIFF structure', async () => (await fromArrayBuffer(buffer)).getImage(0));
  const dir = image.fileDirectory;
  const width = image.getWidth(), height = image.getHeight();
  checkSize(name, width, height, options.maxSamples ?? DEFAULT_MAX_SAMPLES);
  const format = dir.getValue('SampleFormat')?.[0] ?? 1;
  const bits = dir.getValue('BitsPerSample')?.[0] ?? 1;
  const sampleType = sampleTypeOf(format, bits);
  if (!sampleType) fail(`unsupported TIFF sample type: ${['', 'unsigned', 'signed', 'float'][format] ?? `format ${format}`} ${bits}-bit`);
  await guard('bad TIFF structure', () => checkBlocksInFile(image, bytes.length, fail));

  const nodata = image.getGDALNoData();
  const geo = spacingOf(image, height);

  const sink = new SampleSink(allocate, sampleType, width, height, options);
  const blockRows = image.getTileHeight() || height;
  const rowsPerBand = Math.max(1, Math.floor(BAND_SAMPLES / width / blockRows)) * blockRows;
  for (let y0 = 0; y0 < height; y0 += rowsPerBand) {
    const y1 = Math.min(height, y0 + rowsPerBand);
    const band = await guard(`corrupt image data in rows ${y0}..${y1 - 1}`,
      () => image.readRasters({ window: [0, y0, width, y1], samples: [0], interleave: true }));
    if (band.length !== (y1 - y0) * width) fail(`corrupt image data in rows ${y0}..${y1 - 1}`);
    sink.samples.set(band, y0 * width); // int32/float64 convert to float32 here
    await sink.pace(y1 / height);
  }
  if (sampleType === 'f32') rejectInfinities(sink.samples, width, fail);
  return { width, height, sampleType, samples: sink.samples, nodata: Number.isFinite(nodata) ? nodata : null, ...geo };
}

/** Byte offset of the first image file directory (classic TIFF or BigTIFF header). */
function firstDirectoryOffset(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.length);
  const little = bytes[0] === 0x49;
  if (view.getUint16(2, little) === 43) return bytes.length < 16 ? Infinity : Number(view.getBigUint64(8, little));
  return view.getUint32(4, little);
}

function sampleTypeOf(format, bits) {
  if (format === 1 && bits === 8) return 'u8';
  if (format === 1 && bits === 16) return 'u16';
  if (format === 2 && bits === 16) return 'i16';
  if ((format === 1 || format === 2) && bits === 32) return 'f32';
  if (format === 3 && (bits === 32 || bits === 64)) return 'f32';
  return null;
}

/** Every strip or tile must lie inside the file: otherwise it was cut short. */
async function checkBlocksInFile(image, fileBytes, fail) {
  const dir = image.fileDirectory;
  const tiled = dir.hasTag('TileOffsets');
  const offsets = await dir.loadValue(tiled ? 'TileOffsets' : 'StripOffsets');
  const counts = await dir.loadValue(tiled ? 'TileByteCounts' : 'StripByteCounts');
  if (!offsets || !counts) fail(`bad TIFF: no ${tiled ? 'tile' : 'strip'} offsets`);
  const across = Math.ceil(image.getWidth() / image.getTileWidth());
  const down = Math.ceil(image.getHeight() / image.getTileHeight());
  if (offsets.length < across * down || counts.length < across * down) {
    fail(`bad TIFF: ${offsets.length} ${tiled ? 'tiles' : 'strips'} listed, ${across * down} needed`);
  }
  let stored = 0;
  for (let i = 0; i < offsets.length; i++) {
    if (Number(offsets[i]) + Number(counts[i]) > fileBytes) {
      fail(`truncated: ${tiled ? 'tile' : 'strip'} ${i} ends at byte ${Number(offsets[i]) + Number(counts[i])}, the file has ${fileBytes}`);
    }
    stored += Number(counts[i]);
  }
  // No codec expands more than LZW (a 12-bit code stands for at most 4096 bytes): fewer
  // stored bytes than that cannot hold the declared image. Checked before allocating.
  const bits = Array.from(dir.getValue('BitsPerSample') ?? [1]).reduce((a, b) => a + b, 0);
  const rawBytes = image.getWidth() * image.getHeight() * (bits / 8);
  const ratio = (dir.getValue('Compression') ?? 1) === 1 ? 1 : 2731;
  if (stored * ratio < rawBytes) fail(`truncated: ${stored} bytes of image data cannot hold ${image.getWidth()}x${image.getHeight()} samples`);
}

/** Metres between columns and rows from the geotransform, or nulls without one. */
function spacingOf(image, height) {
  let resolution, origin;
  try {
    resolution = image.getResolution();
    origin = image.getOrigin();
  } catch {
    return { spacingX: null, spacingY: null, geographic: false };
  }
  const [rx, ry] = resolution.map(Math.abs);
  if (!(rx > 0) || !(ry > 0) || !Number.isFinite(rx) || !Number.isFinite(ry)) return { spacingX: null, spacingY: null, geographic: false };
  let keys = null;
  try { keys = image.getGeoKeys(); } catch { keys = null; }
  if (keys?.GTModelTypeGeoKey === GEOGRAPHIC_MODEL) {
    const midLatitude = origin[1] + resolution[1] * (height / 2); // resolution[1] < 0: rows go south
    return { ...degreesToMetres(rx, ry, Math.max(-90, Math.min(90, midLatitude))), geographic: true };
  }
  const unit = LINEAR_UNITS_M[keys?.ProjLinearUnitsGeoKey] ?? 1;
  return { spacingX: rx * unit, spacingY: ry * unit, geographic: false };
}

function rejectInfinities(samples, width, fail) {
  for (let i = 0; i < samples.length; i++) {
    if (samples[i] === Infinity || samples[i] === -Infinity) {
      fail(`sample at row ${Math.floor(i / width)}, column ${i % width} is ${samples[i]} (expected finite metres or nodata)`);
    }
  }
}
