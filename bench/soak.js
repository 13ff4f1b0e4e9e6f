#!/usr/bin/env node
// Soak: the WASM core (build/wasm-diag, through web/core/core.js and the loaders, as
// the page drives them) flown for an hour of 60 fps frames over changing settings and terrains,
// with memory read at intervals. After warm-up, memory must be flat. It prints the figures as a
// table and a verdict; exit 1 when something grew after warm-up, 2 for a bad command line.
//
//   node bench/soak.js [--frames 216000] [--seed 1] [--samples 24] [--terrain-every 3600]
//                      [--settings-every 600] [--warmup-cycles 1] [--fields a.png,b.f32,...]
//
// The flight: each terrain is loaded from its file (the fixtures of tests/fixtures and the
// page's default terrain, round robin), flown for --terrain-every frames and destroyed. The
// camera circles the field at a height that rises and sinks (20 m to a tenth of the field's
// extent above the ground), looking ahead and down, with a teleport every 900 frames
// and now and then a straight-down view. Every --settings-every frames the settings change
// at random: tau, the operation budget, the vertical scale, frustum and back-face culling,
// geomorph frames, index layout, normals, a triangle cap with auto tau, max-error mode, the
// viewport, and the embedding (a new mesh). Every frame is one core call (camera, LOD update,
// stream), then the stream is acknowledged, as the page does after its upload.
// A cycle is one pass over the fields. Every random choice is seeded by the seed and the
// frame's place in its cycle, and budgets are operation counts (a time budget would make the
// meshes depend on the machine's speed), so every cycle repeats the same frames: after the
// first, memory has no reason to grow, and any growth is a leak or fragmentation.
//
// Memory, read after a garbage collection:
//   - every frames / --samples frames: WASM memory size (never shrinks: its high-water mark),
//     the allocator's bytes in use (hexlod_diag_heap), the terrain's own accounting
//     (hexlod_frame.memory_bytes), the Node heap, array buffers and RSS;
//   - at the end of each terrain's flight, before it is destroyed: the allocator's bytes in
//     use, which must be the same at the same place of every cycle;
//   - between terrains (the old one destroyed, the next not yet loaded): the allocator's bytes
//     in use, which must come back to the same figure every time.
// Verdict, after the warm-up (--warmup-cycles cycles): the bytes in use between terrains vary
// by at most 4 KB, and at the end of each flight differ from the first cycle's by at most
// 4 KB; from the first terrain switch after the warm-up to the last, WASM memory does not grow
// at all, the Node heap grows by at most 4 MB and RSS by at most 10 %.
import { performance } from 'node:perf_hooks';
import { basename, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { setFlagsFromString } from 'node:v8';
import { runInNewContext } from 'node:vm';
import { UsageError, parseOptions, parseNumber, readInputs, loadFiles, extentOf } from '../lib/cli_common.js';
import { createNodeCore } from '../lib/node_core.js';
import { scriptOptions } from '../lib/script_options.js';
import { seededRandom } from '../web/app/seeded_random.js';

const root = fileURLToPath(new URL('../', import.meta.url));
const DEFAULT_FIELDS = ['tests/fixtures/volcano_maungawhau.f32', 'tests/fixtures/jacksboro_fault.png', 'tests/fixtures/grandcanyon_512.png',
  'public/terrain/globe_himalaya_2048.png', 'tests/fixtures/volcano_maungawhau.png', 'tests/fixtures/jacksboro_fault.f32',
  'tests/fixtures/grandcanyon_512.f32'].map((f) => join(root, f));
const USAGE = `usage: node bench/soak.js [options]
  --frames N           frames to fly (default 216000: an hour at 60 fps)
  --seed S             seed of the settings, flights and teleports (default 1)
  --samples N          memory samples over the run (default 24)
  --terrain-every N    frames on one terrain before the next is loaded (default 3600)
  --settings-every N   frames between settings changes (default 600)
  --warmup-cycles N    passes over the fields before the verdict looks (default 1)
  --fields A,B,...     height fields (default: the fixtures and the page's default terrain)`;
const OPTIONS = { frames: 'string', seed: 'string', samples: 'string', 'terrain-every': 'string', 'settings-every': 'string',
  'warmup-cycles': 'string', fields: 'string' };
const FPS = 60;
const TELEPORT_EVERY = 900;
const MB = 2 ** 20;
// The verdict's limits (see above).
const LIMITS = { heapInUseBytes: 4096, wasmBytes: 0, nodeHeapBytes: 4 * MB, rssShare: 0.1 };

function parse(args) {
  const { values, positionals } = parseOptions(args, OPTIONS);
  if (values.help) return null;
  if (positionals.length > 0) throw new UsageError(`unexpected argument '${positionals[0]}'`);
  const int = (name, fallback, min = 1) => (values[name] === undefined ? fallback : parseNumber(name, values[name], { min, integer: true }));
  return {
    frames: int('frames', 216000),
    seed: int('seed', 1, 0),
    samples: int('samples', 24),
    terrainEvery: int('terrain-every', 3600),
    settingsEvery: int('settings-every', 600),
    warmupCycles: int('warmup-cycles', 1, 0),
    fields: values.fields ? values.fields.split(',').map((f) => (f.startsWith('/') ? f : join(process.cwd(), f))) : DEFAULT_FIELDS,
  };
}

const pick = (random, list) => list[Math.floor(random() * list.length)];

function randomSettings(random) {
  const cap = random() < 0.15;
  const [width, height] = pick(random, [[1920, 1080], [1280, 720], [2560, 1440], [800, 1200], [3840, 2160]]);
  return {
    embedding: random() < 0.7 ? 'exact' : 'shifted',
    tau: pick(random, [0.5, 1, 1, 2, 4, 8]),
    maxError: random() < 0.1 ? pick(random, [1, 5, 20]) : 0,
    maxOperations: pick(random, [0, 200, 2000, 2000, 20000]),
    verticalScale: pick(random, [0.5, 1, 2, 2, 5]),
    culling: random() < 0.9,
    backfaceCulling: random() < 0.8,
    morphFrames: random() < 0.6 ? 8 : 0,
    layout: random() < 0.3 ? 'triangles' : 'fans',
    normals: random() < 0.5,
    maxTriangles: cap ? pick(random, [20000, 100000, 400000]) : 0,
    autoTau: cap && random() < 0.5,
    width, height,
  };
}

function applySettings(terrain, s) {
  terrain.configure({ tauPx: s.tau, maxErrorM: s.maxError > 0 ? s.maxError : 0, verticalScale: s.verticalScale,
    budgetMs: 0, maxOperations: s.maxOperations, noFrustumCulling: !s.culling, noBackfaceCulling: !s.backfaceCulling,
    morphFrames: s.morphFrames, layout: s.layout, noNormals: !s.normals, maxTriangles: s.maxTriangles, autoTau: s.autoTau });
}

/**
 * The camera of frame `f` on the current terrain, written into `camera` (one object for the
 * whole run, as the page keeps one): a circle around the field's centre, the height above the
 * ground rising and sinking, looking ahead and 15 degrees down; after a teleport the circle
 * is centred elsewhere; now and then straight down.
 */
function flyCamera(camera, f, flight, terrain, s) {
  const { xMax, zMax, extent } = flight;
  const t = (f - flight.start) / FPS; // seconds on this terrain
  const angle = flight.phase + (2 * Math.PI * t) / 60; // a lap a minute
  const radius = flight.radius * extent;
  const x = flight.cx + radius * Math.cos(angle), z = flight.cz + radius * Math.sin(angle);
  // Metres above the ground, from 20 m to a tenth of the extent and back, geometrically: as
  // much time at each order of magnitude, most of it low where meshes are large.
  const rise = 0.5 - 0.5 * Math.cos((2 * Math.PI * t) / flight.bob);
  const clearance = 20 * Math.pow(Math.max(1, (0.1 * extent) / 20), rise);
  const ground = terrain.heightAt(Math.min(Math.max(x, 0), xMax), Math.min(Math.max(z, 0), zMax));
  const eyeY = (ground + clearance) * s.verticalScale;
  camera.eye[0] = x; camera.eye[1] = eyeY; camera.eye[2] = z;
  if (flight.down) {
    camera.target[0] = x; camera.target[1] = eyeY - clearance * s.verticalScale; camera.target[2] = z;
    camera.up[0] = 0; camera.up[1] = 0; camera.up[2] = -1;
  } else {
    const ahead = Math.max(clearance, 50) * 4;
    camera.target[0] = x - Math.sin(angle) * ahead; camera.target[2] = z + Math.cos(angle) * ahead;
    camera.target[1] = eyeY - ahead * Math.tan(Math.PI / 12);
    camera.up[0] = 0; camera.up[1] = 1; camera.up[2] = 0;
  }
  camera.aspect = s.width / s.height;
  camera.viewportHeight = s.height;
  camera.near = Math.max(0.05, clearance * 0.3 * s.verticalScale * 0.5);
  camera.far = 4 * extent + clearance * s.verticalScale;
  return camera;
}

function newFlight(random, f, terrain) {
  const { xMax, zMax } = extentOf(terrain);
  const extent = Math.hypot(xMax, zMax);
  return {
    start: f, xMax, zMax, extent,
    cx: xMax * (0.3 + 0.4 * random()), cz: zMax * (0.3 + 0.4 * random()),
    radius: 0.15 + 0.25 * random(), phase: 2 * Math.PI * random(), bob: 20 + 40 * random(),
    down: random() < 0.15,
  };
}

async function main() {
  const { options, exitCode } = scriptOptions('soak', USAGE, parse);
  if (!options) return exitCode;
  setFlagsFromString('--expose-gc');
  const gc = runInNewContext('gc'); // memory is read after a full collection
  const { frames, seed, terrainEvery, settingsEvery } = options;
  const sampleEvery = Math.max(1, Math.floor(frames / options.samples));
  const fields = options.fields.map((path) => ({ name: basename(path), files: readInputs(path) })); // read once: constant memory
  const core = await createNodeCore();
  const heapPointer = core.module._malloc(16);
  const readHeap = () => {
    if (core.module._hexlod_diag_heap(heapPointer) < 0) throw new Error(core.lastError());
    const out = new Float64Array(core.buffer, heapPointer, 2);
    return { inUse: out[0], held: out[1] };
  };
  // The generator of a choice made at frame f: the same at the same place of every cycle.
  const cycleFrames = fields.length * terrainEvery;
  const randomAt = (stream, f) => {
    let h = Math.imul(seed ^ 0x9e3779b9, 0x85ebca6b) ^ Math.imul(stream + 1, 0xc2b2ae35) ^ Math.imul((f % cycleFrames) + 1, 0x27d4eb2f);
    h = Math.imul(h ^ (h >>> 15), 0x2c1b3c6d);
    return seededRandom(h ^ (h >>> 13));
  };
  const camera = { eye: [0, 0, 0], target: [0, 0, 0], up: [0, 1, 0], fovY: Math.PI / 3, aspect: 16 / 9, viewportHeight: 1080, near: 1, far: 2 };
  const samples = [], switches = [], ends = [];
  let terrain = null, fieldIndex = -1, settings = null, flight = null, stats = null;
  let loaded = 0, frameMs = 0, framesTimed = 0, loadMs = 0, maxTriangles = 0;
  const started = performance.now();

  const sample = (f, where) => {
    gc();
    const heap = readHeap(), node = process.memoryUsage();
    return {
      frame: f, where, terrain: terrain ? fields[fieldIndex].name : '-', triangles: stats && terrain ? stats.triangles : 0,
      coreBytes: stats && terrain ? stats.memoryBytes : 0, inUse: heap.inUse, held: heap.held, wasm: core.buffer.byteLength,
      nodeHeap: node.heapUsed, arrayBuffers: node.arrayBuffers, rss: node.rss, msPerFrame: framesTimed ? frameMs / framesTimed : 0,
    };
  };

  for (let f = 0; f < frames; f++) {
    if (f % terrainEvery === 0) {
      if (terrain) {
        ends.push(sample(f, 'end'));
        terrain.destroy();
        terrain = null;
      }
      switches.push(sample(f, 'between'));
      fieldIndex = (fieldIndex + 1) % fields.length;
      const l0 = performance.now();
      ({ terrain } = await loadFiles(core, fields[fieldIndex].files, {}));
      loadMs += performance.now() - l0;
      loaded++;
      settings = null;
    }
    const onTerrain = f % terrainEvery; // frames since this terrain was loaded: settings and teleports keep step with it
    if (settings === null || onTerrain % settingsEvery === 0) {
      const next = randomSettings(randomAt(1, f));
      if (settings === null || next.embedding !== settings.embedding) terrain.resetMesh(next.embedding);
      applySettings(terrain, next);
      settings = next;
    }
    if (onTerrain % TELEPORT_EVERY === 0) flight = newFlight(randomAt(2, f), f, terrain);
    flyCamera(camera, f, flight, terrain, settings);
    const t0 = performance.now();
    stats = terrain.frame(camera);
    terrain.acknowledgeStream(); // the renderer uploaded the dirty ranges
    frameMs += performance.now() - t0;
    framesTimed++;
    maxTriangles = Math.max(maxTriangles, stats.triangles);
    if ((f + 1) % sampleEvery === 0 || f + 1 === frames) {
      samples.push(sample(f + 1, 'flight'));
      frameMs = 0;
      framesTimed = 0;
      const s = samples.at(-1);
      process.stderr.write(`soak: frame ${f + 1} of ${frames}, ${((performance.now() - started) / 60000).toFixed(1)} min, ` +
        `WASM ${(s.wasm / MB).toFixed(0)} MB, in use ${(s.inUse / MB).toFixed(1)} MB, heap ${(s.nodeHeap / MB).toFixed(1)} MB\n`);
    }
  }
  ends.push(sample(frames, 'end'));
  terrain.destroy();
  switches.push(sample(frames, 'between'));
  core.module._free(heapPointer);
  const totalMs = performance.now() - started;

  // The table.
  const mb = (bytes) => (bytes / MB).toFixed(2);
  const header = ['frame', 'minute', 'terrain', 'triangles', 'core MB', 'in use MB', 'WASM MB', 'Node heap MB', 'buffers MB', 'RSS MB', 'ms/frame'];
  const rows = samples.map((s) => [s.frame, (s.frame / FPS / 60).toFixed(1), s.terrain, s.triangles, mb(s.coreBytes), mb(s.inUse),
    mb(s.wasm), mb(s.nodeHeap), mb(s.arrayBuffers), mb(s.rss), s.msPerFrame.toFixed(2)]);
  const widths = header.map((h, k) => Math.max(h.length, ...rows.map((r) => String(r[k]).length)));
  const line = (cells) => cells.map((c, k) => (k === 2 ? String(c).padEnd(widths[k]) : String(c).padStart(widths[k]))).join('  ');
  console.log(`\nsoak: seed ${seed}, ${frames} frames (${(frames / FPS / 60).toFixed(1)} min at ${FPS} fps), a terrain every ` +
    `${terrainEvery} frames, settings every ${settingsEvery}; ${(totalMs / 60000).toFixed(1)} min (loading ${(loadMs / 1000).toFixed(1)} s), ` +
    `${loaded} terrains loaded, largest mesh ${maxTriangles} triangles`);
  console.log(line(header));
  for (const r of rows) console.log(line(r));
  console.log(`between terrains (allocator bytes in use): ${switches.map((s) => s.inUse).join(', ')}`);
  console.log(`as each flight ends (allocator MB in use): ${ends.map((s) => mb(s.inUse)).join(', ')}`);

  // The verdict, after the warm-up.
  const warmFrame = options.warmupCycles * cycleFrames;
  const after = samples.filter((s) => s.frame > warmFrame);
  const betweenAfter = switches.filter((s) => s.frame >= warmFrame);
  // Flights that ended after the warm-up against the same flight of the first cycle.
  const endsAfter = ends.filter((s) => s.frame > warmFrame && s.frame % terrainEvery === 0);
  const endDrift = Math.max(0, ...endsAfter.map((s) => Math.abs(s.inUse - ends[((s.frame - terrainEvery) % cycleFrames) / terrainEvery].inUse)));
  const cycles = (frames / cycleFrames).toFixed(2);
  if (after.length < 2 || betweenAfter.length < 2) {
    console.log(`\nverdict: too short to judge (${cycles} cycles of ${cycleFrames} frames; the warm-up ends at frame ${warmFrame})`);
    return 0;
  }
  // Growth from the first terrain switch after the warm-up to the last: the same moment of a
  // cycle (no terrain loaded), after a garbage collection.
  const first = betweenAfter[0], last = betweenAfter.at(-1);
  const spread = (list, key) => Math.max(...list.map((s) => s[key])) - Math.min(...list.map((s) => s[key]));
  const checks = [
    ['allocator bytes in use between terrains, spread', spread(betweenAfter, 'inUse'), LIMITS.heapInUseBytes, (v) => `${v} B`],
    [`allocator bytes in use as each flight ends, against the first cycle (${endsAfter.length} flights)`, endDrift, LIMITS.heapInUseBytes,
      (v) => `${v} B`],
    ['WASM memory growth', last.wasm - first.wasm, LIMITS.wasmBytes, (v) => `${mb(v)} MB`],
    ['Node heap growth', last.nodeHeap - first.nodeHeap, LIMITS.nodeHeapBytes, (v) => `${mb(v)} MB`],
    ['RSS growth', last.rss - first.rss, LIMITS.rssShare * first.rss, (v) => `${mb(v)} MB`],
  ];
  console.log(`\nverdict after warm-up (${options.warmupCycles} of ${cycles} cycles of ${cycleFrames} frames: frame ${warmFrame} on, ` +
    `${after.length} samples, ${betweenAfter.length} terrain switches):`);
  let flat = true;
  for (const [label, value, limit, show] of checks) {
    const ok = value <= limit;
    flat &&= ok;
    console.log(`  ${ok ? 'flat ' : 'GROWS'}  ${label}: ${show(value)} (limit ${show(limit)})`);
  }
  console.log(flat ? 'memory is flat after warm-up' : 'memory grows after warm-up');
  return flat ? 0 : 1;
}

process.exitCode = await main();
