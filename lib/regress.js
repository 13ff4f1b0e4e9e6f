// hexlod regress: scripted flights (web/app/deterministic/flight.js) over height fields, flown in
// headless Chromium in the page's deterministic mode and replayed in Node on the same WASM core,
// compared with stored references: per-frame mesh hashes and figures exactly (and the page with
// Node), screenshots under a tolerance (web/app/deterministic/tolerance.js). Every run rewrites
// summary.txt and report.html (and --junit, --json), whatever stopped it; --update writes the
// references instead of comparing.
import { existsSync, readFileSync, mkdirSync, writeFileSync, copyFileSync, rmSync } from 'node:fs';
import { join, relative, resolve } from 'node:path';
import { UsageError, parseOptions, parseNumber } from './cli_common.js';
import { createNodeCore } from './node_core.js';
import { EnvironmentError } from './chromium.js';
import { readDem } from './dem_source.js';
import { loadImageFiles } from './image_files.js';
import { collectJobs, InputError } from './regress_jobs.js';
import { compareStats, statsMatch, describeStats, statsLines, flightRecordOf, flightChanges, compareImages, describeImage,
  briefImage, readPng, writePng } from './regress_compare.js';
import { flightLine, summaryText, htmlReport, junitXml, jsonReport } from './regress_report.js';
import { loadTerrain } from '../web/loaders/terrain_source.js';
import { replayFlight, withKeyframes } from '../web/app/deterministic/flight.js';
import { flightTrackKeyframes } from '../web/app/deterministic/track_keyframes.js';
import { useNodeCrsDefinitions } from './crs_definitions.js';
import { readNamedFile } from './image_files.js';
import { DEFAULT_TOLERANCE, toleranceFor } from '../web/app/deterministic/tolerance.js';

export const EXIT = { pass: 0, regression: 1, input: 2, environment: 3 };
const MAX_JOBS = 16;

export const REGRESS_USAGE = `usage: hexlod regress <heightfield> <flight.json> [options]
       hexlod regress <flight.json> [options]     (the flight names its height field: "dem")
       hexlod regress <folder> [options]          (every *.flight.json in it)
  Flies each flight in headless Chromium (the page's deterministic mode: ?flight=, README),
  replays it in Node on the same WASM core, and compares with the references: the mesh hash
  and figures of every frame exactly (and the page with Node), the captured frames' pixels
  under the flight's tolerance. A height field is a file or an http(s) URL. A flight without
  "dem" uses the height field beside it with the same name (NAME.png, .tif, ...). A flight's
  "image" (and "worldFile", else the image's world file beside it) is draped before the first
  frame, or its "layers" ([{"image", "worldFile", "opacity", "visible"} or {"tiles", ...}, ...],
  bottom first; a frame waits for its web map tiles);
  like "dem", paths relative to the flight or URLs. A refused image fails the flight.
  Exit code: 0 all passed, 1 a flight regressed, 2 bad input or usage (a flight file, a height
  field, no reference), 3 the browser or the machine failed; the highest that applies.
  --refs DIR        references (default: refs/ beside the flight files); one folder per flight
  --platform NAME   references of one platform: refs/FLIGHT/NAME/ (e.g. linux-swiftshader)
  --out DIR         new images, diffs, figures, summary.txt and report.html (default: regress-out/)
  --junit FILE      also write the results as JUnit XML;  --json FILE  and as JSON
  --update          write the new results as the references (no comparison)
  --grep REGEX      only the flights whose name matches
  --jobs N          fly N flights at once, each in its own page (default 1; same results)
  --threshold F     per pixel: pixelmatch's perceptual colour distance, 0..1, above which a pixel
                    differs (default ${DEFAULT_TOLERANCE.threshold}: a change of one level per channel passes)
  --max-diff-pixels N, --max-diff-pixel-ratio F
                    differing pixels a capture may have: N, or this share, whichever allows more
                    (defaults ${DEFAULT_TOLERANCE.maxDiffPixels} and ${DEFAULT_TOLERANCE.maxDiffPixelRatio}); these override the flight file's "tolerance"
  --mask X,Y,W,H[;X,Y,W,H...]  rectangles (CSS pixels) left out of every capture's comparison
  --strict          any changed pixel (outside the masks) fails
  --node-only       only the Node replay and its figures (no browser, no pixels)
  --chromium PATH   the browser (default: $CHROMIUM_PATH, else /usr/bin/chromium, else the newest
                    of Playwright's in $PLAYWRIGHT_BROWSERS_PATH or ~/.cache/ms-playwright)`;

