#!/usr/bin/env node
// Figures of the refinement loop under a moving camera, printed, never asserted:
// for each height field, the flights of `hexlod bench` (seed 1, 300 m above the ground, 300
// frames, 1920x1080, fov 60 deg) at 5, 50 and 500 m a frame (fewer frames when the field is
// too small for 300) and the default length (80 % of the shorter side), replayed natively by build/native/hexlod_bench --flight from the mesh
// converged for the first camera:
//   - without a budget: cells tested per frame and the update time of frames that converge,
//     in ms per million drawn triangles (p95); the update time in ms (p50, p95) and the range
//     of drawn triangles, which say what the figure per million triangles is made of;
//   - the floor of those update times (hexlod_bench --floor, a run of its own so that it does
//     not cool the update's caches): the same mesh operations and the bounds of the new cells,
//     nothing judged, in ms per million drawn triangles (p95), which no update can go below;
//   - with a 4 ms budget: cells tested per frame, the largest screen error of the drawn mesh
//     after each update (p50, p95, max; a bound recomputed from the samples for every live
//     cell) and the share of frames within tau, and the bytes per drawn triangle.
//
// The stream keeps no vertex normals, as in the viewer, which lights the terrain from the
// field's own normals (--normals on: the stream keeps them, as older builds did).
//
//   node bench/refiner.js [FIELD ...] [--frames N] [--steps 5,50,500,0] [--budget-ms MS] [--normals on|off]
// FIELD defaults to public/terrain/globe_himalaya_2048.png and tests/fixtures/grandcanyon_512.png.
import { writeFileSync, existsSync, mkdtempSync, rmSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir, cpus } from 'node:os';
import { basename, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadForCommand, extentOf } from '../lib/cli_common.js';
import { flightPath, heightsInMetres } from '../lib/bench_flight.js';

const root = fileURLToPath(new URL('../', import.meta.url));
// HEXLOD_BENCH: another build of the benchmark (e.g. a copy of the one before a change).
const NATIVE_BENCH = process.env.HEXLOD_BENCH || join(root, 'build/native/hexlod_bench');

const args = process.argv.slice(2);
const fields = [];
let frames = 300, steps = [5, 50, 500, 0], budgetMs = 4, normals = false;
for (let k = 0; k < args.length; k++) {
  if (args[k] === '--frames') frames = Number(args[++k]);
  else if (args[k] === '--steps') steps = args[++k].split(',').map(Number);
  else if (args[k] === '--budget-ms') budgetMs = Number(args[++k]);
  else if (args[k] === '--normals') {
    const value = args[++k];
    if (value !== 'on' && value !== 'off') {
      console.error(`--normals must be on or off, got '${value}'`);
      process.exit(2);
    }
    normals = value === 'on';
  }
  else fields.push(args[k]);
}
if (fields.length === 0) fields.push(join(root, 'public/terrain/globe_himalaya_2048.png'), join(root, 'tests/fixtures/grandcanyon_512.png'));
if (!existsSync(NATIVE_BENCH)) {
  console.error(`${NATIVE_BENCH} is not built (ninja -C build/native)`);
  process.exit(1);
}

// hexlod_bench's "triangles min N p50 N max N; splits ...": digits only, as a ';' follows max.
const trianglesLine = /triangles min (\d+) p50 (\d+) max (\d+)/;
const grab = (text, re) => {
  const m = re.exec(text);
  return m ? m.slice(1).map(Number) : null;
};

function runNative(fieldPath, terrain, camerasPath, extra) {
  const run = spawnSync(NATIVE_BENCH, [fieldPath, String(terrain.width), String(terrain.height), String(terrain.spacingX),
    String(terrain.spacingY), '--flight', camerasPath, '--tau', '1', '--viewport', '1920x1080',
    '--tan-half-fov', String(Math.tan(Math.PI / 6)), '--start-converged', ...(normals ? [] : ['--no-normals']), ...extra], { encoding: 'utf8', maxBuffer: 1 << 26 });
  if (run.status !== 0) throw new Error(`hexlod_bench failed: ${run.stderr}`);
  return run.stdout;
}

// null for an older build (HEXLOD_BENCH) that does not know --floor; any other failure (a copy
// of the mesh that did not end as the mesh) stops the benchmark.
function spawnFloor(fieldPath, terrain, camerasPath) {
  try {
    return runNative(fieldPath, terrain, camerasPath, ['--budget-ms', '0', '--budget-ops', '0', '--floor']);
  } catch (error) {
    if (/(unknown option|missing value after) --floor/.test(error.message)) return null;
    throw error;
  }
}

