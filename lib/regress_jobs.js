// Which flights `hexlod regress` runs: a height field and a flight, a flight that names its
// height field, or a folder of *.flight.json files, filtered by --grep. A flight file that cannot
// be used fails that flight alone (its error is kept on the job); the others still run.
import { existsSync, readFileSync, readdirSync, statSync } from 'node:fs';
import { basename, dirname, extname, join, resolve } from 'node:path';
import { UsageError } from './cli_common.js';
import { isUrl, resolveDem } from './dem_source.js';
import { parseFlight } from '../web/app/deterministic/flight.js';

/** Bad input that stops the whole run (exit code 2), e.g. a folder with no flights. */
export class InputError extends Error {}

const DEM_EXTENSIONS = ['.png', '.tif', '.tiff', '.hgt', '.asc', '.pgm', '.r16', '.raw', '.f32'];

/** The flight's name: its file name without .flight.json or .json. */
export const flightName = (path) => basename(path).replace(/(\.flight)?\.json$/i, '');

/** A flight file parsed and checked; throws one line naming the file (and the key). */
function readFlight(path) {
  if (!existsSync(path)) throw new Error(`${path}: no such file`);
  let json;
  try {
    json = JSON.parse(readFileSync(path, 'utf8'));
  } catch (error) {
    throw new Error(`${path}: not valid JSON (${error.message})`);
  }
  return parseFlight(json, path);
}

/** The height field of a flight found in a folder or given alone: its "dem", or NAME.png (.tif, ...) beside it. */
function demOf(flightPath, flight) {
  if (flight.dem) return resolveDem(flight.dem, dirname(flightPath));
  const base = join(dirname(flightPath), flightName(flightPath));
  const found = DEM_EXTENSIONS.map((e) => base + e).find((p) => existsSync(p));
  if (!found) throw new Error(`${flightPath}: no "dem" key and no height field ${base}.png (or .tif, ...) beside it`);
  return found;
}

/** A job for one flight file; a problem with it becomes the job's error, not an exception. */
function jobFor(flightPath, demSource) {
  const job = { name: flightName(flightPath), flightPath: resolve(flightPath), source: null, layers: [], overlays: [], track: null, flight: null, error: null };
  try {
    job.flight = readFlight(flightPath);
    job.source = demSource ?? demOf(flightPath, job.flight);
    if (!isUrl(job.source) && !existsSync(job.source)) throw new Error(`${flightPath}: its height field ${job.source}: no such file`);
    // Each image layer's image and world file, like the height field, relative to the flight file.
    const beside = (text) => (text === null ? null : resolveDem(text, dirname(flightPath)));
    job.layers = job.flight.layers.map((layer) => (layer.kind === 'image' ? { ...layer, image: beside(layer.image), worldFile: beside(layer.worldFile) } : layer));
    for (const layer of job.layers.filter((l) => l.kind === 'image')) {
      for (const [what, path] of [['image', layer.image], ['world file', layer.worldFile]]) {
        if (path !== null && !isUrl(path) && !existsSync(path)) throw new Error(`${flightPath}: its ${what} ${path}: no such file`);
      }
    }
    // Its overlays and its track, likewise.
    job.overlays = job.flight.overlays.map(beside);
    job.track = job.flight.track ? beside(job.flight.track.file) : null;
    for (const [what, path] of [...job.overlays.map((p) => ['overlay', p]), ...(job.track ? [['track', job.track]] : [])]) {
      if (!isUrl(path) && !existsSync(path)) throw new Error(`${flightPath}: its ${what} ${path}: no such file`);
    }
  } catch (error) {
    job.error = String(error.message).split('\n')[0];
  }
  return job;
}

/**
 * The flights to run, in name order: [{name, flightPath, source, flight, error}].
 * @param {string[]} positionals the command's arguments
 * @param {RegExp|null} grep keep the flights whose name it matches
 * @throws UsageError for arguments of the wrong shape, InputError when nothing can run
 */
export function collectJobs(positionals, grep = null) {
  if (positionals.length === 0) throw new UsageError('regress needs a height field and a flight, a flight, or a folder');
  if (positionals.length > 2) throw new UsageError('regress takes a height field and a flight, a flight, or a folder');
  const local = positionals.filter((p) => !isUrl(p));
  for (const p of local) if (!existsSync(p)) throw new InputError(`${p}: no such file or folder`);
  let jobs;
  if (positionals.length === 2) {
    const [dem, flightPath] = positionals;
    if (isUrl(flightPath)) throw new UsageError(`${flightPath}: give the flight as a file (a URL may name the height field)`);
    if (!isUrl(dem) && statSync(dem).isDirectory()) throw new UsageError(`${dem} is a folder: give a folder alone`);
    jobs = [jobFor(flightPath, isUrl(dem) ? resolveDem(dem, '.') : resolve(dem))];
  } else if (isUrl(positionals[0])) {
    throw new UsageError(`${positionals[0]}: give a flight file with the height field's URL`);
  } else if (statSync(positionals[0]).isDirectory()) {
    const folder = positionals[0];
    const files = readdirSync(folder).filter((f) => f.toLowerCase().endsWith('.flight.json')).sort();
    if (files.length === 0) throw new InputError(`${folder}: no *.flight.json files in it`);
    jobs = files.map((f) => (grep && !grep.test(flightName(f)) ? null : jobFor(join(folder, f)))).filter(Boolean);
    if (jobs.length === 0) throw new InputError(`no flight in ${folder} matches --grep ${grep.source} (${files.map(flightName).join(', ')})`);
    return jobs;
  } else {
    const flightPath = positionals[0];
    if (extname(flightPath).toLowerCase() !== '.json') throw new UsageError(`${flightPath}: give a flight (.json) with it, or a flight that names its height field`);
    jobs = [jobFor(flightPath)];
  }
  if (grep && !grep.test(jobs[0].name)) throw new InputError(`the flight ${jobs[0].name} does not match --grep ${grep.source}`);
  return jobs;
}
