// The georeference of a GeoTIFF (the first image): its CRS from the GeoKeys, and the map from
// sample centres to model coordinates from ModelTiepoint + ModelPixelScale, or from a
// ModelTransformation without rotation. Shared by height fields and draped images.
//
// A CRS the GeoKeys call user-defined (32767) is rebuilt from the keys by libgeotiff, which we
// do not have; what we read instead is what GDAL and ESRI leave in the citation keys: a WKT
// ("ESRI PE String = PROJCS[...]"), or a name that says its EPSG code. Otherwise it stays
// 'user-defined' under the citation's name, with no definition (GDAL then also writes the CRS
// into the .aux.xml beside the file, which crs_sidecars.js reads).

import { crsOfEpsg, makeGeoref, parseEpsg, UNKNOWN_CRS } from './georef.js';
import { crsFromWkt, looksLikeWkt } from './crs_wkt.js';
import { CrsError } from './crs_error.js';

const MODEL_PROJECTED = 1, MODEL_GEOGRAPHIC = 2; // GTModelTypeGeoKey
const RASTER_PIXEL_IS_POINT = 2; // GTRasterTypeGeoKey: 1 (the default) is PixelIsArea
const USER_DEFINED = 32767;

/**
 * @param {import('geotiff').GeoTIFFImage} image
 * @returns {import('./georef.js').Georef|null} null without a usable affine map (no tags, a
 *   rotated or sheared grid, non-finite numbers)
 */
export function georefOfTiff(image) {
  const dir = image.fileDirectory;
  let tiepoint, scale, transform, keys;
  try {
    tiepoint = dir.getValue('ModelTiepoint');
    scale = dir.getValue('ModelPixelScale');
    transform = dir.getValue('ModelTransformation');
  } catch {
    return null;
  }
  try { keys = image.getGeoKeys() ?? {}; } catch { keys = {}; }

  // Raster space: PixelIsArea puts (0, 0) at the corner of the first pixel, PixelIsPoint at its centre.
  const toCentre = keys.GTRasterTypeGeoKey === RASTER_PIXEL_IS_POINT ? 0 : 0.5;
  let x0, y0, dx, dy;
  if (tiepoint?.length >= 6 && scale?.length >= 2) {
    const [i, j, , x, y] = tiepoint;
    dx = scale[0];
    dy = -scale[1];
    x0 = x + (toCentre - i) * dx;
    y0 = y + (toCentre - j) * dy;
  } else if (transform?.length >= 16) {
    if (transform[1] !== 0 || transform[4] !== 0) return null; // rotated or sheared
    dx = transform[0];
    dy = transform[5];
    x0 = transform[3] + toCentre * dx;
    y0 = transform[7] + toCentre * dy;
  } else {
    return null;
  }
  return makeGeoref(crsOfGeoKeys(keys), x0, y0, dx, dy, 'GeoTIFF');
}

/** The CRS the GeoKeys name (not resolved yet: resolveCrs). */
export function crsOfGeoKeys(keys) {
  // The model type may itself be user-defined (32767, as GDAL writes ESRI's flavour): a
  // projected CRS key then says what it is.
  const geographic = keys.GTModelTypeGeoKey === MODEL_GEOGRAPHIC;
  const code = geographic ? keys.GeographicTypeGeoKey
    : keys.GTModelTypeGeoKey === MODEL_PROJECTED || keys.GTModelTypeGeoKey === USER_DEFINED ? keys.ProjectedCSTypeGeoKey : undefined;
  if (Number.isInteger(code) && code > 0 && code !== USER_DEFINED) return crsOfEpsg(code, geographic);
  if (code === USER_DEFINED) return userDefined(keys, geographic);
  return { ...UNKNOWN_CRS, geographic };
}

/** A user-defined CRS from its citations: a WKT in one, an EPSG code in one, else its name alone. */
function userDefined(keys, geographic) {
  const citations = [keys.PCSCitationGeoKey, keys.GTCitationGeoKey, keys.GeogCitationGeoKey]
    .filter((c) => typeof c === 'string').map((c) => c.replace(/\0+$/, '').trim()).filter((c) => c !== '');
  for (const citation of citations) {
    const wkt = citation.replace(/^ESRI PE String\s*=\s*/i, '');
    if (!looksLikeWkt(wkt)) continue;
    try {
      return crsFromWkt(wkt, 'its GeoKeys citation');
    } catch (error) {
      if (!(error instanceof CrsError)) throw error; // a WKT proj4 cannot read: its name is still a name
    }
  }
  for (const citation of citations) {
    const epsg = parseEpsg(citation);
    if (epsg !== null) return crsOfEpsg(epsg, geographic);
  }
  const name = citations.find((c) => !looksLikeWkt(c.replace(/^ESRI PE String\s*=\s*/i, ''))) ?? null;
  return { epsg: null, label: 'user-defined', name, proj4: null, geographic };
}
