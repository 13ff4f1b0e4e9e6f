// What the terrain's shading needs from the full-resolution height field, computed once per
// field (or per sun and exaggeration), independent of the mesh's level of detail:
//   - height gradients for per-pixel normals (paper §7 averages the mesh's triangle normals,
//     which change with every split and merge; the field's own normals do not);
//   - the sun's shadow, by one sweep over the field towards the sun (a horizon test);
//   - the 8-bit ambient-occlusion term of paper §7 ("a low-resolution texture storing the
//     ambient occlusion term as 8-bit luminance"), from horizon angles in eight directions.
// Pure functions over typed arrays: they run in the page and in Node (tests, benchmarks).
//
// A field is { width, height, spacingX, spacingZ, heightAt(k) } where heightAt(k) gives the
// height in metres of sample k = row * width + column (row 0 north, z grows south).

/**
 * A field view over raw samples at their native depth: metres = raw * scale + offset.
 * @param {ArrayLike<number>} raw samples, row-major
 * @param {Uint8Array|null} [missing] the no-data samples the loader filled, a bit each
 *   (web/loaders/nodata.js), or null
 */
export function fieldOf(raw, width, height, spacingX, spacingZ, scale = 1, offset = 0, missing = null) {
  return { width, height, spacingX, spacingZ, raw, scale, offset, missing };
}

/**
 * A coarser field of at most `maxSide` samples per side: each sample is the mean of the block
 * of samples it stands for (a box filter keeps the mean height of the area). Returns the
 * field itself (as Float32 metres) when it is small enough; `stride` is the block size.
 * @returns {{width: number, height: number, spacingX: number, spacingZ: number, heights: Float32Array, stride: number}}
 */
export function downsampleField(field, maxSide) {
  const { width, height, raw, scale, offset } = field;
  const stride = Math.max(1, Math.ceil(Math.max(width, height) / maxSide));
  const w = Math.ceil(width / stride), h = Math.ceil(height / stride);
  const heights = new Float32Array(w * h);
  if (stride === 1) {
    for (let k = 0; k < heights.length; ++k) heights[k] = raw[k] * scale + offset;
  } else {
    for (let i = 0; i < h; ++i) {
      const r0 = i * stride, r1 = Math.min(height, r0 + stride);
      for (let j = 0; j < w; ++j) {
        const c0 = j * stride, c1 = Math.min(width, c0 + stride);
        let sum = 0;
        for (let r = r0; r < r1; ++r) {
          const row = r * width;
          for (let c = c0; c < c1; ++c) sum += raw[row + c];
        }
        heights[i * w + j] = (sum / ((r1 - r0) * (c1 - c0))) * scale + offset;
      }
    }
  }
  return { width: w, height: h, spacingX: field.spacingX * stride, spacingZ: field.spacingZ * stride, heights, stride };
}

/**
 * Tiles of the field's height gradient (dh/dx, dh/dz, metres per metre, central differences
 * of the full-resolution samples), height (metres) and presence (0 where the sample was no-data,
else 1: the page's holes), for a texture array (RGBA: gx, gz, h, presence) of at most maxTile texels a side:
 * tile (tx, tz) holds columns [tx*(tileX-1), tx*(tileX-1)+tileX-1] and likewise rows, so
 * neighbouring tiles share their
 * edge texels and bilinear filtering never needs the next tile. Samples past the field repeat
 * its edge. `stride` > 1 keeps every stride-th sample (for fields larger than the texture
 * budget); the gradient is still taken over the neighbouring full-resolution samples.
 * @returns {{tileX: number, tileZ: number, tilesX: number, tilesZ: number, stride: number, texelX: number, texelZ: number,
 *   fill(tx: number, tz: number, out: Float32Array): Float32Array}} fill writes one tile, 4 floats a texel
 */
export function gradientTiles(field, maxTile, stride = 1) {
  const { width, height, raw, scale, offset, spacingX, spacingZ, missing } = field;
  const columns = Math.floor((width - 1) / stride) + 1, rows = Math.floor((height - 1) / stride) + 1;
  const tileX = Math.min(maxTile, columns), tileZ = Math.min(maxTile, rows);
  const tilesX = Math.max(1, Math.ceil((columns - 1) / (tileX - 1))), tilesZ = Math.max(1, Math.ceil((rows - 1) / (tileZ - 1)));
  return {
    tileX, tileZ, tilesX, tilesZ, stride, columns, rows,
    texelX: spacingX * stride, texelZ: spacingZ * stride,
    fill(tx, tz, out = new Float32Array(4 * tileX * tileZ)) {
      for (let a = 0; a < tileZ; ++a) {
        const i = Math.min(rows - 1, tz * (tileZ - 1) + a) * stride;
        const north = Math.max(0, i - 1) * width, south = Math.min(height - 1, i + 1) * width, row = i * width;
        const dz = (Math.min(height - 1, i + 1) - Math.max(0, i - 1)) * spacingZ;
        for (let b = 0; b < tileX; ++b) {
          const j = Math.min(columns - 1, tx * (tileX - 1) + b) * stride;
          const west = Math.max(0, j - 1), east = Math.min(width - 1, j + 1);
          const o = 4 * (a * tileX + b);
          out[o] = ((raw[row + east] - raw[row + west]) * scale) / ((east - west) * spacingX);
          out[o + 1] = ((raw[south + j] - raw[north + j]) * scale) / dz;
          out[o + 2] = raw[row + j] * scale + offset;
          out[o + 3] = missing && (missing[(row + j) >> 3] >> ((row + j) & 7)) & 1 ? 0 : 1;
        }
      }
      return out;
    },
  };
}

