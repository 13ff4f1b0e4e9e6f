// hexlod mesh: refines the hexagon mesh of a height field (view-independent to a maximum error,
// or for a camera) with the page's loaders and WASM core, and writes it as OBJ and figures as
// JSON.
import { writeFileSync } from 'node:fs';
import { basename } from 'node:path';
import {
  UsageError, parseOptions, parseNumber, parseTriple, parseViewport, parseCellSize, parseEmbedding,
  loadForCommand, FILE_OPTIONS, FILE_USAGE, parseFileOptions, extentOf, cameraFor, highestLevel, round,
} from './cli_common.js';
import { decodeFans, resolveDegenerate, clipToRectangle, writeObj } from './mesh_export.js';
import { RESTART_INDEX, STREAM_VERTEX_WORDS } from '../web/core/core.js';

export const MESH_USAGE = `usage: hexlod mesh <heightfield> (--max-error M | --camera X,Y,Z --target X,Y,Z) [options]
  Refines the hexagon mesh until it converges (or for --budget-splits operations), prints a
  summary, and writes the mesh clipped to the data rectangle as OBJ and its figures as JSON.
  --max-error M         view-independent: every sample within M metres of the mesh
  --camera X,Y,Z        view-dependent: the eye, in metres (x east from the first column,
  --target X,Y,Z          y up = height, z south from the first row); --target is required
  --fov DEG             vertical field of view in degrees (default 60)
  --viewport WxH        viewport in pixels (default 1920x1080)
  --tau PX              screen-space error tolerance in pixels (default 1)
                        near plane: max(0.1 m, eye-target distance / 10000); far plane: 10 x
                        the distance from the eye to the field's farthest corner
  --cell-size DX[,DY]   metres between columns (and rows); default: from the file, else 1
  --budget-splits N     stop after one update of at most N operations (default: update until
                        converged, at most ${10000} updates)
  --embedding E         lattice embedding: exact (default) or shifted (the paper's)
  --obj FILE            write the mesh as Wavefront OBJ (y up, faces counter-clockwise from +y)
  --json FILE           write every figure as JSON
${FILE_USAGE}`;

const OPTIONS = {
  'max-error': 'string', camera: 'string', target: 'string', fov: 'string', viewport: 'string', tau: 'string',
  'cell-size': 'string', 'budget-splits': 'string', embedding: 'string', obj: 'string', json: 'string',
  ...FILE_OPTIONS,
};
const MAX_UPDATES = 10000;

/** Checks the command line and turns it into settings; throws UsageError. */
export function meshSettings(args) {
  const { values, positionals } = parseOptions(args, OPTIONS);
  if (values.help) return { help: true };
  if (positionals.length !== 1) {
    throw new UsageError(positionals.length === 0 ? 'mesh needs a height field file' : 'mesh takes exactly one height field file');
  }
  const hasError = values['max-error'] !== undefined, hasCamera = values.camera !== undefined;
  if (hasError === hasCamera) {
    throw new UsageError(hasError ? 'give either --max-error or --camera, not both' : 'give --max-error M or --camera X,Y,Z with --target X,Y,Z');
  }
  if (!hasCamera) {
    for (const name of ['target', 'fov', 'viewport', 'tau']) {
      if (values[name] !== undefined) throw new UsageError(`--${name} goes with --camera, not --max-error`);
    }
  } else if (values.target === undefined) {
    throw new UsageError('--camera needs --target X,Y,Z');
  }
  const settings = {
    file: positionals[0],
    mode: hasCamera ? 'view' : 'max-error',
    embedding: parseEmbedding(values.embedding),
    cellSize: values['cell-size'] !== undefined ? parseCellSize(values['cell-size']) : null,
    fileOptions: parseFileOptions(values),
    budgetSplits: values['budget-splits'] !== undefined
      ? parseNumber('budget-splits', values['budget-splits'], { min: 1, integer: true, max: 2 ** 31 - 1 }) : null,
    obj: values.obj ?? null,
    json: values.json ?? null,
  };
  if (hasError) {
    settings.maxError = parseNumber('max-error', values['max-error'], { min: 0, exclusiveMin: true });
  } else {
    settings.eye = parseTriple('camera', values.camera);
    settings.target = parseTriple('target', values.target);
    if (settings.eye.every((v, i) => v === settings.target[i])) throw new UsageError('--camera and --target are the same point');
    settings.fov = values.fov !== undefined ? parseNumber('fov', values.fov, { min: 0, exclusiveMin: true, max: 179 }) : 60;
    settings.viewport = values.viewport !== undefined ? parseViewport(values.viewport) : [1920, 1080];
    settings.tau = values.tau !== undefined ? parseNumber('tau', values.tau, { min: 0, exclusiveMin: true }) : 1;
  }
  for (const name of ['obj', 'json']) {
    if (settings[name] === '') throw new UsageError(`--${name} needs a file name`);
  }
  return settings;
}

