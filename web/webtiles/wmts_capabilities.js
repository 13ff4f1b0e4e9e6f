// The layers of an OGC WMTS 1.0.0 service that can be draped as web map tiles: those offered in
// a tile matrix set that IS the XYZ pyramid (Web Mercator, the world's corner at the top left,
// 2^z × 2^z tiles at zoom z), as the tile layers of tile_template.js. Each becomes a template,
// from the layer's ResourceURL (REST) or from the GetTile operation's address (KVP), with its
// style, tile matrix set and dimensions (Time, ...) filled in with their defaults.
//
// The XML is read by fast-xml-parser: it runs alike in the page and in Node, where the tests
// read the fixture (the browser's DOMParser has no Node counterpart, so its code path would go
// untested), and it resolves no external entities.
import { XMLParser, XMLValidator } from 'fast-xml-parser';
import { TileSpecError, parseTemplate } from './tile_template.js';
import { EQUATOR_METRES, MAX_ZOOM } from './web_mercator.js';

// The CRSs that are Web Mercator, in the spellings services use (EPSG, OGC URN and URL forms).
const WEB_MERCATOR_CODES = new Set(['3857', '900913', '3785', '102100', '102113']);
const GOOGLE_SCALE_SET = /GoogleMapsCompatible$/i;
// A standard rendering pixel of WMTS (OGC 07-057r7, 6.1): 0.28 mm.
const PIXEL_METRES = 0.00028;
const HALF_WORLD = EQUATOR_METRES / 2;
// Repeated elements, always read as lists.
const LISTS = new Set(['Layer', 'TileMatrixSet', 'TileMatrix', 'TileMatrixSetLink', 'TileMatrixLimits', 'ResourceURL',
  'Format', 'Style', 'Dimension', 'Value', 'Operation', 'DCP', 'Get', 'Constraint']);

/**
 * @typedef {object} WmtsLayer
 * @property {string} identifier the layer's ows:Identifier
 * @property {string} title its title (the identifier when it has none)
 * @property {string} tileMatrixSet the Web Mercator set used
 * @property {'REST'|'KVP'} encoding how its tiles are asked for
 * @property {string} format the tiles' media type
 * @property {number} tileSize texels a tile side
 * @property {number[]|null} bounds [west, south, east, north] degrees (ows:WGS84BoundingBox), null when not given
 * @property {import('./tile_template.js').TileLayerSpec} spec the tile layer
 */

/**
 * @typedef {object} WmtsService
 * @property {string} title the service's title
 * @property {WmtsLayer[]} layers the layers usable in Web Mercator, in the document's order
 * @property {{ identifier: string, reason: string }[]} skipped the others, and why
 */

/**
 * The address of the capabilities document of a service: a URL that asks for none is given
 * the KVP request (a bare endpoint such as https://example.org/wmts); one that names an XML
 * file or a request is kept.
 */
export function capabilitiesUrl(url) {
  const parsed = new URL(url);
  if (/\.xml$/i.test(parsed.pathname) || [...parsed.searchParams.keys()].some((k) => k.toLowerCase() === 'request')) return parsed.href;
  parsed.searchParams.set('SERVICE', 'WMTS');
  parsed.searchParams.set('REQUEST', 'GetCapabilities');
  return parsed.href;
}

/**
 * Fetches and reads a capabilities document.
 * @param {string} url the document, or the service's endpoint (capabilitiesUrl)
 * @param {{ fetch?: typeof fetch, signal?: AbortSignal }} [options]
 * @returns {Promise<WmtsService>}
 * @throws {TileSpecError} with one message: the address, the answer, the document
 */