/**
 * The next mip level of an image of `channels` floats a texel: each texel the mean of the 2 x 2
 * it covers (the last row or column of an odd size repeats). Float textures cannot
 * generateMipmap in WebGL2.
 * @returns {Float32Array} of max(1, w >> 1) x max(1, h >> 1) texels, written into `out` when given
 */
export function halveImage(src, w, h, channels, out) {
  const w2 = Math.max(1, w >> 1), h2 = Math.max(1, h >> 1);
  const dst = out ?? new Float32Array(channels * w2 * h2);
  for (let i = 0; i < h2; ++i) {
    const r0 = Math.min(h - 1, 2 * i) * w, r1 = Math.min(h - 1, 2 * i + 1) * w;
    for (let j = 0; j < w2; ++j) {
      const c0 = Math.min(w - 1, 2 * j), c1 = Math.min(w - 1, 2 * j + 1);
      for (let ch = 0; ch < channels; ++ch) {
        const n = channels;
        dst[n * (i * w2 + j) + ch] = 0.25 * (src[n * (r0 + c0) + ch] + src[n * (r0 + c1) + ch] + src[n * (r1 + c0) + ch] + src[n * (r1 + c1) + ch]);
      }
    }
  }
  return dst;
}

/**
 * The sun's visibility (0..255) at every sample of a (downsampled) field: a sample is in
 * shadow when terrain between it and the sun rises above the sun's ray. One sweep from the
 * sun's side: S, the top of the shadow volume, obeys S(p) = max(h(p), S(p + d) - |d| tan e),
 * where p + d is the neighbour one column (or row) towards the sun, interpolated between two
 * rows (or columns). Cost: a few operations per sample, whatever the sun's direction.
 * @param {{width: number, height: number, spacingX: number, spacingZ: number, heights: Float32Array}} grid
 *
 * On the curved Earth (`earth`: its radius and the flat point under the sun's frame, the field's
 * origin) the sun stands higher towards it and lower away from it: at a sample δ metres from the
 * origin along the sun's compass direction its elevation is e0 + δ / R, and a sample where it is
 * below the horizon is in the night. A ray leaving p at elevation e climbs step tan e plus the
 * Earth's fall step² / 2R over one step: S(p) = max(h(p), S(p + d) - step tan e(p) - step² / 2R)
 * (heights above the curved surface, small angles per step).
 * @param {number[]} sun unit vector towards the sun (x east, y up, z south) in the frame at the origin
 * @param {number} verticalScale the drawn exaggeration of heights
 * @param {Uint8Array} [out]
 * @param {{radius: number, originX: number, originZ: number}|null} [earth] the curved Earth, or the plane
 */
