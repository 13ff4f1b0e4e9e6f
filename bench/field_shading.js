#!/usr/bin/env node
// Time of the field shading (web/render/shading/field_shading.js) on a 4096² field: the
// normal texture's gradients, the sun's shadow sweep (on the field downsampled to 2048²) and the
// 8-bit ambient occlusion (downsampled to 512², paper §7's low-resolution texture), as the page
// computes them (same code, Node's V8 instead of the browser's). The 4096² field is the
// Himalaya 2048² field upsampled bilinearly (no 4k² DEM in the shared data set).
//   node bench/field_shading.js [--repeat 3]
import { readFileSync } from 'node:fs';
import { loadHeightfield } from '../web/loaders/index.js';
import { fieldOf, downsampleField, gradientTiles, sunVisibility, ambientOcclusion } from '../web/render/shading/field_shading.js';
import { OCCLUSION_MAX_SIDE, SUN_MAX_SIDE } from '../web/render/shading/field_textures.js';

const args = process.argv.slice(2);
const repeat = Number(args[args.indexOf('--repeat') + 1] || 3);
const N = 2048, M = 4096;
// The project's own default terrain (16-bit PNG and its sidecar), in metres.
const terrainDir = new URL('../public/terrain/', import.meta.url);
const read = (name) => ({ name, bytes: new Uint8Array(readFileSync(new URL(name, terrainDir))) });
const himalaya = await loadHeightfield([read('globe_himalaya_2048.png'), read('globe_himalaya_2048.json')]);
const small = Float32Array.from(himalaya.samples, (raw) => raw * himalaya.heightScale + himalaya.heightOffset);
const big = new Float32Array(M * M);
for (let i = 0; i < M; ++i) {
  const y = (i * (N - 1)) / (M - 1), i0 = Math.min(N - 2, Math.floor(y)), fy = y - i0;
  for (let j = 0; j < M; ++j) {
    const x = (j * (N - 1)) / (M - 1), j0 = Math.min(N - 2, Math.floor(x)), fx = x - j0;
    const a = small[i0 * N + j0], b = small[i0 * N + j0 + 1], c = small[(i0 + 1) * N + j0], d = small[(i0 + 1) * N + j0 + 1];
    big[i * M + j] = (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
  }
}
const field = fieldOf(big, M, M, 403, 463, 1, 0);
const sun = [Math.cos(0.4) * Math.sin(4.36), Math.sin(0.4), -Math.cos(0.4) * Math.cos(4.36)];
const time = (fn) => { const t = performance.now(); const r = fn(); return [performance.now() - t, r]; };
const best = {};
const keep = (name, ms) => { best[name] = Math.min(best[name] ?? Infinity, ms); };
for (let r = 0; r < repeat; ++r) {
  const tiles = gradientTiles(field, 16384);
  const out = new Float32Array(2 * tiles.tileX * tiles.tileZ);
  keep('gradients and heights (4096² RGBA, one tile)', time(() => tiles.fill(0, 0, out))[0]);
  const [dsSun, sunGrid] = time(() => downsampleField(field, SUN_MAX_SIDE));
  keep(`downsample to ${sunGrid.width}² (sun)`, dsSun);
  keep(`sun shadow sweep on ${sunGrid.width}²`, time(() => sunVisibility(sunGrid, sun, 2))[0]);
  const [dsAo, aoGrid] = time(() => downsampleField(field, OCCLUSION_MAX_SIDE));
  keep(`downsample to ${aoGrid.width}² (AO)`, dsAo);
  keep(`ambient occlusion on ${aoGrid.width}², 8 directions`, time(() => ambientOcclusion(aoGrid, 2))[0]);
  const [dsAo1k, ao1k] = time(() => downsampleField(field, 1024));
  keep('downsample to 1024² (AO at 1024²)', dsAo1k);
  keep('ambient occlusion on 1024², 8 directions', time(() => ambientOcclusion(ao1k, 2))[0]);
}
console.log(`field shading of a ${M}² field, best of ${repeat} (Node ${process.version})`);
for (const [name, ms] of Object.entries(best)) console.log(`  ${name.padEnd(44)} ${ms.toFixed(0)} ms`);
