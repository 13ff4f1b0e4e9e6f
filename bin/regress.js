// hexlod regress: scripted flights (web/app/deterministic/flight.js) over height fields, flown in
// headless Chromium in the page's deterministic mode and replayed in Node on the same WASM core;
// compared with stored references: per-frame mesh hashes and figures exactly (and the page with
// Node), screenshots with a tolerance. Writes new images, diffs, figures, a text summary and an
// HTML report; --update writes the references instead.
import { existsSync, readFileSync, readdirSync, statSync, mkdirSync, writeFileSync, copyFileSync, rmSync } from 'node:fs';
import { basename, dirname, extname, join, relative, resolve } from 'node:path';
import { UsageError, parseOptions, parseNumber, readInputs } from './cli_common.js';
import { createNodeCore } from './node_core.js';
import { loadTerrain } from '../web/loaders/terrain_source.js';
import { parseFlight, replayFlight, FlightError } from '../web/app/deterministic/flight.js';
import { compareStats, compareImages, readPng, writePng, htmlReport, flightLine } from './regress_compare.js';

export const DEFAULT_THRESHOLD = 8;    // channel difference (of 255) above which a pixel differs
export const DEFAULT_MAX_SHARE = 0.002; // share of differing pixels above which a capture regresses

export const REGRESS_USAGE = `usage: hexlod regress <heightfield> <flight.json> [options]
       hexlod regress <flight.json> [options]     (the flight names its height field: "dem")
       hexlod regress <folder> [options]          (every *.flight.json in it)
  Flies each flight in headless Chromium (the page's deterministic mode: ?flight=, README),
  replays it in Node on the same WASM core, and compares with the references: the mesh hash,
  triangle count and other figures of every frame exactly (and the page with Node), the
  captured frames' pixels with a tolerance. Exit code 1 on any regression.
  A flight without "dem" in a folder uses the height field beside it with the same name
  (NAME.flight.json and NAME.png, .tif, ...).
  --refs DIR        references (default: refs/ beside the flight files); one folder per flight
  --out DIR         new screenshots, diffs, figures, summary.txt and report.html
                    (default: regress-out/ in the current directory)
  --update          write the new results as the references (no comparison)
  --threshold N     a pixel differs when a channel differs by more than N of 255 (default ${DEFAULT_THRESHOLD})
  --max-share F     a capture regresses when more than this share of its pixels differ
                    (default ${DEFAULT_MAX_SHARE}, i.e. ${DEFAULT_MAX_SHARE * 100} %)
  --node-only       only the Node replay and its figures (no browser, no pixels)
  --chromium PATH   the browser (default: $CHROMIUM_PATH or /usr/bin/chromium)`;

const OPTIONS = { refs: 'string', out: 'string', update: 'boolean', threshold: 'string', 'max-share': 'string',
  'node-only': 'boolean', chromium: 'string' };
const DEM_EXTENSIONS = ['.png', '.tif', '.tiff', '.hgt', '.asc', '.pgm', '.r16', '.raw', '.f32'];

/** The flight's name: its file name without .flight.json or .json. */
const flightName = (path) => basename(path).replace(/(\.flight)?\.json$/i, '');

function readFlight(path) {
  if (!existsSync(path)) throw new Error(`${path}: no such file`);
  let json;
  try {
    json = JSON.parse(readFileSync(path, 'utf8'));
  } catch (error) {
    throw new FlightError(`${path}: not valid JSON (${error.message})`);
  }
  return parseFlight(json, path);
}

