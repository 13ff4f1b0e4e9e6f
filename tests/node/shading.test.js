// The field shading (web/render/shading/field_shading.js) against brute force: the sun's
// shadow sweep and the ambient-occlusion horizons on random fields, the gradient tiles
// against one big tile, the mip reduction, and the obvious cases (flat ground).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fieldOf, downsampleField, gradientTiles, halveImage, sunVisibility, ambientOcclusion } from '../../web/render/shading/field_shading.js';

/** A rough random field (seeded), heights in metres. */
function randomField(width, height, seed = 7, relief = 200) {
  let s = seed;
  const next = () => ((s = (s * 1103515245 + 12345) >>> 0) / 2 ** 32);
  const heights = new Float32Array(width * height);
  for (let k = 0; k < heights.length; ++k) heights[k] = relief * next();
  return heights;
}

test('flat ground is fully lit and sees the whole sky', () => {
  const grid = downsampleField(fieldOf(new Float32Array(40 * 30).fill(123), 40, 30, 10, 10), 1024);
  assert.ok(sunVisibility(grid, [0.6, 0.3, -0.74], 2).every((v) => v === 255));
  assert.ok(ambientOcclusion(grid, 2).every((v) => v === 255));
});

test('the shadow sweep equals a brute-force march towards a sun on an axis', () => {
  const width = 37, height = 23, spacing = 30, scale = 1.5;
  const heights = randomField(width, height);
  const grid = downsampleField(fieldOf(heights, width, height, spacing, spacing), 1024);
  const e = (12 * Math.PI) / 180;
  const tanE = Math.tan(e);
  const soft = (spacing * tanE) / 2;
  for (const [sx, sz] of [[1, 0], [-1, 0], [0, 1], [0, -1]]) {
    const sun = [Math.cos(e) * sx, Math.sin(e), Math.cos(e) * sz];
    const out = sunVisibility(grid, sun, scale);
    for (let i = 0; i < height; ++i) {
      for (let j = 0; j < width; ++j) {
        let top = -Infinity;
        for (let n = 1; ; ++n) {
          const qi = i + sz * n, qj = j + sx * n;
          if (qi < 0 || qi >= height || qj < 0 || qj >= width) break;
          top = Math.max(top, heights[qi * width + qj] * scale - n * spacing * tanE);
        }
        const depth = top - heights[i * width + j] * scale;
        const expected = depth <= 0 ? 255 : depth >= soft ? 0 : Math.round(255 * (1 - depth / soft));
        assert.ok(Math.abs(out[i * width + j] - expected) <= 1, `sun (${sx}, ${sz}) sample ${i},${j}: ${out[i * width + j]} vs ${expected}`);
      }
    }
  }
});

test('a wall casts a shadow as long as its height over the tangent of the sun elevation', () => {
  const width = 200, height = 3, spacing = 10;
  const heights = new Float32Array(width * height);
  for (let i = 0; i < height; ++i) heights[i * width + 20] = 100; // a wall at x = 200 m
  const e = (30 * Math.PI) / 180;
  const out = sunVisibility(downsampleField(fieldOf(heights, width, height, spacing, spacing), 1024), [-Math.cos(e), Math.sin(e), 0], 1);
  const length = 100 / Math.tan(e); // 173 m east of the wall
  for (let j = 21; j < width; ++j) {
    const x = (j - 20) * spacing;
    if (x < length - spacing) assert.equal(out[width + j], 0, `${x} m behind the wall is in shadow`);
    if (x > length + spacing) assert.equal(out[width + j], 255, `${x} m behind the wall is lit`);
  }
});

// On the curved Earth the sun's elevation changes across a wide field: the sun 4° up from the
// east at the centre of a 2,000 km sea-level plain has set 445 km west of it (4° of arc), and a
// 2 km wall 200 km west of the centre, where the sun stands 2.2° up, casts a shadow as long as
// the ray over the sphere says: until the ray's height above the curved surface,
// s tan e + s² / 2R, reaches the wall's top. On the plane the whole plain is lit, the shadow
// 28.6 km long.
test('on the curved Earth the sun sets across a wide field, and a shadow ends where the ray over the sphere meets the ground', () => {
  const width = 2001, height = 3, spacing = 1000, R = 6371000;
  const heights = new Float32Array(width * height);
  const peak = 800; // column of a 2 km wall, 200 km west of the centre
  for (let i = 0; i < height; ++i) heights[i * width + peak] = 2000;
  const e = (4 * Math.PI) / 180, sun = [Math.cos(e), Math.sin(e), 0];
  const grid = downsampleField(fieldOf(heights, width, height, spacing, spacing), 4096);
  const earth = { radius: R, originX: 1000 * spacing, originZ: spacing };
  const curved = sunVisibility(grid, sun, 1, undefined, earth), flat = sunVisibility(grid, sun, 1);
  const sunset = 1000 - Math.round((e * R) / spacing); // 445 km west of the centre
  for (let j = 0; j < peak - 29; ++j) assert.equal(flat[width + j], 255, `flat: column ${j} lit`);
  for (let j = 0; j < sunset - 1; ++j) assert.equal(curved[width + j], 0, `column ${j}: the sun has set`);
  // West of the wall: in its shadow while the ray from the ground still passes under its top.
  // The ray's height above the sphere s metres out: s tan(e(p)) + s² / 2R, e(p) the sun's
  // elevation at the sample.
  const rayAt = (j) => {
    const s = (peak - j) * spacing, local = e + ((j - 1000) * spacing) / R;
    return s * Math.tan(local) + (s * s) / (2 * R);
  };
  let shadowEnd = peak;
  while (shadowEnd > sunset && rayAt(shadowEnd - 1) < 2000) shadowEnd--;
  assert.ok(peak - shadowEnd > 29, `the curved shadow is longer than the flat one (${peak - shadowEnd} km)`);
  for (let j = sunset + 2; j < peak; ++j) {
    if (j < shadowEnd - 2) assert.equal(curved[width + j], 255, `column ${j}: lit, beyond the wall's shadow`);
    if (j > shadowEnd + 2) assert.equal(curved[width + j], 0, `column ${j}: in the wall's shadow`);
  }
  for (let j = peak + 1; j < width; ++j) assert.equal(curved[width + j], 255, `column ${j}: lit, the sun higher there`);
});