export async function readWmtsCapabilities(url, { fetch: fetchFn = globalThis.fetch, signal } = {}) {
  let address;
  try {
    address = capabilitiesUrl(url);
  } catch {
    throw new TileSpecError(`'${url}' is not an address of a WMTS service`);
  }
  let response;
  try {
    response = await fetchFn(address, { signal });
  } catch (error) {
    if (error?.name === 'AbortError') throw error;
    throw new TileSpecError(`cannot read the WMTS capabilities at ${address}: the server did not answer, or refuses cross-origin reads`);
  }
  if (!response.ok) throw new TileSpecError(`HTTP ${response.status} for the WMTS capabilities at ${address}`);
  return parseWmtsCapabilities(await response.text(), address);
}

/**
 * Reads a capabilities document.
 * @param {string} xml
 * @param {string} documentUrl where it came from: relative addresses in it are resolved against it
 * @returns {WmtsService}
 * @throws {TileSpecError} when it is not one, or offers no layer in Web Mercator
 */
export function parseWmtsCapabilities(xml, documentUrl) {
  // The parser reads what it can of broken XML; the validator says where it breaks.
  const valid = XMLValidator.validate(String(xml ?? ''));
  if (valid !== true) {
    throw new TileSpecError(`the WMTS capabilities at ${documentUrl} are not XML (${valid.err.msg} at line ${valid.err.line})`);
  }
  let root;
  try {
    const parser = new XMLParser({
      ignoreAttributes: false, attributeNamePrefix: '', removeNSPrefix: true,
      parseTagValue: false, parseAttributeValue: false, trimValues: true,
      isArray: (name) => LISTS.has(name),
    });
    root = parser.parse(xml);
  } catch (error) {
    throw new TileSpecError(`the WMTS capabilities at ${documentUrl} are not XML (${error.message})`);
  }
  const exception = root.ExceptionReport ?? root.ServiceExceptionReport;
  if (exception) {
    const text = exception.Exception?.ExceptionText ?? exception.ServiceException ?? '';
    throw new TileSpecError(`the WMTS service at ${documentUrl} answered with an exception${text ? `: ${textOf(text)}` : ''}`);
  }
  const capabilities = root.Capabilities;
  if (!capabilities || typeof capabilities !== 'object') {
    throw new TileSpecError(`${documentUrl} is not a WMTS capabilities document (no <Capabilities> element)`);
  }
  const contents = capabilities.Contents ?? {};
  const sets = new Map();
  for (const set of contents.TileMatrixSet ?? []) sets.set(textOf(set.Identifier), set);
  const kvp = getTileAddress(capabilities.OperationsMetadata, documentUrl);
  const layers = [], skipped = [];
  for (const layer of contents.Layer ?? []) {
    const identifier = textOf(layer.Identifier);
    const result = readLayer(layer, sets, kvp, documentUrl);
    if (typeof result === 'string') skipped.push({ identifier, reason: result });
    else layers.push(result);
  }
  if (layers.length === 0) {
    const why = skipped.map((s) => `${s.identifier}: ${s.reason}`).join('; ');
    throw new TileSpecError(`no layer of the WMTS service at ${documentUrl} is in Web Mercator (EPSG:3857, ` +
      `GoogleMapsCompatible)${why ? ` (${why})` : ''}`);
  }
  return { title: textOf(capabilities.ServiceIdentification?.Title) || documentUrl, layers, skipped };
}

