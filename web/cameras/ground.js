// The ground the cameras stand on, in drawn metres (heights times the exaggeration).
//   ground(x, z): the full-resolution field: the highest sample of the sample squares around
//     the point, which bounds any triangulation of the samples there (bilinear would not).
//   floor(x, z): the walk camera's: also the surface as drawn now, geomorph blends included
//     (Terrain.drawnHeightAt), which may lie above the field where the mesh is coarse.
import { emptyWorld } from './clip_planes.js';

const MAX_SAMPLES_ACROSS = 8; // bounds the work of a wide reach

/**
 * @param {import('../core/core.js').Terrain} terrain
 * @param {{extentX: number, extentZ: number, low: number, high: number}} extent drawn metres
 * @param {() => number} verticalScale the current exaggeration
 * @param {() => number} reach metres around the point that must stay above ground (the near plane)
 */
export function createWorld(terrain, extent, verticalScale, reach) {
  const sx = terrain.spacingX, sz = terrain.spacingY;
  const lastColumn = terrain.width - 1, lastRow = terrain.height - 1;
  const world = Object.assign(emptyWorld(), extent, { spacing: Math.min(sx, sz), version: 0 });
  const memo = { x: NaN, z: NaN, version: -1, value: 0 };

  world.ground = (x, z) => {
    const r = Math.min(reach(), MAX_SAMPLES_ACROSS * Math.min(sx, sz));
    const j0 = clamp(Math.floor((x - r) / sx), 0, lastColumn), j1 = clamp(Math.ceil((x + r) / sx), 0, lastColumn);
    const i0 = clamp(Math.floor((z - r) / sz), 0, lastRow), i1 = clamp(Math.ceil((z + r) / sz), 0, lastRow);
    let high = -Infinity;
    for (let i = i0; i <= i1; ++i) {
      for (let j = j0; j <= j1; ++j) high = Math.max(high, terrain.heightAt(j * sx, i * sz));
    }
    return high * verticalScale();
  };

  // A scan of the mesh: asked once per frame and point (world.version moves every frame).
  world.floor = (x, z) => {
    if (memo.x === x && memo.z === z && memo.version === world.version) return memo.value;
    const drawn = terrain.drawnHeightAt(x, z) * verticalScale();
    const field = world.ground(x, z);
    memo.x = x; // field by field: no object per frame
    memo.z = z;
    memo.version = world.version;
    memo.value = Number.isNaN(drawn) ? field : Math.max(drawn, field);
    return memo.value;
  };
  return world;
}

function clamp(v, lo, hi) {
  return Math.min(Math.max(v, lo), hi);
}
