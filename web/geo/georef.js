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
 * @property {string} label for people: "EPSG:32611", "EPSG:4326", "user-defined", "unknown"
 * @property {boolean} geographic coordinates are degrees of longitude and latitude
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

/** The CRS of an EPSG code (the geographic ones are the common datums' lat/lon codes). */
export function crsOfEpsg(epsg) {
  return { epsg, label: `EPSG:${epsg}`, geographic: isGeographicEpsg(epsg) };
}

/** A CRS nobody named: grids in it match only grids in the same file family's unknown CRS. */
export const UNKNOWN_CRS = Object.freeze({ epsg: null, label: 'unknown', geographic: false });

// Geographic 2D CRSs people's data uses: WGS 84, NAD83, NAD27, ETRS89, GDA94, GDA2020, JGD2000, WGS 72.
const GEOGRAPHIC_EPSG = new Set([4326, 4269, 4267, 4258, 4283, 7844, 4612, 4322, 4979]);
function isGeographicEpsg(epsg) {
  return GEOGRAPHIC_EPSG.has(epsg);
}

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
 * How two CRSs relate: 'same' (one EPSG code), 'different' (two codes), or 'assumed' when one
 * is not known (a world file, an ASCII grid without its .prj): then, as GIS programs do, the
 * grid is taken to be in the other's CRS, and the page says so.
 */
export function compareCrs(a, b) {
  if (a.epsg === null || b.epsg === null) return 'assumed';
  return a.epsg === b.epsg ? 'same' : 'different';
}
