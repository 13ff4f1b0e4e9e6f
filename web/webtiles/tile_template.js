// A web map tile layer as a person gives it: an address template with placeholders, as Leaflet
// and OpenLayers take them (https://{s}.tile.example.org/{z}/{x}/{y}.png), and the few facts a
// template cannot say (its zooms, subdomains, attribution).
//
// Placeholders: {z} the zoom, {x} the column from the west, {y} the row from the north, {-y} the
// row from the south (TMS), {s} a subdomain, {r} the "@2x" suffix of high-resolution tiles
// (always empty here: one texel a tile pixel). A WMTS REST template's {TileMatrix}, {TileCol}
// and {TileRow} are read as {z}, {x} and {y}.
//
// The page's address carries a layer as ONE value, `?tiles=SPEC` (URL-encoded; repeat it for
// more layers), where SPEC is the template followed by options, each after a `|`:
//   https://{s}.tile.example.org/{z}/{x}/{y}.png|zoom=0-19|subdomains=abc|attribution=© Example
//   zoom=MIN-MAX     the zooms the service has (default 0-19)
//   subdomains=abc   one subdomain a character, or a,b,c separated by commas (default a,b,c)
//   attribution=TEXT the credit the page shows; a `|` or `%` in it is written %7C or %25
//   matrices=A,B,... WMTS TileMatrix identifiers by zoom (index 0 first) when {z} is not the zoom number
// One value for a layer keeps its options together when there are several layers, and `|` is
// a character tile addresses do not use.
import { MAX_ZOOM } from './web_mercator.js';

/** A tile layer specification that cannot be used: `message` says why, for the status line. */
export class TileSpecError extends Error {
  constructor(message) {
    super(message);
    this.name = 'TileSpecError';
  }
}

/**
 * @typedef {object} TileLayerSpec
 * @property {string} template the address with placeholders ({TileMatrix} etc. already read as {z} etc.)
 * @property {string[]} subdomains what {s} becomes, chosen by the tile
 * @property {number} minZoom coarsest zoom the service has
 * @property {number} maxZoom finest zoom the service has
 * @property {string} attribution credit to show ('' when none given)
 * @property {string[]|null} matrices what {z} becomes at each zoom (WMTS identifiers), null: the zoom number
 * @property {Array<string|number>} parts the template cut at its placeholders: text, or a PLACE_* code
 */

export const DEFAULT_SUBDOMAINS = ['a', 'b', 'c'];
export const DEFAULT_MIN_ZOOM = 0;
export const DEFAULT_MAX_ZOOM = 19;

const PLACE_Z = 0, PLACE_X = 1, PLACE_Y = 2, PLACE_FLIPPED_Y = 3, PLACE_S = 4, PLACE_R = 5;
const PLACEHOLDERS = {
  z: PLACE_Z, x: PLACE_X, y: PLACE_Y, '-y': PLACE_FLIPPED_Y, s: PLACE_S, r: PLACE_R,
  tilematrix: PLACE_Z, tilecol: PLACE_X, tilerow: PLACE_Y,
};
const KNOWN = '{z} {x} {y} {-y} {s} {r}';
const OPTIONS = ['zoom', 'subdomains', 'attribution', 'matrices'];

/**
 * Reads a layer from the page's `tiles=` value: a template and `|option=value` suffixes.
 * @param {string} text
 * @returns {TileLayerSpec}
 * @throws {TileSpecError} with one message saying what is wrong
 */
export function parseTileSpec(text) {
  const [template, ...options] = String(text ?? '').trim().split('|');
  const layer = parseTemplate(template);
  for (const option of options) {
    const at = option.indexOf('=');
    const key = (at < 0 ? option : option.slice(0, at)).trim().toLowerCase();
    const raw = at < 0 ? '' : option.slice(at + 1).trim(), value = decodeValue(raw);
    if (!OPTIONS.includes(key)) {
      throw new TileSpecError(`unknown tile layer option '${key}' after the template (known: ${OPTIONS.join(', ')})`);
    }
    if (key === 'zoom') [layer.minZoom, layer.maxZoom] = parseZoomRange(value);
    else if (key === 'subdomains') layer.subdomains = parseSubdomains(value);
    else if (key === 'attribution') layer.attribution = value;
    else layer.matrices = raw.split(',').map((id) => decodeValue(id.trim()));
  }
  if (layer.matrices && layer.matrices.length <= layer.maxZoom) {
    throw new TileSpecError(`matrices= names ${layer.matrices.length} TileMatrix identifiers, one for each zoom 0..${layer.maxZoom} is needed`);
  }
  return layer;
}

/**
 * A layer from a template alone, with the default options.
 * @throws {TileSpecError}
 */
