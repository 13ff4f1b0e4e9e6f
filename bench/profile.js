#!/usr/bin/env node
// How long the measuring tools take on the default terrain (the Himalaya, 2048 x 2048 samples
// 806.9 x 926 m apart) through the WASM core in Node, as the page runs them: figures printed,
// never asserted.
//
//   - a 10 km profile from Everest's summit east-south-east, at the field's spacing (the page's
//     default) and every metre (10 001 samples: the cost per sample);
//   - a profile across the whole field, corner to corner, at the field's spacing;
//   - the same profiles over a plain JS array of the same heights (samplerOfArray), the ratio
//     telling what a core call per sample costs;
//   - the surface area of a 100 km star around Everest (a concave polygon).
// Each is the median of N runs after N / 10 unmeasured ones.
//
//   node bench/profile.js [--runs N]   (default 101)
import { cpus, loadavg } from 'node:os';
import { fileURLToPath } from 'node:url';
import { loadForCommand, quantile } from '../lib/cli_common.js';
import { fieldSampler, samplerOfArray } from '../web/measure/field_sampler.js';
import { computeProfile } from '../web/measure/profile.js';
import { measurePolygon } from '../web/measure/polygon_area.js';

const HIMALAYA = fileURLToPath(new URL('../public/terrain/globe_himalaya_2048.png', import.meta.url));
const args = process.argv.slice(2);
const runsAt = args.indexOf('--runs');
const runs = runsAt >= 0 ? Number(args[runsAt + 1]) : 101;
if (!(Number.isInteger(runs) && runs > 0)) throw new Error(`--runs must be a positive integer, got ${args[runsAt + 1]}`);

const { terrain, field, spacingX, spacingY } = await loadForCommand(HIMALAYA, null);
const core = fieldSampler(terrain, field.georef);
// The same heights in metres in a JS array: the core's own bilinear at every sample.
const heights = new Float64Array(terrain.width * terrain.height);
for (let j = 0; j < terrain.height; j++) for (let i = 0; i < terrain.width; i++) heights[j * terrain.width + i] = terrain.heightAt(i * spacingX, j * spacingY);
const array = samplerOfArray(heights, terrain.width, terrain.height, spacingX, spacingY);

// Everest's summit: 86.925 E, 27.988 N, in the field's columns and rows (georef: sample centres).
const { x0, y0, dx, dy } = field.georef;
const everest = [((86.925 - x0) / dx) * spacingX, ((27.988 - y0) / dy) * spacingY];
const tenKm = [everest, [everest[0] + 8000, everest[1] + 6000]];
const across = [[0, 0], [core.extentX, core.extentZ]];
const star = Array.from({ length: 10 }, (_, k) => {
  const r = k % 2 ? 20000 : 50000, a = (Math.PI * k) / 5;
  return [everest[0] + r * Math.cos(a), everest[1] + r * Math.sin(a)];
});

/** Median milliseconds of `runs` calls (after a tenth as many unmeasured), and the last result. */
function time(work) {
  let result;
  for (let k = 0; k < Math.ceil(runs / 10); k++) result = work();
  const ms = [];
  for (let k = 0; k < runs; k++) {
    const start = performance.now();
    result = work();
    ms.push(performance.now() - start);
  }
  return { ms: quantile(ms, 0.5), result };
}

const cases = [
  ['10 km profile, field spacing', (s) => computeProfile(tenKm, s)],
  ['10 km profile, every 1 m', (s) => computeProfile(tenKm, s, { step: 1 })],
  ['corner to corner, field spacing', (s) => computeProfile(across, s)],
];
console.log(`hexlod measuring benchmark: ${field.source} ${terrain.width} x ${terrain.height}, ${spacingX} x ${spacingY} m; ` +
  `median of ${runs} runs; ${cpus()[0]?.model ?? 'unknown CPU'} x ${cpus().length}, load ${loadavg().map((l) => l.toFixed(2)).join(' ')}`);
console.log('case                               samples   length       core ms   JS array ms   core / array');
for (const [name, work] of cases) {
  const viaCore = time(() => work(core)), viaArray = time(() => work(array));
  const p = viaCore.result;
  console.log(`${name.padEnd(34)} ${String(p.samples.distance.length).padStart(7)}   ${(p.summary.length / 1000).toFixed(2).padStart(7)} km ` +
    `${viaCore.ms.toFixed(3).padStart(9)} ${viaArray.ms.toFixed(3).padStart(13)}   ${(viaCore.ms / viaArray.ms).toFixed(2).padStart(8)}`);
}
const area = time(() => measurePolygon(star, core));
console.log(`area of a 100 km star (concave): ${(area.result.planimetric / 1e6).toFixed(1)} km² on the map, ` +
  `${(area.result.surface / 1e6).toFixed(1)} km² on the ground, ${area.ms.toFixed(3)} ms (core)`);
terrain.destroy();
