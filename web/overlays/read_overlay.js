// Reads a GPX (1.0, 1.1), KML, KMZ or GeoJSON file into an overlay: its features (geojson_
// features.js) and the CRS their coordinates are in. KML goes through @tmcw/togeojson (the
// well-kept converter of Mapbox's former toGeoJSON), over the browser's XML parser or xmldom in
// Node (parse_xml.js); KMZ is unzipped with fflate; GeoJSON is JSON.parse. GPX is read from its
// DOM directly (gpx_features.js): togeojson keeps only the times a track has, which shifts them
// onto the wrong points when one point has none, and drops a point it cannot read. KML's
// altitudeMode, which togeojson leaves out, is read from each Placemark, and its coordinates
// are checked there, as togeojson would drop a broken tuple silently.
//
// Every way a file can be wrong gets an OverlayError that says how: empty, malformed XML or
// JSON, a KMZ without KML, no features, coordinates that are not longitude and latitude, an
// unknown legacy "crs" member. GeoJSON is WGS 84 (RFC 7946); a legacy "crs" member (the 2008
// specification's) is honoured, and the overlay's notes say so.
import { kml } from '@tmcw/togeojson';
import { unzipSync } from 'fflate';
import { crsOfEpsg, parseEpsg, resolveCrs } from '../geo/index.js';
import { OverlayError } from './overlay_error.js';
import { overlayKind } from './overlay_kind.js';
import { parseXml } from './parse_xml.js';
import { featuresOf } from './geojson_features.js';
import { gpxFeatures } from './gpx_features.js';

const FORMAT = { gpx: 'GPX', kml: 'KML', kmz: 'KMZ', geojson: 'GeoJSON' };
const CRS84 = /CRS84$|OGC:1\.3:CRS84/i;

/**
 * @typedef {object} Overlay
 * @property {string} name the file's
 * @property {'GPX'|'KML'|'KMZ'|'GeoJSON'} format
 * @property {import('../geo/georef.js').Crs} crs the CRS of the coordinates: WGS 84 longitude and
 *   latitude (EPSG:4326, x = longitude) unless a legacy GeoJSON "crs" member says otherwise
 * @property {import('./geojson_features.js').Feature[]} features
 * @property {string[]} notes what the page should tell
 */

/**
 * @param {string} name the file's name (its extension says the format; a .json must hold GeoJSON)
 * @param {Uint8Array} bytes
 * @returns {Promise<Overlay>}
 * @throws {OverlayError}
 */
export async function readOverlay(name, bytes) {
  const kind = overlayKind(name, bytes.subarray(0, 4096));
  if (!kind) throw new OverlayError('not an overlay: GPX, KML, KMZ and GeoJSON files are (.gpx, .kml, .kmz, .geojson, or a .json holding GeoJSON)');
  if (bytes.length === 0) throw new OverlayError('the file is empty');
  const notes = [];
  let geojson = null, altitudes = null, features = null, crs = crsOfEpsg(4326, true);
  if (kind === 'geojson') {
    geojson = parseJson(textOf(bytes));
    const legacy = legacyCrs(geojson);
    if (legacy) {
      crs = legacy;
      notes.push(`its legacy "crs" member (${legacy.label}) was honoured`);
    }
  } else {
    const text = kind === 'kmz' ? kmlOfKmz(bytes) : textOf(bytes);
    const doc = await parseXml(text);
    const root = doc.documentElement?.localName ?? doc.documentElement?.nodeName;
    const expected = kind === 'gpx' ? 'gpx' : 'kml';
    if (root !== expected) throw new OverlayError(`not a ${FORMAT[expected]} document: its root element is <${root}>, not <${expected}>`);
    if (kind === 'gpx') features = gpxFeatures(doc);
    else {
      geojson = kml(doc);
      altitudes = placemarkAltitudes(doc, geojson.features.length, notes);
    }
  }
  features ??= featuresOf(geojson, {
    source: kind === 'geojson' ? 'feature' : 'placemark',
    altitudeOf: (k) => altitudes?.[k] ?? 'clamp',
  });
  if (features.length === 0) throw new OverlayError(`no features with a geometry in this ${FORMAT[kind]} file`);
  if (crs.epsg === 4326) checkLonLat(features);
  const resolved = await resolveCrs(crs);
  if (crs.epsg !== 4326 && !resolved.proj4) throw new OverlayError(`its legacy "crs" member names ${crs.label}, which has no definition here`);
  return { name, format: FORMAT[kind], crs: resolved, features, notes };
}

