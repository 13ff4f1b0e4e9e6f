// An overlay placed on a terrain: each position carried from the overlay's CRS into the
// terrain's (geo/crs_transform.js, as images are reprojected; nothing to do when they are the
// same), then to local metres (x east from the first sample, z south), and marked on or off the
// field. Features entirely off the field are counted: the page says how many, and draws nothing
// in the void.
import { crsTransform, crsToLocal } from '../geo/index.js';
import { clipSegment } from '../measure/clip.js';
import { OverlayError } from './overlay_error.js';

/**
 * @typedef {object} PlacedFeature
 * @property {import('./geojson_features.js').Feature} feature
 * @property {Array<{x: Float64Array, z: Float64Array, inside: Uint8Array}>} paths local metres, one per feature path
 * @property {'all'|'part'|'none'} onTerrain
 */

/**
 * @param {import('./read_overlay.js').Overlay} overlay
 * @param {import('../geo/georef.js').Georef|null} georef the terrain's, its CRS resolved
 * @param {{columns: number, rows: number, spacingX: number, spacingY: number}} field
 * @returns {{overlay: object, features: PlacedFeature[], offTerrain: number, partlyOff: number}}
 * @throws {OverlayError} a terrain without a georeference, or one whose CRS has no definition
 */
export function placeOverlay(overlay, georef, { columns, rows, spacingX, spacingY }) {
  if (!georef) {
    throw new OverlayError('the terrain on screen has no georeference, so an overlay cannot be placed on it; open a georeferenced height field (GeoTIFF, or with a world file, .prj or .aux.xml)');
  }
  const toTerrain = crsTransform(overlay.crs, georef.crs);
  if (!toTerrain) throw new OverlayError(`the terrain's CRS (${georef.crs.label}) has no definition to carry ${overlay.crs.label} coordinates into it`);
  const extentX = (columns - 1) * spacingX, extentZ = (rows - 1) * spacingY;
  let offTerrain = 0, partlyOff = 0;
  const features = overlay.features.map((feature) => {
    let inCount = 0, total = 0;
    const paths = feature.paths.map(({ x: fx, y: fy }) => {
      const n = fx.length, x = new Float64Array(n), z = new Float64Array(n), inside = new Uint8Array(n);
      for (let k = 0; k < n; k++) {
        const [cx, cy] = toTerrain(fx[k], fy[k]);
        const [lx, lz] = crsToLocal(georef, cx, cy, spacingX, spacingY);
        x[k] = lx;
        z[k] = lz;
        inside[k] = lx >= 0 && lx <= extentX && lz >= 0 && lz <= extentZ ? 1 : 0;
        inCount += inside[k];
      }
      total += n;
      return { x, z, inside };
    });
    // A line may cross the field between two vertices off it.
    const onTerrain = inCount === total ? 'all' : inCount > 0 || crosses(paths, extentX, extentZ) ? 'part' : 'none';
    if (onTerrain === 'none') offTerrain++;
    if (onTerrain === 'part') partlyOff++;
    return { feature, paths, onTerrain };
  });
  return { overlay, features, offTerrain, partlyOff };
}

/** Whether a path whose vertices all lie off the field still passes over it: a segment crosses it. */
function crosses(paths, extentX, extentZ) {
  return paths.some(({ x, z }) => {
    for (let k = 1; k < x.length; k++) if (clipSegment(x[k - 1], z[k - 1], x[k], z[k], extentX, extentZ)) return true;
    return false;
  });
}
