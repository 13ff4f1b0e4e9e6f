// The npm package as a user gets it (lib/packed_install.js): `npm pack` of this project, then
// `npm install` of the tarball into an empty folder with no compiler on PATH, where the hexlod
// command runs info, mesh, profile, bench and regress (headless Chromium on the built page).
// The regress commands are the ones of the CI jobs in examples/ci/, which the README shows.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { copyFileSync, existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { COMPILERS, INSTALL_FLAGS, folderSize, noCompilerEnv, noCompilerPath, packAndInstall, run, which } from '../../lib/packed_install.js';

const root = fileURLToPath(new URL('../../', import.meta.url));
const fixtures = join(root, 'tests/fixtures');
const CI_FILES = ['examples/ci/github-actions.yml', 'examples/ci/gitlab-ci.yml'];
// Measured for 0.2.0: 6.75 MB packed (5.6 MB of it the default terrain, a PNG that does not
// compress), 8.85 MB unpacked, 240 files. The caps leave room for the API's modules and types.
const MAX_PACKED = 8e6, MAX_UNPACKED = 11e6, MAX_FILES = 320;

let installed, work;
before(async () => {
  installed = await packAndInstall();
  const { pack, dir, installMs } = installed;
  const mb = (bytes) => `${(bytes / 1e6).toFixed(2)} MB`;
  const modules = folderSize(join(dir, 'node_modules'));
  console.log(`package: ${mb(pack.size)} packed, ${mb(pack.unpackedSize)} unpacked, ${pack.files.length} files; ` +
    `installed with its dependencies: ${mb(modules.bytes)} in ${modules.files} files; ` +
    `install ${installMs === null ? 'reused (same tarball)' : `${(installMs / 1000).toFixed(1)} s`}`);
  // The commands run in a folder of this test's own inside the project that installed hexlod.
  work = mkdtempSync(join(dir, 'run-'));
  for (const name of ['volcano_maungawhau.png', 'volcano_maungawhau.json']) copyFileSync(join(fixtures, name), join(work, name));
  copyFileSync(join(fixtures, 'crs/jacksboro_5070.tif'), join(work, 'jacksboro_5070.tif'));
});
after(() => { if (work) rmSync(work, { recursive: true, force: true }); });

