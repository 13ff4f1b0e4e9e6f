// Makes tests/fixtures/shading/etopo5_global_540x270.{png,json}, the small Earth of the shading
// tests, from the shared ETOPO5 field: 4 x 4 block means, 16-bit PNG + sidecar.
// Usage: node scripts/make_shading_fixtures.js path/to/etopo5_global_2160x1080.f32
import { readFileSync, writeFileSync } from 'node:fs';
import { encode } from 'fast-png';
const W = 2160, H = 1080, K = 4, w = W / K, h = H / K;
if (!process.argv[2]) {
  console.error('usage: node scripts/make_shading_fixtures.js path/to/etopo5_global_2160x1080.f32 (the source is not in the project)');
  process.exit(2);
}
const buf = readFileSync(process.argv[2]);
const src = new Float32Array(buf.buffer.slice(buf.byteOffset, buf.byteOffset + W * H * 4));
const out = new Float64Array(w * h);
for (let i = 0; i < h; ++i) for (let j = 0; j < w; ++j) {
  let s = 0; for (let a = 0; a < K; ++a) for (let b = 0; b < K; ++b) s += src[(i * K + a) * W + j * K + b];
  out[i * w + j] = s / (K * K);
}
let min = Infinity, max = -Infinity; for (const v of out) { min = Math.min(min, v); max = Math.max(max, v); }
min = Math.floor(min); max = Math.ceil(max);
const data = new Uint16Array(w * h);
for (let k = 0; k < out.length; ++k) data[k] = Math.round(((out[k] - min) / (max - min)) * 65535);
writeFileSync('tests/fixtures/shading/etopo5_global_540x270.png', encode({ width: w, height: h, data, depth: 16, channels: 1 }));
const meta = JSON.parse(readFileSync(process.argv[2].replace(/\.f32$/, '.json'), 'utf8'));
writeFileSync('tests/fixtures/shading/etopo5_global_540x270.json', JSON.stringify({
  width: w, height: h, min, max, units: 'm', cell_size_m: 18520 * K, cell_size_deg: 40 / 60,
  crs: meta.crs, license: meta.license, real_measured: true,
  origin: `etopo5_global_2160x1080 of the shared data set (${meta.origin}), 4 x 4 block means: 540 x 270 samples of 40 arc-minutes, for the shading tests`,
  row_order: meta.row_order,
  png: { file: 'etopo5_global_540x270.png', bit_depth: 16, color: 'grayscale', decode: 'h = min + v / 65535 * (max - min)', quantum_m: (max - min) / 65535 },
}, null, 1) + '\n');
console.log(min, max);