/** The flights to run: [{name, flightPath, demPath, flight}]. */
export function collectJobs(positionals) {
  if (positionals.length === 0) throw new UsageError('regress needs a height field and a flight, a flight, or a folder');
  if (positionals.length > 2) throw new UsageError('regress takes a height field and a flight, a flight, or a folder');
  for (const p of positionals) if (!existsSync(p)) throw new Error(`${p}: no such file or folder`);
  const demBeside = (flightPath, flight) => {
    if (flight.dem) return resolve(dirname(flightPath), flight.dem);
    const base = join(dirname(flightPath), flightName(flightPath));
    const found = DEM_EXTENSIONS.map((e) => base + e).find((p) => existsSync(p));
    if (!found) throw new Error(`${flightPath}: no "dem" key and no height field ${base}.png (or .tif, ...) beside it`);
    return found;
  };
  let jobs;
  if (positionals.length === 2) {
    const [demPath, flightPath] = positionals;
    if (statSync(demPath).isDirectory()) throw new UsageError(`${demPath} is a folder: give a folder alone`);
    jobs = [{ flightPath, demPath, flight: readFlight(flightPath) }];
  } else if (statSync(positionals[0]).isDirectory()) {
    const folder = positionals[0];
    const files = readdirSync(folder).filter((f) => f.toLowerCase().endsWith('.flight.json')).sort();
    if (files.length === 0) throw new Error(`${folder}: no *.flight.json files in it`);
    jobs = files.map((f) => {
      const flightPath = join(folder, f);
      const flight = readFlight(flightPath);
      return { flightPath, demPath: demBeside(flightPath, flight), flight };
    });
  } else {
    const flightPath = positionals[0];
    if (extname(flightPath).toLowerCase() !== '.json') throw new UsageError(`${flightPath}: give a flight (.json) with it, or a flight that names its height field`);
    const flight = readFlight(flightPath);
    jobs = [{ flightPath, demPath: demBeside(flightPath, flight), flight }];
  }
  for (const job of jobs) {
    job.name = flightName(job.flightPath);
    if (!existsSync(job.demPath)) throw new Error(`${job.flightPath}: its height field ${job.demPath}: no such file`);
  }
  const names = jobs.map((j) => j.name);
  const twice = names.find((n, i) => names.indexOf(n) !== i);
  if (twice) throw new UsageError(`two flights named ${twice}: their references would collide`);
  return jobs;
}

/** Loads the height field as the page does (auto PNG colours, a spacing guessed when none). */
async function replayInNode(job) {
  const core = await createNodeCore();
  let loaded;
  try {
    loaded = await loadTerrain(core, readInputs(job.demPath), { encoding: 'auto', guessSpacing: true });
  } catch (error) {
    const message = error.needsSize ? `${error.message} (give the size in a NAME.json sidecar: width, height)` : error.message;
    throw new Error(`${job.demPath}: the height field does not load: ${message.replace(/^[^:]*: /, '')}`);
  }
  const record = replayFlight(loaded.terrain, job.flight);
  loaded.terrain.destroy();
  return record.toArray();
}

const frameFile = (frame) => `frame-${String(frame).padStart(4, '0')}.png`;

/** Compares (or, updating, stores) one flight's results; returns its result for the report. */
function judge(job, run, { refs, out, update, threshold, maxShare, nodeOnly }) {
  const dir = join(out, job.name), refDir = join(refs, job.name);
  mkdirSync(dir, { recursive: true });
  const problems = [];
  const statsDoc = { flight: relative(refs, job.flightPath), dem: basename(job.demPath), frames: job.flight.frames, stats: run.stats };
  writeFileSync(join(dir, 'stats.json'), JSON.stringify(statsDoc, null, 0).replace(/\},\{/g, '},\n{') + '\n');
  if (run.nodeMismatch) problems.push(`the page and Node disagree: ${run.nodeMismatch}`);
  if (run.pageProblems?.length) problems.push(`the page reported: ${run.pageProblems[0]}`);
  const captures = [];
  if (update) {
    if (problems.length === 0) {
      if (!nodeOnly) rmSync(refDir, { recursive: true, force: true }); // a Node-only update keeps the images
      mkdirSync(refDir, { recursive: true });
      copyFileSync(join(dir, 'stats.json'), join(refDir, 'stats.json'));
    }
    for (const [frame, image] of run.images) {
      writePng(join(dir, frameFile(frame)), image);
      if (problems.length === 0) copyFileSync(join(dir, frameFile(frame)), join(refDir, frameFile(frame)));
      captures.push({ frame, image: `${job.name}/${frameFile(frame)}` });
    }
    return { name: job.name, dem: job.demPath, frames: job.flight.frames, captures, problems, updated: problems.length === 0 };
  }
  const refStats = join(refDir, 'stats.json');
  if (!existsSync(refStats)) {
    problems.push(`no reference in ${refDir}: run with --update to make one`);
  } else {
    const mismatch = compareStats(JSON.parse(readFileSync(refStats, 'utf8')).stats, run.stats, 'the reference');
    if (mismatch) problems.push(mismatch);
  }
  for (const [frame, image] of run.images) {
    const name = frameFile(frame), capture = { frame, image: `${job.name}/${name}` };
    writePng(join(dir, name), image);
    const refPath = join(refDir, name);
    if (!existsSync(refPath)) {
      if (existsSync(refStats)) problems.push(`frame ${frame}: no reference image`);
      captures.push(capture);
      continue;
    }
    const refCopy = name.replace('.png', '-ref.png'), diffName = name.replace('.png', '-diff.png');
    copyFileSync(refPath, join(dir, refCopy));
    capture.reference = `${job.name}/${refCopy}`;
    const result = compareImages(readPng(readFileSync(refPath)), image, threshold);
    if (result.sizeMismatch) {
      capture.problem = `size ${result.sizeMismatch}`;
      problems.push(`frame ${frame}: ${capture.problem}`);
    } else {
      writePng(join(dir, diffName), result.diff);
      Object.assign(capture, { diff: `${job.name}/${diffName}`, share: result.share, maxDelta: result.maxDelta });
      if (result.share > maxShare) {
        capture.problem = `${(100 * result.share).toFixed(3)} % of pixels differ (max ${result.maxDelta})`;
        problems.push(`frame ${frame}: ${capture.problem}`);
      }
    }
    captures.push(capture);
  }
  if (!nodeOnly) {
    for (const frame of job.flight.captures) {
      if (!run.images.has(frame)) problems.push(`frame ${frame}: not captured`);
    }
  }
  return { name: job.name, dem: job.demPath, frames: job.flight.frames, captures, problems };
}

