// How an image is laid out on the GPU, decided from its size alone, before it is decoded:
//   - an image no larger than MAX_TEXTURE_SIZE a side is one texture layer of its own size;
//   - a larger one is cut into tiles of at most MAX_TEXTURE_SIZE (layers of a texture array),
//     each with an apron of APRON pixels copied from its neighbours, so that filtering and the
//     first mip levels never read past a tile's edge (no seam); for the coarser levels, where
//     a screen pixel spans more than the apron, the shader reads an overview of the whole
//     image instead: the whole image resampled to one more layer of the same size (the
//     array's last), so that an image takes two samplers however it is cut.
// And whether it fits: the GPU memory it takes (RGBA8 with mipmaps: 4/3 of 4 bytes a texel) is
// checked against a budget, and the pixels the browser decodes at once against a cap, so that a
// person hears "too big" before the tab runs out of memory.

import { ImageError } from './image_error.js';

export const APRON = 8;
/** Pixels the browser may decode at once (PNG, JPEG, WebP are decoded whole): 1 GiB of RGBA. */
export const MAX_DECODED_PIXELS = 2 ** 28;
/** GPU memory an image may take, by default. */
export const DEFAULT_BUDGET_BYTES = 1.5 * 2 ** 30;
const MIPMAPPED = 4 / 3;

/**
 * @typedef {object} ImageTiling
 * @property {number} width image pixels
 * @property {number} height
 * @property {number} tileWidth texels a layer (the image's own size when it is one layer)
 * @property {number} tileHeight
 * @property {number} apron pixels each tile repeats of its neighbours (0 for one layer)
 * @property {number} strideX image pixels between the starts of neighbouring tiles, across
 * @property {number} strideY and down
 * @property {number} tilesX
 * @property {number} tilesY
 * @property {{ width: number, height: number }|null} overview the whole image, smaller, for coarse
 *   views: the layer after the tiles, tileWidth × tileHeight
 * @property {number} gpuBytes tiles and overview, mipmaps included
 */

/**
 * @param {number} width
 * @param {number} height
 * @param {{ maxTextureSize: number, maxLayers: number, budgetBytes?: number, wholeDecode: boolean, name: string }} limits
 *   wholeDecode: the browser decodes the file in one piece (PNG, JPEG, WebP), not in bands (TIFF)
 * @returns {ImageTiling}
 * @throws {ImageError} when it does not fit
 */
export function planImageTiling(width, height, { maxTextureSize, maxLayers, budgetBytes = DEFAULT_BUDGET_BYTES, wholeDecode, name }) {
  const size = `${width} × ${height}`;
  const megapixels = (width * height) / 1e6;
  const shrink = (factor) => `${Math.floor(width / factor)} × ${Math.floor(height / factor)}`;
  if (wholeDecode && width * height > MAX_DECODED_PIXELS) {
    const factor = Math.ceil(Math.sqrt((width * height) / MAX_DECODED_PIXELS));
    throw new ImageError(name, `${size} pixels (${megapixels.toFixed(0)} Mpx) is more than the browser can decode at once ` +
      `(${(MAX_DECODED_PIXELS / 1e6).toFixed(0)} Mpx); save it as a tiled GeoTIFF, read in bands, or at ${shrink(factor)} or less`);
  }
  let tiling;
  if (width <= maxTextureSize && height <= maxTextureSize) {
    tiling = { width, height, tileWidth: width, tileHeight: height, apron: 0, strideX: width, strideY: height, tilesX: 1, tilesY: 1, overview: null };
  } else {
    // As few tiles as the limit allows, then as small as they can be: a 16384² image is 3 x 3
    // tiles of 5478², not of 8192² (2.25 times the memory).
    const most = maxTextureSize - 2 * APRON;
    const tilesX = Math.ceil(width / most), tilesY = Math.ceil(height / most);
    const strideX = Math.ceil(width / tilesX), strideY = Math.ceil(height / tilesY);
    const tileWidth = strideX + 2 * APRON, tileHeight = strideY + 2 * APRON;
    tiling = { width, height, tileWidth, tileHeight, apron: APRON, strideX, strideY, tilesX, tilesY, overview: { width: tileWidth, height: tileHeight } };
  }
  const layers = tiling.tilesX * tiling.tilesY;
  tiling.gpuBytes = Math.round(arrayLayers(tiling) * tiling.tileWidth * tiling.tileHeight * 4 * MIPMAPPED);
  if (arrayLayers(tiling) > maxLayers) {
    throw new ImageError(name, `${size} pixels need ${layers} tiles (at most ${maxTextureSize}² each), more than this GPU's ${maxLayers}; ` +
      `use an image of at most ${shrink(Math.sqrt(layers / maxLayers))}`);
  }
  if (tiling.gpuBytes > budgetBytes) {
    const factor = Math.sqrt(tiling.gpuBytes / budgetBytes);
    throw new ImageError(name, `${size} pixels need ${(tiling.gpuBytes / 2 ** 30).toFixed(1)} GB of GPU memory with mipmaps, ` +
      `more than the ${(budgetBytes / 2 ** 30).toFixed(1)} GB an image may take; use one of at most ${shrink(factor)} ` +
      `(e.g. gdal_translate -outsize ${Math.floor(100 / factor)}% ${Math.floor(100 / factor)}%)`);
  }
  return tiling;
}

/**
 * The image pixels a tile holds, apron included (clipped to the image): [x0, y0, x1, y1).
 * @param {ImageTiling} tiling
 */
export function tileSource(tiling, tx, ty) {
  const x0 = tx * tiling.strideX - tiling.apron, y0 = ty * tiling.strideY - tiling.apron;
  return [Math.max(0, x0), Math.max(0, y0), Math.min(tiling.width, x0 + tiling.tileWidth), Math.min(tiling.height, y0 + tiling.tileHeight)];
}

/** Layers of the image's texture array: its tiles, and the overview after them. */
export function arrayLayers(tiling) {
  return tiling.tilesX * tiling.tilesY + (tiling.overview ? 1 : 0);
}
