// Runs fuzz cases in watched workers and tallies them per format; shrinks and saves the
// failing ones. Shared by the command (bench/fuzz/fuzz.js) and the test
// (tests/node/fuzz.test.js).
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { WatchedWorker } from './watched_worker.js';
import { makeCase, parseCaseId, seedsOf, FORMATS } from './cases.js';
import { minimiseFiles } from './minimise.js';
import { signatureOf } from './judge.js';

/** The worker module that runs cases (worker.js), for a WatchedWorker. */
export const WORKER = new URL('./worker.js', import.meta.url);
const BATCH = 250; // cases per job: a job is the unit the workers take turns on
export const FAILURE_KINDS = ['crash', 'hang', 'blowup', 'insane'];

function emptyCounts() {
  return { inputs: 0, refused: 0, accepted: 0, crash: 0, hang: 0, blowup: 0, insane: 0, ms: 0, slowestMs: 0, refusals: new Map() };
}

/** The outcome of a case that stopped its worker. */
function stoppedOutcome(stop, caseMs) {
  if (stop.kind === 'hang') return { kind: 'hang', detail: `no answer within ${stop.limitMs ?? caseMs} ms`, signature: 'hang', ms: stop.ms };
  if (stop.kind === 'memory') {
    const detail = stop.error ? `worker ran out of JS heap (${stop.error.message})` : 'process memory grew past the cap during the case';
    return { kind: 'blowup', detail, signature: signatureOf(detail), ms: stop.ms };
  }
  const detail = `worker died: ${stop.error?.name ?? ''}: ${String(stop.error?.message ?? 'exited').split('\n')[0]}`;
  return { kind: 'crash', detail, signature: signatureOf(detail), ms: stop.ms };
}

/**
 * Runs cases [from, to) of a format on one watched worker, calling onOutcome(index, outcome)
 * for every case; a case that stops the worker is reported and the rest go on in a new one.
 */
async function runRange(watched, format, seed, from, to, caseMs, onOutcome) {
  let next = from;
  while (next < to) {
    let fuzzerError = null;
    const stop = await watched.run({ range: { format, seed, from: next, to } }, (m) => {
      if ('result' in m) { onOutcome(m.result, m.outcome); next = m.result + 1; }
      if (m.fuzzerError) fuzzerError = m.fuzzerError;
    });
    if (fuzzerError) throw new Error(`fuzzer bug: ${fuzzerError}`);
    if (!stop) return;
    const index = stop.key ?? next; // between cases: blame the next one
    onOutcome(index, stoppedOutcome(stop, caseMs));
    next = index + 1;
  }
}

/** Runs one explicit case (files and options) on a watched worker; resolves with its outcome. */
export async function runFiles(watched, format, files, options, caseMs, invalid = null) {
  let outcome = null;
  const stop = await watched.run({ files, format, options, invalid, key: 'files' }, (m) => { if ('result' in m) outcome = m.outcome; });
  return stop ? stoppedOutcome(stop, caseMs) : outcome;
}

/** Options as JSON, keeping NaN, infinities and undefined apart (a sidecar-less RAW size may be any of them). */
export function encodeOptions(options) {
  return JSON.stringify(options, (k, v) => (typeof v === 'number' && !Number.isFinite(v) ? { number: String(v) } : v === undefined ? { undefined: true } : v), 1);
}
export function decodeOptions(text) {
  return JSON.parse(text, (k, v) => (v && typeof v === 'object' && 'number' in v ? Number(v.number) : v && typeof v === 'object' && v.undefined ? undefined : v));
}

/** A file name with its folders flattened into it, to save it (case.json keeps the real one). */
export const flatName = (name) => name.replace(/[\\/]/g, '_');

/**
 * Shrinks a failing case and writes it to outDir/<format>-<seed>-<index>-<kind>/: the files as
 * generated, the minimised ones in min/, case.json and README.txt with the replay commands.
 */
