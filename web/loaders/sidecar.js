// The .json sidecar that travels with a height field (NAME.f32 + NAME.json,
// optionally NAME.png + NAME.json). Only the fields the loaders use are read;
// the rest (crs, bounds, licence, ...) is ignored.

import { HeightfieldError } from './common.js';

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
  return { name, width, height, min, max, spacingX, spacingY, nodata };
}
