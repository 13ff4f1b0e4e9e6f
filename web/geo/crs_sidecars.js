// The sidecars that say which CRS a grid (a height field or an image) is in: its .prj (x.prj
// beside x.asc or x.png) and GDAL's .aux.xml (x.tif.aux.xml, or x.aux.xml), whose <SRS> gives
// the CRS and whose <GeoTransform> may place a grid that cannot place itself. A sidecar that
// cannot be read is a note, never the end of the file it came with.
import { sameCrs } from './georef.js';
import { crsFromWkt } from './crs_wkt.js';
import { parseAuxXml } from './aux_xml.js';
import { CrsError } from './crs_error.js';
import { extensionOfName } from './sidecar_names.js';

/** Past this a file is no .prj or .aux.xml of ours (GDAL's histograms stay far below it). */
export const CRS_SIDECAR_BYTES = 4 * 2 ** 20;

/**
 * @typedef {{ name: string, bytes: Uint8Array }} NamedBytes
 * @typedef {object} CrsSidecars
 * @property {import('./georef.js').Crs|null} crs the .aux.xml's SRS, else the .prj's (not resolved yet)
 * @property {import('./georef.js').Georef|null} georef the .aux.xml's geotransform, in that CRS
 * @property {string[]} notes what was not used and why, each naming its file
 */

/**
 * @param {{ prj?: NamedBytes|null, auxXml?: NamedBytes|null }} sidecars
 * @returns {Promise<CrsSidecars>}
 */
export async function readCrsSidecars({ prj = null, auxXml = null } = {}) {
  const notes = [];
  let crs = null, georef = null;
  const attempt = async (file, read) => {
    if (file.bytes.length > CRS_SIDECAR_BYTES) {
      notes.push(`${file.name}: more than ${CRS_SIDECAR_BYTES / 2 ** 20} MB is too big for a .${extensionOfName(file.name)}; not used`);
      return null;
    }
    try {
      return await read(new TextDecoder().decode(file.bytes), file.name);
    } catch (error) {
      if (!(error instanceof CrsError)) throw error;
      notes.push(`${error.message}; not used`);
      return null;
    }
  };
  if (auxXml) {
    const aux = await attempt(auxXml, parseAuxXml);
    crs = aux?.crs ?? null;
    georef = aux?.georef ?? null;
  }
  if (prj) {
    const own = await attempt(prj, crsFromWkt);
    if (own && crs && !sameCrs(own, crs)) notes.push(`${prj.name} names ${own.label} and ${auxXml.name} ${crs.label}: the .aux.xml's is used`);
    crs ??= own;
  }
  if (georef && crs && georef.crs !== crs) georef = { ...georef, crs };
  return { crs, georef, notes };
}

/**
 * A grid's georeference in its sidecars' CRS when the file names none of its own: a world
 * file, an ASCII grid (whose lat/lon is only guessed from its numbers), a GeoTIFF with a
 * user-defined CRS proj4 cannot read. A file that names a CRS keeps it; a sidecar that names
 * another is a note.
 * @param {import('./georef.js').Georef|null} georef
 * @param {import('./georef.js').Crs|null} crs from the sidecars
 * @param {string} fileName the grid's, for the note
 * @returns {{ georef: import('./georef.js').Georef|null, note: string|null }}
 */
export function withSidecarCrs(georef, crs, fileName) {
  if (!georef || !crs) return { georef, note: null };
  const own = georef.crs;
  const guessed = georef.from === 'ASCII header' || georef.from === 'world file' || georef.from === '.aux.xml';
  if (guessed || (own.epsg === null && own.proj4 === null)) return { georef: { ...georef, crs }, note: null };
  if (sameCrs(own, crs)) return { georef, note: null };
  return { georef, note: `${fileName} names ${own.label} itself and its sidecar ${crs.label}: the file's is used` };
}
