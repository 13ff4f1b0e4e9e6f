// Pieces shared by the hexlod commands: argument parsing with one-line errors, reading a
// height field and its sidecar, loading it into the WASM core, and the camera of
// view-dependent refinement.
import { readFileSync, readdirSync, existsSync, statSync } from 'node:fs';
import { basename, extname, join, dirname } from 'node:path';
import { createNodeCore } from './node_core.js';
import { loadTerrain } from '../web/loaders/terrain_source.js';
import { crsSidecarNames } from '../web/geo/sidecar_names.js';

/** A mistake in the command line (exit code 2); its message is one line. */
export class UsageError extends Error {}

/**
 * Parses `--name value`, `--name=value`, boolean `--name`, and positionals. Unlike
 * util.parseArgs, a value may start with '-' (a negative coordinate), since every option
 * declared with a value always takes the next argument.
 * @param {string[]} args
 * @param {Record<string, 'string'|'boolean'>} spec option name (without --) -> kind
 * @returns {{values: Record<string, string|boolean>, positionals: string[]}}
 */
export function parseOptions(args, spec) {
  const values = {}, positionals = [];
  for (let i = 0; i < args.length; i++) {
    const arg = args[i];
    if (arg === '--') {
      positionals.push(...args.slice(i + 1));
      break;
    }
    if (arg === '-h') {
      values.help = true;
      continue;
    }
    if (!arg.startsWith('--') || arg === '-') {
      if (arg.startsWith('-') && arg !== '-') throw new UsageError(`unknown option '${arg}'`);
      positionals.push(arg);
      continue;
    }
    const eq = arg.indexOf('=');
    const name = arg.slice(2, eq < 0 ? undefined : eq);
    const kind = name === 'help' ? 'boolean' : spec[name];
    if (!kind) throw new UsageError(`unknown option '--${name}'`);
    if (Object.hasOwn(values, name)) throw new UsageError(`--${name} given twice`);
    if (kind === 'boolean') {
      if (eq >= 0) throw new UsageError(`--${name} takes no value`);
      values[name] = true;
    } else if (eq >= 0) {
      values[name] = arg.slice(eq + 1);
    } else {
      if (i + 1 >= args.length) throw new UsageError(`--${name} needs a value`);
      values[name] = args[++i];
    }
  }
  return { values, positionals };
}

/** A finite number from an option value; `check` says what else it must satisfy. */
export function parseNumber(name, text, { min = -Infinity, exclusiveMin = false, max = Infinity, integer = false } = {}) {
  const value = text.trim() === '' ? NaN : Number(text);
  const what = integer ? 'an integer' : 'a number';
  if (!Number.isFinite(value) || (integer && !Number.isInteger(value))) {
    throw new UsageError(`--${name} must be ${what}, got '${text}'`);
  }
  if (exclusiveMin ? value <= min : value < min) {
    throw new UsageError(`--${name} must be ${exclusiveMin ? 'greater than' : 'at least'} ${min}, got '${text}'`);
  }
  if (value > max) throw new UsageError(`--${name} must be at most ${max}, got '${text}'`);
  return value;
}

/** Three finite numbers X,Y,Z. */
export function parseTriple(name, text) {
  const parts = text.split(',');
  const numbers = parts.map((p) => (p.trim() === '' ? NaN : Number(p)));
  if (parts.length !== 3 || !numbers.every(Number.isFinite)) {
    throw new UsageError(`--${name} must be three numbers X,Y,Z in metres, got '${text}'`);
  }
  return numbers;
}

/** A viewport WxH in pixels, both positive integers. */
export function parseViewport(text) {
  const match = /^(\d+)x(\d+)$/i.exec(text.trim());
  const width = match ? Number(match[1]) : 0, height = match ? Number(match[2]) : 0;
  if (!match || width < 1 || height < 1 || width > 1e5 || height > 1e5) {
    throw new UsageError(`--viewport must be WIDTHxHEIGHT in pixels, both from 1 to 100000, got '${text}'`);
  }
  return [width, height];
}

/** Cell size DX[,DY] in metres, both positive. */
export function parseCellSize(text) {
  const parts = text.split(',');
  const numbers = parts.map((p) => (p.trim() === '' ? NaN : Number(p)));
  if (parts.length > 2 || !numbers.every((n) => Number.isFinite(n) && n > 0)) {
    throw new UsageError(`--cell-size must be DX or DX,DY in metres, positive, got '${text}'`);
  }
  return { x: numbers[0], y: numbers[1] ?? numbers[0] };
}

/** 'shifted' or 'exact'. */
export function parseEmbedding(text = 'exact') {
  if (text !== 'shifted' && text !== 'exact') {
    throw new UsageError(`--embedding must be 'shifted' or 'exact', got '${text}'`);
  }
  return text;
}

/** Options of every command that say how to read the file (RAW size, PNG colour encoding). */
export const FILE_OPTIONS = { width: 'string', height: 'string', encoding: 'string' };
export const FILE_USAGE = `  --width N, --height N  size of a RAW/R16 file (a square one is inferred)
  --encoding E          heights of an RGB PNG: terrain-rgb or terrarium (default: from the name or colours)`;

/** { width, height, encoding } for the loaders from parsed option values; throws UsageError. */
export function parseFileOptions(values) {
  const size = (name) => (values[name] !== undefined ? parseNumber(name, values[name], { min: 1, integer: true, max: 2 ** 31 - 1 }) : undefined);
  const encoding = values.encoding ?? 'auto';
  if (!['auto', 'terrain-rgb', 'terrarium'].includes(encoding)) {
    throw new UsageError(`--encoding must be terrain-rgb or terrarium, got '${encoding}'`);
  }
  return { width: size('width'), height: size('height'), encoding };
}