console.log(`bench_refiner: ${frames} frames a flight, tau 1 px, 1920x1080, fov 60 deg, stream normals ${normals ? 'on' : 'off'}, native build; ${cpus().length} cores (${cpus()[0]?.model ?? '?'})`);
for (const file of fields) {
  const { terrain, field } = await loadForCommand(file, null, {});
  const heights = heightsInMetres(terrain, field);
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-bench-refiner-'));
  try {
    const fieldPath = join(dir, 'field.f32');
    writeFileSync(fieldPath, new Uint8Array(heights.buffer, heights.byteOffset, heights.byteLength));
    console.log(`\n${basename(file)} (${terrain.width} x ${terrain.height})`);
    console.log('| flight | cells tested / frame, no budget p50 / p95 | converged frames, no budget | update ms per M triangles p95, wall / thread CPU (converged, no budget) | ' +
      'update ms p50 / p95 and triangles min – max, no budget | ' +
      'floor ms per M triangles p95, operations and new bounds / operations alone | ' +
      `cells tested / frame, ${budgetMs} ms p50 | frames within tau, ${budgetMs} ms | screen error p50 / p95 / max px, ${budgetMs} ms | ` +
      'triangles p50 | B / triangle live p50 / at capacity p50 / at capacity max |');
    console.log('| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |');
    // Wall-clock figures on a shared machine: see the thread CPU column.
    for (const step of steps) {
      // A flight is at most 80 % of the shorter side long: fewer frames when the step needs it.
      const { xMax, zMax } = extentOf(terrain);
      const count = step > 0 ? Math.max(2, Math.min(frames, Math.floor((0.8 * Math.min(xMax, zMax)) / step) + 1)) : frames;
      const path = flightPath(terrain, { frames: count, seed: 1, altitude: 300, step });
      const camerasPath = join(dir, 'cameras.txt');
      writeFileSync(camerasPath, path.cameras.map(({ eye, target }) => [...eye, ...target].join(' ')).join('\n') + '\n');
      const free = runNative(fieldPath, terrain, camerasPath, ['--budget-ms', '0', '--budget-ops', '0']);
      const floorRun = spawnFloor(fieldPath, terrain, camerasPath);
      const budgeted = runNative(fieldPath, terrain, camerasPath, ['--budget-ms', String(budgetMs), '--measure-error']);
      const testedFree = grab(free, /cells tested per frame p50 (\S+) p95 (\S+) max (\S+)/);
      const conv = grab(free, /converged after the update in (\d+) of (\d+) frames; their update ms per million triangles p50 (\S+) p95 (\S+)/);
      const cpu = grab(free, /the same in thread CPU time: p50 (\S+) p95 (\S+)/);
      const floor = floorRun && grab(floorRun, /floor \(.*\): ms per million triangles p50 (\S+) p95 (\S+); operations alone p50 (\S+) p95 (\S+);/);
      // The update's own time and the mesh's range: a figure per million triangles rises as the
      // mesh shrinks (a camera nearing the edge of a small field) even when the update does not.
      const updateFree = grab(free, /update ms p50 (\S+) p95 (\S+);/);
      const trisFree = grab(free, trianglesLine);
      const testedBudget = grab(budgeted, /cells tested per frame p50 (\S+) p95 (\S+) max (\S+)/);
      const err = grab(budgeted, /screen error of the drawn mesh after the update: p50 (\S+) p95 (\S+) max (\S+) px; within tau in (\S+) %/);
      const tris = grab(budgeted, trianglesLine);
      const bytes = grab(budgeted, /live p50 (\S+) max (\S+); at capacity p50 (\S+) max (\S+)/);
      const name = (step > 0 ? `${Math.round(path.step)} m/frame` : `default (${Math.round(path.step)} m/frame)`) +
        (count < frames ? ` (${count} frames)` : '');
      console.log(`| ${name} | ${testedFree[0]} / ${testedFree[1]} | ${conv[0]} of ${conv[1]} | ${conv[3].toFixed(2)} / ${cpu[1].toFixed(2)} | ` +
        `${updateFree[0].toFixed(3)} / ${updateFree[1].toFixed(3)}; ${trisFree[0]} – ${trisFree[2]} | ${floor ? `${floor[1].toFixed(2)} / ${floor[3].toFixed(2)}` : 'n/a'} | ${testedBudget[0]} | ` +
        `${err[3].toFixed(1)} % | ${err[0].toFixed(2)} / ${err[1].toFixed(2)} / ${err[2].toFixed(2)} | ${tris[1]} | ${bytes[0].toFixed(1)} / ${bytes[2].toFixed(1)} / ${bytes[3].toFixed(1)} |`);
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}
