// A control grid over a field that stands in for an exact map from the field's samples to
// another grid's coordinates (an image in another CRS, web map tiles in Web Mercator): the map
// is evaluated exactly at the grid's nodes and interpolated bilinearly between them, as the
// drape shader does (shaders/image_drape.glsl). The grid is refined until the interpolation
// stays within a tolerance of the exact map (gdalwarp's approximate transformer works alike),
// so a reprojected image lands where the exact map would put it to a fraction of a texel.
//
// Nodes where the map has no value (off its projection's domain) hold NO_VALUE; the shader
// draws nothing in cells that touch one.

export const NO_VALUE = -1e30;
/** Cells a side the grid may reach: 1024² cells are 8 MB of nodes, and far finer than any map's bend. */
export const MAX_CELLS = 1024;
// Points per axis where the interpolation is checked at each refinement (the map is smooth:
// its error is the same in neighbouring cells).
const CHECKS = 48;

/**
 * @typedef {object} WarpGrid
 * @property {number} nodesX nodes across (cells + 1)
 * @property {number} nodesY nodes down
 * @property {Float32Array} values x, y of the map at each node, row by row (NO_VALUE where it has none)
 * @property {number} columnsPerCell field columns between neighbouring nodes
 * @property {number} rowsPerCell field rows between neighbouring nodes
 * @property {number} maxError the largest distance found between the interpolation and the map, in its units
 */

/**
 * @param {number} width field samples across
 * @param {number} height field samples down
 * @param {(column: number, row: number) => [number, number]|null} map exact map of a
 *   (fractional) sample position; null or non-finite where it has no value
 * @param {number} tolerance the largest interpolation error allowed, in the map's units
 * @returns {WarpGrid}
 */
export function makeWarpGrid(width, height, map, tolerance) {
  const spanX = Math.max(width - 1, 1), spanY = Math.max(height - 1, 1);
  const exact = (column, row) => {
    const p = map(column, row);
    return p && Number.isFinite(p[0]) && Number.isFinite(p[1]) ? p : null;
  };
  let grid = null;
  for (let cells = 1; ; cells *= 2) {
    const cellsX = Math.min(cells, Math.max(1, Math.ceil(spanX))), cellsY = Math.min(cells, Math.max(1, Math.ceil(spanY)));
    grid = sample(cellsX, cellsY, spanX, spanY, exact);
    grid.maxError = interpolationError(grid, spanX, spanY, exact);
    const finest = cellsX >= Math.min(MAX_CELLS, spanX) && cellsY >= Math.min(MAX_CELLS, spanY);
    if (grid.maxError <= tolerance || finest) return grid;
  }
}

function sample(cellsX, cellsY, spanX, spanY, exact) {
  const nodesX = cellsX + 1, nodesY = cellsY + 1;
  const values = new Float32Array(nodesX * nodesY * 2);
  const columnsPerCell = spanX / cellsX, rowsPerCell = spanY / cellsY;
  for (let j = 0; j < nodesY; j++) {
    for (let i = 0; i < nodesX; i++) {
      const p = exact(i * columnsPerCell, j * rowsPerCell);
      const k = 2 * (j * nodesX + i);
      values[k] = p ? p[0] : NO_VALUE;
      values[k + 1] = p ? p[1] : NO_VALUE;
    }
  }
  return { nodesX, nodesY, values, columnsPerCell, rowsPerCell, maxError: 0 };
}

/** The grid's bilinear value at a (fractional) sample position, or null in a cell without values. */
export function interpolate(grid, column, row) {
  const { nodesX, nodesY, values } = grid;
  const gx = Math.min(Math.max(column / grid.columnsPerCell, 0), nodesX - 1);
  const gy = Math.min(Math.max(row / grid.rowsPerCell, 0), nodesY - 1);
  const i = Math.min(Math.floor(gx), nodesX - 2), j = Math.min(Math.floor(gy), nodesY - 2); // nodes >= 2 a side
  const fx = gx - i, fy = gy - j;
  const at = (a, b, axis) => values[2 * ((j + b) * nodesX + i + a) + axis];
  const result = [0, 0];
  for (let axis = 0; axis < 2; axis++) {
    const v00 = at(0, 0, axis), v10 = at(1, 0, axis), v01 = at(0, 1, axis), v11 = at(1, 1, axis);
    if (v00 === NO_VALUE || v10 === NO_VALUE || v01 === NO_VALUE || v11 === NO_VALUE) return null;
    result[axis] = (v00 * (1 - fx) + v10 * fx) * (1 - fy) + (v01 * (1 - fx) + v11 * fx) * fy;
  }
  return result;
}

/**
 * The largest distance between interpolation and map at points spread over the field: cell
 * centres and edge midpoints of a spread of cells, where a bilinear patch strays most.
 */
function interpolationError(grid, spanX, spanY, exact) {
  const cellsX = grid.nodesX - 1, cellsY = grid.nodesY - 1;
  const stepX = Math.max(1, Math.floor(cellsX / CHECKS)), stepY = Math.max(1, Math.floor(cellsY / CHECKS));
  let worst = 0;
  for (let cy = Math.floor(stepY / 2); cy < cellsY; cy += stepY) {
    for (let cx = Math.floor(stepX / 2); cx < cellsX; cx += stepX) {
      for (const [fx, fy] of [[0.5, 0.5], [0.5, 0], [0, 0.5]]) {
        const column = (cx + fx) * grid.columnsPerCell, row = (cy + fy) * grid.rowsPerCell;
        const want = exact(column, row), got = interpolate(grid, column, row);
        if (!want || !got) continue;
        worst = Math.max(worst, Math.hypot(got[0] - want[0], got[1] - want[1]));
      }
    }
  }
  return worst;
}
