// GeoJSON features (RFC 7946, and what @tmcw/togeojson makes of KML) as the overlays' features:
// points, lines and polygons with their coordinates in typed arrays (x, y and the altitude z
// where a position has one; the times of a KML track), their name and properties.
// A GeometryCollection (KML's MultiGeometry) becomes one feature per kind of geometry in it.
import { OverlayError } from './overlay_error.js';

/**
 * @typedef {object} Path one line, ring or set of points
 * @property {Float64Array} x longitude, or the CRS's x
 * @property {Float64Array} y latitude, or the CRS's y
 * @property {Float64Array|null} z altitude, metres (NaN where a position has none); null when none has one
 * @property {Float64Array|null} t time, ms since the epoch (NaN where missing); null when none has one
 */

/**
 * @typedef {object} Feature
 * @property {'point'|'line'|'polygon'} kind
 * @property {string|null} name
 * @property {object} properties the file's, as plain values
 * @property {'clamp'|'absolute'} altitude how the file wants it drawn
 * @property {string} source 'track' | 'route' | 'waypoint' | 'placemark' | 'feature'
 * @property {Path[]} paths points: one path (of one or more points) each; lines: one per line; polygons: every ring
 * @property {number[][]|null} polygons polygons: the ring indices of each polygon, outer first
 */

const KIND = { Point: 'point', MultiPoint: 'point', LineString: 'line', MultiLineString: 'line', Polygon: 'polygon', MultiPolygon: 'polygon' };

/**
 * @param {object} geojson a FeatureCollection, a Feature or a bare geometry
 * @param {{source?: string, altitudeOf?: (index: number) => 'clamp'|'absolute'}} [options]
 *   source: what the features are ('feature', 'placemark'); altitudeOf: the altitude mode of the
 *   index-th feature (KML's altitudeMode)
 * @returns {Feature[]}
 * @throws {OverlayError}
 */
export function featuresOf(geojson, { source = 'feature', altitudeOf = () => 'clamp' } = {}) {
  const list = geojson.type === 'FeatureCollection' ? geojson.features
    : geojson.type === 'Feature' ? [geojson] : [{ type: 'Feature', properties: {}, geometry: geojson }];
  if (!Array.isArray(list)) throw new OverlayError('"features" of the FeatureCollection is not an array');
  const out = [];
  list.forEach((feature, index) => {
    if (!feature || feature.type !== 'Feature') throw new OverlayError(`feature ${index + 1} is not a GeoJSON Feature (its "type" is ${JSON.stringify(feature?.type)})`);
    const { coordinateProperties, ...rest } = feature.properties ?? {};
    const properties = plain(rest);
    const name = typeof properties.name === 'string' && properties.name.trim() ? properties.name.trim() : null;
    const base = { name, properties, altitude: altitudeOf(index), source };
    for (const geometry of flatten(feature.geometry, index)) {
      const kind = KIND[geometry.type];
      const times = coordinateProperties?.times ?? null;
      out.push({ ...base, kind, ...pathsOf(geometry, times, index) });
    }
  });
  return merged(out);
}

/** The simple geometries of a (possibly nested) GeometryCollection; none for a null geometry. */
function flatten(geometry, index) {
  if (geometry === null || geometry === undefined) return [];
  if (geometry.type === 'GeometryCollection') {
    if (!Array.isArray(geometry.geometries)) throw new OverlayError(`feature ${index + 1}: a GeometryCollection without "geometries"`);
    return geometry.geometries.flatMap((g) => flatten(g, index));
  }
  if (!KIND[geometry.type]) throw new OverlayError(`feature ${index + 1}: unknown geometry type ${JSON.stringify(geometry.type)}`);
  if (!Array.isArray(geometry.coordinates)) throw new OverlayError(`feature ${index + 1}: its ${geometry.type} has no "coordinates" array`);
  return [geometry];
}

/** A geometry collection's parts of one kind go together again: one feature per kind. */
function merged(features) {
  const out = [];
  for (const f of features) {
    const last = out.at(-1);
    if (last && last.kind === f.kind && last.properties === f.properties && f.kind !== 'polygon') last.paths.push(...f.paths);
    else if (last && last.kind === 'polygon' && f.kind === 'polygon' && last.properties === f.properties) {
      const offset = last.paths.length;
      last.paths.push(...f.paths);
      last.polygons.push(...f.polygons.map((rings) => rings.map((r) => r + offset)));
    } else out.push(f);
  }
  return out;
}

function pathsOf(geometry, times, index) {
  const where = `feature ${index + 1} (${geometry.type})`;
  const c = geometry.coordinates;
  switch (geometry.type) {
    case 'Point': return { paths: [path([c], null, where)], polygons: null };
    case 'MultiPoint': return { paths: [path(c, null, where)], polygons: null };
    case 'LineString': return { paths: [path(c, Array.isArray(times?.[0]) ? times[0] : times, where)], polygons: null };
    case 'MultiLineString': {
      // togeojson gives a KML multi-track's times per track, and none for a track without: they
      // are trusted only where their number matches.
      const aligned = Array.isArray(times) && times.length === c.length;
      return { paths: c.map((line, k) => path(line, aligned ? times[k] : null, where)), polygons: null };
    }
    case 'Polygon': return { paths: c.map((ring) => path(ring, null, where)), polygons: [c.map((_, k) => k)] };
    default: { // MultiPolygon
      const paths = [], polygons = [];
      for (const polygon of c) {
        polygons.push(polygon.map((_, k) => paths.length + k));
        for (const ring of polygon) paths.push(path(ring, null, where));
      }
      return { paths, polygons };
    }
  }
}

/** Positions [x, y, z?] as typed arrays; checks that each is two or three finite numbers. */
function path(positions, times, where) {
  if (!Array.isArray(positions) || positions.length === 0) throw new OverlayError(`${where}: no positions`);
  const n = positions.length, x = new Float64Array(n), y = new Float64Array(n), z = new Float64Array(n).fill(NaN);
  let hasZ = false;
  for (let k = 0; k < n; k++) {
    const p = positions[k];
    if (!Array.isArray(p) || p.length < 2 || !Number.isFinite(p[0]) || !Number.isFinite(p[1])) {
      throw new OverlayError(`${where}: position ${k + 1} is not a pair of numbers (${JSON.stringify(p)?.slice(0, 60)})`);
    }
    x[k] = p[0];
    y[k] = p[1];
    if (Number.isFinite(p[2])) { z[k] = p[2]; hasZ = true; }
  }
  let t = null;
  if (Array.isArray(times) && times.length === n) {
    t = Float64Array.from(times, (s) => (typeof s === 'string' ? Date.parse(s) : NaN));
    if (!t.some(Number.isFinite)) t = null;
  }
  return { x, y, z: hasZ ? z : null, t };
}

/** Properties as plain values: nested objects kept as JSON, nothing a tooltip cannot show. */
function plain(properties) {
  const out = {};
  for (const [key, value] of Object.entries(properties)) {
    out[key] = value !== null && typeof value === 'object' ? JSON.stringify(value) : value;
  }
  return out;
}
