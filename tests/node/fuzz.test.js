// A short seeded run of the loaders' fuzzer (lib/fuzz) over every format, as the page loads
// files (loadTerrain into the WebAssembly core), each case in a worker with a time limit and a
// memory watch: every input is refused with a clear one-line message or loads as a sane field,
// and none crashes, hangs or takes memory its size does not justify. The long runs are
// `node bench/fuzz/fuzz.js` (too long for CI).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { runFuzz } from '../../lib/fuzz/runner.js';
import { FORMAT_NAMES } from '../../lib/fuzz/cases.js';

// About 3 000 cases, fewer where one costs more (an SRTM tile is 1201 x 1201 samples).
const COUNT = { png: 600, tiff: 600, hgt: 120, asc: 400, pgm: 500, raw: 500, f32: 300 };
const SEED = 29;
// A case that does not finish is a hang. The slowest case here takes well under 1 s on an idle
// machine; the limit leaves room for a loaded one (CI shares two cores) and still ends a loop.
const CASE_MS = 15000;

test('fuzzed files of every format are refused cleanly or load sane: no crash, hang or memory blow-up', async (t) => {
  assert.deepEqual(Object.keys(COUNT).sort(), [...FORMAT_NAMES].sort(), 'every format of the fuzzer is run');
  const { counts, failures } = await runFuzz({ formats: FORMAT_NAMES, count: COUNT, seed: SEED, caseMs: CASE_MS });
  for (const [format, c] of Object.entries(counts)) {
    t.diagnostic(`${format}: ${c.inputs} inputs, ${c.refused} refused, ${c.accepted} accepted, ${(c.ms / 1000).toFixed(1)} s, ` +
      `slowest ${c.slowestId} ${c.slowestMs.toFixed(0)} ms`);
  }
  // Each failure names its case: node bench/fuzz/fuzz.js --replay ID --save shrinks and keeps it.
  assert.deepEqual(failures.map((f) => `${f.id} ${f.kind}: ${f.detail} [${f.how}]`), []);
  for (const [format, c] of Object.entries(counts)) {
    assert.equal(c.inputs, COUNT[format], `${format}: every case ran`);
    // The mutations must reach both ends: files refused for many reasons, and files accepted.
    assert.ok(c.refusals.size >= 5, `${format}: only ${c.refusals.size} kinds of refusal`);
    assert.ok(c.accepted >= COUNT[format] / 20, `${format}: only ${c.accepted} of ${c.inputs} accepted`);
  }
});