export async function regress(args) {
  const { values, positionals } = parseOptions(args, OPTIONS);
  if (values.help) { console.log(REGRESS_USAGE); return 0; }
  const threshold = values.threshold !== undefined ? parseNumber('threshold', values.threshold, { min: 0, max: 255, integer: true }) : DEFAULT_THRESHOLD;
  const maxShare = values['max-share'] !== undefined ? parseNumber('max-share', values['max-share'], { min: 0, max: 1 }) : DEFAULT_MAX_SHARE;
  const jobs = collectJobs(positionals);
  const refs = resolve(values.refs ?? join(dirname(jobs[0].flightPath), 'refs'));
  const out = resolve(values.out ?? 'regress-out');
  const nodeOnly = !!values['node-only'];
  const options = { refs, out, update: !!values.update, threshold, maxShare, nodeOnly };
  mkdirSync(out, { recursive: true });

  // Node first: a height field that does not load stops everything before a browser starts.
  const runs = [];
  for (const job of jobs) {
    const started = performance.now();
    runs.push({ stats: await replayInNode(job), images: new Map(), nodeMs: performance.now() - started });
  }
  const session = nodeOnly ? null : await (await import('./regress_browser.js')).startBrowser({ chromium: values.chromium });
  const results = [];
  try {
    for (let i = 0; i < jobs.length; i++) {
      const job = jobs[i], run = runs[i];
      const started = performance.now();
      if (session) {
        try {
          const page = await (await import('./regress_browser.js')).flyInPage(session, { id: i, ...job });
          run.nodeMismatch = compareStats(run.stats, page.stats, 'Node');
          run.pageProblems = page.problems;
          run.stats = page.stats;
          run.images = page.images;
        } catch (error) {
          run.pageProblems = [String(error.message).split('\n')[0]]; // this flight fails; the others still fly
        }
      }
      const result = judge(job, run, options);
      results.push(result);
      const seconds = ((performance.now() - started + run.nodeMs) / 1000).toFixed(1);
      console.log(`[${i + 1}/${jobs.length}] ${job.name}: ${flightLine(result)} ${seconds} s`);
    }
  } finally {
    await session?.close();
  }
  const failed = results.filter((r) => r.problems.length);
  const summary = [
    `hexlod regress: ${results.length} flights, ${failed.length} regressed${options.update ? ', references written' : ''}` +
      (nodeOnly ? ' (Node only: no pixels)' : ''),
    ...results.map((r) => `  ${r.name}: ${flightLine(r)}`),
    `references ${refs}`,
    `report     ${join(out, 'report.html')}`,
  ].join('\n');
  writeFileSync(join(out, 'summary.txt'), summary + '\n');
  writeFileSync(join(out, 'report.html'), htmlReport(results, { threshold, maxShare }));
  console.log(summary);
  return failed.length ? 1 : 0;
}