/** A WmtsLayer, or why the layer cannot be used (a string). */
function readLayer(layer, sets, kvp, documentUrl) {
  const identifier = textOf(layer.Identifier);
  let pyramid = null, reason = 'it links no tile matrix set';
  for (const link of layer.TileMatrixSetLink ?? []) {
    const name = textOf(link.TileMatrixSet), set = sets.get(name);
    const found = set ? webMercatorPyramid(set, link) : `its tile matrix set ${name} is not in the document`;
    if (typeof found !== 'string') { pyramid = { name, ...found }; break; }
    reason = found;
  }
  if (!pyramid) return reason;
  const styles = layer.Style ?? [];
  const style = textOf((styles.find((s) => s.isDefault === 'true') ?? styles[0])?.Identifier) || 'default';
  const dimensions = (layer.Dimension ?? []).map((d) => [textOf(d.Identifier), textOf(d.Default) || textOf(d.Value?.[0])]);
  const images = (layer.ResourceURL ?? []).filter((r) => (r.resourceType ?? 'tile') === 'tile' && /^image\//.test(r.format ?? ''));
  const resource = images.find((r) => r.format === 'image/png') ?? images[0];
  // TileMatrix identifiers that are the zoom number, or a common prefix and the zoom number, fit
  // in the template; others are listed per zoom.
  const ids = pyramid.ids, prefix = commonZoomPrefix(ids, pyramid.minZoom, pyramid.maxZoom);
  const matrixText = prefix === null ? '{z}' : `${prefix}{z}`;
  let template, format, encoding;
  if (resource) {
    encoding = 'REST';
    format = resource.format;
    template = resolve(resource.template, documentUrl);
    const values = { style, tilematrixset: pyramid.name, ...Object.fromEntries(dimensions.map(([k, v]) => [k.toLowerCase(), v])) };
    template = template.replace(/\{([^{}]+)\}/g, (whole, name) => {
      const key = name.toLowerCase();
      if (key === 'tilematrix') return matrixText;
      if (key === 'tilerow') return '{y}';
      if (key === 'tilecol') return '{x}';
      return values[key] !== undefined ? values[key] : whole; // an unknown one: the template's parser names it
    });
  } else if (kvp) {
    encoding = 'KVP';
    const formats = (layer.Format ?? []).map(textOf);
    format = formats.find((f) => f === 'image/png') ?? formats.find((f) => /^image\//.test(f)) ?? formats[0] ?? 'image/png';
    const q = encodeURIComponent;
    const fields = [['SERVICE', 'WMTS'], ['REQUEST', 'GetTile'], ['VERSION', '1.0.0'], ['LAYER', identifier], ['STYLE', style],
      ['TILEMATRIXSET', pyramid.name], ['FORMAT', format], ...dimensions];
    const base = kvp + (kvp.includes('?') ? (/[?&]$/.test(kvp) ? '' : '&') : '?');
    template = `${base}${fields.map(([k, v]) => `${q(k)}=${q(v)}`).join('&')}` +
      `&TILEMATRIX=${prefix === null ? '{z}' : `${q(prefix)}{z}`}&TILEROW={y}&TILECOL={x}`;
  } else {
    return 'it has no ResourceURL and the service names no GetTile address';
  }
  let spec;
  try {
    spec = parseTemplate(template);
  } catch (error) {
    return error.message;
  }
  spec.minZoom = pyramid.minZoom;
  spec.maxZoom = pyramid.maxZoom;
  if (prefix === null) spec.matrices = Array.from(ids, (id) => id ?? '');
  const box = layer.WGS84BoundingBox;
  const lower = numbersOf(box?.LowerCorner), upper = numbersOf(box?.UpperCorner);
  return {
    identifier, title: textOf(layer.Title) || identifier, tileMatrixSet: pyramid.name, encoding, format,
    tileSize: pyramid.tileSize, bounds: lower.length === 2 && upper.length === 2 ? [...lower, ...upper] : null, spec,
  };
}

/**
 * Whether a tile matrix set (within a link's limits) is the XYZ pyramid: its matrices by zoom,
 * or why not (a string).
 */
function webMercatorPyramid(set, link) {
  const name = textOf(set.Identifier);
  const crs = textOf(set.SupportedCRS), scaleSet = textOf(set.WellKnownScaleSet);
  const code = /(\d+)\s*$/.exec(crs)?.[1];
  if (!WEB_MERCATOR_CODES.has(code) && !GOOGLE_SCALE_SET.test(scaleSet)) {
    return `its tile matrix set ${name} is in ${crs || 'no CRS'}, not Web Mercator`;
  }
  const limited = new Set((link.TileMatrixSetLimits?.TileMatrixLimits ?? []).map((l) => textOf(l.TileMatrix)));
  const ids = [];
  let tileSize = 0;
  for (const matrix of set.TileMatrix ?? []) {
    const id = textOf(matrix.Identifier);
    if (limited.size > 0 && !limited.has(id)) continue;
    const width = Number(textOf(matrix.MatrixWidth)), height = Number(textOf(matrix.MatrixHeight));
    const tileWidth = Number(textOf(matrix.TileWidth)), tileHeight = Number(textOf(matrix.TileHeight));
    const scale = Number(textOf(matrix.ScaleDenominator));
    const [left, top] = numbersOf(matrix.TopLeftCorner);
    const z = Math.log2(width);
    const pixel = scale * PIXEL_METRES; // metres a texel
    const standard = Number.isInteger(z) && z <= MAX_ZOOM && height === width && tileWidth === tileHeight && tileWidth > 0 &&
      Math.abs(pixel * tileWidth * width / EQUATOR_METRES - 1) < 1e-3 &&
      Math.abs(left + HALF_WORLD) < 0.01 * pixel && Math.abs(top - HALF_WORLD) < 0.01 * pixel;
    if (!standard) return `its tile matrix ${id} of ${name} is not a zoom of the XYZ pyramid (the world's corner at the top left, 2^z × 2^z tiles)`;
    if (tileSize && tileWidth !== tileSize) return `the tile matrices of ${name} have tiles of different sizes`;
    tileSize = tileWidth;
    ids[z] = id;
  }
  const zooms = ids.map((_, z) => z).filter((z) => ids[z] !== undefined);
  if (zooms.length === 0) return `its tile matrix set ${name} has no tile matrix`;
  const minZoom = zooms[0], maxZoom = zooms[zooms.length - 1];
  if (zooms.length !== maxZoom - minZoom + 1) return `its tile matrix set ${name} skips zooms between ${minZoom} and ${maxZoom}`;
  return { ids, minZoom, maxZoom, tileSize };
}

/**
 * What every TileMatrix identifier of zooms min..max has before its zoom number ('EPSG:900913:'
 * for 'EPSG:900913:5', '' for bare numbers), or null when they do not follow one pattern.
 */
function commonZoomPrefix(ids, minZoom, maxZoom) {
  const first = ids[minZoom];
  if (!first.endsWith(String(minZoom))) return null;
  const prefix = first.slice(0, first.length - String(minZoom).length);
  for (let z = minZoom; z <= maxZoom; z++) if (ids[z] !== `${prefix}${z}`) return null;
  return prefix;
}

/** The GetTile operation's KVP address, or null. */
function getTileAddress(metadata, documentUrl) {
  const operation = (metadata?.Operation ?? []).find((o) => o.name === 'GetTile');
  for (const dcp of operation?.DCP ?? []) {
    for (const get of dcp.HTTP?.Get ?? []) {
      const encodings = (get.Constraint ?? []).filter((c) => c.name === 'GetEncoding')
        .flatMap((c) => (c.AllowedValues?.Value ?? []).map(textOf));
      if (get.href && (encodings.length === 0 || encodings.some((e) => e.toUpperCase() === 'KVP'))) return resolve(get.href, documentUrl);
    }
  }
  return null;
}

/** An absolute address: a relative one resolved against the document's (placeholders kept). */
function resolve(address, documentUrl) {
  if (/^https?:\/\//i.test(address)) return address;
  try {
    // URL() would escape the braces of placeholders: resolve the part before the first one.
    const at = address.indexOf('{');
    const head = at < 0 ? address : address.slice(0, at);
    return new URL(head, documentUrl).href + (at < 0 ? '' : address.slice(at));
  } catch {
    return address;
  }
}

/** The text of an element: a string, an object's '#text', or the first of a list. */
function textOf(value) {
  if (value === undefined || value === null) return '';
  if (Array.isArray(value)) return textOf(value[0]);
  if (typeof value === 'object') return String(value['#text'] ?? '').trim();
  return String(value).trim();
}

function numbersOf(value) {
  return textOf(value).split(/\s+/).filter(Boolean).map(Number);
}
