#!/usr/bin/env node
// The refinement loop under a moving camera: figures printed, never asserted.
//
// For each height field, the flight of `hexlod bench` (seed 1, 300 m above the ground, looking
// 10 deg down, 1920x1080, fov 60 deg, tau 1 px, exact embedding) at 5, 50 and 500 m a frame:
// 300 frames, or fewer when 80 % of the field's shorter side is shorter than that. Each flight
// starts from the mesh converged for its first camera and is replayed
//   - natively (build/native/hexlod_bench --flight) and in WebAssembly (build/wasm-diag in this
//     Node process, the same cameras and planes), without a budget: the LOD update's CPU time
//     per frame (p50, p95; native the thread's, WASM the process's) and the range of drawn
//     triangles, against the goal of an update of at most 1 ms at p95, and beside it the wall
//     clock (on a loaded machine a wall-clock p95 is mostly time slices given to others);
//   - natively with a 4 ms budget: the share of frames whose drawn mesh is within tau after the
//     update (the screen error is the paper's §5 bound of every live cell recomputed from the
//     samples), the largest screen error, and the bytes per drawn triangle of the mesh, the
//     refiner and the fan stream, live and at capacity, and at the last frame by owner.
//
// The fields: the Himalaya (the default terrain, 2048^2), the Grand Canyon (512^2) and, unless
// --large 0, a larger field made here deterministically: the Himalaya tiled and mirrored at
// every seam to SIZE x SIZE samples (default 8193), so it stays continuous real terrain.
// The stream keeps no vertex normals, as in the viewer, which lights from the field's normals.
//
//   node bench/refiner.js [FIELD ...] [--large SIZE] [--frames N] [--steps 5,50,500]
//                         [--budget-ms MS] [--normals on|off] [--no-wasm]
// FIELD defaults to public/terrain/globe_himalaya_2048.png and tests/fixtures/grandcanyon_512.png.
// HEXLOD_BENCH=/path/to/hexlod_bench replays the native flights with another build.
import { writeFileSync, existsSync, mkdtempSync, rmSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir, cpus, totalmem, loadavg } from 'node:os';
import { basename, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadForCommand, extentOf, cameraFor, quantile } from '../lib/cli_common.js';
import { flightPath, heightsInMetres } from '../lib/bench_flight.js';

const root = fileURLToPath(new URL('../', import.meta.url));
const NATIVE_BENCH = process.env.HEXLOD_BENCH || join(root, 'build/native/hexlod_bench');
const HIMALAYA = join(root, 'public/terrain/globe_himalaya_2048.png');
const GOAL_MS = 1; // the LOD update's goal per frame at p95, milliseconds
const VIEWPORT = [1920, 1080], FOV_DEG = 60, TAU = 1;

