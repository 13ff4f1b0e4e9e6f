// EPSG CRS definitions for Node: the command line reads them from disk (useNodeCrsDefinitions),
// and the page's build writes one small file per code from the same function (crs_files_plugin.js).
//
// Two npm packages, each for what it does best. epsg-index (one JSON file per code, 8112 codes)
// gives every code's name, kind and area, and a PROJ string; proj4-list (5434 codes) gives PROJ
// strings whose datum shifts proj4 can apply. Checked against PROJ (gdaltransform) at the centre
// of every code's area, proj4-list's strings agree better (within 1 m for 562 codes where
// epsg-index's are off, against 101 the other way): epsg-index names NTv2 grids that proj4
// cannot have (309 codes, which give NaN) and carries some shifts wrongly, e.g. EPSG:28992's
// Molodensky-Badekas rotations as a Helmert's, 150 m off. So a code's PROJ string is
// proj4-list's where it has one, else epsg-index's.
//
// We ship no datum grids: a +nadgrids= grid (but @null) is dropped from a string, as PROJ falls
// back without its grid, so such a CRS has no datum shift (a datum proj4 knows by name keeps
// its own). A string proj4 cannot parse (vertical CRSs, +geoidgrids) is no definition.
import { existsSync, readFileSync, readdirSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';
import proj4 from 'proj4';
import { setCrsSource } from '../web/geo/index.js';

const require = createRequire(import.meta.url);
const INDEX_DIR = join(dirname(require.resolve('epsg-index/package.json')), 's');
let listed = null; // proj4-list's table, read on first use (777 KB)
const proj4List = () => (listed ??= require('proj4-list'));

/**
 * @typedef {import('../web/geo/crs_definitions.js').CrsDefinition & { kind: string|null, area: string|null,
 *   bbox: number[]|null }} NodeCrsDefinition bbox: [north, west, south, east] degrees, as epsg-index gives it
 */

/**
 * The definition of an EPSG code, or null when neither package knows it.
 * @param {number} code
 * @returns {NodeCrsDefinition|null}
 */
export function crsDefinition(code) {
  if (!Number.isInteger(code) || code <= 0 || code > 999999) return null;
  const file = join(INDEX_DIR, `${code}.json`);
  const entry = existsSync(file) ? JSON.parse(readFileSync(file, 'utf8')) : null;
  const fromList = proj4List()[`EPSG:${code}`]?.[1] ?? null;
  if (!entry && !fromList) return null;
  const definition = [fromList, entry?.proj4].map(runnable).find((d) => d !== null) ?? null;
  return { code, name: entry?.name ?? null, proj4: definition, kind: entry?.kind ?? null, area: entry?.area ?? null,
    bbox: Array.isArray(entry?.bbox) ? entry.bbox : null };
}

/** Every code either package knows, ascending. */
export function crsCodes() {
  const codes = new Set(readdirSync(INDEX_DIR).map((name) => /^(\d+)\.json$/.exec(name)?.[1]).filter(Boolean).map(Number));
  for (const key of Object.keys(proj4List())) {
    const m = /^EPSG:(\d+)$/.exec(key);
    if (m) codes.add(Number(m[1]));
  }
  return [...codes].sort((a, b) => a - b);
}

/** A PROJ string proj4 can run: without grids we do not ship, tidied; null when proj4 cannot parse it. */
function runnable(text) {
  if (typeof text !== 'string') return null;
  const definition = text.replace(/\s*\+nadgrids=(?!@null(\s|$))\S+/g, '').replace(/\s+/g, ' ').trim();
  try {
    const projection = proj4.Proj(definition);
    return projection?.projName ? definition : null;
  } catch {
    return null;
  }
}

/** Makes web/geo/ resolve EPSG codes from the packages on disk (the command line, Node tests). */
export function useNodeCrsDefinitions() {
  setCrsSource(async (code) => crsDefinition(code));
}
