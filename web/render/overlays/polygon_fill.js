// Polygons filled lightly on the ground: an overlay's polygons drawn into a raster over their
// bounding box (a 2D canvas, even-odd, so holes stay open), draped on the terrain as an image
// layer is (render/shading/drape_layers.js), so the fill lies on the true surface at every
// pixel, over ridges and into valleys, at no cost per frame beyond one drape. The raster's
// pixel is a fraction of the field's spacing, up to MAX_FILL_PIXELS a side.
import { makeWarpGrid } from '../../geo/index.js';
import { planImageTiling } from '../../imagery/image_tiling.js';

export const MAX_FILL_PIXELS = 2048;
/** How see-through the fill is: the ground shows through. */
export const FILL_OPACITY = 0.3;
const PIXELS_PER_SPACING = 4;

/**
 * Where the raster lies: its box in local metres (clipped to the field) and its pixel size, or
 * null when the overlay has no polygon on the field.
 * @param {{features: Array<{feature: {kind: string}, paths: Array<{x: ArrayLike<number>, z: ArrayLike<number>}>}>}} placed
 * @param {{extentX: number, extentZ: number, spacing: number}} sampler
 */
export function fillFrame(placed, sampler) {
  let x0 = Infinity, z0 = Infinity, x1 = -Infinity, z1 = -Infinity;
  for (const { feature, paths } of placed.features) {
    if (feature.kind !== 'polygon') continue;
    for (const { x, z } of paths) {
      for (let k = 0; k < x.length; k++) {
        x0 = Math.min(x0, x[k]); x1 = Math.max(x1, x[k]);
        z0 = Math.min(z0, z[k]); z1 = Math.max(z1, z[k]);
      }
    }
  }
  x0 = Math.max(x0, 0); z0 = Math.max(z0, 0); x1 = Math.min(x1, sampler.extentX); z1 = Math.min(z1, sampler.extentZ);
  if (!(x1 > x0 && z1 > z0)) return null;
  const pixel = Math.max(sampler.spacing / PIXELS_PER_SPACING, Math.max(x1 - x0, z1 - z0) / MAX_FILL_PIXELS);
  return { x0, z0, pixel, width: Math.max(1, Math.ceil((x1 - x0) / pixel)), height: Math.max(1, Math.ceil((z1 - z0) / pixel)) };
}

/**
 * The fill of an overlay's polygons as a drape (kind 'image'), its textures filled.
 * @param {object} placed overlays/place_overlay.js
 * @param {import('../../measure/field_sampler.js').FieldSampler} sampler
 * @param {number[]} rgb 0..1
 * @param {import('../shading/image_textures.js').ImageTextures} textures new, the layer's own
 * @returns {import('../shading/drape_layers.js').Drape|null} null when no polygon lies on the field
 */
export function polygonFillDrape(placed, sampler, rgb, textures) {
  const frame = fillFrame(placed, sampler);
  if (!frame) return null;
  const { x0, z0, pixel, width, height } = frame;
  const canvas = typeof OffscreenCanvas === 'function' ? new OffscreenCanvas(width, height)
    : Object.assign(document.createElement('canvas'), { width, height });
  const g = canvas.getContext('2d');
  g.fillStyle = `rgb(${rgb.map((c) => Math.round(c * 255)).join(',')})`;
  for (const { feature, paths } of placed.features) {
    if (feature.kind !== 'polygon') continue;
    for (const rings of feature.polygons ?? [paths.map((_, k) => k)]) {
      g.beginPath();
      for (const k of rings) {
        const { x, z } = paths[k];
        for (let i = 0; i < x.length; i++) {
          const px = (x[i] - x0) / pixel, py = (z[i] - z0) / pixel;
          if (i === 0) g.moveTo(px, py); else g.lineTo(px, py);
        }
        g.closePath();
      }
      g.fill('evenodd');
    }
  }
  textures.begin(planImageTiling(width, height, { ...textures.limits(), wholeDecode: true, name: 'polygon fill' }));
  textures.uploadBitmap(canvas);
  // Field sample (column, row) -> raster pixel: affine, so the coarsest grid is exact.
  const warp = makeWarpGrid(sampler.columns, sampler.rows,
    (column, row) => [(column * sampler.spacingX - x0) / pixel, (row * sampler.spacingY - z0) / pixel], 0.01);
  return { kind: 'image', warp, opacity: FILL_OPACITY, textures };
}
