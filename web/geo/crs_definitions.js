// The definitions of EPSG CRSs, looked up when a file names a code: its name and a definition
// proj4 parses. Where they come from is given by whoever runs this module (setCrsSource): the
// page fetches one small file per code from beside itself (web/app/crs_source.js), the command
// line reads the definitions packages from disk (lib/crs_definitions.js). So nothing is loaded
// until a file names a CRS, and this module needs neither a network nor a file system.
//
// A file opens with the CRS it names (crsOfEpsg, a .prj's crsFromWkt, ...); resolveCrs, called
// once where terrains and images are opened, fills in the name, the definition and whether it
// is geographic. Everything after that is synchronous.
import { isGeographicDefinition, projectionOf } from './crs_transform.js';

/**
 * @typedef {object} CrsDefinition
 * @property {number} code
 * @property {string|null} name "CH1903+ / LV95"
 * @property {string|null} proj4 a PROJ string proj4 parses, null when there is none
 */

/** @type {((code: number) => Promise<CrsDefinition|null>)|null} */
let source = null;
/** code -> the definition's promise: each code is asked for once (a failure is asked again) */
const asked = new Map();

/**
 * Sets where EPSG definitions come from; without one, CRSs keep what their files say.
 * @param {((code: number) => Promise<CrsDefinition|null>)|null} load null: the code has no
 *   definition; a rejection (a network failure) counts as none this time
 */
export function setCrsSource(load) {
  source = load;
  asked.clear();
}

/** The definition of an EPSG code, or null (no source, an unknown code, a failure). */
function definitionOf(code) {
  if (!source || !Number.isInteger(code)) return Promise.resolve(null);
  if (!asked.has(code)) {
    const pending = Promise.resolve().then(() => source(code)).then((d) => (d && typeof d === 'object' ? d : null), () => {
      asked.delete(code); // a failed fetch may work next time
      return null;
    });
    asked.set(code, pending);
  }
  return asked.get(code);
}

/**
 * A CRS with its name and definition: an EPSG code's from the definitions (its proj4 text, with
 * the datum shift it carries), else the file's own (a WKT proj4 parses); `geographic` from the
 * definition when there is one. Cached per code.
 * @param {import('./georef.js').Crs} crs
 * @returns {Promise<import('./georef.js').Crs>} a new object (crs is not changed)
 */
export async function resolveCrs(crs) {
  if (!crs) return crs;
  const definition = crs.epsg === null ? null : await definitionOf(crs.epsg);
  const usable = (text) => (projectionOf(text) ? text : null);
  const proj4 = usable(definition?.proj4) ?? usable(crs.proj4 ?? null);
  const name = definition?.name || crs.name || null;
  return { ...crs, name, proj4, geographic: proj4 ? isGeographicDefinition(proj4) : crs.geographic };
}

/** A georeference with its CRS resolved (resolveCrs); null stays null. */
export async function resolveGeoref(georef) {
  return georef && { ...georef, crs: await resolveCrs(georef.crs) };
}
