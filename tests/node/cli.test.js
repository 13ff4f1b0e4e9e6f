// The hexlod command line, run as a user runs it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, writeFileSync, readFileSync, copyFileSync, symlinkSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const cli = fileURLToPath(new URL('../../bin/hexlod.js', import.meta.url));
const fixture = (name) => fileURLToPath(new URL(`../fixtures/${name}`, import.meta.url));
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 60000 });

test('hexlod info prints size, spacing, height range and load time of a 16-bit PNG', () => {
  const r = run('info', fixture('volcano_maungawhau.png'));
  assert.equal(r.status, 0, r.stderr);
  assert.match(r.stdout, /size\s+87 x 61 samples/);
  assert.match(r.stdout, /spacing\s+10 x 10 m \(from the file\)/);
  assert.match(r.stdout, /heights\s+94\.00 \.\. 195\.00 m/);
  assert.match(r.stdout, /load\s+[\d.]+ ms/);
  assert.equal(r.stderr, '');
});

test('hexlod info --json reports the f32 pair exactly', () => {
  const r = run('info', fixture('jacksboro_fault.f32'), '--json');
  assert.equal(r.status, 0, r.stderr);
  const report = JSON.parse(r.stdout);
  assert.equal(report.width, 403);
  assert.equal(report.height, 344);
  assert.equal(report.spacingX, 74.4);
  assert.equal(report.spacingY, 92.6);
  assert.equal(report.sampleType, 'f32');
  assert.ok(Math.abs(report.minHeight - 236) < 0.5 && Math.abs(report.maxHeight - 1076) < 0.5);
});

test('a PNG without a sidecar gets an assumed spacing of 1, and says so', () => {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-cli-'));
  copyFileSync(fixture('volcano_maungawhau.png'), join(dir, 'alone.png'));
  const r = run('info', join(dir, 'alone.png'));
  assert.equal(r.status, 0, r.stderr);
  assert.match(r.stdout, /spacing\s+1 x 1 m \(assumed: the file gives none\)/);
  assert.match(r.stdout, /heights\s+94\.00 \.\. 195\.00 m/, 'height range comes from the tEXt chunks');
});

test('bad input exits non-zero with one clear line naming the file', () => {
  const dir = mkdtempSync(join(tmpdir(), 'hexlod-cli-'));
  const truncated = join(dir, 'cut.png');
  writeFileSync(truncated, readFileSync(fixture('grandcanyon_512.png')).subarray(0, 5000));
  const empty = join(dir, 'empty.png');
  writeFileSync(empty, '');
  for (const [args, pattern] of [
    [['info', join(dir, 'nothing.png')], /nothing\.png: no such file/],
    [['info', truncated], /cut\.png/],
    [['info', empty], /empty\.png.*empty/],
    [['info', dir], /not a file/],
  ]) {
    const r = run(...args);
    assert.equal(r.status, 1, `${args}: ${r.stderr}`);
    const lines = r.stderr.trim().split('\n');
    assert.equal(lines.length, 1, `one line: ${r.stderr}`);
    assert.match(lines[0], /^hexlod: /);
    assert.match(lines[0], pattern);
    assert.equal(r.stdout, '');
  }
});

test('usage mistakes exit 2 and show the usage', () => {
  for (const args of [['frobnicate'], ['info'], ['info', 'a', 'b'], ['info', '--bogus', 'x']]) {
    const r = run(...args);
    assert.equal(r.status, 2, `${args}: ${r.stderr}`);
    assert.match(r.stderr, /usage: hexlod info/);
  }
  const help = run('--help');
  assert.equal(help.status, 0);
  assert.match(help.stdout, /usage: hexlod info/);
});

test('before a build the command says what to run, with exit code 2 and no stack trace', () => {
  // The launcher in a clone that has not been set up: no npm packages, no WebAssembly core.
  const clone = mkdtempSync(join(tmpdir(), 'hexlod-unbuilt-'));
  mkdirSync(join(clone, 'bin'));
  mkdirSync(join(clone, 'src/api'), { recursive: true });
  copyFileSync(cli, join(clone, 'bin/hexlod.js'));
  copyFileSync(new URL('../../src/api/hexlod.h', import.meta.url), join(clone, 'src/api/hexlod.h'));
  const bare = spawnSync(process.execPath, [join(clone, 'bin/hexlod.js'), '--help'], { encoding: 'utf8', timeout: 60000 });
  assert.equal(bare.status, 2);
  assert.equal(bare.stdout, '');
  assert.equal(bare.stderr.trim(), 'hexlod: the npm packages and the WebAssembly core (build/wasm, build/wasm-diag) are missing: ' +
    'run scripts/setup.sh && ./build.sh wasm');
  // Set up (the packages are there) but not built.
  symlinkSync(fileURLToPath(new URL('../../node_modules', import.meta.url)), join(clone, 'node_modules'));
  const unbuilt = spawnSync(process.execPath, [join(clone, 'bin/hexlod.js'), 'info', fixture('volcano_maungawhau.png')],
    { encoding: 'utf8', timeout: 60000 });
  assert.equal(unbuilt.status, 2);
  assert.equal(unbuilt.stderr.trim(), 'hexlod: the WebAssembly core (build/wasm, build/wasm-diag) is missing: run ./build.sh wasm');
  // An installed package (no src/) ships the core: one without it is a broken install, which no build fixes.
  rmSync(join(clone, 'src'), { recursive: true });
  const installed = spawnSync(process.execPath, [join(clone, 'bin/hexlod.js'), 'info', fixture('volcano_maungawhau.png')],
    { encoding: 'utf8', timeout: 60000 });
  assert.equal(installed.status, 2);
  assert.equal(installed.stderr.trim(), `hexlod: the WebAssembly core (build/wasm, build/wasm-diag) is missing: this hexlod package in ${clone}/ is incomplete: reinstall it (npm install hexlod)`);
});