/**
 * Refines as the settings say: resets the mesh, sets the mode, then either one update of at
 * most budgetSplits operations or updates until converged (at most MAX_UPDATES).
 * @returns {{updates, operations, splits, merges, converged, refineMs, coreMs, camera}}
 */
export function refine(terrain, settings) {
  terrain.resetMesh(settings.embedding);
  let camera = null;
  if (settings.mode === 'view') {
    camera = cameraFor(terrain, settings.eye, settings.target, settings.fov, settings.viewport);
    terrain.setLodCamera(camera);
    terrain.configure({ tauPx: settings.tau, maxErrorM: 0 });
  } else {
    terrain.configure({ maxErrorM: settings.maxError });
  }
  terrain.configure({ budgetMs: 0, maxOperations: settings.budgetSplits ?? 0 });
  const run = { updates: 0, operations: 0, splits: 0, merges: 0, converged: false, refineMs: 0, coreMs: 0, camera };
  const limit = settings.budgetSplits !== null ? 1 : MAX_UPDATES;
  while (run.updates < limit) {
    const start = performance.now();
    const operations = terrain.updateLod();
    run.refineMs += performance.now() - start;
    const figures = terrain.lodStats();
    run.updates += 1;
    run.operations += operations;
    run.splits += figures.splits;
    run.merges += figures.merges;
    run.coreMs += figures.updateMs;
    run.converged = figures.converged;
    if (run.converged) break;
  }
  return run;
}

/** Triangles and cells per level, from the fan stream's level offsets. */
function levelFigures(indices, levelOffsets) {
  const levels = [];
  for (let level = 0; level + 1 < levelOffsets.length; level++) {
    let cells = 0, triangles = 0, length = 0;
    for (let i = levelOffsets[level]; i < levelOffsets[level + 1]; i++) {
      if (indices[i] === RESTART_INDEX) {
        cells += 1;
        triangles += Math.max(0, length - 2);
        length = 0;
      } else {
        length += 1;
      }
    }
    if (cells > 0) levels.push({ level, cells, triangles });
  }
  return levels;
}

