// hexlod bench: figures of the WASM core on a scripted low-altitude flight, of refining from
// scratch, and of @mapbox/martini (RTIN, from npm) on the same heights. It prints figures; it
// is not a test, and nothing asserts them.
import { writeFileSync, existsSync, mkdtempSync, rmSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import {
  UsageError, parseOptions, parseNumber, parseViewport, parseCellSize, parseEmbedding, loadForCommand,
  FILE_OPTIONS, FILE_USAGE, parseFileOptions,
  extentOf, cameraFor, quantile, round,
} from './cli_common.js';
import { inCheckout } from './node_core.js';
import { decodeFans } from './mesh_export.js';
import { STREAM_VERTEX_BYTES, STREAM_VERTEX_WORDS } from '../web/core/core.js';
import { gridMeshError, padToPowerOfTwoPlusOne } from './rtin_error.js';
import { flightPath, heightsInMetres } from './bench_flight.js';

export const BENCH_USAGE = `usage: hexlod bench <heightfield> [options]
  Prints figures, asserts nothing: a scripted low-altitude flight across the field (per frame
  one LOD update, then the fan stream, as the page does), the time from heights in memory to a
  converged mesh, and @mapbox/martini on the same heights at the same measured max error.
  The flight: a straight line through the field's centre on a seeded heading, 80 % of the
  shorter side long (or --step metres a frame), swaying sideways, --altitude above the highest ground under the next 10
  frames, looking 10 degrees down; it starts from the mesh converged for its first camera.
  --frames N            frames of the flight (default 300)
  --seed S              seed of the flight's heading and sway (default 1)
  --budget-ms MS        time budget per update (default 4, or none with --budget-ops alone)
  --budget-ops N        operations per update (default: no limit)
  --altitude M          height above the terrain in metres (default 300)
  --step M              metres flown per frame (default: 80 % of the shorter side over --frames)
  --no-backface         turn off back-face culling (the popping meter cannot tell a vertex hidden
                        behind a ridge from a visible one; back-face culled cells that turn to
                        face the camera are refined at once)
  --tau PX              screen-space tolerance in pixels (default 1)
  --fov DEG             vertical field of view in degrees (default 60)
  --viewport WxH        viewport in pixels (default 1920x1080)
  --max-error M         max error of the comparison with martini (default 5)
  --embedding E         exact (default) or shifted
  --morph-frames N      geomorph blends over N frames in the flight (default 8); popping is
                        measured with them and again without (0)
  --cell-size DX[,DY]   metres between columns (and rows); default: from the file, else 1
  --verbose             one line per frame
  --no-native           skip the comparison with build/native/hexlod_bench --flight (the same
                        flight without a budget in both builds, for the WASM/native ratio)
  --json FILE           every figure as JSON
${FILE_USAGE}`;

const OPTIONS = {
  frames: 'string', seed: 'string', 'budget-ms': 'string', 'budget-ops': 'string', altitude: 'string',
  tau: 'string', fov: 'string', viewport: 'string', 'max-error': 'string', embedding: 'string', step: 'string',
  'cell-size': 'string', verbose: 'boolean', json: 'string', 'no-native': 'boolean', 'morph-frames': 'string', 'no-backface': 'boolean',
  ...FILE_OPTIONS,
};
const MAX_UPDATES = 10000;
const NATIVE_BENCH = fileURLToPath(new URL('../build/native/hexlod_bench', import.meta.url));

function benchSettings(args) {
  const { values, positionals } = parseOptions(args, OPTIONS);
  if (values.help) return { help: true };
  if (positionals.length !== 1) {
    throw new UsageError(positionals.length === 0 ? 'bench needs a height field file' : 'bench takes exactly one height field file');
  }
  const number = (name, fallback, limits) => (values[name] !== undefined ? parseNumber(name, values[name], limits) : fallback);
  const budgetOps = number('budget-ops', 0, { min: 1, integer: true, max: 2 ** 31 - 1 });
  return {
    file: positionals[0],
    frames: number('frames', 300, { min: 1, integer: true, max: 1e6 }),
    seed: number('seed', 1, { integer: true, min: 0, max: 2 ** 32 - 1 }),
    budgetMs: number('budget-ms', values['budget-ops'] !== undefined ? 0 : 4, { min: 0 }),
    budgetOps,
    altitude: number('altitude', 300, { min: 0, exclusiveMin: true }),
    step: number('step', 0, { min: 0, exclusiveMin: true }),
    backface: !values['no-backface'],
    tau: number('tau', 1, { min: 0, exclusiveMin: true }),
    fov: number('fov', 60, { min: 0, exclusiveMin: true, max: 179 }),
    viewport: values.viewport !== undefined ? parseViewport(values.viewport) : [1920, 1080],
    maxError: number('max-error', 5, { min: 0, exclusiveMin: true }),
    embedding: parseEmbedding(values.embedding),
    morphFrames: number('morph-frames', 8, { min: 0, max: 1000, integer: true }),
    cellSize: values['cell-size'] !== undefined ? parseCellSize(values['cell-size']) : null,
    fileOptions: parseFileOptions(values),
    verbose: !!values.verbose,
    native: !values['no-native'],
    json: values.json ?? null,
  };
}

/** Updates without a budget until converged; returns the wall time, updates and operations. */
function refineToConvergence(terrain) {
  terrain.configure({ budgetMs: 0, maxOperations: 0 });
  let updates = 0, operations = 0;
  const start = performance.now();
  while (updates < MAX_UPDATES) {
    operations += terrain.updateLod();
    updates += 1;
    if (terrain.query().converged) break;
  }
  return { ms: performance.now() - start, updates, operations, converged: terrain.query().converged };
}

/** Triangles of the stream that reach into the rectangle [0, xMax] x [0, zMax]. */
function trianglesOverField(terrain, xMax, zMax) {
  const { triangles } = decodeFans(terrain.levelView(false).indices.slice());
  terrain.updateStream();
  const p = terrain.stream().vertices;
  let count = 0;
  for (let t = 0; t < triangles.length; t += 3) {
    let left = 0, right = 0, top = 0, bottom = 0;
    for (let k = 0; k < 3; k++) {
      const v = triangles[t + k] * STREAM_VERTEX_WORDS;
      if (p[v] <= 0) left += 1;
      if (p[v] >= xMax) right += 1;
      if (p[v + 2] <= 0) top += 1;
      if (p[v + 2] >= zMax) bottom += 1;
    }
    if (left < 3 && right < 3 && top < 3 && bottom < 3) count += 1;
  }
  return count;
}

/** Martini triangles that reach into the field's columns and rows. */
function martiniTrianglesOverField({ vertices, triangles }, width, height) {
  let count = 0;
  for (let t = 0; t < triangles.length; t += 3) {
    let outX = 0, outY = 0;
    for (let k = 0; k < 3; k++) {
      const v = triangles[t + k];
      if (vertices[2 * v] >= width - 1) outX += 1;
      if (vertices[2 * v + 1] >= height - 1) outY += 1;
    }
    if (outX < 3 && outY < 3) count += 1;
  }
  return count;
}

/**
 * @mapbox/martini on the same heights: the largest maxError parameter found whose mesh, measured
 * on the original samples, is within `target` metres (bisection, then 8 larger probes up to
 * twice the target; martini's own error estimate looks only at edge midpoints, so its
 * parameter and its measured error differ, and not monotonically).
 */
async function martiniFigures(heights, width, height, target) {
  // A development dependency: an installation without it (npm ci --omit=dev) skips the comparison.
  const Martini = await import('@mapbox/martini').then((m) => m.default, () => null);
  if (!Martini) return { missing: `@mapbox/martini is not installed (${inCheckout() ? 'npm install --include=dev' : 'npm install @mapbox/martini'})` };
  let start = performance.now();
  const padded = padToPowerOfTwoPlusOne(heights, width, height);
  const padMs = performance.now() - start;

  start = performance.now();
  const coldMartini = new Martini(padded.size);
  const coldTile = coldMartini.createTile(padded.heights);
  const coldFirst = coldTile.getMesh(target);
  const coldMs = performance.now() - start;
  void coldFirst;

  const measure = (p) => gridMeshError(coldTile.getMesh(p), padded.heights, padded.size, heights, width, height).max;
  let lo = 0, hi = Math.max(target, 1e-3) * 2, searches = 0;
  while (measure(hi) <= target && hi < 1e5) {
    lo = hi;
    hi *= 2;
    searches += 1;
  }
  for (let i = 0; i < 30 && hi - lo > 1e-4 * Math.max(target, 1e-3); i++) {
    const mid = (lo + hi) / 2;
    if (measure(mid) <= target) lo = mid;
    else hi = mid;
    searches += 1;
  }
  // The measured error is not monotonic in the parameter: a few larger parameters may still
  // be within the target; the largest such is kept (fewer triangles for martini).
  let parameter = lo;
  for (let k = 1; k <= 8; k++) {
    const p = lo * (2 * Math.max(target, 1e-3) / Math.max(lo, 1e-6)) ** (k / 8);
    if (p > parameter && measure(p) <= target) parameter = p;
    searches += 1;
  }

  // Timed again warm (the JIT has compiled martini by now), with the matched parameter.
  start = performance.now();
  const martini = new Martini(padded.size);
  const tile = martini.createTile(padded.heights);
  const mesh = tile.getMesh(parameter);
  const firstMs = performance.now() - start;
  const error = gridMeshError(mesh, padded.heights, padded.size, heights, width, height, { quantiles: true });

  start = performance.now();
  const coarser = tile.getMesh(parameter * 2);
  const rebuildCoarserMs = performance.now() - start;
  start = performance.now();
  const finer = tile.getMesh(parameter / 2);
  const rebuildFinerMs = performance.now() - start;
  return {
    gridSize: padded.size,
    padMs,
    maxErrorParameter: parameter,
    searchSteps: searches,
    triangles: mesh.triangles.length / 3,
    trianglesOverField: martiniTrianglesOverField(mesh, width, height),
    vertices: mesh.vertices.length / 2,
    error,
    firstMeshColdMs: coldMs,
    firstMeshMs: firstMs,
    rebuildAtDoubleErrorMs: rebuildCoarserMs,
    rebuildAtDoubleErrorTriangles: coarser.triangles.length / 3,
    rebuildAtHalfErrorMs: rebuildFinerMs,
    rebuildAtHalfErrorTriangles: finer.triangles.length / 3,
  };
}

/**
 * The camera build/native/hexlod_bench --flight makes from an eye and a target (up +y, near
 * max(0.5 m, d / 10^4), far 1000 d, d the eye-target distance), so that both builds refine for
 * exactly the same views.
 */
function nativeStyleCamera(eye, target, settings) {
  const d = Math.hypot(target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]);
  const [width, height] = settings.viewport;
  return { eye, target, up: [0, 1, 0], tanHalfFovY: Math.tan((settings.fov * Math.PI) / 360), aspect: width / height,
    viewportHeight: height, near: Math.max(0.5, d * 1e-4), far: d * 1e3 };
}