test('ambient occlusion equals brute-force horizons in eight directions', () => {
  const width = 29, height = 19, sx = 25, sz = 35, scale = 2;
  const heights = randomField(width, height, 3, 300);
  const out = ambientOcclusion(downsampleField(fieldOf(heights, width, height, sx, sz), 1024), scale);
  const directions = [[1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [-1, -1], [1, -1], [-1, 1]];
  for (let i = 0; i < height; ++i) {
    for (let j = 0; j < width; ++j) {
      let sum = 0;
      for (const [dj, di] of directions) {
        let best = 0; // tan of the horizon's elevation, at least level
        for (let n = 1; ; ++n) {
          const qi = i - di * n, qj = j - dj * n; // looking back along the direction of travel
          if (qi < 0 || qi >= height || qj < 0 || qj >= width) break;
          const run = n * Math.hypot(dj * sx, di * sz);
          best = Math.max(best, ((heights[qi * width + qj] - heights[i * width + j]) * scale) / run);
        }
        sum += 1 / (1 + best * best);
      }
      const expected = Math.round((255 * sum) / 8);
      assert.ok(Math.abs(out[i * width + j] - expected) <= 1, `sample ${i},${j}: ${out[i * width + j]} vs ${expected}`);
    }
  }
});

test('gradient tiles share their edges and agree with one big tile', () => {
  const width = 70, height = 45;
  const field = fieldOf(randomField(width, height), width, height, 20, 30);
  const whole = gradientTiles(field, 4096);
  assert.deepEqual([whole.tilesX, whole.tilesZ, whole.tileX, whole.tileZ], [1, 1, 70, 45]);
  const big = whole.fill(0, 0);
  const tiled = gradientTiles(field, 16);
  assert.deepEqual([tiled.tilesX, tiled.tilesZ], [Math.ceil(69 / 15), Math.ceil(44 / 15)]);
  for (let tz = 0; tz < tiled.tilesZ; ++tz) {
    for (let tx = 0; tx < tiled.tilesX; ++tx) {
      const tile = tiled.fill(tx, tz);
      for (let a = 0; a < 16; ++a) {
        for (let b = 0; b < 16; ++b) {
          const i = tz * 15 + a, j = tx * 15 + b;
          if (i >= height || j >= width) continue;
          for (let c = 0; c < 4; ++c) assert.equal(tile[4 * (a * 16 + b) + c], big[4 * (i * width + j) + c]);
        }
      }
    }
  }
  // A plane rising 0.5 m per metre east and 0.25 m per metre south has that gradient everywhere.
  const plane = new Float32Array(width * height);
  for (let i = 0; i < height; ++i) for (let j = 0; j < width; ++j) plane[i * width + j] = 0.5 * 20 * j + 0.25 * 30 * i;
  const g = gradientTiles(fieldOf(plane, width, height, 20, 30), 4096).fill(0, 0);
  for (let k = 0; k < g.length; k += 4) assert.ok(Math.abs(g[k] - 0.5) < 1e-4 && Math.abs(g[k + 1] - 0.25) < 1e-4);
  assert.equal(g[4 * (3 * width + 5) + 2], plane[3 * width + 5], 'the height of sample (3, 5)');
});

test('the gradient texels carry each sample\'s presence: 0 where the loader filled no-data', () => {
  const width = 40, height = 30, stride = 2;
  const missing = new Uint8Array(Math.ceil((width * height) / 8));
  const isMissing = (i, j) => (i >= 10 && i < 16 && j >= 4 && j < 20) || (i === 0 && j === 0);
  for (let i = 0; i < height; ++i) for (let j = 0; j < width; ++j) if (isMissing(i, j)) missing[(i * width + j) >> 3] |= 1 << ((i * width + j) & 7);
  const raw = randomField(width, height);
  for (const step of [1, stride]) {
    const tiles = gradientTiles(fieldOf(raw, width, height, 20, 30, 1, 0, missing), 4096, step);
    const texels = tiles.fill(0, 0);
    for (let a = 0; a < tiles.tileZ; ++a) {
      for (let b = 0; b < tiles.tileX; ++b) {
        assert.equal(texels[4 * (a * tiles.tileX + b) + 3], isMissing(a * step, b * step) ? 0 : 1, `sample ${a * step}, ${b * step}, stride ${step}`);
      }
    }
  }
  // Without a mask every sample is present.
  const plain = gradientTiles(fieldOf(raw, width, height, 20, 30), 4096).fill(0, 0);
  for (let k = 3; k < plain.length; k += 4) assert.equal(plain[k], 1);
});

test('a mip level is the mean of the texels it covers', () => {
  const src = Float32Array.from({ length: 2 * 5 * 3 }, (_, k) => k);
  const half = halveImage(src, 5, 3, 2);
  assert.equal(half.length, 2 * 2 * 1);
  assert.equal(half[0], (0 + 2 + 10 + 12) / 4);
  assert.equal(half[3], (5 + 7 + 15 + 17) / 4); // texel (0, 1), channel 1
});
