// GDAL's .aux.xml (its "persistent auxiliary metadata", PAM) beside a raster: the CRS GDAL
// knows it by (<SRS>, a WKT) and, for a format that cannot hold one, its geotransform
// (<GeoTransform>: x of the first pixel's corner, x step, row rotation, y of the corner, column
// rotation, y step). The rest (statistics, histograms, metadata) is not read.
// The XML is read with fast-xml-parser, a well-kept parser that runs in the page and in Node
// (entities, CDATA and comments are its business, not ours); it is loaded only when a file has
// an .aux.xml.
import { makeGeoref, UNKNOWN_CRS } from './georef.js';
import { crsFromWkt } from './crs_wkt.js';
import { CrsError } from './crs_error.js';

/**
 * @param {string} text the file's text
 * @param {string} fileName for messages
 * @returns {Promise<{ crs: import('./georef.js').Crs|null, georef: import('./georef.js').Georef|null }>}
 *   crs: from <SRS> (not resolved yet), null without one; georef: from <GeoTransform>, in that
 *   CRS (unknown without one), null without one
 * @throws {CrsError} naming the file: not XML, not GDAL's PAM, an SRS proj4 cannot read, a
 *   geotransform that is not six numbers or is rotated
 */
export async function parseAuxXml(text, fileName) {
  const { XMLParser, XMLValidator } = await import('fast-xml-parser');
  const valid = XMLValidator.validate(text);
  if (valid !== true) throw new CrsError(`${fileName}: not XML (${valid.err?.msg ?? 'unreadable'}, line ${valid.err?.line ?? '?'})`);
  const doc = new XMLParser({ ignoreAttributes: true, parseTagValue: false, trimValues: true }).parse(text);
  const pam = doc?.PAMDataset;
  if (pam === undefined) throw new CrsError(`${fileName}: not a GDAL .aux.xml (no <PAMDataset>)`);
  const srs = textOf(pam?.SRS);
  const crs = srs ? crsFromWkt(srs, fileName) : null;
  const transform = textOf(pam?.GeoTransform);
  return { crs, georef: transform ? georefOf(transform, crs, fileName) : null };
}

/** An element's text: fast-xml-parser gives a string, or an object for an element with attributes left out. */
function textOf(value) {
  if (Array.isArray(value)) value = value[0];
  if (typeof value === 'string') return value.trim() || null;
  if (value && typeof value === 'object' && typeof value['#text'] === 'string') return value['#text'].trim() || null;
  return null;
}

/** GDAL's geotransform (corner of the first pixel) as our georeference (sample centres). */
function georefOf(text, crs, fileName) {
  const numbers = text.split(',').map((part) => (part.trim() === '' ? NaN : Number(part)));
  if (numbers.length !== 6 || !numbers.every(Number.isFinite)) {
    throw new CrsError(`${fileName}: its <GeoTransform> is not six numbers (${text.slice(0, 60)})`);
  }
  const [x, dx, rowRotation, y, columnRotation, dy] = numbers;
  if (rowRotation !== 0 || columnRotation !== 0) throw new CrsError(`${fileName}: its <GeoTransform> is rotated; only north-up grids are placed`);
  const georef = makeGeoref(crs ?? UNKNOWN_CRS, x + dx / 2, y + dy / 2, dx, dy, '.aux.xml');
  if (!georef) throw new CrsError(`${fileName}: its <GeoTransform> has a step of zero or a negative x step`);
  return georef;
}
