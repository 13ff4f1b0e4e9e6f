// The native GoogleTest suite and the same suite built to WebAssembly (scripts/build_wasm_tests.sh)
// must agree: both pass, run the same tests with the same results, and print the same
// `agree: <key> <value>` lines (mesh hashes, error figures, ... that tests print to stdout so that
// the two builds can be compared value for value).
import { describe, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { existsSync, readdirSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../../', import.meta.url));
const nativeBinary = join(root, 'build/native/hexlod_tests');
const wasmLoader = join(root, 'build/wasm-tests/hexlod_tests.js');
const wasmBinary = join(root, 'build/wasm-tests/hexlod_tests.wasm');

const RUN_TIMEOUT_MS = 10 * 60 * 1000; // per suite; the WASM build runs several times slower than native
// Full, uncoloured, timed output from both (the result lines are parsed below). GTEST_* variables
// are removed from the environment: the native binary would obey them, the WASM one cannot see them.
const GTEST_ARGS = ['--gtest_color=no', '--gtest_brief=0', '--gtest_print_time=1'];
const env = Object.fromEntries(Object.entries(process.env).filter(([name]) => !name.startsWith('GTEST_')));

function run(file, args) {
  return new Promise((resolve) => {
    const started = performance.now();
    execFile(file, args, { cwd: root, env, encoding: 'utf8', timeout: RUN_TIMEOUT_MS, maxBuffer: 256 * 1024 * 1024 },
      (error, stdout, stderr) => {
        const ms = performance.now() - started;
        let failure = null; // why the run did not end with exit code 0
        if (error) {
          if (error.killed && error.signal) failure = `killed by ${error.signal} (timeout of ${RUN_TIMEOUT_MS / 1000} s?)`;
          else if (typeof error.code === 'number') failure = `exit code ${error.code}`;
          else if (error.signal) failure = `killed by ${error.signal}`;
          else failure = error.message;
        }
        resolve({ failure, stdout: stdout.replace(/\r\n/g, '\n'), stderr, ms });
      });
  });
}

// What a GoogleTest run printed: the tests it started, each test's result, the closing count,
// and the `agree:` lines, each with the test that printed it.
function parse(stdout) {
  const started = [];
  const results = new Map(); // Suite.Name -> OK | FAILED | SKIPPED
  const agree = new Map(); // key -> [{ value, test }] in the order printed
  let ran = null;
  let current = '(outside any test)';
  for (const line of stdout.split('\n')) {
    let m;
    if ((m = /^\[ RUN {6}\] (\S+)$/.exec(line))) {
      current = m[1];
      started.push(current);
    } else if ((m = /^\[ +(OK|FAILED|SKIPPED) +\] (\S+?)(?:, where .*)? \(\d+ ms\)$/.exec(line))) {
      // Only per-test lines carry a time; the closing summary's "[  FAILED  ] Suite.Name" does not.
      results.set(m[2], m[1]);
    } else if ((m = /^\[==========\] (\d+) tests? from \d+ test suites? ran\./.exec(line))) {
      ran = Number(m[1]);
    } else if ((m = /^agree:\s+(\S+)(?:\s+(.*?))?\s*$/.exec(line))) {
      if (!agree.has(m[1])) agree.set(m[1], []);
      agree.get(m[1]).push({ value: m[2] ?? '', test: current });
    }
  }
  return { started, results, agree, ran };
}

// A note for failure messages when a binary is older than the sources it is built from.
function staleness() {
  const sources = [];
  for (const dir of ['src', 'tests/native']) {
    for (const name of readdirSync(join(root, dir))) {
      if (/\.(cpp|h|hpp)$/.test(name)) sources.push(join(root, dir, name));
    }
  }
  const newest = Math.max(...sources.map((file) => statSync(file).mtimeMs));
  const stale = [nativeBinary, wasmBinary].filter((file) => existsSync(file) && statSync(file).mtimeMs < newest);
  return stale.length ? `\n(older than the newest source: ${stale.join(', ')}; rebuild both with ./build.sh)` : '';
}

const tail = (text, lines = 40) => text.trimEnd().split('\n').slice(-lines).join('\n');

describe('the native and the WASM build of the GoogleTest suite agree', () => {
  let native, wasm;

  before(async () => {
    const missing = [nativeBinary, wasmLoader, wasmBinary].filter((file) => !existsSync(file));
    assert.equal(missing.length, 0,
      `missing test build(s): ${missing.join(', ')}; run ./build.sh (it builds the native suite and the WASM suite)`);
    const [n, w] = await Promise.all([run(nativeBinary, GTEST_ARGS), run(process.execPath, [wasmLoader, ...GTEST_ARGS])]);
    native = { ...n, ...parse(n.stdout) };
    wasm = { ...w, ...parse(w.stdout) };
  }, { timeout: RUN_TIMEOUT_MS + 60 * 1000 });

  test('both suites run to the end and pass', (t) => {
    t.diagnostic(`native ${native.ms.toFixed(0)} ms, WASM under node ${wasm.ms.toFixed(0)} ms`);
    for (const [name, r] of [['native (build/native/hexlod_tests)', native], ['WASM (node build/wasm-tests/hexlod_tests.js)', wasm]]) {
      const failed = [...r.results].filter(([, result]) => result === 'FAILED').map(([test]) => test);
      assert.equal(r.failure, null,
        `${name} failed: ${r.failure}${failed.length ? `\nfailed tests: ${failed.join(', ')}` : ''}` +
        `\n--- stdout (end) ---\n${tail(r.stdout)}\n--- stderr (end) ---\n${tail(r.stderr)}${staleness()}`);
      assert.notEqual(r.ran, null, `${name} printed no "[==========] N tests ... ran." line\n${tail(r.stdout)}`);
      assert.ok(r.ran > 0, `${name} ran no tests`);
      const unfinished = r.started.filter((test) => !r.results.has(test));
      assert.deepEqual(unfinished, [],
        `${name}: tests started without a result line (a crash, or output printed without a trailing newline)`);
    }
  });

  test('both ran the same tests with the same results', () => {
    const onlyIn = (a, b) => [...a.results.keys()].filter((test) => !b.results.has(test));
    const differing = [...native.results].filter(([test, result]) => wasm.results.has(test) && wasm.results.get(test) !== result)
      .map(([test, result]) => `${test}: native ${result}, WASM ${wasm.results.get(test)}`);
    const problems = [
      ...onlyIn(native, wasm).map((test) => `${test}: a result from native only`),
      ...onlyIn(wasm, native).map((test) => `${test}: a result from WASM only`),
      ...differing,
    ];
    assert.deepEqual(problems, [], `the two builds disagree on the tests:\n${problems.join('\n')}${staleness()}`);
    assert.deepEqual(Object.fromEntries(wasm.results), Object.fromEntries(native.results));
    assert.equal(wasm.ran, native.ran, `"[==========] N tests ran": native ${native.ran}, WASM ${wasm.ran}${staleness()}`);
    assert.equal(native.results.size, native.ran, 'every test that ran has a result line');
  });

  test('every "agree: <key> <value>" line is printed identically by both', (t) => {
    const show = (entries) => (entries ? entries.map((e) => `${JSON.stringify(e.value)} (in ${e.test})`).join(', ') : 'nothing');
    const keys = [...new Set([...native.agree.keys(), ...wasm.agree.keys()])].sort();
    const problems = keys
      .filter((key) => JSON.stringify(native.agree.get(key)?.map((e) => e.value)) !== JSON.stringify(wasm.agree.get(key)?.map((e) => e.value)))
      .map((key) => `agree: ${key}: native printed ${show(native.agree.get(key))}, WASM printed ${show(wasm.agree.get(key))}`);
    t.diagnostic(`${keys.length} agree key(s) compared`);
    assert.deepEqual(problems, [], `the two builds print different values:\n${problems.join('\n')}${staleness()}`);
  });
});
