// Real-world coordinates of a point of the field: the CRS coordinates its georeference gives
// (web/geo/georef.js), and latitude and longitude too: a geographic CRS's own, and for a
// projected CRS with a definition (crs_definitions.js: any EPSG code, or a .prj's WKT) latitude
// and longitude on WGS 84 through proj4, with the definition's datum shift.
import { sampleToCrs } from './georef.js';
import { toLonLat } from './crs_transform.js';

/** What the HUD says of a field without a georeference. */
export const localLabel = 'local metres (no CRS)';

/**
 * @typedef {object} GeoCoordinates
 * @property {number|null} easting CRS x in metres (projected CRSs), else null
 * @property {number|null} northing CRS y in metres (projected CRSs), else null
 * @property {number|null} lat degrees north (negative south), null when the CRS has no definition
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
  const inverse = toLonLat(georef.crs);
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
