// A CRS written as WKT: an ESRI .prj (WKT1 with ESRI's names), an OGC WKT1 or a WKT2 text
// (GDAL's .aux.xml, gdalsrsinfo). An EPSG code at the top level (WKT1 AUTHORITY, WKT2 ID) makes
// it that EPSG CRS, whose definition then comes from the EPSG definitions (resolveCrs), datum
// shift included; a WKT without one is a CRS of its own, defined by the WKT text itself, when
// proj4 (its wkt-parser) can read it.
//
// proj4 reads the WKT; what it does not say is which code stands at the top level (its title
// also comes from a nested one: a projected CRS without its own ID would take its base
// geographic CRS's code), so the top node's children are found here by counting brackets.
import { crsOfEpsg, parseEpsg } from './georef.js';
import { isGeographicDefinition, projectionOf } from './crs_transform.js';
import { CrsError } from './crs_error.js';
import { shown } from './shown.js';

const CRS_KEYWORDS = /^(PROJCS|GEOGCS|GEOCCS|PROJCRS|PROJECTEDCRS|GEOGCRS|GEOGRAPHICCRS|GEODCRS|GEODETICCRS)$/i;
const COMPOUND = /^(COMPD_CS|COMPOUNDCRS)$/i;

/**
 * @param {string} text the WKT
 * @param {string} fileName for messages
 * @returns {import('./georef.js').Crs} not resolved yet (resolveCrs)
 * @throws {CrsError} naming the file: no WKT, or one proj4 cannot read (with the CRS's name)
 */
export function crsFromWkt(text, fileName) {
  const wkt = String(text).replace(/^\uFEFF/, '').replace(/\0+$/, '').trim();
  if (wkt === '') throw new CrsError(`${fileName}: empty, where a CRS in WKT was expected`);
  if (/^(EPSG|urn:ogc:def:crs:EPSG:[\d.]*):{1,2}\d{1,6}$/i.test(wkt)) return crsOfEpsg(parseEpsg(wkt)); // some tools write the code alone
  const node = topNode(wkt);
  if (!node) throw new CrsError(`${fileName}: not a CRS in WKT (it starts with ${shown(wkt.slice(0, 30))})`);
  const name = firstQuoted(wkt) ?? 'unnamed';
  let epsg = epsgOf(node);
  if (epsg === null && COMPOUND.test(node.keyword)) {
    // Horizontal + heights without a code of its own: the horizontal part is the grid's CRS.
    const horizontal = node.children.find((child) => CRS_KEYWORDS.test(child.keyword));
    if (horizontal) return crsFromWkt(horizontal.text, fileName);
  }
  if (epsg === null && /^BOUNDCRS$/i.test(node.keyword)) {
    // A CRS with its transformation to WGS 84 (WKT2's TOWGS84): the source CRS's code.
    const source = node.children.find((child) => /^SOURCECRS$/i.test(child.keyword));
    const inner = source && topNode(source.text).children.find((child) => CRS_KEYWORDS.test(child.keyword));
    epsg = inner ? epsgOf(topNode(inner.text)) : null;
  }
  const definition = projectionOf(wkt) ? wkt : null;
  if (epsg !== null) {
    return { ...crsOfEpsg(epsg, definition ? isGeographicDefinition(definition) : /^GEOG/i.test(node.keyword)), name, proj4: definition };
  }
  if (!definition) {
    throw new CrsError(`${fileName}: proj4 cannot read the CRS "${name}" in it (${node.keyword}[...] without an EPSG code); ` +
      'write it with one (e.g. gdalsrsinfo -o wkt1 EPSG:NNNN)');
  }
  return { epsg: null, label: `custom (${name} from the WKT)`, name, proj4: definition, geographic: isGeographicDefinition(definition) };
}

/** True when a text looks like a WKT CRS (a GeoTIFF citation may hold one). */
export function looksLikeWkt(text) {
  const node = typeof text === 'string' ? /^\s*([A-Za-z_]\w*)\s*[[(]/.exec(text) : null;
  return !!node && (CRS_KEYWORDS.test(node[1]) || COMPOUND.test(node[1]) || /^BOUNDCRS$/i.test(node[1]));
}

/**
 * The top node of a WKT text: its keyword and its children that are nodes themselves
 * (KEYWORD[...]), each with its text; null when the text does not start with KEYWORD[.
 */
function topNode(wkt) {
  const open = /^\s*([A-Za-z_]\w*)\s*[[(]/.exec(wkt);
  if (!open) return null;
  const children = [];
  let depth = 1, segment = open[0].length;
  for (let i = segment; i < wkt.length && depth > 0; i++) {
    const ch = wkt[i];
    if (ch === '"') {
      i = endOfQuote(wkt, i);
    } else if (ch === '[' || ch === '(') {
      if (depth === 1) {
        const keyword = wkt.slice(segment, i).trim();
        children.push({ keyword, start: wkt.indexOf(keyword, segment), text: null });
      }
      depth++;
    } else if (ch === ']' || ch === ')') {
      depth--;
      const child = children.at(-1);
      if (depth === 1 && child && child.text === null) child.text = wkt.slice(child.start, i + 1);
    } else if (ch === ',' && depth === 1) {
      segment = i + 1;
    }
  }
  return { keyword: open[1], children: children.filter((child) => child.text !== null) };
}

/** The index of the quote that closes the string opened at `start` ("" is a quote inside it). */
function endOfQuote(wkt, start) {
  let i = start + 1;
  while (i < wkt.length) {
    if (wkt[i] === '"') {
      if (wkt[i + 1] !== '"') return i;
      i++;
    }
    i++;
  }
  return wkt.length;
}

/** The EPSG code among a node's own AUTHORITY or ID children, else null. */
function epsgOf(node) {
  for (const child of node?.children ?? []) {
    if (!/^(AUTHORITY|ID)$/i.test(child.keyword)) continue;
    const m = /^\w+\s*[[(]\s*"EPSG"\s*,\s*"?\s*(\d{1,6})\s*"?/i.exec(child.text);
    if (m) return Number(m[1]);
  }
  return null;
}

/** The first quoted string of the text: the top-level CRS's name (a BOUNDCRS's: its source's). */
function firstQuoted(wkt) {
  const m = /"((?:[^"]|"")*)"/.exec(wkt);
  return m ? m[1].replace(/""/g, '"').trim() || null : null;
}