const OPTIONS = { refs: 'string', out: 'string', update: 'boolean', threshold: 'string', 'max-diff-pixels': 'string',
  'max-diff-pixel-ratio': 'string', mask: 'string', strict: 'boolean', 'node-only': 'boolean', chromium: 'string',
  junit: 'string', json: 'string', grep: 'string', jobs: 'string', platform: 'string' };

/** The --out of the arguments, read before they are checked, so a usage mistake still rewrites the report. */
function outOf(args) {
  const i = args.findIndex((a) => a === '--out' || a.startsWith('--out='));
  if (i < 0) return 'regress-out';
  return args[i].startsWith('--out=') ? args[i].slice(6) : (args[i + 1] ?? 'regress-out');
}

function parseMasks(text) {
  return text.split(';').map((part) => {
    const numbers = part.split(',').map((p) => (p.trim() === '' ? NaN : Number(p)));
    if (numbers.length !== 4 || !numbers.every((n) => Number.isFinite(n) && n >= 0) || numbers[2] <= 0 || numbers[3] <= 0) {
      throw new UsageError(`--mask must be X,Y,W,H in CSS pixels (several joined by ;), with a positive width and height, got '${text}'`);
    }
    return numbers;
  });
}

/** The checked options of a run. */
function readOptions(values) {
  const overrides = {};
  if (values.threshold !== undefined) overrides.threshold = parseNumber('threshold', values.threshold, { min: 0, max: 1 });
  if (values['max-diff-pixels'] !== undefined) overrides.maxDiffPixels = parseNumber('max-diff-pixels', values['max-diff-pixels'], { min: 0, integer: true });
  if (values['max-diff-pixel-ratio'] !== undefined) overrides.maxDiffPixelRatio = parseNumber('max-diff-pixel-ratio', values['max-diff-pixel-ratio'], { min: 0, max: 1 });
  if (values.strict && Object.keys(overrides).length) throw new UsageError('--strict takes no --threshold or --max-diff-* with it');
  if (values.strict) overrides.strict = true;
  if (values.mask !== undefined) overrides.masks = parseMasks(values.mask);
  let grep = null;
  if (values.grep !== undefined) {
    try {
      grep = new RegExp(values.grep);
    } catch (error) {
      throw new UsageError(`--grep must be a regular expression: ${error.message}`);
    }
  }
  if (values.platform !== undefined && !/^[A-Za-z0-9][A-Za-z0-9._-]{0,63}$/.test(values.platform)) {
    throw new UsageError(`--platform must be a folder name of letters, digits, '.', '_' and '-', got '${values.platform}'`);
  }
  if (values.update && (values.strict || Object.keys(overrides).length)) throw new UsageError('--update compares nothing: give no tolerance options with it');
  const jobs = values.jobs !== undefined ? parseNumber('jobs', values.jobs, { min: 1, max: MAX_JOBS, integer: true }) : 1;
  return { overrides, grep, jobs, update: !!values.update, nodeOnly: !!values['node-only'], platform: values.platform ?? null };
}

/** Deletes what an earlier run left that this one would write, so no report shows another run. */
function clearStale(out, files) {
  mkdirSync(out, { recursive: true });
  for (const file of [join(out, 'summary.txt'), join(out, 'report.html'), ...files]) rmSync(file, { force: true });
}

/** The height field's files, read once per source however many flights fly over it. */
class DemCache {
  constructor(jobs) {
    this.uses = new Map();
    for (const job of jobs) if (job.source) this.uses.set(job.source, (this.uses.get(job.source) ?? 0) + 1);
    this.reads = new Map();
  }

  get(source) {
    if (!this.reads.has(source)) this.reads.set(source, readDem(source));
    return this.reads.get(source);
  }

  /** A flight is done with it: the bytes go when no other flight needs them. */
  release(source) {
    const left = this.uses.get(source) - 1;
    this.uses.set(source, left);
    if (left === 0) this.reads.delete(source);
  }
}

/**
 * Replays a flight in Node as the page does (auto PNG colours, a spacing guessed when none);
 * `trackFile` ({ name, bytes }): the flight's track, whose keyframes it makes first, or null.
 */
