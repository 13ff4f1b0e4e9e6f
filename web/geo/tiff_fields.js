// What a TIFF's tags say, read the same way for height fields, draped images and tiled COG
// tiles: its signature, its sample type, the GDAL no-data tag, and the metres between samples.
import { shown } from './shown.js';
import { degreesToMetres } from './ground_spacing.js';

const GEOGRAPHIC_MODEL = 2; // GTModelTypeGeoKey: 1 projected, 2 geographic
const LINEAR_UNITS_M = { 9001: 1, 9002: 0.3048, 9003: 0.3048006096012192 }; // EPSG unit codes

/** True when bytes start with a TIFF or BigTIFF header. */
export function hasTiffSignature(bytes) {
  return bytes.length >= 4 && ((bytes[0] === 0x49 && bytes[1] === 0x49 && (bytes[2] === 0x2a || bytes[2] === 0x2b) && bytes[3] === 0) ||
    (bytes[0] === 0x4d && bytes[1] === 0x4d && bytes[2] === 0 && (bytes[3] === 0x2a || bytes[3] === 0x2b)));
}

/**
 * The GDAL no-data tag (42113): ASCII text holding a number, "-32768" (with or without its
 * terminating NUL). "nan" and "inf" give no value: NaN samples are no-data anyway, and an
 * infinite one is damage.
 */
export function parseNodata(value, fail) {
  if (value === undefined) return null;
  if (typeof value !== 'string') fail(`bad TIFF: the no-data tag (42113) holds ${shown(value)}, not the text of a number`);
  const text = value.replace(/\0+$/, '').trim();
  if (/^[+-]?(nan|inf|infinity)$/i.test(text)) return null;
  const v = text === '' ? NaN : Number(text);
  if (!Number.isFinite(v)) fail(`bad TIFF: the no-data tag (42113) is not a number (${JSON.stringify(text.slice(0, 40))})`);
  return v;
}

/** Our sample type for a TIFF's SampleFormat and BitsPerSample, or null when we do not read it. */
export function sampleTypeOf(format, bits) {
  if (format === 1 && bits === 8) return 'u8';
  if (format === 1 && bits === 16) return 'u16';
  if (format === 2 && bits === 16) return 'i16';
  if ((format === 1 || format === 2) && bits === 32) return 'f32';
  if (format === 3 && (bits === 32 || bits === 64)) return 'f32';
  return null;
}

/** Metres between columns and rows from the geotransform, or nulls without one. */
export function spacingOf(image, middleRow) {
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
    const midLatitude = origin[1] + resolution[1] * middleRow; // resolution[1] < 0: rows go south
    return { ...degreesToMetres(rx, ry, Math.max(-90, Math.min(90, midLatitude))), geographic: true };
  }
  const unit = LINEAR_UNITS_M[keys?.ProjLinearUnitsGeoKey] ?? 1;
  return { spacingX: rx * unit, spacingY: ry * unit, geographic: false };
}

/**
 * The heights' scale and offset GDAL keeps in its metadata tag (42112) for band 1
 * (`gdal_translate -a_scale S -a_offset O`, or a DEM stored as decimetres in Int16): metres =
 * raw x scale + offset. Its STATISTICS_* items are of the raw values.
 * @param {Record<string, unknown>|null} items the band's metadata items (geotiff's getGDALMetadata(0))
 * @returns {{ heightScale: number, heightOffset: number }} 1 and 0 when the file states neither
 */
export function heightScaling(items, fail) {
  const read = (name, fallback) => {
    const text = items?.[name];
    if (text === undefined || text === null) return fallback;
    const value = typeof text === 'string' && text.trim() !== '' ? Number(text) : NaN;
    if (!Number.isFinite(value)) fail(`bad TIFF: the GDAL metadata's ${name} is not a number (${shown(text)})`);
    return value;
  };
  const heightScale = read('SCALE', 1), heightOffset = read('OFFSET', 0);
  if (heightScale === 0) fail('bad TIFF: the GDAL metadata\'s SCALE is 0, which would make every height the same');
  return { heightScale, heightOffset };
}