function textOf(bytes) {
  const text = new TextDecoder().decode(bytes).replace(/^\uFEFF/, '');
  if (text.trim() === '') throw new OverlayError('the file is empty (only white space)');
  return text;
}

/** JSON.parse, its error with the place it happened. */
function parseJson(text) {
  let value;
  try {
    value = JSON.parse(text);
  } catch (error) {
    const at = /position (\d+)/.exec(error.message);
    const where = at ? ` at line ${text.slice(0, Number(at[1])).split('\n').length}` : '';
    throw new OverlayError(`malformed JSON${where}: ${error.message}`);
  }
  if (!value || typeof value !== 'object' || typeof value.type !== 'string') {
    throw new OverlayError('not GeoJSON: the JSON is not an object with a "type"');
  }
  return value;
}

/** The KML inside a KMZ (a zip): doc.kml, else its first .kml. */
function kmlOfKmz(bytes) {
  let files;
  try {
    files = unzipSync(bytes);
  } catch (error) {
    throw new OverlayError(`not a readable KMZ (a zip archive): ${error.message}`);
  }
  const names = Object.keys(files);
  const kmlName = names.find((n) => n.toLowerCase() === 'doc.kml') ?? names.find((n) => n.toLowerCase().endsWith('.kml'));
  if (!kmlName) {
    const held = names.length ? `it holds ${names.slice(0, 8).join(', ')}${names.length > 8 ? ', …' : ''}` : 'it is empty';
    throw new OverlayError(`a KMZ without a KML document inside (${held})`);
  }
  return textOf(files[kmlName]);
}

/** Each Placemark's altitudeMode, in the order togeojson gives their features; its coordinates checked. */
function placemarkAltitudes(doc, featureCount, notes) {
  const placemarks = Array.from(doc.getElementsByTagName('Placemark'));
  placemarks.forEach(checkCoordinates);
  const modes = placemarks.map((placemark) => {
    const element = placemark.getElementsByTagName('altitudeMode')[0] ?? placemark.getElementsByTagName('gx:altitudeMode')[0];
    return element?.textContent.trim() ?? 'clampToGround';
  });
  if (modes.includes('relativeToGround')) notes.push('relativeToGround is drawn on the ground');
  if (placemarks.length !== featureCount) return null; // cannot pair them: every one on the ground
  return modes.map((mode) => (mode === 'absolute' ? 'absolute' : 'clamp'));
}

/** Every tuple of a Placemark's <coordinates> must be 2 or 3 numbers: togeojson would drop it silently. */
function checkCoordinates(placemark, index) {
  for (const element of Array.from(placemark.getElementsByTagName('coordinates'))) {
    const tuples = element.textContent.trim().split(/\s+/).filter((s) => s !== '');
    for (let k = 0; k < tuples.length; k++) {
      const parts = tuples[k].split(',');
      if (parts.length < 2 || parts.length > 3 || parts.some((p) => p.trim() === '' || !Number.isFinite(Number(p)))) {
        const name = placemark.getElementsByTagName('name')[0]?.textContent.trim();
        throw new OverlayError(`placemark ${index + 1}${name ? ` ("${name}")` : ''}: coordinate ${k + 1} "${tuples[k].slice(0, 60)}" is not longitude,latitude[,altitude] numbers`);
      }
    }
  }
}

/** A legacy "crs" member's CRS, or null (none, or CRS84, which is WGS 84). */
function legacyCrs(geojson) {
  const member = geojson.crs;
  if (member === undefined || member === null) return null;
  const name = member?.properties?.name;
  if (member.type !== 'name' || typeof name !== 'string') {
    throw new OverlayError(`its legacy "crs" member is not of the form {"type": "name", "properties": {"name": "EPSG:..."}} (${JSON.stringify(member).slice(0, 80)})`);
  }
  if (CRS84.test(name)) return null;
  const epsg = parseEpsg(name);
  if (epsg === null) throw new OverlayError(`its legacy "crs" member names ${name}, which is not an EPSG code`);
  return crsOfEpsg(epsg);
}

/** Coordinates of WGS 84 must be longitudes and latitudes. */
function checkLonLat(features) {
  for (const feature of features) {
    for (const { x, y } of feature.paths) {
      for (let k = 0; k < x.length; k++) {
        if (Math.abs(x[k]) > 180 || Math.abs(y[k]) > 90) {
          throw new OverlayError(`coordinates (${x[k]}, ${y[k]}) are not WGS 84 longitude and latitude (a projected CRS's metres?); ` +
            'GeoJSON is WGS 84 (RFC 7946): reproject it, e.g. ogr2ogr -t_srs EPSG:4326 out.geojson in.geojson');
        }
      }
    }
  }
}
