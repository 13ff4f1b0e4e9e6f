// The shipped command line (bin/hexlod.js and every module it reaches) needs no development
// dependency: an installed package runs every command, and the package's file list holds every
// module the command reaches. (tests/browser/package.test.js installs and runs the package.)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../../', import.meta.url));
const pkg = JSON.parse(readFileSync(`${root}package.json`, 'utf8'));
// Imported lazily with a fallback: `hexlod bench` prints "NOT COMPARED" without it.
const OPTIONAL = new Set(['@mapbox/martini']);
// Imported only in a checkout: hexlod regress serves the source with Vite there, and the built
// site (dist/) in an installed package (lib/regress_browser.js).
const CHECKOUT_ONLY = new Set(['vite']);

/** Every bare package a module graph imports (statically or dynamically), with the importing file. */
function packagesReachedFrom(entry) {
  const seen = new Set(), packages = new Map(), queue = [entry];
  while (queue.length) {
    const file = queue.pop();
    if (seen.has(file)) continue;
    seen.add(file);
    const source = readFileSync(file, 'utf8');
    for (const m of source.matchAll(/(?:\bfrom\s*|\bimport\s*\(\s*|^\s*import\s+)['"]([^'"]+)['"]/gm)) {
      const specifier = m[1].split('?')[0];
      if (specifier.startsWith('node:')) continue;
      if (specifier.startsWith('.')) {
        if (specifier.endsWith('.js') || specifier.endsWith('.mjs')) queue.push(resolve(dirname(file), specifier));
        continue;
      }
      const name = specifier.startsWith('@') ? specifier.split('/').slice(0, 2).join('/') : specifier.split('/')[0];
      if (!packages.has(name)) packages.set(name, file.slice(root.length));
    }
  }
  return { packages, modules: seen.size, files: [...seen].map((file) => file.slice(root.length)) };
}

test('every package the hexlod command reaches is a runtime dependency', () => {
  const { packages, modules } = packagesReachedFrom(`${root}bin/hexlod.js`);
  assert.ok(modules > 10, `only ${modules} modules reached: the import scan is broken`);
  assert.ok(packages.has('playwright-core') && packages.has('fflate'), `the scan sees the regress and loader packages: ${[...packages.keys()]}`);
  for (const [name, from] of packages) {
    if (OPTIONAL.has(name) || CHECKOUT_ONLY.has(name)) continue;
    assert.ok(pkg.dependencies?.[name], `${from} imports ${name}, which is not in package.json "dependencies"`);
  }
  for (const name of CHECKOUT_ONLY) {
    assert.ok(packages.has(name) && !pkg.dependencies?.[name] && pkg.devDependencies?.[name], `${name} is a development dependency the command imports`);
  }
});

test('the package holds every module the hexlod command reaches, and the files it needs beside them', () => {
  // npm's own list of what `npm pack` would put in the tarball (the prepack build is not run).
  const [packed] = JSON.parse(execFileSync('npm', ['pack', '--dry-run', '--json', '--ignore-scripts'], { cwd: root, encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }));
  const inPackage = new Set(packed.files.map((f) => f.path));
  const { files } = packagesReachedFrom(`${root}bin/hexlod.js`);
  const missing = files.filter((file) => !inPackage.has(file));
  assert.deepEqual(missing, [], 'modules the command imports that package.json "files" leaves out');
  // What the code reads beside its modules: the cores' .wasm, the built page of hexlod regress.
  for (const file of ['build/wasm/hexlod_core.wasm', 'build/wasm-diag/hexlod_core.wasm', 'dist/index.html']) assert.ok(inPackage.has(file), file);
  assert.ok(files.includes('lib/regress_browser.js') && files.length > 50, `the scan reached ${files.length} modules`);
});
