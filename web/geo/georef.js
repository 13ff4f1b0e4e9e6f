// Where a grid lies on the Earth: its coordinate reference system (CRS) and the affine map from
// sample (column, row) to that CRS's coordinates. Height fields and draped images both carry
// one; two grids in the same CRS can be placed on each other (an image on the terrain), and a
// sample's real coordinates can be shown.
//
// The map is to sample centres, whatever the file's convention (GeoTIFF PixelIsArea/PixelIsPoint,
// ESRI corner or centre, cell-edge bounds): x = x0 + column * dx, y = y0 + row * dy. Rows go
// south in a north-up grid, so dy < 0 there. No rotation: a rotated or sheared grid has none.

/**
 * @typedef {object} Crs
 * @property {number|null} epsg the EPSG code, or null when the file defines its own or says none
 * @property {string} label for people: "EPSG:32611", "custom (NAME from the WKT)", "user-defined", "unknown"
 * @property {string|null} name what the definitions or the file call it ("CH1903+ / LV95"), else null
 * @property {string|null} proj4 a definition proj4 parses (a PROJ string or a WKT), or null when
 *   none is known; an EPSG code's is filled in by resolveCrs (crs_definitions.js)
 * @property {boolean} geographic coordinates are degrees of longitude and latitude: what the
 *   definition says (+proj=longlat) once there is one, until then what the file said (a
 *   GeoTIFF's model type, an SRTM tile)
 */

/**
 * @typedef {object} Georef
 * @property {Crs} crs
 * @property {number} x0 x of the centre of sample (0, 0), in CRS units
 * @property {number} y0 y of the centre of sample (0, 0)
 * @property {number} dx x step per column (> 0)
 * @property {number} dy y step per row (< 0 for north-up grids)
 * @property {string} from what placed it: 'GeoTIFF', 'tile name', 'ASCII header', 'sidecar', 'world file'
 */

/**
 * The CRS of an EPSG code, before its definition is looked up (resolveCrs).
 * @param {number} epsg
 * @param {boolean} [geographic] whether the file says its grid is in degrees (until the definition says)
 */
export function crsOfEpsg(epsg, geographic = false) {
  return { epsg, label: `EPSG:${epsg}`, name: null, proj4: null, geographic };
}

/** A CRS nobody named: grids in it match only grids in the same file family's unknown CRS. */
export const UNKNOWN_CRS = Object.freeze({ epsg: null, label: 'unknown', name: null, proj4: null, geographic: false });

/** "EPSG:4326 (anything)", "epsg:32611", "urn:ogc:def:crs:EPSG::3857" or 4326 -> its code, else null. */
export function parseEpsg(value) {
  if (Number.isInteger(value) && value > 0 && value < 1e6) return value;
  if (typeof value !== 'string') return null;
  const m = /EPSG:{1,2}(\d{1,6})\b/i.exec(value);
  return m ? Number(m[1]) : null;
}

/**
 * A georeference, checked: finite numbers and steps that are not zero. Returns null (no
 * georeference) rather than a map that would place the grid nowhere.
 */
export function makeGeoref(crs, x0, y0, dx, dy, from) {
  if (![x0, y0, dx, dy].every(Number.isFinite) || dx <= 0 || dy === 0) return null;
  return { crs, x0, y0, dx, dy, from };
}

/** The georeference of the part of a grid that starts at (column, row). */
export function shiftGeoref(georef, column, row) {
  return georef && { ...georef, x0: georef.x0 + column * georef.dx, y0: georef.y0 + row * georef.dy };
}

/** CRS coordinates of a (fractional) sample position. */
export function sampleToCrs(georef, column, row) {
  return [georef.x0 + column * georef.dx, georef.y0 + row * georef.dy];
}

/** The (fractional) sample position of CRS coordinates. */
export function crsToSample(georef, x, y) {
  return [(x - georef.x0) / georef.dx, (y - georef.y0) / georef.dy];
}

/**
 * Whether two CRSs are one: the same EPSG code, or, for CRSs without a code (a .prj's custom
 * WKT), the same definition. A CRS that names nothing is the same as no other.
 */
export function sameCrs(a, b) {
  if (a.epsg !== null || b.epsg !== null) return a.epsg === b.epsg;
  return a.proj4 !== null && a.proj4 === b.proj4;
}

/**
 * How two CRSs relate: 'same' (sameCrs), 'different' (both named, and not the same), or
 * 'assumed' when one names nothing (a world file without its .prj, an ASCII grid without its
 * .prj): then, as GIS programs do, the grid is taken to be in the other's CRS, and the page
 * says so.
 */
export function compareCrs(a, b) {
  if (sameCrs(a, b)) return 'same';
  const named = (crs) => crs.epsg !== null || crs.proj4 !== null;
  return named(a) && named(b) ? 'different' : 'assumed';
}