async function replayInNode(job, dem, trackFile) {
  const core = await createNodeCore();
  let loaded;
  try {
    loaded = await loadTerrain(core, dem.files, { encoding: 'auto', guessSpacing: true });
  } catch (error) {
    const message = error.needsSize ? `${error.message} (give the size in a NAME.json sidecar: width, height)` : error.message;
    throw new InputError(`${job.source}: the height field does not load: ${message.replace(/^[^:]*: /, '')}`);
  }
  try {
    // A flight along a track: its keyframes from the track on this terrain, as the page makes them.
    if (job.flight.track) {
      useNodeCrsDefinitions();
      let keyframes;
      try {
        keyframes = await flightTrackKeyframes(job.flight.track, trackFile, loaded.terrain, loaded.field.georef ?? null);
      } catch (error) {
        throw new InputError(`${shown(job.track)}: ${error.message}`);
      }
      job.flight = withKeyframes(job.flight, keyframes);
    }
    return replayFlight(loaded.terrain, job.flight, loaded.field.georef ?? null).toArray();
  } finally {
    loaded.terrain.destroy();
  }
}

const frameFile = (frame) => `frame-${String(frame).padStart(4, '0')}.png`;

/** A path as the user reads it: relative to the current folder when inside it. */
const shown = (path) => {
  const rel = relative(process.cwd(), path);
  return rel && !rel.startsWith('..') ? rel : path;
};

/** A result with no comparison: the flight could not be flown or had nothing to compare with. */
const outcome = (job, verdict, problem, extra = {}) => ({
  name: job.name, flightPath: shown(job.flightPath), dem: job.source,
  verdict, problems: [problem], details: [], frameLines: [], changes: [], frames: job.flight?.frames ?? 0, differingFrames: [], captures: [],
  table: null, ...extra,
});

/** The command that makes a missing reference. */
function updateCommand(job, context) {
  const quote = (s) => (/^[\w./:@%+=,-]+$/.test(s) ? s : `'${s.replace(/'/g, "'\\''")}'`);
  const args = ['hexlod', 'regress', ...(job.demGiven ? [shown(job.source)] : []), shown(job.flightPath)];
  if (context.refsGiven) args.push('--refs', context.refs);
  if (context.platform) args.push('--platform', context.platform);
  return [...args, '--update'].map(quote).join(' ');
}

/**
 * Compares one flown flight with its reference (or, updating, writes it as the reference) and
 * writes its images and figures into out/NAME/.
 */
function judge(job, flown, dem, context) {
  const { out, refs, platform, update, nodeOnly, overrides } = context;
  const dir = join(out, job.name), refDir = platform ? join(refs, job.name, platform) : join(refs, job.name);
  mkdirSync(dir, { recursive: true });
  const record = flightRecordOf(job.flight, dem);
  const doc = { flight: relative(refDir, job.flightPath), ...record, frames: job.flight.frames, stats: flown.stats };
  writeFileSync(join(dir, 'stats.json'), JSON.stringify(doc).replace(/\},\{/g, '},\n{') + '\n');
  const result = outcome(job, 'pass', null, { problems: [], table: { actual: flown.stats, reference: null } });
  if (flown.nodeDiff && !statsMatch(flown.nodeDiff)) {
    result.problems.push(`the page and Node disagree: ${describeStats(flown.nodeDiff, 'Node')}`);
    result.frameLines.push(...statsLines(flown.nodeDiff).map((line) => `page against Node: ${line}`));
  }
  for (const problem of flown.pageProblems) result.problems.push(`the page reported: ${problem}`);

  if (update) {
    result.captures = [...flown.images].map(([frame, image]) => {
      writePng(join(dir, frameFile(frame)), image);
      return { frame, verdict: 'pass', images: { actual: `${job.name}/${frameFile(frame)}` } };
    });
    if (result.problems.length) {
      result.verdict = 'regression';
      result.problems.push('the reference was not written');
      return result;
    }
    if (!nodeOnly) rmSync(refDir, { recursive: true, force: true }); // a Node-only update keeps the images
    mkdirSync(refDir, { recursive: true });
    copyFileSync(join(dir, 'stats.json'), join(refDir, 'stats.json'));
    for (const frame of flown.images.keys()) copyFileSync(join(dir, frameFile(frame)), join(refDir, frameFile(frame)));
    result.verdict = 'updated';
    return result;
  }

  const reference = context.reference;
  result.table.reference = reference.stats;
  result.changes = flightChanges(reference, record);
  if (!reference.spec) result.details.push('the reference records no flight settings (an older hexlod made it): run --update to record them');
  const statsDiff = compareStats(reference.stats, flown.stats);
  result.differingFrames = statsDiff.frames;
  if (!statsMatch(statsDiff)) {
    result.problems.push(`mesh: ${describeStats(statsDiff, 'the reference')}`);
    result.frameLines.push(...statsLines(statsDiff));
  }
  for (const frame of nodeOnly ? [] : job.flight.captures) {
    const image = flown.images.get(frame);
    const name = frameFile(frame);
    const capture = { frame, verdict: 'pass', images: {} };
    result.captures.push(capture);
    if (!image) {
      capture.verdict = 'fail';
      result.problems.push(`frame ${frame}: not captured`);
      continue;
    }
    writePng(join(dir, name), image);
    capture.images.actual = `${job.name}/${name}`;
    const refPath = join(refDir, name);
    if (!existsSync(refPath)) {
      capture.verdict = 'fail';
      capture.summary = 'no reference image';
      result.problems.push(`frame ${frame}: no reference image`);
      continue;
    }
    copyFileSync(refPath, join(dir, name.replace('.png', '-ref.png')));
    capture.images.reference = `${job.name}/${name.replace('.png', '-ref.png')}`;
    const tolerance = toleranceFor(job.flight.tolerance, frame, overrides);
    const compared = compareImages(readPng(readFileSync(refPath)), image, tolerance, job.flight.dpr);
    capture.tolerance = tolerance;
    if (compared.sizeMismatch) {
      capture.verdict = 'fail';
      capture.summary = `size ${compared.sizeMismatch}`;
      result.problems.push(`frame ${frame}: ${capture.summary}`);
      continue;
    }
    writePng(join(dir, name.replace('.png', '-diff.png')), compared.diff);
    capture.images.diff = `${job.name}/${name.replace('.png', '-diff.png')}`;
    const { diff, passed, ...figures } = compared;
    Object.assign(capture, figures, { verdict: passed ? 'pass' : 'fail', summary: describeImage(compared, tolerance) });
    if (!passed) {
      result.problems.push(`frame ${frame}: ${briefImage(compared)}`);
      result.details.push(`frame ${frame}: ${capture.summary}`);
    }
  }
  if (result.problems.length) {
    result.verdict = 'regression';
    if (result.changes.length) result.problems.unshift(`the flight changed: ${result.changes.join(', ')}`);
    else result.details.unshift('the flight and its height field are as the reference recorded them: the difference comes from hexlod (core, shaders, page) or the browser');
  }
  return result;
}

