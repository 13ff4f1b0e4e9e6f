// Coordinates from one CRS to another, with proj4 on the CRSs' definitions (crs_definitions.js
// fills them in). A definition with a datum shift (+towgs84, or a datum proj4 knows) is
// shifted on the way; one without is taken on its own ellipsoid. Converters are made once per
// pair of definitions and kept: a readout under the pointer asks every frame.
import proj4 from 'proj4';
import { sameCrs } from './georef.js';

/** Latitude and longitude on WGS 84, what toLonLat gives. */
const WGS84 = '+proj=longlat +datum=WGS84 +no_defs';

const projections = new Map(); // definition text -> proj4 projection, or null when proj4 cannot parse it
const converters = new Map(); // 'from\ntto' -> proj4 converter

/**
 * The projection proj4 makes of a definition, or null when it cannot (it throws, or the
 * definition names a kind of CRS it does not draw, e.g. vertical only).
 * @param {string|null} definition a PROJ string or a WKT
 */
export function projectionOf(definition) {
  if (typeof definition !== 'string' || definition === '') return null;
  if (!projections.has(definition)) {
    let projection = null;
    try {
      projection = proj4.Proj(definition);
      if (!projection || typeof projection.forward !== 'function' || !projection.projName) projection = null;
    } catch {
      projection = null;
    }
    projections.set(definition, projection);
  }
  return projections.get(definition);
}

/** Whether a definition is latitude and longitude (+proj=longlat, a GEOGCS). */
export function isGeographicDefinition(definition) {
  return projectionOf(definition)?.projName === 'longlat';
}

/** Metres per unit of a projected definition's coordinates (US survey feet: 0.3048006), 1 when it does not say. */
export function metresPerUnit(crs) {
  const projection = projectionOf(crs?.proj4);
  const toMeter = Number(projection?.to_meter);
  return projection && projection.projName !== 'longlat' && toMeter > 0 && Number.isFinite(toMeter) ? toMeter : 1;
}

function converter(from, to) {
  const key = `${from}\n${to}`;
  if (!converters.has(key)) converters.set(key, proj4(from, to));
  return converters.get(key);
}

/**
 * The map from one CRS's coordinates to another's: identity for the same CRS, else through
 * both definitions. Degrees for geographic CRSs (longitude first), the CRS's units otherwise.
 * A point the projection cannot take comes out as non-finite numbers.
 * @param {import('./georef.js').Crs} fromCrs
 * @param {import('./georef.js').Crs} toCrs
 * @returns {((x: number, y: number) => [number, number])|null} null when either has no definition
 */
export function crsTransform(fromCrs, toCrs) {
  if (!fromCrs || !toCrs) return null;
  if (sameCrs(fromCrs, toCrs)) return (x, y) => [x, y];
  if (!projectionOf(fromCrs.proj4) || !projectionOf(toCrs.proj4)) return null;
  return mapping(fromCrs.proj4, toCrs.proj4);
}

/**
 * The map from a CRS's coordinates to longitude and latitude on WGS 84 (degrees), the datum
 * shift of its definition applied.
 * @param {import('./georef.js').Crs} crs
 * @returns {((x: number, y: number) => [number, number])|null} null when it has no definition
 */
export function toLonLat(crs) {
  if (!projectionOf(crs?.proj4)) return null;
  return mapping(crs.proj4, WGS84);
}

/** (x, y) -> [x, y] between two definitions; a point proj4 refuses (it may throw far outside a projection's area) is NaN. */
function mapping(from, to) {
  let c;
  try {
    c = converter(from, to);
  } catch {
    return null;
  }
  return (x, y) => {
    try {
      const result = c.forward([x, y]);
      return [result[0], result[1]];
    } catch {
      return [NaN, NaN];
    }
  };
}
