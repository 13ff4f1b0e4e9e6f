// The one view of a height field the measuring tools read: its extent in local metres and the
// bilinear height of its full-resolution samples at a point. Two sources give one: the core's
// terrain (the page and the CLI) and a plain array (tests, and the reference the core is
// checked against).
//
// Local metres: x = column * spacingX (east), z = row * spacingY (south in a north-up grid).
// No-data: the loaders fill voids before the core sees them (web/loaders/nodata.js
// interpolates each missing sample from the valid ones around it), so a core field has a height
// everywhere and those heights are estimates; an array may hold NaN for a missing sample, and a
// point whose cell touches one has no height (NaN).

/**
 * @typedef {object} FieldSampler
 * @property {number} extentX metres from the first to the last column (x runs 0..extentX)
 * @property {number} extentZ metres from the first to the last row (z runs 0..extentZ)
 * @property {number} spacing metres, the finer of spacingX and spacingY: the natural sampling step
 * @property {number} spacingX metres between columns
 * @property {number} spacingY metres between rows
 * @property {number} columns samples per row
 * @property {number} rows rows of samples
 * @property {(x: number, z: number) => number} heightAt metres, bilinear between the four
 *   samples around (x, z) metres; NaN outside [0, extentX] x [0, extentZ] or on no-data
 * @property {import('../geo/georef.js').Georef|null} georef where the samples lie on the Earth
 */

/**
 * A sampler over a core terrain (web/core/core.js Terrain, after setScale and prepare).
 * @param {{width: number, height: number, spacingX: number, spacingY: number, heightAt: (x: number, z: number) => number}} terrain
 * @param {import('../geo/georef.js').Georef|null} [georef]
 * @returns {FieldSampler}
 */
export function fieldSampler(terrain, georef = null) {
  const { width, height, spacingX, spacingY } = terrain;
  const extentX = (width - 1) * spacingX, extentZ = (height - 1) * spacingY;
  return {
    ...frame(width, height, spacingX, spacingY, georef),
    // The core clamps a point outside to the edge; a measurement must not invent heights there.
    heightAt: (x, z) => (x >= 0 && x <= extentX && z >= 0 && z <= extentZ ? terrain.heightAt(x, z) : NaN),
  };
}

/**
 * A sampler over heights in metres held in an array, row by row (NaN marks a missing sample).
 * @param {ArrayLike<number>} samples width * height heights, row 0 first
 * @param {number} width samples per row (>= 2)
 * @param {number} height rows (>= 2)
 * @param {number} spacingX metres between columns (> 0)
 * @param {number} spacingY metres between rows (> 0)
 * @returns {FieldSampler}
 */
export function samplerOfArray(samples, width, height, spacingX, spacingY) {
  if (!(width >= 2 && height >= 2 && samples.length >= width * height)) {
    throw new Error(`samplerOfArray needs at least 2 x 2 samples and width * height of them, got ${width} x ${height} and ${samples.length}`);
  }
  if (!(spacingX > 0 && spacingY > 0)) throw new Error(`sample spacing must be positive, got ${spacingX} x ${spacingY} m`);
  const extentX = (width - 1) * spacingX, extentZ = (height - 1) * spacingY;
  const heightAt = (x, z) => {
    if (!(x >= 0 && x <= extentX && z >= 0 && z <= extentZ)) return NaN;
    const u = x / spacingX, v = z / spacingY;
    // The last column and row belong to the cell before them.
    const i = Math.min(Math.floor(u), width - 2), j = Math.min(Math.floor(v), height - 2);
    const fu = u - i, fv = v - j, k = j * width + i;
    const top = samples[k] * (1 - fu) + samples[k + 1] * fu;
    const bottom = samples[k + width] * (1 - fu) + samples[k + width + 1] * fu;
    return top * (1 - fv) + bottom * fv;
  };
  return { ...frame(width, height, spacingX, spacingY, null), heightAt };
}

function frame(width, height, spacingX, spacingY, georef) {
  return {
    extentX: (width - 1) * spacingX,
    extentZ: (height - 1) * spacingY,
    spacing: Math.min(spacingX, spacingY),
    spacingX,
    spacingY,
    columns: width,
    rows: height,
    georef,
  };
}
