#!/usr/bin/env node
// The loaders' fuzzer: structure-aware mutations of every format the page opens, loaded as the
// page loads them (web/loaders/terrain_source.js into the WebAssembly core), each case in a
// worker with a time limit and a memory watch. Not part of CI; a short seeded run is
// tests/node/fuzz.test.js. The cases, workers, verdicts and shrinking are in lib/fuzz/.
//
//   node bench/fuzz/fuzz.js --format png --count 100000 --seed 1
//   node bench/fuzz/fuzz.js --replay png:1:4711
//   node bench/fuzz/fuzz.js --run fuzz-out/png-1-4711-crash/min
import { readdirSync, readFileSync, existsSync } from 'node:fs';
import { join, dirname } from 'node:path';
import { parseArgs } from 'node:util';
import {
  runFuzz, runFiles, saveReproducer, decodeOptions, checkSeeds, flatName, WORKER,
} from '../../lib/fuzz/runner.js';
import { formatReport } from '../../lib/fuzz/report.js';
import { WatchedWorker } from '../../lib/fuzz/watched_worker.js';
import { makeCase, parseCaseId, FORMAT_NAMES, FORMATS } from '../../lib/fuzz/cases.js';

const HELP = `usage: node bench/fuzz/fuzz.js [options]
  --format LIST      formats, comma-separated, or all (default): ${FORMAT_NAMES.join(', ')}
  --count N          cases per format (default 1000)
  --seed S           the run's seed (default 1); case i of a format is the same in every run
  --from I           first case index (default 0)
  --time-limit MS    a case that takes longer, plus 400 ms a megabyte of input, is a hang (default 5000)
  --memory-cap-mb M  a case during which the process grows more is a blow-up (default 2048)
  --jobs N           workers at once (default 1)
  --out DIR          minimised reproducers go here (default fuzz-out)
  --no-save          do not minimise or save failing cases
  --replay F:S:I     run one case (e.g. png:1:4711) and print its outcome; --save keeps it in --out
  --run DIR          run the files in DIR (a reproducer's min/ folder; options from ../case.json)
exit code: 0 no failures, 1 failures found, 2 usage`;

let args;
try {
  ({ values: args } = parseArgs({ options: {
    format: { type: 'string', default: 'all' }, count: { type: 'string', default: '1000' }, seed: { type: 'string', default: '1' },
    from: { type: 'string', default: '0' }, 'time-limit': { type: 'string', default: '5000' }, 'memory-cap-mb': { type: 'string', default: '2048' },
    jobs: { type: 'string', default: '1' }, out: { type: 'string', default: 'fuzz-out' }, 'no-save': { type: 'boolean' },
    replay: { type: 'string' }, save: { type: 'boolean' }, run: { type: 'string' }, help: { type: 'boolean' },
  } }));
} catch (e) {
  console.error(`${e.message}\n${HELP}`);
  process.exit(2);
}
if (args.help) { console.log(HELP); process.exit(0); }
const int = (key) => {
  const v = Number(args[key]);
  if (!Number.isInteger(v) || v < 0) { console.error(`--${key} must be a whole number ≥ 0 (got ${args[key]})\n${HELP}`); process.exit(2); }
  return v;
};
const caseMs = int('time-limit');
const log = (line) => console.log(line);

async function replay(id) {
  let parsed;
  try { parsed = parseCaseId(id); } catch (e) { console.error(e.message); process.exit(2); }
  const c = makeCase(parsed.format, parsed.seed, parsed.index);
  console.log(`${id}: ${c.files.map((f) => `${f.name} (${f.bytes.length} bytes)`).join(', ')}; options ${JSON.stringify(c.options)}\nmutations: ${c.how}`);
  const watched = new WatchedWorker(WORKER, { caseMs });
  const outcome = await runFiles(watched, c.format, c.files, c.options, caseMs, c.invalid);
  await watched.close();
  console.log(`${outcome.kind}: ${outcome.detail} (${outcome.ms?.toFixed(0)} ms)`);
  const failed = !['refused', 'accepted'].includes(outcome.kind);
  if (failed && args.save) await saveReproducer({ id, ...outcome }, { outDir: args.out, caseMs, maxTests: 2000, log });
  return failed ? 1 : 0;
}

async function runDir(dir) {
  const caseFile = [join(dir, 'case.json'), join(dirname(dir), 'case.json')].find(existsSync);
  const meta = caseFile ? decodeOptions(readFileSync(caseFile, 'utf8')) : {};
  const names = readdirSync(dir).filter((n) => n !== 'case.json' && n !== 'README.txt');
  // The height field first, then its sidecar, under their names in case.json (a tile's name
  // gives its latitude) rather than the flattened ones they were saved under.
  const files = names.sort((a, b) => a.endsWith('.json') - b.endsWith('.json')).map((saved) => ({
    name: meta.files?.find((n) => flatName(n) === saved) ?? saved, bytes: new Uint8Array(readFileSync(join(dir, saved))) }));
  const format = meta.format ?? FORMAT_NAMES.find((f) => FORMATS[f].extension === files[0]?.name.split('.').pop().toLowerCase()) ?? 'png';
  const options = meta.options ?? {};
  // What makes an acceptance wrong comes from the bytes where the format can tell, else from the case.
  const claim = FORMATS[format].mustRefuseFiles;
  const invalid = claim ? claim(files, options) : meta.invalid ?? null;
  const watched = new WatchedWorker(WORKER, { caseMs });
  const outcome = await runFiles(watched, format, files, options, caseMs, invalid);
  await watched.close();
  console.log(`${files.map((f) => f.name).join(' + ')}: ${outcome.kind}: ${outcome.detail} (${outcome.ms?.toFixed(0)} ms)`);
  return ['refused', 'accepted'].includes(outcome.kind) ? 0 : 1;
}

async function main() {
  if (args.replay) return replay(args.replay);
  if (args.run) return runDir(args.run);
  const formats = args.format === 'all' ? FORMAT_NAMES : args.format.split(',');
  const unknown = formats.filter((f) => !FORMATS[f]);
  if (unknown.length) { console.error(`unknown format ${unknown.join(', ')}: expected ${FORMAT_NAMES.join(', ')} or all`); return 2; }
  const seed = int('seed'), count = int('count');
  console.log(`fuzz: ${formats.join(', ')}, ${count} cases each from index ${int('from')}, seed ${seed}, time limit ${caseMs} ms, ${int('jobs')} worker(s)`);
  const result = await runFuzz({
    formats, count, seed, from: int('from'), caseMs, jobs: Math.max(1, int('jobs')), memoryCapBytes: int('memory-cap-mb') * 2 ** 20,
    outDir: args['no-save'] ? null : args.out, log,
    onProgress: (format, c, ms) => console.error(`  ${format}: ${c.inputs}/${count} in ${(ms / 1000).toFixed(0)} s: ${c.refused} refused, ` +
      `${c.accepted} accepted, ${c.crash} crashes, ${c.hang} hangs, ${c.blowup} blow-ups, ${c.insane} insane`),
  });
  console.log(`\n${formatReport(result, { seed })}`);
  // The seeds are valid files: one that is refused is a finding of its own (a valid file refused).
  const badSeeds = await checkSeeds(formats, caseMs);
  console.log(badSeeds.length ? `\nseeds not accepted (valid files):\n${badSeeds.map((b) => `  ${b.format} ${b.name}: ${b.kind}: ${b.detail}`).join('\n')}`
    : '\nevery seed loads as it is');
  return result.failures.length ? 1 : 0;
}

process.exitCode = await main();