const args = process.argv.slice(2);
const fields = [];
let frames = 300, steps = [5, 50, 500], budgetMs = 4, normals = false, large = 8193, wasm = true;
for (let k = 0; k < args.length; k++) {
  if (args[k] === '--frames') frames = Number(args[++k]);
  else if (args[k] === '--steps') steps = args[++k].split(',').map(Number);
  else if (args[k] === '--budget-ms') budgetMs = Number(args[++k]);
  else if (args[k] === '--large') large = Number(args[++k]);
  else if (args[k] === '--no-wasm') wasm = false;
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
if (!(large === 0 || (Number.isInteger(large) && large > 2048))) {
  console.error(`--large must be 0 (none) or a size above 2048, got '${large}'`);
  process.exit(2);
}
if (fields.length === 0) fields.push(HIMALAYA, join(root, 'tests/fixtures/grandcanyon_512.png'));
if (!existsSync(NATIVE_BENCH)) {
  console.error(`${NATIVE_BENCH} is not built (./build.sh native)`);
  process.exit(1);
}

// hexlod_bench's "triangles min N p50 N max N; splits ...": digits only, as a ';' follows max.
const trianglesLine = /triangles min (\d+) p50 (\d+) max (\d+)/;
const grab = (text, re) => {
  const m = re.exec(text);
  if (!m) throw new Error(`hexlod_bench printed no ${re}:\n${text}`);
  return m.slice(1).map(Number);
};

function runNative(fieldPath, terrain, camerasPath, extra) {
  const run = spawnSync(NATIVE_BENCH, [fieldPath, String(terrain.width), String(terrain.height), String(terrain.spacingX),
    String(terrain.spacingY), '--flight', camerasPath, '--tau', String(TAU), '--viewport', VIEWPORT.join('x'),
    '--tan-half-fov', String(Math.tan((FOV_DEG * Math.PI) / 360)), '--start-converged', ...(normals ? [] : ['--no-normals']), ...extra],
  { encoding: 'utf8', maxBuffer: 1 << 26 });
  if (run.status !== 0) throw new Error(`hexlod_bench failed: ${run.stderr}`);
  return run.stdout;
}

/**
 * The same flight in WebAssembly, as hexlod_bench --flight --start-converged replays it: the
 * same cameras and planes, no budget, no geomorphing; the core's own time of each update.
 */
function wasmFlight(terrain, cameras) {
  const camera = ({ eye, target }) => cameraFor(terrain, eye, target, FOV_DEG, VIEWPORT);
  terrain.resetMesh('exact');
  terrain.configure({ tauPx: TAU, budgetMs: 0, maxOperations: 0, morphFrames: 0, noBackfaceCulling: false, noNormals: !normals });
  terrain.setLodCamera(camera(cameras[0]));
  for (let n = 0; n < 1000; n++) {
    terrain.updateLod();
    if (terrain.query().converged) break;
  }
  terrain.updateStream(); // the start's stream is not the flight's cost
  terrain.acknowledgeStream();
  const updateMs = [], cpuMs = [], triangles = [];
  for (const c of cameras) {
    terrain.setLodCamera(camera(c));
    const cpu = process.cpuUsage();
    terrain.updateLod();
    const used = process.cpuUsage(cpu);
    cpuMs.push((used.user + used.system) / 1e3);
    updateMs.push(terrain.query().updateMs);
    terrain.updateStream();
    terrain.acknowledgeStream();
    triangles.push(terrain.query().triangles);
  }
  return { p50: quantile(cpuMs, 0.5), p95: quantile(cpuMs, 0.95), wallP50: quantile(updateMs, 0.5), wallP95: quantile(updateMs, 0.95),
    min: Math.min(...triangles), max: Math.max(...triangles) };
}

/** The Himalaya tiled and mirrored at every seam to size x size samples, as a .f32 with its sidecar. */
async function writeLargeField(dir, size) {
  const { terrain, field } = await loadForCommand(HIMALAYA, null, {});
  const w = terrain.width, h = terrain.height;
  const heights = heightsInMetres(terrain, field);
  const mirror = (i, n) => {
    const period = 2 * n - 2, k = i % period;
    return k < n ? k : period - k;
  };
  const out = new Float32Array(size * size);
  for (let y = 0; y < size; y++) {
    const row = mirror(y, h) * w;
    for (let x = 0; x < size; x++) out[y * size + x] = heights[row + mirror(x, w)];
  }
  const name = `himalaya_mirrored_${size}`;
  const path = join(dir, `${name}.f32`);
  writeFileSync(path, new Uint8Array(out.buffer));
  writeFileSync(join(dir, `${name}.json`), JSON.stringify({
    width: size, height: size, min: terrain.minHeight, max: terrain.maxHeight, units: 'm',
    cell_size_x_m: terrain.spacingX, cell_size_y_m: terrain.spacingY,
    raw: { dtype: 'float32', byte_order: 'little-endian', layout: 'row-major, width*height values, no header' },
  }));
  return path;
}

const emcc = spawnSync('em++', ['--version'], { encoding: 'utf8' });
const emccVersion = /\b(\d+\.\d+\.\d+)\b/.exec(emcc.stdout ?? '')?.[1] ?? 'unknown';
console.log(`bench_refiner: ${frames} frames a flight at most, tau ${TAU} px, ${VIEWPORT.join('x')}, fov ${FOV_DEG} deg, ` +
  `stream normals ${normals ? 'on' : 'off'}`);
console.log(`machine: ${cpus().length} cores (${cpus()[0]?.model ?? '?'}), ${(totalmem() / 2 ** 30).toFixed(1)} GiB, ` +
  `Node ${process.version}, emcc ${emccVersion}; load average at the start ${loadavg().map((v) => v.toFixed(2)).join(' ')}`);

const rows = [];
const work = mkdtempSync(join(tmpdir(), 'hexlod-bench-refiner-'));
try {
  if (large > 0) fields.push(await writeLargeField(work, large));
  for (const file of fields) {
    const { terrain, field } = await loadForCommand(file, null, {});
    const heights = heightsInMetres(terrain, field);
    const dir = mkdtempSync(join(work, 'field-'));
    const fieldPath = join(dir, 'field.f32');
    writeFileSync(fieldPath, new Uint8Array(heights.buffer, heights.byteOffset, heights.byteLength));
    const label = `${basename(file).replace(/\.[^.]*$/, '')} (${terrain.width}²)`;
    for (const step of steps) {
      // A flight is at most 80 % of the shorter side long: fewer frames when the step needs it.
      const { xMax, zMax } = extentOf(terrain);
      const count = step > 0 ? Math.max(2, Math.min(frames, Math.floor((0.8 * Math.min(xMax, zMax)) / step) + 1)) : frames;
      const path = flightPath(terrain, { frames: count, seed: 1, altitude: 300, step });
      const camerasPath = join(dir, 'cameras.txt');
      writeFileSync(camerasPath, path.cameras.map(({ eye, target }) => [...eye, ...target].join(' ')).join('\n') + '\n');
      const free = runNative(fieldPath, terrain, camerasPath, ['--budget-ms', '0', '--budget-ops', '0']);
      const budgeted = runNative(fieldPath, terrain, camerasPath, ['--budget-ms', String(budgetMs), '--measure-error', '--verbose']);
      const [wallP50, wallP95] = grab(free, /update ms p50 (\S+) p95 (\S+);/);
      const [p50, p95] = grab(free, /update thread CPU ms p50 (\S+) p95 (\S+)/);
      const [min, , max] = grab(free, trianglesLine);
      const err = grab(budgeted, /screen error of the drawn mesh after the update: p50 (\S+) p95 (\S+) max (\S+) px; within tau in (\S+) %/);
      const tris = grab(budgeted, trianglesLine);
      const bytes = grab(budgeted, /live p50 (\S+) max (\S+); at capacity p50 (\S+) max (\S+)/);
      // Who holds the bytes at the last frame, at capacity (the refiner's share includes the
      // field's min/max pyramid, which grows with the field, not the mesh).
      const [meshB, , refinerB, streamB, lastTris] = grab(budgeted, /bytes at the end: mesh (\d+) \(vertex pool (\d+);.*\), refiner (\d+), stream (\d+); (\d+) triangles/);
      rows.push({
        field: label, step: Math.round(path.step), frames: count,
        native: { p50, p95, wallP50, wallP95, min, max },
        wasm: wasm ? wasmFlight(terrain, path.cameras) : null,
        budgeted: { within: err[3], p95: err[1], max: err[2], triangles: tris[1], live: bytes[0], capacity: bytes[2], capacityMax: bytes[3] },
        owners: { mesh: meshB / lastTris, refiner: refinerB / lastTris, stream: streamB / lastTris, triangles: lastTris },
      });
      process.stderr.write(`  ${label} ${Math.round(path.step)} m/frame done\n`);
    }
  }
} finally {
  rmSync(work, { recursive: true, force: true });
}

const n = (v) => v.toLocaleString('en-US');
const updateTable = (title, key) => {
  console.log(`\n${title}`);
  console.log(`| field | m / frame (frames) | update p50 ms | update p95 ms | drawn triangles (min – max) | goal: p95 ≤ ${GOAL_MS} ms | ` +
    'wall clock p50 / p95 ms |');
  console.log('| --- | --- | --- | --- | --- | --- | --- |');
  for (const r of rows) {
    const f = r[key];
    console.log(`| ${r.field} | ${r.step} (${r.frames}) | ${f.p50.toFixed(3)} | ${f.p95.toFixed(3)} | ${n(f.min)} – ${n(f.max)} | ` +
      `${f.p95 <= GOAL_MS ? 'yes' : '**no**'} | ${f.wallP50.toFixed(3)} / ${f.wallP95.toFixed(3)} |`);
  }
};
updateTable('LOD update per frame, no budget, native (build/native/hexlod_bench), thread CPU time:', 'native');
if (wasm) updateTable('LOD update per frame, no budget, WebAssembly in Node (build/wasm-diag), process CPU time:', 'wasm');
console.log(`\nWith a ${budgetMs} ms budget per update, native: the drawn mesh after each update, and memory:`);
console.log('| field | m / frame (frames) | frames within tau | screen error p95 / max px | triangles p50 | ' +
  'B / drawn triangle: live p50, at capacity p50 / max |');
console.log('| --- | --- | --- | --- | --- | --- |');
for (const r of rows) {
  const b = r.budgeted;
  console.log(`| ${r.field} | ${r.step} (${r.frames}) | ${b.within.toFixed(1)} % | ${b.p95.toFixed(2)} / ${b.max.toFixed(2)} | ` +
    `${n(b.triangles)} | ${b.live.toFixed(1)}, ${b.capacity.toFixed(1)} / ${b.capacityMax.toFixed(1)} |`);
}
console.log(`\nBytes per drawn triangle at the last frame of each ${budgetMs} ms flight, at capacity, by owner (native):`);
console.log('| field | m / frame (frames) | triangles | mesh | refiner (with the min/max pyramid) | stream | all |');
console.log('| --- | --- | --- | --- | --- | --- | --- |');
for (const r of rows) {
  const o = r.owners;
  console.log(`| ${r.field} | ${r.step} (${r.frames}) | ${n(o.triangles)} | ${o.mesh.toFixed(1)} | ${o.refiner.toFixed(1)} | ${o.stream.toFixed(1)} | ` +
    `${(o.mesh + o.refiner + o.stream).toFixed(1)} |`);
}
console.log(`\nload average at the end ${loadavg().map((v) => v.toFixed(2)).join(' ')}`);