/**
 * The speed comparison with the native build: the flight again without any budget (every frame
 * converges), from the base mesh, in WASM here and natively through
 *   hexlod_bench FILE.f32 WIDTH HEIGHT SPACING_X SPACING_Y --flight CAMERAS.txt --tau PX
 *     --budget-ms 0 --budget-ops 0 --viewport WxH --tan-half-fov T
 * (CAMERAS.txt: eye x y z and target x y z per line; exact embedding only). With a time budget
 * both builds would just fill it, so only unbudgeted updates compare the builds' speed.
 * Returns { missing } with the reason when the native flight cannot run.
 */
function nativeComparison(heights, terrain, path, settings) {
  if (settings.embedding !== 'exact') return { missing: 'hexlod_bench --flight refines the exact embedding only' };
  if (!existsSync(NATIVE_BENCH)) return { missing: inCheckout() ? `${NATIVE_BENCH} is not built (./build.sh native)` : 'the package has no native build (a checkout builds one: ./build.sh native)' };
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-bench-'));
  let output;
  try {
    const fieldPath = join(dir, 'field.f32');
    const camerasPath = join(dir, 'cameras.txt');
    writeFileSync(fieldPath, new Uint8Array(heights.buffer, heights.byteOffset, heights.byteLength));
    writeFileSync(camerasPath, path.cameras.map(({ eye, target }) => [...eye, ...target].join(' ')).join('\n') + '\n');
    const args = [fieldPath, String(terrain.width), String(terrain.height), String(terrain.spacingX), String(terrain.spacingY),
      '--flight', camerasPath, '--tau', String(settings.tau), '--budget-ms', '0', '--budget-ops', '0',
      '--viewport', settings.viewport.join('x'), '--tan-half-fov', String(Math.tan((settings.fov * Math.PI) / 360))];
    const run = spawnSync(NATIVE_BENCH, args, { encoding: 'utf8', maxBuffer: 1 << 26 });
    output = `${run.stdout ?? ''}`;
    if (run.status !== 0 || !output.includes('native flight:')) {
      const why = `${run.stderr ?? ''}${run.error?.message ?? ''}`.trim().split('\n')[0];
      return { missing: `build/native/hexlod_bench has no working --flight mode (${why || `exit ${run.status}`})` };
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
  const number = (pattern) => {
    const match = pattern.exec(output);
    return match ? Number(match[1]) : NaN;
  };
  const native = {
    updateMsP50: number(/update ms p50 ([\d.]+)/),
    updateMsP95: number(/update ms p50 [\d.]+ p95 ([\d.]+)/),
    streamMsP50: number(/stream ms p50 ([\d.]+)/),
    streamMsP95: number(/stream ms p50 [\d.]+ p95 ([\d.]+)/),
    trianglesP50: number(/triangles min \d+ p50 (\d+)/),
    splitsP50: number(/splits p50 (\d+)/),
    mergesP50: number(/merges p50 (\d+)/),
    bytesPerTriangle: number(/([\d.]+) B\/triangle/),
  };

  // The same flight in WASM, from the base mesh, without a budget.
  terrain.resetMesh('exact');
  terrain.configure({ tauPx: settings.tau, maxErrorM: 0 });
  terrain.configure({ budgetMs: 0, maxOperations: 0 });
  terrain.configure({ morphFrames: 0 });
  const updateMs = [], streamMs = [], triangles = [];
  for (const { eye, target } of path.cameras) {
    terrain.setLodCamera(nativeStyleCamera(eye, target, settings));
    terrain.updateLod();
    updateMs.push(terrain.query().updateMs);
    const start = performance.now();
    terrain.updateStream();
    streamMs.push(performance.now() - start);
    triangles.push(terrain.query().triangles);
  }
  const wasm = {
    updateMsP50: quantile(updateMs, 0.5),
    updateMsP95: quantile(updateMs, 0.95),
    streamMsP50: quantile(streamMs, 0.5),
    streamMsP95: quantile(streamMs, 0.95),
    trianglesP50: quantile(triangles, 0.5),
  };
  return {
    native,
    wasm,
    ratios: {
      updateP50: wasm.updateMsP50 / native.updateMsP50,
      updateP95: wasm.updateMsP95 / native.updateMsP95,
      streamP50: wasm.streamMsP50 / native.streamMsP50,
    },
  };
}

/**
 * Puts the terrain where the flight starts: converged for the first camera, every blend done,
 * the popping meter primed; then sets the flight's budget.
 */
function startFlight(terrain, camera, settings, morphFrames) {
  terrain.resetMesh(settings.embedding);
  terrain.configure({ tauPx: settings.tau, maxErrorM: 0 });
  terrain.configure({ budgetMs: 0, maxOperations: 0 });
  terrain.configure({ morphFrames });
  terrain.configure({ noBackfaceCulling: !settings.backface });
  terrain.setLodCamera(camera);
  refineToConvergence(terrain);
  terrain.updateStream(); // blends start when the stream takes the new vertices, as in the page
  for (let i = 0; i <= morphFrames; i++) {
    terrain.updateLod();
    terrain.updateStream();
  }
  terrain.acknowledgeStream();
  terrain.measurePopping();
  terrain.configure({ budgetMs: settings.budgetMs, maxOperations: settings.budgetOps });
}

/** The flight with `morphFrames` blends: the largest vertex jump on screen, max and p99 of frames. */
function popping(terrain, cameras, settings, morphFrames) {
  startFlight(terrain, cameras[0], settings, morphFrames);
  const jumps = cameras.map((camera) => {
    terrain.setLodCamera(camera);
    terrain.updateLod();
    terrain.updateStream();
    return terrain.measurePopping().maxJumpPx;
  });
  return { max: Math.max(...jumps), p99: quantile(jumps, 0.99) };
}

export async function bench(args) {
  const settings = benchSettings(args);
  if (settings.help) {
    console.log(BENCH_USAGE);
    return;
  }
  const { terrain, field, spacingX, spacingY } = await loadForCommand(settings.file, settings.cellSize, settings.fileOptions);
  const { xMax, zMax } = extentOf(terrain);
  const heights = heightsInMetres(terrain, field);
  const path = flightPath(terrain, settings);
  const cameras = path.cameras.map(({ eye, target }) => cameraFor(terrain, eye, target, settings.fov, settings.viewport));
  const print = (line) => console.log(line);
  print(`${basename(settings.file)}: ${terrain.width} x ${terrain.height} samples, spacing ${spacingX} x ${spacingY} m, ` +
    `heights ${round(terrain.minHeight, 1)} .. ${round(terrain.maxHeight, 1)} m; ${settings.embedding} embedding`);

  // 1. From heights in memory to the first converged frame (the flight's first camera), twice:
  // the first run also pays for V8 tiering up the WASM code.
  const firstFrame = [];
  for (let run = 0; run < 2; run++) {
    const start = performance.now();
    terrain.resetMesh(settings.embedding);
    terrain.setLodCamera(cameras[0]);
    terrain.configure({ tauPx: settings.tau, maxErrorM: 0 });
    const refined = refineToConvergence(terrain);
    terrain.updateStream();
    const ms = performance.now() - start;
    firstFrame.push({ ms, updates: refined.updates, operations: refined.operations, converged: refined.converged,
      triangles: terrain.query().triangles, streamIndices: terrain.stream().indices.length });
  }

  // 2. The flight, from that converged mesh: per frame one budgeted update, then the stream,
  // as the page does; with geomorphing, and again without it for the popping figure.
  const withoutMorph = popping(terrain, cameras, settings, 0);
  const frames = [];
  const jumps = [];
  startFlight(terrain, cameras[0], settings, settings.morphFrames);
  for (let i = 0; i < cameras.length; i++) {
    terrain.setLodCamera(cameras[i]);
    const t0 = performance.now();
    const operations = terrain.updateLod();
    const t1 = performance.now();
    terrain.updateStream();
    const t2 = performance.now();
    const lod = { ...terrain.query() };
    const stream = terrain.stream();
    let uploadBytes = 0;
    for (let k = 1; k < stream.dirtyVertices.length; k += 2) uploadBytes += stream.dirtyVertices[k] * STREAM_VERTEX_BYTES;
    for (let k = 1; k < stream.dirtyIndices.length; k += 2) uploadBytes += stream.dirtyIndices[k] * 4;
    terrain.acknowledgeStream();
    jumps.push(terrain.measurePopping().maxJumpPx);
    const frame = {
      frame: i, updateMs: t1 - t0, coreUpdateMs: lod.updateMs, streamMs: t2 - t1, operations, uploadBytes,
      fullBytes: stream.vertexBytes.length + stream.indices.length * 4, popPx: jumps.at(-1),
      splits: lod.splits, merges: lod.merges, triangles: terrain.query().triangles, converged: lod.converged, tau: lod.tau,
      refined: lod.refined, fading: lod.pendingMerges > 0,
    };
    frames.push(frame);
    if (settings.verbose) {
      const [x, y, z] = cameras[i].eye;
      print(`frame ${String(i).padStart(4)}  eye ${x.toFixed(0)},${y.toFixed(0)},${z.toFixed(0)}  update ${frame.updateMs.toFixed(2)} ms  ` +
        `stream ${frame.streamMs.toFixed(2)} ms  ${frame.triangles} triangles  ${frame.splits} splits  ${frame.merges} merges` +
        `${frame.refined ? '  within tau' : ''}${frame.fading ? `  ${lod.pendingMerges} fades pending` : ''}`);
    }
  }
  const col = (key) => frames.map((f) => f[key]);
  const perMillion = frames.map((f) => f.updateMs / Math.max(f.triangles / 1e6, 1e-6));
  const flight = {
    frames: frames.length,
    step: path.step,
    headingDeg: (path.heading * 180) / Math.PI,
    budgetMs: settings.budgetMs,
    budgetOps: settings.budgetOps,
    updateMsP50: quantile(col('updateMs'), 0.5),
    updateMsP95: quantile(col('updateMs'), 0.95),
    updateMsMax: Math.max(...col('updateMs')),
    streamMsP50: quantile(col('streamMs'), 0.5),
    streamMsP95: quantile(col('streamMs'), 0.95),
    trianglesMin: Math.min(...col('triangles')),
    trianglesP50: quantile(col('triangles'), 0.5),
    trianglesMax: Math.max(...col('triangles')),
    splitsP50: quantile(col('splits'), 0.5),
    splitsMax: Math.max(...col('splits')),
    mergesP50: quantile(col('merges'), 0.5),
    mergesMax: Math.max(...col('merges')),
    // Within tau: the update resolved every failing test. Fades pending: merges wait for their
    // vertices to fade out, the mesh finer than needed meanwhile (§7); neither says the other.
    withinTauFrames: frames.filter((f) => f.refined).length,
    fadingFrames: frames.filter((f) => f.fading).length,
    convergedFrames: frames.filter((f) => f.converged).length,
    updateMsPerMillionTrianglesP95: quantile(perMillion, 0.95),
    uploadBytesP50: quantile(col('uploadBytes'), 0.5),
    uploadBytesP95: quantile(col('uploadBytes'), 0.95),
    fullStreamBytesP50: quantile(col('fullBytes'), 0.5),
    morphFrames: settings.morphFrames,
    poppingMaxPx: Math.max(...jumps),
    poppingP99Px: quantile(jumps, 0.99),
    poppingWithoutMorphMaxPx: withoutMorph.max,
    poppingWithoutMorphP99Px: withoutMorph.p99,
  };

  // 3. View-independent: ours to a max error, measured on the original samples.
  const start = performance.now();
  terrain.resetMesh(settings.embedding);
  terrain.configure({ morphFrames: 0 });
  terrain.configure({ maxErrorM: settings.maxError });
  const refined = refineToConvergence(terrain);
  terrain.updateStream();
  const oursMs = performance.now() - start;
  const oursTriangles = terrain.query().triangles;
  const oursOverField = trianglesOverField(terrain, xMax, zMax);
  const oursError = terrain.measureError(false);
  const ours = { maxError: settings.maxError, ms: oursMs, updates: refined.updates, converged: refined.converged,
    triangles: oursTriangles, trianglesOverField: oursOverField, error: oursError };

  // 4. martini on the same heights, at our measured max error.
  const martini = await martiniFigures(heights, terrain.width, terrain.height, oursError.max);

  // 5. WASM against the native build on the same flight, both without a budget.
  const native = settings.native ? nativeComparison(heights, terrain, path, settings) : { missing: 'skipped (--no-native)' };

  const ms = (v) => `${v.toFixed(2)} ms`;
  const kb = (bytes) => `${(bytes / 1024).toFixed(1)} KB`;
  const [cold, warm] = firstFrame;
  const budget = [settings.budgetMs > 0 && `${settings.budgetMs} ms`, settings.budgetOps > 0 && `${settings.budgetOps} operations`]
    .filter(Boolean).join(' and ') || 'none';
  print(`flight    ${flight.frames} frames, ${round(flight.step, 1)} m per frame at ${settings.altitude} m above the ground, ` +
    `${settings.viewport.join('x')} px, fov ${settings.fov} deg, tau ${settings.tau} px, budget ${budget} per update`);
  print(`  update  p50 ${ms(flight.updateMsP50)}, p95 ${ms(flight.updateMsP95)}, max ${ms(flight.updateMsMax)}; ` +
    `p95 per million triangles ${ms(flight.updateMsPerMillionTrianglesP95)}`);
  print(`  stream  p50 ${ms(flight.streamMsP50)}, p95 ${ms(flight.streamMsP95)}; uploaded per frame p50 ` +
    `${kb(flight.uploadBytesP50)}, p95 ${kb(flight.uploadBytesP95)} of ${kb(flight.fullStreamBytesP50)} in the whole stream`);
  print(`  popping largest vertex jump ${round(flight.poppingMaxPx, 3)} px (p99 of frames ${round(flight.poppingP99Px, 3)} px) ` +
    `with geomorphing over ${settings.morphFrames} frames; ${round(flight.poppingWithoutMorphMaxPx, 3)} px ` +
    `(p99 ${round(flight.poppingWithoutMorphP99Px, 3)} px) without`);
  print(`  mesh    triangles min ${flight.trianglesMin}, p50 ${flight.trianglesP50}, max ${flight.trianglesMax}; ` +
    `splits per frame p50 ${flight.splitsP50}, max ${flight.splitsMax}; merges p50 ${flight.mergesP50}, max ${flight.mergesMax}; ` +
    `within tau in ${flight.withinTauFrames} of ${flight.frames} frames, fades pending in ${flight.fadingFrames}, ` +
    `both settled in ${flight.convergedFrames}`);
  print(`first frame  heights in memory to a converged view (${warm.updates} update${warm.updates === 1 ? '' : 's'}, ` +
    `${warm.triangles} triangles${warm.converged ? '' : ', NOT converged'}): ${ms(warm.ms)} (first run ${ms(cold.ms)})`);
  print(`max error  ours at ${settings.maxError} m: ${oursTriangles} triangles (${oursOverField} over the field), ` +
    `measured max ${round(oursError.max, 3)} m, p99 ${round(oursError.p99, 3)} m; from heights in ${ms(oursMs)}`);
  if (martini.missing) print(`martini   NOT COMPARED: ${martini.missing}`);
  else {
    print(`martini   ${martini.gridSize}^2 grid (padding ${ms(martini.padMs)}); maxError ${round(martini.maxErrorParameter, 4)} ` +
      `gives measured max ${round(martini.error.max, 3)} m <= ours, p99 ${round(martini.error.p99, 3)} m: ` +
      `${martini.triangles} triangles (${martini.trianglesOverField} over the field)`);
    print(`  ratio   triangles ours / martini ${round(oursTriangles / martini.triangles, 3)} ` +
      `(over the field ${round(oursOverField / martini.trianglesOverField, 3)})`);
    print(`  time    new Martini + createTile + getMesh ${ms(martini.firstMeshMs)} (first run ${ms(martini.firstMeshColdMs)}); ` +
      `getMesh again at 2x error ${ms(martini.rebuildAtDoubleErrorMs)}, at half ${ms(martini.rebuildAtHalfErrorMs)}`);
    print(`  ratio   our first converged frame / martini first mesh ${round(warm.ms / martini.firstMeshMs, 3)}; ` +
      `our max-error mesh / martini first mesh ${round(oursMs / martini.firstMeshMs, 3)}`);
  }
  if (native.missing) {
    print(`native    NATIVE FLIGHT NOT MEASURED: ${native.missing}; WASM/native ratio unavailable`);
  } else {
    const { wasm, native: n, ratios } = native;
    print(`native    the same flight without a budget (every frame converges, from the base mesh; core-timed updates):`);
    print(`  update  WASM p50 ${ms(wasm.updateMsP50)}, p95 ${ms(wasm.updateMsP95)}; native p50 ${ms(n.updateMsP50)}, p95 ${ms(n.updateMsP95)}; ` +
      `WASM/native p50 ${round(ratios.updateP50, 2)}, p95 ${round(ratios.updateP95, 2)}`);
    print(`  stream  WASM p50 ${ms(wasm.streamMsP50)}; native p50 ${ms(n.streamMsP50)}; WASM/native ${round(ratios.streamP50, 2)} ` +
      `(triangles p50: WASM ${wasm.trianglesP50}, native ${n.trianglesP50})`);
  }

  if (settings.json) {
    const report = {
      file: basename(settings.file), width: terrain.width, height: terrain.height, spacingX, spacingY,
      settings: { ...settings, json: undefined, verbose: undefined, file: undefined },
      firstFrame: { cold, warm },
      flight,
      frames,
      maxError: ours,
      martini,
      ratios: {
        trianglesOursOverMartini: martini.missing ? null : oursTriangles / martini.triangles,
        trianglesOverFieldOursOverMartini: martini.missing ? null : oursOverField / martini.trianglesOverField,
        firstConvergedFrameOverMartiniFirstMesh: martini.missing ? null : warm.ms / martini.firstMeshMs,
        maxErrorMeshOverMartiniFirstMesh: martini.missing ? null : oursMs / martini.firstMeshMs,
        wasmOverNativeUpdateP50: native.missing ? null : native.ratios.updateP50,
        wasmOverNativeUpdateP95: native.missing ? null : native.ratios.updateP95,
        wasmOverNativeStreamP50: native.missing ? null : native.ratios.streamP50,
      },
      native,
    };
    writeFileSync(settings.json, JSON.stringify(report, null, 1) + '\n');
  }
}