export function sunVisibility(grid, sun, verticalScale, out = new Uint8Array(grid.width * grid.height), earth = null) {
  const { width, height, spacingX, spacingZ, heights } = grid;
  const horizontal = Math.hypot(sun[0], sun[2]);
  if (!earth && sun[1] <= 0) return out.fill(0);
  if (horizontal < 1e-6) return out.fill(sun[1] > 0 ? 255 : 0);
  const tanE = sun[1] / horizontal;
  const ux = sun[0] / horizontal, uz = sun[2] / horizontal;
  // March along columns when the sun's direction is mostly east-west (in samples), else rows.
  const alongX = Math.abs(ux) / spacingX >= Math.abs(uz) / spacingZ;
  const lines = alongX ? width : height;     // sweep steps
  const across = alongX ? height : width;    // samples per line
  const sign = alongX ? Math.sign(ux) : Math.sign(uz);
  // One step towards the sun: `stepLength` metres along the ground, `shift` samples across.
  const stepLength = alongX ? spacingX / Math.abs(ux) : spacingZ / Math.abs(uz);
  const shift = alongX ? (uz * stepLength) / spacingZ : (ux * stepLength) / spacingX;
  const drop = stepLength * tanE;
  // Penumbra: the sun's disc is about half a degree wide; a shadow edge a step away blurs over
  // about a step's worth of drop. Depths below `soft` metres are partly lit.
  const soft = Math.max(drop * 0.5, 1e-3);
  // The curved Earth: the sun's elevation at the origin, and its rise per metre towards the sun.
  const e0 = Math.atan2(sun[1], horizontal), perMetre = earth ? 1 / earth.radius : 0;
  const fall = earth ? (stepLength * stepLength) / (2 * earth.radius) : 0;
  const spacingLine = alongX ? spacingX : spacingZ, spacingAcross = alongX ? spacingZ : spacingX;
  const uLine = alongX ? ux : uz, uAcross = alongX ? uz : ux;
  const originLine = earth ? (alongX ? earth.originX : earth.originZ) : 0, originAcross = earth ? (alongX ? earth.originZ : earth.originX) : 0;
  let previous = new Float64Array(across), current = new Float64Array(across);
  const index = alongX ? (line, k) => k * width + line : (line, k) => line * width + k;
  const start = sign > 0 ? lines - 1 : 0;
  for (let n = 0; n < lines; ++n) {
    const line = start - sign * n;
    const lineAlong = (line * spacingLine - originLine) * uLine;
    for (let k = 0; k < across; ++k) {
      const idx = index(line, k);
      const h = heights[idx] * verticalScale;
      let climb = drop, night = false;
      if (earth) {
        const e = e0 + (lineAlong + (k * spacingAcross - originAcross) * uAcross) * perMetre;
        night = e <= 0;
        climb = stepLength * Math.tan(e) + fall;
      }
      let top = -Infinity;
      if (n > 0) {
        const at = k + shift;
        const k0 = Math.floor(at), f = at - k0;
        if (k0 >= 0 && k0 + 1 < across) top = previous[k0] * (1 - f) + previous[k0 + 1] * f;
        else if (k0 === across - 1 && f < 1e-9) top = previous[k0];
        top -= climb;
      }
      const depth = top - h;
      out[idx] = night ? 0 : depth <= 0 ? 255 : depth >= soft ? 0 : Math.round(255 * (1 - depth / soft));
      current[k] = Math.max(h, top);
    }
    const swap = previous; previous = current; current = swap;
  }
  return out;
}

// The eight directions of the ambient-occlusion horizons: rows, columns and both diagonals,
// each walked both ways.
const AO_DIRECTIONS = [[1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [-1, -1], [1, -1], [-1, 1]];

/**
 * Ambient occlusion (0..255) at every sample of a (downsampled) field: the fraction of the
 * cosine-weighted sky above the horizon, averaged over eight directions (horizon elevation θ
 * hides sin²θ of a horizontal surface's sky). Each horizon is exact over the whole line: the
 * upper convex hull of the heights behind a sample, kept on a stack, gives the highest
 * elevation angle in O(1) amortised per sample (cf. Stewart 1998, "Fast horizon computation
 * at all points of a terrain with visibility and shading applications").
 * @param {number} verticalScale the drawn exaggeration of heights
 */
export function ambientOcclusion(grid, verticalScale, out = new Uint8Array(grid.width * grid.height)) {
  const { width, height, spacingX, spacingZ, heights } = grid;
  const sum = new Float32Array(width * height);
  const longest = width + height;
  const stackD = new Float64Array(longest), stackH = new Float64Array(longest);
  const lineIdx = new Int32Array(longest);
  for (const [dj, di] of AO_DIRECTIONS) {
    const stepLength = Math.hypot(dj * spacingX, di * spacingZ);
    // Every line of this direction starts at a sample whose predecessor lies outside.
    for (let i0 = 0; i0 < height; ++i0) {
      for (let j0 = 0; j0 < width; ++j0) {
        const pi = i0 - di, pj = j0 - dj;
        if (pi >= 0 && pi < height && pj >= 0 && pj < width) continue; // not a line start
        let n = 0;
        for (let i = i0, j = j0; i >= 0 && i < height && j >= 0 && j < width; i += di, j += dj) lineIdx[n++] = i * width + j;
        let top = -1;
        for (let k = 0; k < n; ++k) {
          const h = heights[lineIdx[k]] * verticalScale, d = k * stepLength;
          // Pop hull points that the previous hull point hides, as seen from this sample.
          while (top >= 1 && (stackH[top - 1] - h) * (d - stackD[top]) >= (stackH[top] - h) * (d - stackD[top - 1])) --top;
          let visible = 1;
          if (top >= 0) {
            const rise = stackH[top] - h;
            if (rise > 0) {
              const run = d - stackD[top];
              visible = (run * run) / (run * run + rise * rise); // cos² of the horizon's elevation
            }
          }
          sum[lineIdx[k]] += visible;
          ++top;
          stackD[top] = d;
          stackH[top] = h;
        }
      }
    }
  }
  for (let k = 0; k < sum.length; ++k) out[k] = Math.round((255 * sum[k]) / AO_DIRECTIONS.length);
  return out;
}