/**
 * The file and, when they sit beside it, its .json sidecar, its .prj and its GDAL .aux.xml
 * (x.prj, x.tif.aux.xml or x.aux.xml: web/geo/sidecar_names.js), as loader inputs.
 */
export function readInputs(path) {
  if (!existsSync(path)) throw new Error(`${path}: no such file`);
  if (!statSync(path).isFile()) throw new Error(`${path}: not a file`);
  const files = [{ name: basename(path), bytes: new Uint8Array(readFileSync(path)) }];
  const sidecar = join(dirname(path), basename(path, extname(path)) + '.json');
  if (extname(path).toLowerCase() !== '.json' && existsSync(sidecar)) {
    files.push({ name: basename(sidecar), bytes: new Uint8Array(readFileSync(sidecar)) });
  }
  if (!/\.(json|prj|xml)$/i.test(path)) {
    const beside = besideFile(path), { prj, auxXml } = crsSidecarNames(basename(path));
    for (const found of [beside(prj), beside(auxXml)]) {
      if (found !== null) files.push({ name: basename(found), bytes: new Uint8Array(readFileSync(found)) });
    }
  }
  return files;
}

/**
 * Loads a height field into a new WASM core, with the cell size of the file, or `cellSize`
 * when given. Warns on stderr when neither gives one.
 * @param {string|string[]} paths one file (its sidecar is read from beside it), or the tiles of
 *   a mosaic (no sidecars: the tiles place themselves)
 * @returns {Promise<{core, terrain, field, missing, loadMs, spacingX: number, spacingY: number}>}
 */
export async function loadForCommand(paths, cellSize, fileOptions = {}) {
  const list = [].concat(paths);
  const files = list.length === 1 ? readInputs(list[0]) : list.map((path) => readInputs(path)[0]);
  const core = await createNodeCore();
  const loaded = await loadFiles(core, files, { ...fileOptions, ...(cellSize ? { spacing: cellSize } : {}) });
  if (!cellSize && !loaded.field.spacingFromFile) {
    console.error(`hexlod: warning: ${loaded.field.source} has no cell size; using 1 m, set --cell-size`);
  }
  return { core, ...loaded, spacingX: loaded.terrain.spacingX, spacingY: loaded.terrain.spacingY };
}

/** loadTerrain, with the flags named when a RAW file needs its size. */
export async function loadFiles(core, files, options) {
  try {
    return await loadTerrain(core, files, options);
  } catch (error) {
    if (error.needsSize) error.message += ' (--width and --height)';
    throw error;
  }
}

/**
 * (names) -> the path of the first of them that lies beside `path`, else null. Names match in
 * any case: a file written elsewhere may be X.JGW or X.PRJ.
 */
export function besideFile(path) {
  const folder = dirname(path);
  const present = new Map(readdirSync(folder).map((n) => [n.toLowerCase(), n]));
  return (names) => {
    const found = names.map((n) => present.get(n.toLowerCase())).find((n) => n !== undefined && statSync(join(folder, n)).isFile());
    return found === undefined ? null : join(folder, found);
  };
}

/** Metres east and south from the first sample to the last column and row. */
export function extentOf(terrain) {
  return { xMax: (terrain.width - 1) * terrain.spacingX, zMax: (terrain.height - 1) * terrain.spacingY };
}

/**
 * The camera given to the core for an eye looking at a target: +y up (north up when looking
 * straight down), near = max(0.1 m, eye-target distance / 10^4), far = 10 times the distance
 * from the eye to the farthest corner of the field's box (heights included), so the whole
 * field is always inside.
 * @returns {{eye, target, up, fovY, tanHalfFovY, aspect, viewportHeight, near, far}}
 */
export function cameraFor(terrain, eye, target, fovDeg, [width, height]) {
  const d = [target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]];
  const distance = Math.hypot(...d);
  const horizontal = Math.hypot(d[0], d[2]);
  const up = horizontal <= 1e-3 * distance ? [0, 0, -1] : [0, 1, 0];
  const { xMax, zMax } = extentOf(terrain);
  let farthest = 0;
  for (const x of [0, xMax]) {
    for (const z of [0, zMax]) {
      for (const y of [terrain.minHeight, terrain.maxHeight]) {
        farthest = Math.max(farthest, Math.hypot(x - eye[0], y - eye[1], z - eye[2]));
      }
    }
  }
  const fovY = (fovDeg * Math.PI) / 180;
  return {
    eye,
    target,
    up,
    fovY,
    tanHalfFovY: Math.tan(fovY / 2),
    aspect: width / height,
    viewportHeight: height,
    near: Math.max(0.1, distance / 1e4),
    far: 10 * Math.max(farthest, distance, 1),
  };
}

/** The highest level with a non-empty range in the stream's level offsets (-1 if none). */
export function highestLevel(levelOffsets) {
  for (let level = levelOffsets.length - 2; level >= 0; level--) {
    if (levelOffsets[level + 1] > levelOffsets[level]) return level;
  }
  return -1;
}

/** The value at quantile q (0..1) of numbers, nearest rank. */
export function quantile(values, q) {
  if (values.length === 0) return NaN;
  const sorted = Float64Array.from(values).sort();
  return sorted[Math.min(sorted.length - 1, Math.max(0, Math.ceil(q * sorted.length) - 1))];
}

/** A number with `digits` decimals, as a number (for JSON). */
export const round = (value, digits = 3) => (Number.isFinite(value) ? Number(value.toFixed(digits)) : value);