/** Reads a flight's reference, or says why there is none to compare with. */
function readReference(job, context) {
  const refDir = context.platform ? join(context.refs, job.name, context.platform) : join(context.refs, job.name);
  const path = join(refDir, 'stats.json');
  if (!existsSync(path)) return { missing: `no reference in ${refDir}; make one with: ${updateCommand(job, context)}` };
  try {
    const doc = JSON.parse(readFileSync(path, 'utf8'));
    if (!Array.isArray(doc?.stats)) throw new Error('it has no "stats" list');
    return { doc };
  } catch (error) {
    return { bad: `${path}: not a reference (${error.message}); make it again with --update` };
  }
}

/** Flies one flight: its height field, the Node replay, the page; returns its result. */
async function runJob(job, index, context) {
  if (job.error) return outcome(job, 'bad-input', job.error);
  try {
    return await flyJob(job, index, context);
  } finally {
    context.dems.release(job.source);
  }
}

async function flyJob(job, index, context) {
  let reference = null;
  if (!context.update) {
    const found = readReference(job, context);
    if (found.missing) return outcome(job, 'no-reference', found.missing);
    if (found.bad) return outcome(job, 'bad-input', found.bad);
    reference = found.doc;
  }
  rmSync(join(context.out, job.name), { recursive: true, force: true });
  let dem;
  try {
    dem = await context.dems.get(job.source);
    // The track is read once: Node makes its keyframes from it and the page gets the same bytes.
    const trackFile = job.track ? await readNamedFile(job.track, 'track').catch((error) => { throw new InputError(error.message); }) : null;
    const nodeStats = await replayInNode(job, dem, trackFile);
    const overlayFiles = [];
    for (const path of job.overlays) overlayFiles.push(await readNamedFile(path, 'overlay').catch((error) => { throw new InputError(error.message); }));
    const layerFiles = [];
    for (const layer of job.layers) {
      layerFiles.push(layer.kind !== 'image' ? null : await loadImageFiles(layer.image, layer.worldFile).catch((error) => {
        throw new InputError(error.message); // an image that cannot be read is bad input, as a height field is
      }));
    }
    const flown = { stats: nodeStats, images: new Map(), pageProblems: [], nodeDiff: null };
    if (!context.nodeOnly) {
      const session = await context.browser();
      try {
        const page = await context.browserModule.flyInPage(session, { id: index, demFiles: dem.files, layerFiles, overlayFiles, trackFile,
          flightPath: job.flightPath, flight: job.flight });
        Object.assign(flown, { stats: page.stats, images: page.images, pageProblems: page.problems, nodeDiff: compareStats(nodeStats, page.stats) });
      } catch (error) {
        if (error instanceof EnvironmentError) throw error;
        return outcome(job, 'regression', `the page failed: ${String(error.message).split('\n')[0]}`);
      }
    }
    return judge(job, flown, dem, { ...context, reference });
  } catch (error) {
    const message = String(error.message).split('\n')[0];
    if (error instanceof EnvironmentError) return outcome(job, 'error', message);
    if (error instanceof InputError || !dem) return outcome(job, 'bad-input', message);
    return outcome(job, 'error', message); // the core failed on a height field that loaded
  }
}

