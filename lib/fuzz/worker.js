// The fuzz worker: one WebAssembly core per worker; it makes each case from its id (or takes
// files given to it, for the minimiser and for saved reproducers), loads it as the page does,
// and reports { start } before and { result } after each case to the watching thread. The core
// is made anew after a WASM trap or when its memory has grown large, so that every case is
// measured from a small, sound core.
import { parentPort } from 'node:worker_threads';
import { createNodeCore } from '../node_core.js';
import { makeCase, FORMATS } from './cases.js';
import { judgeCase, spyOnCore } from './judge.js';

const FRESH_CORE_ABOVE = 256 << 20; // bytes of WASM memory

let core = null, spy = null;
async function freshCore() {
  core = await createNodeCore();
  spy = spyOnCore(core);
}

async function runOne(key, c) {
  parentPort.postMessage({ start: key, bytes: c.files.reduce((n, f) => n + f.bytes.length, 0) });
  const outcome = await judgeCase(core, spy, c, FORMATS[c.format].declaredSize);
  outcome.how = c.how;
  parentPort.postMessage({ result: key, outcome });
  if (outcome.trap || outcome.kind === 'blowup' || core.buffer.byteLength > FRESH_CORE_ABOVE) await freshCore();
}

parentPort.on('message', async (job) => {
  if (!core) await freshCore();
  if (job.range) {
    const { format, seed, from, to } = job.range;
    for (let i = from; i < to; i++) {
      let c;
      try {
        c = makeCase(format, seed, i);
      } catch (e) {
        // A bug of the fuzzer, not a finding: the run stops and says so.
        parentPort.postMessage({ fuzzerError: `making case ${format}:${seed}:${i}: ${e.stack}` });
        break;
      }
      await runOne(i, c);
    }
  } else if (job.files) {
    await runOne(job.key, { format: job.format, files: job.files, options: job.options ?? {}, how: job.how ?? '', invalid: job.invalid ?? null });
  }
  parentPort.postMessage({ done: true });
});