export async function saveReproducer(failure, { outDir, caseMs, maxTests, log }) {
  const { id, kind, signature } = failure;
  const { format, seed, index } = parseCaseId(id);
  const c = makeCase(format, seed, index);
  const dir = join(outDir, `${id.replace(/:/g, '-')}-${kind}`);
  mkdirSync(join(dir, 'min'), { recursive: true });
  for (const f of c.files) writeFileSync(join(dir, flatName(f.name)), f.bytes);
  const watched = new WatchedWorker(WORKER, { caseMs });
  // A cut-down file may stop being invalid: a format that can tell from the bytes says so for
  // every candidate; a claim only a mutation step could make holds for the case as made.
  const claim = FORMATS[c.format].mustRefuseFiles;
  const sameFailure = async (files) => {
    const invalid = claim ? claim(files, c.options) : files === c.files ? c.invalid : null;
    const o = await runFiles(watched, c.format, files, c.options, caseMs, invalid);
    return o.kind === kind && (kind === 'hang' || o.signature === signature);
  };
  let min = { files: c.files, tests: 0 };
  const keepWhole = !claim && c.invalid && kind === 'insane' && failure.detail.startsWith('accepted, but');
  try {
    // A hang costs the whole time limit per test: few tests for those.
    if (!keepWhole && await sameFailure(c.files)) min = await minimiseFiles(c.files, sameFailure, { format: FORMATS[c.format], maxTests: kind === 'hang' ? 24 : maxTests });
  } finally {
    await watched.close();
  }
  for (const f of min.files) writeFileSync(join(dir, 'min', flatName(f.name)), f.bytes);
  const sizes = min.files.map((f) => `${f.name} ${f.bytes.length} bytes`).join(', ');
  writeFileSync(join(dir, 'case.json'), `{"id": ${JSON.stringify(id)}, "format": ${JSON.stringify(c.format)}, "kind": ${JSON.stringify(kind)},
 "detail": ${JSON.stringify(failure.detail)}, "how": ${JSON.stringify(c.how)},
 "files": ${JSON.stringify(c.files.map((f) => f.name))}, "options": ${encodeOptions(c.options)}, "invalid": ${JSON.stringify(c.invalid)}}\n`);
  writeFileSync(join(dir, 'README.txt'), [
    `${kind} in ${c.format}: ${failure.detail}`,
    `mutations: ${c.how}`,
    `replay the case:           node bench/fuzz/fuzz.js --replay ${id}`,
    `run the minimised files:   node bench/fuzz/fuzz.js --run ${join(dir, 'min')}`,
    `minimised (${min.tests} tests): ${sizes}`, '',
  ].join('\n'));
  log?.(`  saved ${dir} (minimised to ${sizes})`);
  return { dir, files: min.files };
}

/**
 * Loads every seed of the formats as it is: they are valid files, so each must be accepted.
 * @returns {Promise<Array<{ format: string, name: string, kind: string, detail: string }>>} the seeds that were not
 */
export async function checkSeeds(formats, caseMs = 5000) {
  const watched = new WatchedWorker(WORKER, { caseMs });
  const bad = [];
  try {
    for (const format of formats) {
      for (const s of seedsOf(format)) {
        const o = await runFiles(watched, format, s.files, { ...s.options }, caseMs);
        if (o.kind !== 'accepted') bad.push({ format, name: s.files[0].name, kind: o.kind, detail: o.detail });
      }
    }
  } finally {
    await watched.close();
  }
  return bad;
}

/**
 * Runs `count` cases of each format with `seed`.
 * @param {{ formats: string[], count: number|Record<string, number>, seed: number, from?: number, caseMs?: number, jobs?: number,
 *   memoryCapBytes?: number, outDir?: string|null, maxTests?: number, log?: (line: string) => void,
 *   onProgress?: (format: string, counts: object, ms: number) => void }} o
 *   count: cases per format, or a count for each format; outDir: where minimised reproducers go
 *   (null: none are made); jobs: workers run at once
 * @returns {Promise<{ counts: Record<string, object>, failures: object[], saved: object[] }>}
 *   failures: every failing case { id, kind, detail, signature, how }
 */
export async function runFuzz(o) {
  const { formats, count, seed, from = 0, caseMs = 5000, jobs = 1, memoryCapBytes, outDir = null, maxTests = 2000, log } = o;
  const counts = {}, failures = [], saved = [];
  const workers = Array.from({ length: jobs }, () => new WatchedWorker(WORKER, { caseMs, memoryCapBytes }));
  try {
    for (const format of formats) {
      const n = typeof count === 'number' ? count : count[format] ?? 0;
      const c = (counts[format] = emptyCounts());
      const start = performance.now();
      const onOutcome = (index, outcome) => {
        c.inputs++;
        c[outcome.kind]++;
        if (outcome.kind !== 'hang' && (outcome.ms ?? 0) > c.slowestMs) { c.slowestMs = outcome.ms; c.slowestId = `${format}:${seed}:${index}`; }
        if (outcome.kind === 'refused' && (c.refusals.size < 500 || c.refusals.has(outcome.signature))) {
          c.refusals.set(outcome.signature, (c.refusals.get(outcome.signature) ?? 0) + 1);
        }
        if (FAILURE_KINDS.includes(outcome.kind)) {
          const failure = { id: `${format}:${seed}:${index}`, kind: outcome.kind, detail: outcome.detail, signature: outcome.signature, how: outcome.how };
          failures.push(failure);
          log?.(`${failure.id} ${failure.kind}: ${failure.detail}${failure.how ? ` [${failure.how}]` : ''}`);
        }
        if (c.inputs % 1000 === 0) o.onProgress?.(format, c, performance.now() - start);
      };
      // Batches of the range, taken in turn by the free workers.
      let next = from;
      await Promise.all(workers.map(async (w) => {
        while (next < from + n) {
          const lo = next, hi = Math.min(from + n, lo + BATCH);
          next = hi;
          await runRange(w, format, seed, lo, hi, caseMs, onOutcome);
        }
      }));
      c.ms = performance.now() - start;
    }
  } finally {
    await Promise.all(workers.map((w) => w.close()));
  }
  if (outDir) {
    // One reproducer per format, kind and message: the first case that showed it.
    const seen = new Set();
    for (const f of failures) {
      const key = `${f.id.split(':')[0]}|${f.kind}|${f.signature}`;
      if (seen.has(key)) continue;
      seen.add(key);
      saved.push({ ...f, ...(await saveReproducer(f, { outDir, caseMs, maxTests, log })) });
    }
  }
  return { counts, failures, saved };
}