/** `npx hexlod ...` (a command line of the docs, split at spaces) in the work folder, with no compiler on PATH. */
function npx(line) {
  assert.match(line, /^npx hexlod [^'"`$]+$/, 'a plain command line');
  return run(join(noCompilerPath(), 'npx'), line.split(' ').slice(1), { cwd: work, env: noCompilerEnv() });
}

/** The shell command lines of a CI file (its `run:` steps and `script:` items). */
function ciCommands(file) {
  return readFileSync(join(root, file), 'utf8').split('\n')
    .map((line) => /^\s*-?\s*(?:run:\s*|-\s+)?((?:npx|npm|apt-get) .*)$/.exec(line)?.[1]).filter(Boolean);
}

test('the tarball holds the two WebAssembly cores, the page, the modules and the CLI, and no tests, fixtures, C++ or native builds', () => {
  const { files, size, unpackedSize } = installed.pack;
  for (const file of ['build/wasm/hexlod_core.mjs', 'build/wasm/hexlod_core.wasm', 'build/wasm-diag/hexlod_core.mjs',
    'build/wasm-diag/hexlod_core.wasm', 'bin/hexlod.js', 'lib/cli.js', 'web/core/core.js', 'shaders/terrain.frag',
    'library/hexlod.js', 'library/element.js', 'dist/index.html', 'CHANGELOG.md', 'README.md', 'package.json']) {
    assert.ok(files.includes(file), `${file} is in the package`);
  }
  const unwanted = files.filter((f) => /^(tests|scripts|src|bench|docs|examples|build\/native|build\/wasm-tests|dist\/crs|lib\/fuzz)\//.test(f) ||
    /\.(cpp|h|hpp|cc)$/.test(f) || /fixtures|build\.stamp|\/include\//.test(f) || f.startsWith('dist/assets/globe_himalaya'));
  assert.deepEqual(unwanted, []);
  assert.ok(files.some((f) => /^dist\/assets\/hexlod_core-.*\.wasm$/.test(f)), 'the built page carries its core');
  for (const asset of [/hexlod_core-.*\.wasm$/, /globe_himalaya_2048-.*\.png$/, /tile_worker-.*\.js$/, /viewer-.*\.css$/]) {
    assert.ok(files.some((f) => f.startsWith('library/assets/') && asset.test(f)), `the browser library carries ${asset}`);
  }
  assert.ok(size <= MAX_PACKED, `packed ${size} bytes > ${MAX_PACKED}`);
  assert.ok(unpackedSize <= MAX_UNPACKED, `unpacked ${unpackedSize} bytes > ${MAX_UNPACKED}`);
  assert.ok(files.length <= MAX_FILES, `${files.length} files > ${MAX_FILES}`);
  // What was installed is what was packed: the package folder holds no source to build from.
  const packageDir = join(installed.dir, 'node_modules/hexlod');
  assert.ok(existsSync(join(packageDir, 'build/wasm-diag/hexlod_core.wasm')) && !existsSync(join(packageDir, 'src')));
  assert.ok(!existsSync(join(installed.dir, 'node_modules/vite')), 'Vite, a development dependency, is not installed');
});

test('the PATH the package is installed and run with finds node, npm and npx but no compiler', () => {
  const path = noCompilerPath();
  for (const program of ['node', 'npm', 'npx', 'sh']) assert.ok(which(program, path), `${program} is on it`);
  for (const program of COMPILERS) assert.equal(which(program, path), null, `${program} is on it`);
  assert.ok(which('cc') || which('em++'), 'the machine has a compiler, which the PATH above leaves out');
});

test('the installed hexlod runs info, mesh, profile and bench', async () => {
  const info = await npx('npx hexlod info jacksboro_5070.tif --json');
  assert.equal(info.code, 0, info.stderr);
  const report = JSON.parse(info.stdout);
  assert.equal(report.width, 207);
  assert.equal(report.height, 200);
  assert.equal(report.crs.epsg, 5070);

  const mesh = await npx('npx hexlod mesh jacksboro_5070.tif --max-error 5 --obj fault.obj --json fault.json');
  assert.equal(mesh.code, 0, mesh.stderr);
  const figures = JSON.parse(readFileSync(join(work, 'fault.json'), 'utf8'));
  assert.ok(figures.converged && figures.triangles.afterClipping > 1000, `${figures.triangles.afterClipping} triangles`);
  assert.match(readFileSync(join(work, 'fault.obj'), 'utf8'), /^v [-\d.]+ [-\d.]+ [-\d.]+$/m);

  const profile = await npx('npx hexlod profile jacksboro_5070.tif --line 1000,1000,15000,12000 --csv fault.csv');
  assert.equal(profile.code, 0, profile.stderr);
  assert.match(profile.stdout, /^csv +fault\.csv \(\d+ rows\)$/m);
  assert.ok(readFileSync(join(work, 'fault.csv'), 'utf8').split('\n').length > 100);

  const bench = await npx('npx hexlod bench volcano_maungawhau.png --frames 20');
  assert.equal(bench.code, 0, bench.stderr);
  assert.match(bench.stdout, /^flight +20 frames/m);
  assert.match(bench.stdout, /^native +NATIVE FLIGHT NOT MEASURED: the package has no native build/m);
  assert.match(bench.stdout, /^martini +NOT COMPARED: @mapbox\/martini is not installed \(npm install @mapbox\/martini\)$/m);
});

test("the CI jobs' commands run in the installed package: references written once, then a passing regress in Chromium", async () => {
  const [github, gitlab] = CI_FILES.map(ciCommands);
  assert.deepEqual(github, gitlab, 'both CI jobs run the same commands');
  const [aptGet, install, ...flights] = github;
  assert.match(aptGet, /apt-get install -y chromium$/);
  // The jobs install from the registry with flags the package test installs with too.
  const installFlags = /^npm install ((?:--\S+ )*)hexlod$/.exec(install)?.[1].trim().split(' ');
  assert.ok(installFlags?.every((flag) => INSTALL_FLAGS.includes(flag)), install);
  assert.deepEqual(flights, ['npx hexlod regress flights/ --junit regress-out/junit.xml']);

  // A user's flight over a GeoTIFF in EPSG:5070: the page fetches crs/5070.json from the command's server.
  mkdirSync(join(work, 'flights'));
  writeFileSync(join(work, 'flights/fault.flight.json'), `${JSON.stringify({
    description: 'The Jacksboro fault from the south-west', dem: '../jacksboro_5070.tif', fps: 10, viewport: [160, 90],
    settings: { tau: 2 }, captures: [5],
    keyframes: [
      { time: 0, position: [2000, 4000, 18000], target: [10000, 600, 10000] },
      { time: 0.5, position: [4000, 3500, 16000], target: [12000, 600, 9000], fov: 45 },
    ],
  }, null, 2)}\n`);
  const update = await npx('npx hexlod regress jacksboro_5070.tif flights/fault.flight.json --update');
  assert.equal(update.code, 0, `${update.stdout}\n${update.stderr}`);
  assert.match(update.stdout, /^hexlod regress: 1 flight: 1 written as references$/m);
  const refs = join(work, 'flights/refs/fault');
  assert.deepEqual(readdirSync(refs).sort(), ['frame-0005.png', 'stats.json']);

  for (const line of flights) {
    const result = await npx(line);
    assert.equal(result.code, 0, `${line}\n${result.stdout}\n${result.stderr}`);
    assert.match(result.stdout, /^\[1\/1\] fault: ok: 6 frames, 1 capture; pixels identical/m);
    assert.match(result.stdout, /^hexlod regress: 1 flight: 1 passed$/m);
  }
  assert.match(readFileSync(join(work, 'regress-out/junit.xml'), 'utf8'), /<testcase classname="hexlod.regress" name="fault"/);

  // The README's way of making the references writes the same ones again, byte for byte.
  const before = readFileSync(join(refs, 'frame-0005.png'));
  const readmeUpdate = /```sh\nnpm install hexlod\n(npx hexlod .*)\n```/.exec(readFileSync(join(root, 'README.md'), 'utf8'))?.[1];
  assert.equal(readmeUpdate, 'npx hexlod regress flights/ --update');
  const again = await npx(readmeUpdate);
  assert.equal(again.code, 0, `${again.stdout}\n${again.stderr}`);
  assert.ok(readFileSync(join(refs, 'frame-0005.png')).equals(before), 'the same pixels on a second run');

  // No Chromium where one is named: exit code 3 and one line saying how to get one.
  const missing = await npx('npx hexlod regress flights/ --chromium /nonexistent/chrome');
  assert.equal(missing.code, 3);
  assert.equal(missing.stderr, 'hexlod: no Chromium at /nonexistent/chrome (--chromium): name the Chromium program, or install one with apt-get install chromium (Debian) or npx playwright-core install chromium\n');
});

test("the README's CI jobs are the files in examples/ci/", () => {
  const readme = readFileSync(join(root, 'README.md'), 'utf8');
  const section = readme.slice(readme.indexOf('## Use `hexlod regress` in your CI'));
  const blocks = [...section.matchAll(/^```yaml\n([\s\S]*?)^```$/gm)].map((m) => m[1]);
  assert.equal(blocks.length, 2);
  CI_FILES.forEach((file, k) => {
    assert.ok(section.includes(`(\`${file}\`)`), `the README names ${file}`);
    assert.equal(blocks[k], readFileSync(join(root, file), 'utf8'), `the README's block ${k + 1} is ${file}`);
  });
});
