// The opening view of a terrain: the region of greatest local relief (on the default terrain,
// the Himalaya's front range rising from the Ganges plain), seen from the south, its lit side
// (the renderer's sun stands in the south-west), low enough that the peaks stand up.
const GRID = 96;   // coarse samples per side of the search
const WINDOW = 4;  // half-width, in coarse samples, of the neighbourhood whose relief counts

/**
 * @param {import('./core.js').Terrain} terrain
 * @param {number} extentX @param {number} extentZ metres
 * @returns {{x: number, z: number, height: number, extent: number}} the point to look at
 *   (height unscaled) and the size of the region around it worth seeing, metres
 */
export function reliefFocus(terrain, extentX, extentZ) {
  const heights = new Float64Array(GRID * GRID);
  for (let i = 0; i < GRID; ++i) {
    for (let j = 0; j < GRID; ++j) heights[i * GRID + j] = terrain.heightAt((j / (GRID - 1)) * extentX, (i / (GRID - 1)) * extentZ);
  }
  // The highest point whose neighbourhood spans the most height: a peak above a deep valley.
  let best = { score: -Infinity, i: 0, j: 0 };
  for (let i = 0; i < GRID; ++i) {
    for (let j = 0; j < GRID; ++j) {
      let low = Infinity, high = -Infinity;
      for (let a = Math.max(0, i - WINDOW); a <= Math.min(GRID - 1, i + WINDOW); ++a) {
        for (let b = Math.max(0, j - WINDOW); b <= Math.min(GRID - 1, j + WINDOW); ++b) {
          low = Math.min(low, heights[a * GRID + b]);
          high = Math.max(high, heights[a * GRID + b]);
        }
      }
      const h = heights[i * GRID + j];
      const score = (high - low) + (h - low); // relief around it, and standing high in it
      if (score > best.score) best = { score, i, j };
    }
  }
  const x = (best.j / (GRID - 1)) * extentX, z = (best.i / (GRID - 1)) * extentZ;
  const extent = (2 * WINDOW + 1) * Math.hypot(extentX, extentZ) / GRID;
  return { x, z, height: heights[best.i * GRID + best.j], extent };
}
