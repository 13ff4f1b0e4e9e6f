#!/usr/bin/env node
// Teleports: the WASM core (build/wasm-diag, through web/core/core.js as the page
// drives it) flown through seeded random camera jumps, with the mesh and the stream checked
// after every LOD update. It prints its figures and the failures, each with the seed and index
// that replay it; it asserts nothing else (exit 1 when a check failed, 2 for a bad command line).
//
//   node bench/teleports.js [--teleports 10000] [--seed 1] [--converge-every 25] [--per-terrain 500]
//                           [--fields a.png,b.f32,...] [--from INDEX] [--verbose]
//
// Each teleport puts the camera somewhere new, one of: inside the field's box (heights times
// the vertical scale), far outside (up to a million field extents, or 5e11 m, away), below the ground,
// edge-on (level with the terrain, looking across it), straight down, straight up, a hair
// above the ground with the target micrometres away, a target astronomically far; each with a
// random field of view (0.5 to 170 degrees), aspect (0.2 to 5), viewport height (1 to 8640 px)
// and near and far planes (mostly the page's choice, sometimes arbitrary). Then one frame: the
// camera, one LOD update within the segment's operation budget (deterministic, unlike a time
// budget, so a replay reproduces it), the stream; then the checks:
//   - mesh: the core's checkInvariants() (paper §4: neighbour symmetry, no hanging nodes,
//     balance rule, counters, free lists), hexlod_diag_check_mesh;
//   - stream: the triangles the GPU would assemble tile one disc (no T-junction or crack,
//     every interior edge shared by exactly two triangles), hexlod_diag_check_stream;
//   - refusal: every 16th teleport also sends an absurd camera (NaN, infinite, zero, near >=
//     far, eye on the target, up along the view), which must be refused leaving the mesh hash
//     and stream version as they were.
// Every --converge-every teleports the mesh is also converged (the budget lifted) and checked,
// and the achieved screen error (census) must be within the tau in use (paper §5's bound),
// unless a triangle cap holds cells back.
// Terrains change every --per-terrain teleports (round robin over --fields); each segment
// resets the mesh with a random embedding and random settings: tau, vertical scale, budget,
// morph frames, layout, culling, normals, sometimes a triangle cap with auto tau. Every random
// choice is seeded by the seed and the teleport's (or segment's) index, and a segment starts
// from a new mesh, so --from replays a failure from the start of its segment alone.
import { performance } from 'node:perf_hooks';
import { basename, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { UsageError, parseOptions, parseNumber, readInputs, loadFiles, extentOf } from '../lib/cli_common.js';
import { createNodeCore } from '../lib/node_core.js';
import { scriptOptions } from '../lib/script_options.js';
import { CoreError, FRAME } from '../web/core/core.js';
import { seededRandom } from '../web/app/seeded_random.js';

const root = fileURLToPath(new URL('../', import.meta.url));
const DEFAULT_FIELDS = ['tests/fixtures/volcano_maungawhau.f32', 'tests/fixtures/jacksboro_fault.png',
  'tests/fixtures/grandcanyon_512.png', 'public/terrain/globe_himalaya_2048.png'].map((f) => join(root, f));
const USAGE = `usage: node bench/teleports.js [options]
  --teleports N        camera jumps (default 10000)
  --seed S             seed of every random choice (default 1)
  --converge-every N   converge and check the error bound every N teleports (default 25; 0: never)
  --per-terrain N      teleports before the next terrain and settings (default 500)
  --fields A,B,...     height fields (default: the fixtures and the page's default terrain)
  --from INDEX         start at the segment holding teleport INDEX (a replay; the same other options)
  --verbose            one line per teleport`;
const OPTIONS = { teleports: 'string', seed: 'string', 'converge-every': 'string', 'per-terrain': 'string', fields: 'string',
  from: 'string', verbose: 'boolean' };
const MAX_CONVERGE_FRAMES = 2000;

function parse(args) {
  const { values, positionals } = parseOptions(args, OPTIONS);
  if (values.help) return null;
  if (positionals.length > 0) throw new UsageError(`unexpected argument '${positionals[0]}'`);
  const int = (name, fallback, min) => (values[name] === undefined ? fallback
    : parseNumber(name, values[name], { min, integer: true }));
  return {
    teleports: int('teleports', 10000, 1),
    seed: int('seed', 1, 0),
    convergeEvery: int('converge-every', 25, 0),
    perTerrain: int('per-terrain', 500, 1),
    from: int('from', 0, 0),
    fields: values.fields ? values.fields.split(',').map((f) => (f.startsWith('/') ? f : join(process.cwd(), f))) : DEFAULT_FIELDS,
    verbose: Boolean(values.verbose),
  };
}

/** A generator for one purpose (stream) of teleport or segment `index`: replays need no history. */
function rngFor(seed, stream, index) {
  let h = Math.imul(seed ^ 0x9e3779b9, 0x85ebca6b) ^ Math.imul(stream + 1, 0xc2b2ae35) ^ Math.imul(index + 1, 0x27d4eb2f);
  h = Math.imul(h ^ (h >>> 15), 0x2c1b3c6d);
  return seededRandom(h ^ (h >>> 13));
}
const uniform = (random, a, b) => a + (b - a) * random();
const logUniform = (random, a, b) => Math.exp(uniform(random, Math.log(a), Math.log(b)));
const pick = (random, list) => list[Math.floor(random() * list.length)];
const unitVector = (random) => {
  for (;;) {
    const v = [uniform(random, -1, 1), uniform(random, -1, 1), uniform(random, -1, 1)];
    const n = Math.hypot(...v);
    if (n > 0.05 && n <= 1) return v.map((c) => c / n);
  }
};

/** The segment's settings, as the facade's setters take them. */
function segmentSettings(random) {
  const cap = random() < 0.15;
  return {
    embedding: random() < 0.5 ? 'exact' : 'shifted',
    tau: pick(random, [0.5, 1, 1, 2, 4, 8]),
    verticalScale: pick(random, [1, 1, 2, 0.5, 5]),
    maxOperations: Math.round(logUniform(random, 20, 5000)),
    morphFrames: random() < 0.4 ? pick(random, [4, 8, 30]) : 0,
    layout: random() < 0.3 ? 'triangles' : 'fans',
    culling: random() < 0.9,
    backfaceCulling: random() < 0.8,
    normals: random() < 0.5,
    maxTriangles: cap ? Math.round(logUniform(random, 2000, 200000)) : 0,
    autoTau: cap && random() < 0.5,
  };
}

function applySettings(terrain, s) {
  terrain.configure({ tauPx: s.tau, maxErrorM: 0, verticalScale: s.verticalScale, budgetMs: 0,
    maxOperations: s.maxOperations, morphFrames: s.morphFrames, layout: s.layout, noFrustumCulling: !s.culling,
    noBackfaceCulling: !s.backfaceCulling, noNormals: !s.normals, maxTriangles: s.maxTriangles, autoTau: s.autoTau });
}

const KINDS = ['inside', 'far', 'below', 'edge-on', 'down', 'up', 'tiny', 'huge'];

/**
 * Teleport `index`'s camera over a field of box [0, xMax] x [low, high] x [0, zMax] (y already
 * times the vertical scale): {kind, camera}.
 */
function teleportCamera(random, box, groundAt) {
  const { xMax, zMax, low, high } = box;
  const extent = Math.hypot(xMax, zMax, high - low);
  const relief = Math.max(high - low, 1);
  const inBox = () => [uniform(random, 0, xMax), uniform(random, low, high), uniform(random, 0, zMax)];
  const centre = [xMax / 2, (low + high) / 2, zMax / 2];
  const along = (eye, direction, distance) => eye.map((c, k) => c + direction[k] * distance);
  const kind = pick(random, KINDS);
  let eye, target, up = [0, 1, 0];
  switch (kind) {
    case 'inside':
      eye = inBox();
      target = along(eye, unitVector(random), logUniform(random, 1, extent));
      break;
    case 'far': // up to a million extents away, within the core's coordinates (1e12 m, hexlod.h)
      eye = along(centre, unitVector(random), Math.min(extent * logUniform(random, 2, 1e6), 5e11));
      target = random() < 0.7 ? centre : inBox();
      break;
    case 'below':
      eye = [uniform(random, -0.2, 1.2) * xMax, low - logUniform(random, 0.01, 10 * relief), uniform(random, -0.2, 1.2) * zMax];
      target = random() < 0.5 ? inBox() : along(eye, unitVector(random), logUniform(random, 1, extent));
      break;
    case 'edge-on': { // level with the terrain, from beside one edge across to the opposite one
      const y = uniform(random, low, high), margin = uniform(random, 0, 0.2), far = random() < 0.5;
      if (random() < 0.5) {
        eye = [far ? (1 + margin) * xMax : -margin * xMax, y, uniform(random, 0, zMax)];
        target = [far ? 0 : xMax, y, uniform(random, 0, zMax)];
      } else {
        eye = [uniform(random, 0, xMax), y, far ? (1 + margin) * zMax : -margin * zMax];
        target = [uniform(random, 0, xMax), y, far ? 0 : zMax];
      }
      break;
    }
    case 'down':
    case 'up': {
      const x = uniform(random, -0.1, 1.1) * xMax, z = uniform(random, -0.1, 1.1) * zMax;
      const y = kind === 'down' ? high + logUniform(random, 0.01, 100 * extent) : low - logUniform(random, 0.01, extent);
      eye = [x, kind === 'down' || random() < 0.5 ? y : uniform(random, low, high), z];
      target = [x, eye[1] + (kind === 'down' ? -1 : 1) * logUniform(random, 1e-3, 10 * extent), z];
      const a = uniform(random, 0, 2 * Math.PI);
      up = [Math.sin(a), 0, -Math.cos(a)]; // straight down or up, +y cannot be up
      break;
    }
    case 'tiny': { // a hair above the ground, the target micrometres to millimetres away
      const x = uniform(random, 0, xMax), z = uniform(random, 0, zMax);
      eye = [x, groundAt(x, z) + logUniform(random, 1e-3, 1), z];
      target = along(eye, unitVector(random), logUniform(random, 2e-6, 1e-2));
      break;
    }
    case 'huge': // a target up to 1e11 m away
      eye = inBox();
      target = along(eye, unitVector(random), logUniform(random, 1e5, 1e11));
      break;
  }
  // A view (almost) straight up or down needs an up off its direction.
  const d = target.map((c, k) => c - eye[k]);
  const look = Math.hypot(...d);
  if (Math.abs(up[1]) === 1 && Math.hypot(d[0], d[2]) <= 1e-3 * look) up = [0, 0, -1];
  // Near and far: mostly as the page chooses them (web/cameras/clip_planes.js), sometimes arbitrary.
  let far = 0;
  for (const x of [0, xMax]) for (const z of [0, zMax]) for (const y of [low, high]) far = Math.max(far, Math.hypot(x - eye[0], y - eye[1], z - eye[2]));
  far = far * 1.05 + 1;
  let near = Math.max(far / 1e6, Math.min(0.3 * Math.max(eye[1] - high, 0.01), 0.5 * look));
  if (random() < 0.25) {
    near = logUniform(random, 1e-6, 100);
    far = near * logUniform(random, 1.001, 1e9);
  }
  near = Math.max(near, 1e-6);
  far = Math.min(Math.max(far, near * 10), 1e12);
  if (!(near < far)) near = far / 10;
  const viewportHeight = Math.round(logUniform(random, 1, 8640));
  return {
    kind,
    camera: {
      eye, target, up, tanHalfFovY: Math.tan((logUniform(random, 0.5, 170) * Math.PI) / 360), aspect: logUniform(random, 0.2, 5),
      viewportHeight, near, far,
    },
  };
}

/** An absurd camera: the good one with one field spoiled (each must be refused). */
function absurdCamera(random, good) {
  const spoil = pick(random, [
    (c) => { c.viewportHeight = Infinity; }, (c) => { c.viewportHeight = 0; }, (c) => { c.eye = [NaN, c.eye[1], c.eye[2]]; },
    (c) => { c.target = [c.target[0], -Infinity, c.target[2]]; }, (c) => { c.tanHalfFovY = 0; }, (c) => { c.aspect = NaN; },
    (c) => { c.near = c.far; }, (c) => { c.near = 0; }, (c) => { c.far = Infinity; }, (c) => { c.target = [...c.eye]; },
    (c) => { c.up = [c.target[0] - c.eye[0], c.target[1] - c.eye[1], c.target[2] - c.eye[2]]; }, (c) => { c.eye = [2e12, 0, 0]; },
  ]);
  const bad = { ...good };
  spoil(bad);
  return bad;
}

async function main() {
  const { options, exitCode } = scriptOptions('teleports', USAGE, parse);
  if (!options) return exitCode;
  const { teleports, seed, convergeEvery, perTerrain, verbose } = options;
  const core = await createNodeCore();
  const started = performance.now();
  const terrains = [];
  for (const path of options.fields) {
    const { terrain } = await loadFiles(core, readInputs(path), {});
    terrains.push({ name: basename(path), terrain });
  }
  const loadMs = performance.now() - started;

  const counts = { teleports: 0, frames: 0, mesh: 0, stream: 0, refusals: 0, converged: 0, errorBound: 0, skippedBound: 0 };
  const byKind = Object.fromEntries(KINDS.map((k) => [k, 0]));
  const failures = [];
  const times = { frame: 0, checks: 0, converge: 0 };
  let maxTriangles = 0, maxConvergeFrames = 0;
  let current = null; // {name, terrain, settings, box}

  const fail = (index, check, error, camera) => {
    failures.push({ index, terrain: current.name, check, message: error.message ?? String(error), camera });
    console.log(`FAIL teleport ${index} (${current.name}) ${check}: ${error.message ?? error}`);
    // Go on from a fresh mesh with the same settings: a replay reproduces the failure anyway.
    current.terrain.resetMesh(current.settings.embedding);
  };
  const check = (index, camera) => {
    const t0 = performance.now();
    let ok = true;
    try {
      current.terrain.checkMesh();
      counts.mesh++;
    } catch (error) {
      fail(index, 'mesh invariants', error, camera);
      ok = false;
    }
    if (ok) {
      try {
        current.terrain.readDiagnostic('check_stream', 7, 'stream not watertight');
        counts.stream++;
      } catch (error) {
        fail(index, 'stream watertightness', error, camera);
        ok = false;
      }
    }
    times.checks += performance.now() - t0;
    return ok;
  };

  const first = Math.floor(options.from / perTerrain) * perTerrain; // a segment starts from a new mesh
  for (let index = first; index < teleports; index++) {
    if (index > first && index % 500 === 0) {
      process.stderr.write(`teleports: ${index} of ${teleports}, ${failures.length} failures, ` +
        `${((performance.now() - started) / 60000).toFixed(1)} min\n`);
    }
    const segment = Math.floor(index / perTerrain);
    if (index % perTerrain === 0) {
      const random = rngFor(seed, 1, segment);
      const { name, terrain } = terrains[segment % terrains.length];
      const settings = segmentSettings(random);
      terrain.resetMesh(settings.embedding);
      applySettings(terrain, settings);
      const { xMax, zMax } = extentOf(terrain);
      const s = settings.verticalScale;
      current = { name, terrain, settings, box: { xMax, zMax, low: terrain.minHeight * s, high: terrain.maxHeight * s } };
      if (verbose) console.log(`segment ${segment}: ${name} ${JSON.stringify(settings)}`);
    }
    const { terrain, settings, box } = current;
    const random = rngFor(seed, 0, index);
    const groundAt = (x, z) => terrain.heightAt(x, z) * settings.verticalScale;
    const { kind, camera } = teleportCamera(random, box, groundAt);
    byKind[kind]++;
    counts.teleports++;

    // Now and then an absurd camera first: refused, and nothing moves.
    if (index % 16 === 15) {
      const before = terrain.query(FRAME.hash);
      const hash = before.hash(), version = before.version;
      const bad = absurdCamera(random, camera);
      let refused = false;
      try {
        terrain.frame(bad);
      } catch (error) {
        refused = error instanceof CoreError && /invalid camera/.test(error.message);
      }
      const after = terrain.query(FRAME.hash);
      if (!refused) fail(index, 'absurd camera accepted', new Error(JSON.stringify(bad)), bad);
      else if (after.hash() !== hash || after.version !== version) fail(index, 'refused camera changed the mesh', new Error(`hash ${hash} -> ${after.hash()}`), bad);
      else counts.refusals++;
    }

    const t0 = performance.now();
    let stats;
    try {
      stats = terrain.frame(camera);
    } catch (error) {
      times.frame += performance.now() - t0;
      fail(index, 'valid camera refused', error, camera);
      continue;
    }
    times.frame += performance.now() - t0;
    counts.frames++;
    maxTriangles = Math.max(maxTriangles, stats.triangles);
    if (verbose) {
      console.log(`${index} ${kind}: ${stats.operations} operations, ${stats.triangles} triangles, converged ${stats.converged}`);
    }
    if (!check(index, camera)) continue;

    if (convergeEvery > 0 && (index + 1) % convergeEvery === 0) {
      const c0 = performance.now();
      terrain.configure({ budgetMs: 0, maxOperations: 0 });
      let frames = 0;
      for (stats = terrain.frame(null); !stats.converged && frames < MAX_CONVERGE_FRAMES; frames++) stats = terrain.frame(null);
      terrain.configure({ budgetMs: 0, maxOperations: settings.maxOperations });
      times.converge += performance.now() - c0;
      counts.frames += frames + 1;
      maxConvergeFrames = Math.max(maxConvergeFrames, frames + 1);
      maxTriangles = Math.max(maxTriangles, stats.triangles);
      if (!stats.converged) {
        fail(index, 'convergence', new Error(`not converged after ${MAX_CONVERGE_FRAMES} frames`), camera);
        continue;
      }
      if (!check(index, camera)) continue;
      counts.converged++;
      const census = terrain.query(FRAME.census);
      if (settings.maxTriangles > 0) {
        counts.skippedBound++; // a cap holds failing cells back: no bound is promised
      } else if (census.achievedErrorPx <= census.tau * (1 + 1e-9)) {
        counts.errorBound++;
      } else {
        fail(index, 'error bound', new Error(`achieved ${census.achievedErrorPx} px > tau ${census.tau} px once converged`), camera);
      }
    }
  }
  for (const { terrain } of terrains) terrain.destroy();
  const totalMs = performance.now() - started;

  const rows = [
    ['teleports', counts.teleports + (first > 0 ? ` (from ${first})` : '')],
    ['frames (LOD updates)', counts.frames],
    ['mesh invariant checks passed', counts.mesh],
    ['stream watertightness checks passed', counts.stream],
    ['absurd cameras refused, mesh unchanged', counts.refusals],
    ['convergences checked', counts.converged],
    ['  within tau once converged', counts.errorBound],
    ['  under a triangle cap (no bound)', counts.skippedBound],
    ['failures', failures.length],
    ['largest mesh (triangles)', maxTriangles],
    ['most frames to converge', maxConvergeFrames],
    ['time: loading (s)', (loadMs / 1000).toFixed(1)],
    ['time: teleport frames (s)', (times.frame / 1000).toFixed(1)],
    ['time: checks (s)', (times.checks / 1000).toFixed(1)],
    ['time: convergences (s)', (times.converge / 1000).toFixed(1)],
    ['time: total (s)', (totalMs / 1000).toFixed(1)],
  ];
  console.log(`\nteleports: seed ${seed}, ${teleports} teleports, converged every ${convergeEvery || 'never'}, ` +
    `${perTerrain} per terrain, fields ${options.fields.map((f) => basename(f)).join(', ')}`);
  const width = Math.max(...rows.map(([label]) => label.length));
  for (const [label, value] of rows) console.log(`  ${label.padEnd(width)}  ${value}`);
  console.log(`  kinds: ${KINDS.map((k) => `${k} ${byKind[k]}`).join(', ')}`);
  if (failures.length > 0) {
    const fields = options.fields === DEFAULT_FIELDS ? '' : ` --fields ${options.fields.join(',')}`;
    console.log('\nfailures (replay: the same options, --from index --teleports index + 1):');
    for (const f of failures.slice(0, 50)) {
      console.log(`  teleport ${f.index} on ${f.terrain}, ${f.check}: ${f.message}`);
      console.log(`    node bench/teleports.js --seed ${seed} --per-terrain ${perTerrain} --converge-every ${convergeEvery}` +
        ` --from ${f.index} --teleports ${f.index + 1}${fields}`);
      console.log(`    camera ${JSON.stringify(f.camera)}`);
    }
    return 1;
  }
  console.log('\nno failures');
  return 0;
}

process.exitCode = await main();