/** Runs the jobs, `count` at a time; results in the jobs' order, progress lines as they end. */
async function runAll(jobs, context, count) {
  const results = new Array(jobs.length);
  let next = 0;
  const worker = async () => {
    while (next < jobs.length) {
      const i = next++;
      const started = performance.now();
      results[i] = await runJob(jobs[i], i, context);
      results[i].seconds = (performance.now() - started) / 1000;
      console.log(`[${i + 1}/${jobs.length}] ${jobs[i].name}: ${flightLine(results[i])} (${results[i].seconds.toFixed(1)} s)`);
    }
  };
  await Promise.all(Array.from({ length: Math.min(count, jobs.length) }, worker));
  return results;
}

/** The exit code of a run: the most serious of its outcomes (EXIT). */
function exitCodeOf(run) {
  const verdicts = new Set(run.results.map((r) => r.verdict));
  if (run.error?.kind === 'environment' || verdicts.has('error')) return EXIT.environment;
  if (run.error || verdicts.has('bad-input') || verdicts.has('no-reference')) return EXIT.input;
  if (verdicts.has('regression')) return EXIT.regression;
  return EXIT.pass;
}

export async function regress(args) {
  if (args.includes('--help') || args.includes('-h')) { console.log(REGRESS_USAGE); return 0; }
  const started = performance.now();
  const run = { options: { out: resolve(outOf(args)) }, error: null, results: [], exitCode: 0, startedAt: new Date().toISOString(), seconds: 0 };
  const reports = [];
  let session = null;
  try {
    const { values, positionals } = parseOptions(args, OPTIONS);
    const options = readOptions(values);
    if (values.junit) reports.push([resolve(values.junit), junitXml]);
    if (values.json) reports.push([resolve(values.json), jsonReport]);
    clearStale(run.options.out, reports.map(([path]) => path));
    const jobs = collectJobs(positionals, options.grep);
    const firstFlight = jobs[0].flightPath;
    const refs = resolve(values.refs ?? join(firstFlight, '..', 'refs'));
    Object.assign(run.options, { refs, platform: options.platform, update: options.update, nodeOnly: options.nodeOnly,
      jobs: options.jobs, grep: values.grep ?? null, tolerance: options.overrides });
    for (const job of jobs) job.demGiven = positionals.length === 2;
    const browserModule = options.nodeOnly ? null : await import('./regress_browser.js');
    let starting = null;
    const context = {
      ...options, out: run.options.out, refs, refsGiven: values.refs !== undefined, dems: new DemCache(jobs), browserModule,
      // The browser starts when the first flight needs it: a run whose flights all fail early needs none.
      browser: () => (starting ??= browserModule.startBrowser({ chromium: values.chromium }).then((s) => (session = s))),
    };
    run.results = await runAll(jobs, context, options.jobs);
    const broken = run.results.find((r) => r.verdict === 'error');
    if (broken) run.error = { kind: 'environment', message: broken.problems[0] };
  } catch (error) {
    const kind = error instanceof UsageError || error?.code?.startsWith?.('ERR_PARSE_ARGS') ? 'usage'
      : error instanceof EnvironmentError ? 'environment' : 'input';
    run.error = { kind, message: String(error?.message ?? error).replace(/\s*\n\s*/g, ' ') };
  } finally {
    await session?.close();
    run.seconds = (performance.now() - started) / 1000;
    run.exitCode = exitCodeOf(run);
    try {
      mkdirSync(run.options.out, { recursive: true });
      writeFileSync(join(run.options.out, 'summary.txt'), summaryText(run));
      writeFileSync(join(run.options.out, 'report.html'), htmlReport(run));
      for (const [path, format] of reports) writeFileSync(path, format(run));
    } catch (error) {
      console.error(`hexlod: the report could not be written: ${error.message}`);
    }
  }
  if (run.results.length) process.stdout.write(summaryText(run));
  if (run.error) console.error(`hexlod: ${run.error.message}${run.error.kind === 'usage' ? '; see hexlod regress --help' : ''}`);
  return run.exitCode;
}