export async function mesh(args) {
  const settings = meshSettings(args);
  if (settings.help) {
    console.log(MESH_USAGE);
    return;
  }
  const { terrain, field, spacingX, spacingY } = await loadForCommand(settings.file, settings.cellSize);
  const run = refine(terrain, settings);

  const stats = terrain.meshStats();
  // Copies: the views die at the next core call that grows memory.
  const levelView = terrain.levelView(false);
  const indices = levelView.indices.slice();
  const levelOffsets = Int32Array.from(levelView.levelOffsets);
  terrain.updateStream();
  const positions = terrain.stream().vertices.slice();
  const { triangles, fans } = decodeFans(indices);
  const levels = levelFigures(indices, levelOffsets);
  const bytes = terrain.meshStats().bytes; // now including the fan stream
  const hash = terrain.meshHash();
  const errorStored = terrain.measureError(true);
  const errorOriginal = terrain.measureError(false);

  const { xMax, zMax } = extentOf(terrain);
  const repaired = resolveDegenerate(positions, STREAM_VERTEX_WORDS, triangles);
  const clipped = clipToRectangle(positions, STREAM_VERTEX_WORDS, repaired.triangles, xMax, zMax);
  const name = basename(settings.file);
  if (settings.obj) {
    writeObj(settings.obj, clipped, [
      `hexlod mesh of ${name}: ${clipped.vertices.length / 3} vertices, ${clipped.faces.length / 3} triangles`,
      'metres: x east from the first column, y up (height), z south from the first row',
      `clipped to the data rectangle [0, ${xMax}] x [0, ${zMax}]; faces counter-clockwise seen from +y`,
    ], xMax, zMax);
  }

  const report = {
    file: name,
    width: terrain.width,
    height: terrain.height,
    spacingX,
    spacingY,
    spacingFromFile: settings.cellSize ? false : field.spacingFromFile,
    rectangle: { xMax, zMax },
    settings: {
      mode: settings.mode,
      embedding: settings.embedding,
      ...(settings.mode === 'max-error' ? { maxError: settings.maxError } : {
        camera: settings.eye,
        target: settings.target,
        up: run.camera.up,
        fovDeg: settings.fov,
        viewport: settings.viewport,
        tau: settings.tau,
        near: run.camera.near,
        far: run.camera.far,
      }),
      budgetSplits: settings.budgetSplits,
      maxUpdates: settings.budgetSplits !== null ? 1 : MAX_UPDATES,
      cellSize: settings.cellSize,
    },
    converged: run.converged,
    updates: run.updates,
    operations: run.operations,
    splits: run.splits,
    merges: run.merges,
    refineMs: round(run.refineMs),
    refineCoreMs: round(run.coreMs),
    triangles: {
      drawn: stats.triangles,
      afterClipping: clipped.faces.length / 3,
      keptWhole: clipped.inside,
      cut: clipped.clipped,
      droppedOutside: clipped.dropped,
      zeroArea: repaired.degenerate,
    },
    cells: {
      total: stats.cells,
      fullHexagons: fans.full,
      boundarySemiHexagons: fans.boundarySemi,
      interiorSemiHexagons: fans.interiorSemi,
      other: fans.other,
    },
    vertices: { mesh: stats.vertices, stream: positions.length / STREAM_VERTEX_WORDS, obj: clipped.vertices.length / 3 },
    maxLevel: highestLevel(levelOffsets),
    finestLevel: stats.maxLevel,
    levels,
    bytes,
    bytesPerTriangle: round(bytes / Math.max(1, stats.triangles), 2),
    error: {
      stored: errorStored,
      original: errorOriginal,
    },
    hash,
  };
  if (settings.json) writeFileSync(settings.json, JSON.stringify(report, null, 1) + '\n');

  const m = (v) => `${round(v, 3)} m`;
  const modeLine = settings.mode === 'max-error'
    ? `max error ${settings.maxError} m`
    : `camera ${settings.eye.join(',')} -> ${settings.target.join(',')}, fov ${settings.fov} deg, ` +
      `${settings.viewport.join('x')} px, tau ${settings.tau} px`;
  const refineLine = run.converged
    ? `converged after ${run.updates} update${run.updates === 1 ? '' : 's'}`
    : settings.budgetSplits !== null
      ? `stopped after 1 update (budget ${settings.budgetSplits} operations), not converged`
      : `NOT converged after ${run.updates} updates`;
  const lines = [
    `file      ${name}: ${terrain.width} x ${terrain.height} samples, spacing ${spacingX} x ${spacingY} m`,
    `mode      ${modeLine}, ${settings.embedding} embedding`,
    `refine    ${refineLine}: ${run.operations} operations (${run.splits} splits, ${run.merges} merges) in ${round(run.refineMs, 1)} ms`,
    `mesh      ${stats.triangles} triangles drawn, ${report.triangles.afterClipping} after clipping to the field; ` +
      `${stats.cells} cells (${fans.full} hexagons, ${fans.boundarySemi} boundary and ${fans.interiorSemi} interior semi-hexagons)`,
    `          ${stats.vertices} vertices; levels up to ${report.maxLevel} of ${stats.maxLevel}`,
    `memory    ${(bytes / 1048576).toFixed(2)} MB in the core, ${report.bytesPerTriangle} B per triangle`,
    `error     vs stored field: max ${m(errorStored.max)}, p99 ${m(errorStored.p99)}; ` +
      `vs original samples: max ${m(errorOriginal.max)}, p99 ${m(errorOriginal.p99)}`,
    `hash      ${hash}`,
  ];
  const written = [settings.obj && `${settings.obj} (${report.vertices.obj} vertices, ${report.triangles.afterClipping} faces)`, settings.json]
    .filter(Boolean);
  if (written.length) lines.push(`wrote     ${written.join(', ')}`);
  console.log(lines.join('\n'));
}