export function parseTemplate(template) {
  template = String(template ?? '').trim();
  if (template === '') throw new TileSpecError('the tile template is empty: give an address such as https://tile.example.org/{z}/{x}/{y}.png');
  if (!/^https?:\/\/[^/]/i.test(template)) {
    throw new TileSpecError(`a tile template must be an http:// or https:// address, not '${shorten(template)}'`);
  }
  const parts = [];
  const seen = new Set();
  let rest = 0;
  for (const match of template.matchAll(/\{([^{}]*)\}/g)) {
    // {z} {x} {y} as written (a {Z} is a typo); WMTS's names in any case, as its servers write them.
    const code = match[1].length <= 2 ? PLACEHOLDERS[match[1]] : PLACEHOLDERS[match[1].toLowerCase()];
    if (code === undefined) {
      throw new TileSpecError(`unknown placeholder {${match[1]}} in the tile template (known: ${KNOWN})`);
    }
    if (match.index > rest) parts.push(template.slice(rest, match.index));
    parts.push(code);
    seen.add(code);
    rest = match.index + match[0].length;
  }
  if (rest < template.length) parts.push(template.slice(rest));
  if (!seen.has(PLACE_Z)) throw new TileSpecError(`the tile template has no {z} (the zoom): ${shorten(template)}`);
  if (!seen.has(PLACE_X)) throw new TileSpecError(`the tile template has no {x} (the column): ${shorten(template)}`);
  if (!seen.has(PLACE_Y) && !seen.has(PLACE_FLIPPED_Y)) {
    throw new TileSpecError(`the tile template has no {y} or {-y} (the row): ${shorten(template)}`);
  }
  return { template, subdomains: DEFAULT_SUBDOMAINS.slice(), minZoom: DEFAULT_MIN_ZOOM, maxZoom: DEFAULT_MAX_ZOOM,
    attribution: '', matrices: null, parts };
}

/** The address of tile (z, x, y) of a layer. */
export function tileUrl(layer, z, x, y) {
  let url = '';
  for (const part of layer.parts) {
    if (typeof part === 'string') url += part;
    else if (part === PLACE_Z) url += layer.matrices ? layer.matrices[z] : z;
    else if (part === PLACE_X) url += x;
    else if (part === PLACE_Y) url += y;
    else if (part === PLACE_FLIPPED_Y) url += 2 ** z - 1 - y;
    // The same tile always on the same subdomain, so the browser's cache serves it again.
    else if (part === PLACE_S) url += layer.subdomains[(x + y) % layer.subdomains.length];
  }
  return url;
}

/** The `tiles=` value of a layer: parseTileSpec(formatTileSpec(layer)) gives the layer back. */
export function formatTileSpec(layer) {
  let text = layer.template;
  if (layer.minZoom !== DEFAULT_MIN_ZOOM || layer.maxZoom !== DEFAULT_MAX_ZOOM) text += `|zoom=${layer.minZoom}-${layer.maxZoom}`;
  if (layer.subdomains.join(',') !== DEFAULT_SUBDOMAINS.join(',')) {
    const single = layer.subdomains.every((s) => s.length === 1);
    text += `|subdomains=${single ? layer.subdomains.join('') : layer.subdomains.join(',')}`;
  }
  if (layer.matrices) text += `|matrices=${layer.matrices.map((id) => encodeValue(id).replace(/,/g, '%2C')).join(',')}`;
  if (layer.attribution) text += `|attribution=${encodeValue(layer.attribution)}`;
  return text;
}

/** The host of a layer's addresses, for messages ("tile.example.org"). */
export function layerHost(layer) {
  return /^https?:\/\/([^/?#]+)/i.exec(layer.template)?.[1] ?? layer.template;
}

function parseZoomRange(value) {
  const match = /^(\d+)\s*-\s*(\d+)$/.exec(value) ?? /^(\d+)$/.exec(value);
  const min = match ? Number(match[1]) : NaN, max = match ? Number(match[2] ?? match[1]) : NaN;
  if (!(min >= 0 && max >= min && max <= MAX_ZOOM)) {
    throw new TileSpecError(`zoom must be MIN-MAX with whole numbers 0 <= MIN <= MAX <= ${MAX_ZOOM}, not '${value}'`);
  }
  return [min, max];
}

function parseSubdomains(value) {
  const list = value.includes(',') ? value.split(',').map((s) => s.trim()) : [...value];
  if (list.length === 0 || list.some((s) => s === '' || /[/?#{}|\s]/.test(s))) {
    throw new TileSpecError(`subdomains must be letters or names separated by commas, not '${value}'`);
  }
  return list;
}

// Option values may carry %-escapes (a `|` is %7C); text that is not a valid escape stays as written.
function decodeValue(value) {
  try {
    return decodeURIComponent(value);
  } catch {
    return value;
  }
}

function encodeValue(value) {
  return value.replace(/[%|]/g, (c) => encodeURIComponent(c));
}

function shorten(text) {
  return text.length > 120 ? `${text.slice(0, 117)}…` : text;
}
