// The georeference of a GeoTIFF (the first image): its CRS from the GeoKeys, and the map from
// sample centres to model coordinates from ModelTiepoint + ModelPixelScale, or from a
// ModelTransformation without rotation. Shared by height fields and draped images.

import { crsOfEpsg, makeGeoref, UNKNOWN_CRS } from './georef.js';

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
  return makeGeoref(crsOf(keys), x0, y0, dx, dy, 'GeoTIFF');
}

/** The CRS the GeoKeys name. */
function crsOf(keys) {
  const code = keys.GTModelTypeGeoKey === MODEL_GEOGRAPHIC ? keys.GeographicTypeGeoKey
    : keys.GTModelTypeGeoKey === MODEL_PROJECTED ? keys.ProjectedCSTypeGeoKey : undefined;
  if (Number.isInteger(code) && code > 0 && code !== USER_DEFINED) {
    return { ...crsOfEpsg(code), geographic: keys.GTModelTypeGeoKey === MODEL_GEOGRAPHIC };
  }
  if (code === USER_DEFINED) return { epsg: null, label: 'user-defined', geographic: keys.GTModelTypeGeoKey === MODEL_GEOGRAPHIC };
  return { ...UNKNOWN_CRS, geographic: keys.GTModelTypeGeoKey === MODEL_GEOGRAPHIC };
}
