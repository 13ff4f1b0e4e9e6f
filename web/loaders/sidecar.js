// The .json sidecar that travels with a height field (NAME.f32 + NAME.json,
// optionally NAME.png + NAME.json). Only the fields the loaders use are read;
// the rest (licence, origin, ...) is ignored.

import { HeightfieldError } from './common.js';
import { crsOfEpsg, makeGeoref, parseEpsg, UNKNOWN_CRS } from '../geo/index.js';

/**
 * @typedef {object} Sidecar
 * @property {string} name file name of the sidecar
 * @property {number|undefined} width samples per row, if given
 * @property {number|undefined} height rows, if given
 * @property {number|undefined} min lowest height in metres, if given (with max)
 * @property {number|undefined} max highest height in metres, if given (with min)
 * @property {number|null} spacingX metres between columns (cell_size_x_m, else cell_size_m), null if absent
 * @property {number|null} spacingY metres between rows (cell_size_y_m, else cell_size_m), null if absent
 * @property {number|null} nodata raw no-data value, if given
 * @property {{ west: number, east: number, south: number, north: number }|null} bounds the
 *   grid's outer cell edges in its CRS (`bounds`, `bounds_deg` or `bounds_epsgNNNN`), if given
 * @property {import('../geo/georef.js').Crs} crs from `crs` ("EPSG:32611 ..."), or unknown
 */

/**
 * Parses and validates a sidecar.
 * @param {Uint8Array} bytes UTF-8 JSON text
 * @param {string} name file name, for messages
 * @returns {Sidecar}
 */
export function parseSidecar(bytes, name) {
  const fail = (problem) => { throw new HeightfieldError(name, problem); };
  let json;
  try {
    json = JSON.parse(new TextDecoder('utf-8').decode(bytes));
  } catch (e) {
    fail(`not valid JSON (${e.message.split('\n')[0]})`);
  }
  if (json === null || typeof json !== 'object' || Array.isArray(json)) fail('expected a JSON object');

  const positiveInteger = (key) => {
    const v = json[key];
    if (v === undefined) return undefined;
    if (!Number.isInteger(v) || v <= 0) fail(`${key} must be a positive integer (got ${JSON.stringify(v)})`);
    return v;
  };
  const finite = (key, positive) => {
    const v = json[key];
    if (v === undefined || v === null) return undefined;
    if (typeof v !== 'number' || !Number.isFinite(v) || (positive && v <= 0)) {
      fail(`${key} must be a ${positive ? 'positive' : 'finite'} number (got ${JSON.stringify(v)})`);
    }
    return v;
  };

  const width = positiveInteger('width');
  const height = positiveInteger('height');
  const min = finite('min');
  const max = finite('max');
  if ((min === undefined) !== (max === undefined)) fail(`${min === undefined ? 'max' : 'min'} given without ${min === undefined ? 'min' : 'max'}`);
  if (min !== undefined && max < min) fail(`max (${max}) is below min (${min})`);
  if (min !== undefined && !Number.isFinite(max - min)) fail(`min ${min} and max ${max} span more than a number can hold`);

  const cell = finite('cell_size_m', true);
  const spacingX = finite('cell_size_x_m', true) ?? cell ?? null;
  const spacingY = finite('cell_size_y_m', true) ?? cell ?? null;
  if ((spacingX === null) !== (spacingY === null)) {
    fail(`${spacingX === null ? 'cell_size_y_m' : 'cell_size_x_m'} given without ${spacingX === null ? 'cell_size_x_m' : 'cell_size_y_m'} or cell_size_m`);
  }
  const nodata = finite('nodata') ?? null;
  const epsg = parseEpsg(json.crs) ?? parseEpsg(json.epsg);
  const boundsKeys = Object.keys(json).filter((key) => /^bounds(_deg|_epsg\d+)?$/i.test(key));
  if (boundsKeys.length > 1) fail(`several bounds given (${boundsKeys.join(', ')}); keep the one in the grid's crs`);
  const bounds = boundsKeys.length ? parseBounds(json[boundsKeys[0]], boundsKeys[0], fail) : null;
  const keyEpsg = parseEpsg(boundsKeys[0]?.replace(/^bounds_epsg/i, 'EPSG:') ?? null);
  if (epsg !== null && keyEpsg !== null && keyEpsg !== epsg) fail(`${boundsKeys[0]} is not in the crs (${json.crs})`);
  const code = epsg ?? keyEpsg ?? (boundsKeys[0]?.toLowerCase() === 'bounds_deg' ? 4326 : null);
  const crs = code === null ? UNKNOWN_CRS : crsOfEpsg(code, boundsKeys[0]?.toLowerCase() === 'bounds_deg');
  return { name, width, height, min, max, spacingX, spacingY, nodata, bounds, crs };
}

/** A bounds object: four finite numbers, east of west and north of south. */
function parseBounds(value, key, fail) {
  if (value === null || typeof value !== 'object') fail(`${key} must be an object with west, east, south and north`);
  const edges = {};
  for (const edge of ['west', 'east', 'south', 'north']) {
    if (typeof value[edge] !== 'number' || !Number.isFinite(value[edge])) fail(`${key}.${edge} must be a finite number (got ${JSON.stringify(value[edge])})`);
    edges[edge] = value[edge];
  }
  if (!(edges.east > edges.west) || !(edges.north > edges.south)) fail(`${key}: east must lie east of west and north north of south`);
  return edges;
}

/**
 * The georeference a sidecar gives a width x height grid (north row first): its bounds are the
 * outer edges of the outer cells, so sample centres lie half a cell inside.
 * @returns {import('../geo/georef.js').Georef|null}
 */
export function sidecarGeoref(sidecar, width, height) {
  if (!sidecar?.bounds) return null;
  const { west, east, south, north } = sidecar.bounds;
  const dx = (east - west) / width, dy = -(north - south) / height;
  return makeGeoref(sidecar.crs, west + dx / 2, north + dy / 2, dx, dy, 'sidecar');
}
