// Real-world coordinates of a point of the field: the CRS coordinates its georeference gives
// (web/geo/georef.js), and latitude and longitude too, directly for a geographic CRS and
// through proj4 for the projected CRSs whose definition is a line we can write here: UTM on
// WGS 84 (EPSG:326zz north, 327zz south), on NAD83 (269zz) and on ETRS89 (258zz), and Web
// Mercator (3857). NAD83 and ETRS89 latitudes and longitudes are given in their own datum
// (within about a metre of WGS 84); no datum shift is applied.
import proj4 from 'proj4';
import { sampleToCrs } from './georef.js';

/** What the HUD says of a field without a georeference. */
export const localLabel = 'local metres (no CRS)';

/**
 * @typedef {object} GeoCoordinates
 * @property {number|null} easting CRS x in metres (projected CRSs), else null
 * @property {number|null} northing CRS y in metres (projected CRSs), else null
 * @property {number|null} lat degrees north (negative south), null when the CRS is not one we can invert
 * @property {number|null} lon degrees east (negative west)
 * @property {string} crsLabel 'EPSG:32645', 'unknown', ...
 * @property {boolean} geographic whether the CRS itself is latitude and longitude
 */

/**
 * @param {import('./georef.js').Georef|null} georef
 * @param {number} x local metres east of the first sample (x = column * spacingX)
 * @param {number} z local metres south of the first sample (z = row * spacingY)
 * @param {number} spacingX metres between columns, as the terrain has it
 * @param {number} spacingY metres between rows
 * @returns {GeoCoordinates|null} null without a georeference
 */
export function geoCoordinates(georef, x, z, spacingX, spacingY) {
  if (!georef) return null;
  const [cx, cy] = sampleToCrs(georef, x / spacingX, z / spacingY);
  const crsLabel = georef.crs.label;
  if (georef.crs.geographic) return { easting: null, northing: null, lat: cy, lon: cx, crsLabel, geographic: true };
  const inverse = inverseOf(georef.crs.epsg);
  const [lon, lat] = inverse ? inverse(cx, cy) : [null, null];
  return { easting: cx, northing: cy, lat, lon, crsLabel, geographic: false };
}

/**
 * CRS coordinates to local metres, the inverse of geoCoordinates' first step (the CLI's --crs).
 * @returns {[number, number]} [x, z] local metres
 */
export function crsToLocal(georef, cx, cy, spacingX, spacingY) {
  return [((cx - georef.x0) / georef.dx) * spacingX, ((cy - georef.y0) / georef.dy) * spacingY];
}

/**
 * Short text for the HUD: 'E 512 340 m N 3 012 455 m (EPSG:32645) · 27.9879° N 86.9250° E',
 * '27.9879° N 86.9250° E (EPSG:4326)', or localLabel for null.
 * @param {GeoCoordinates|null} c
 */
export function formatCoordinates(c) {
  if (!c) return localLabel;
  const latLon = c.lat === null || c.lon === null || !Number.isFinite(c.lat) ? null
    : `${Math.abs(c.lat).toFixed(4)}° ${c.lat < 0 ? 'S' : 'N'} ${Math.abs(c.lon).toFixed(4)}° ${c.lon < 0 ? 'W' : 'E'}`;
  if (c.geographic) return `${latLon} (${c.crsLabel})`;
  const projected = `E ${grouped(c.easting)} m N ${grouped(c.northing)} m (${c.crsLabel})`;
  return latLon ? `${projected} · ${latLon}` : projected;
}

/** Whole metres in groups of three: 3012455.4 -> '3 012 455'. */
function grouped(metres) {
  const whole = Math.round(metres);
  const digits = String(Math.abs(whole)).replace(/\B(?=(\d{3})+(?!\d))/g, ' ');
  return whole < 0 ? `-${digits}` : digits;
}

// proj4 definitions by EPSG code, made on first use and kept.
const inverses = new Map();

/** (easting, northing) -> [lon, lat] for a CRS we can define, else null. */
function inverseOf(epsg) {
  if (!Number.isInteger(epsg)) return null;
  if (!inverses.has(epsg)) {
    const definition = definitionOf(epsg);
    const converter = definition && proj4(definition, 'EPSG:4326');
    inverses.set(epsg, converter ? (e, n) => converter.forward([e, n]) : null);
  }
  return inverses.get(epsg);
}

/** A proj4 definition for the CRSs above, else null. */
export function definitionOf(epsg) {
  const utm = (zone, rest) => `+proj=utm +zone=${zone} ${rest} +units=m +no_defs`;
  if (epsg >= 32601 && epsg <= 32660) return utm(epsg - 32600, '+datum=WGS84');
  if (epsg >= 32701 && epsg <= 32760) return utm(epsg - 32700, '+south +datum=WGS84');
  if (epsg >= 26901 && epsg <= 26923) return utm(epsg - 26900, '+ellps=GRS80 +towgs84=0,0,0,0,0,0,0');
  if (epsg >= 25828 && epsg <= 25838) return utm(epsg - 25800, '+ellps=GRS80 +towgs84=0,0,0,0,0,0,0');
  if (epsg === 3857) return 'EPSG:3857';
  return null;
}

/**
 * The map from one CRS's coordinates to another's, or null when either has no definition we
 * can write. Identity for one CRS.
 * @returns {((x: number, y: number) => [number, number])|null}
 */
export function crsTransform(from, to) {
  if (from.epsg !== null && from.epsg === to.epsg) return (x, y) => [x, y];
  const a = from.proj4 ?? (from.epsg === 4326 ? 'EPSG:4326' : definitionOf(from.epsg));
  const b = to.proj4 ?? (to.epsg === 4326 ? 'EPSG:4326' : definitionOf(to.epsg));
  if (!a || !b) return null;
  const converter = proj4(a, b);
  return (x, y) => converter.forward([x, y]);
}

/** (x, y) in a CRS -> [lon, lat] in degrees, or null when the CRS has no definition we can write. */
export function toLonLat(crs) {
  if (crs.geographic) return (x, y) => [x, y];
  return crsTransform(crs, { epsg: 4326, label: 'EPSG:4326', geographic: true });
}
