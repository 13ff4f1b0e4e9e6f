// The shipped command line (bin/hexlod.js and every module it reaches) needs no development
// dependency: an installation with `npm ci --omit=dev` runs every command.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../../', import.meta.url));
const pkg = JSON.parse(readFileSync(`${root}package.json`, 'utf8'));
// Imported lazily with a fallback: `hexlod bench` prints "NOT COMPARED" without it.
const OPTIONAL = new Set(['@mapbox/martini']);

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
  return { packages, modules: seen.size };
}

test('every package the hexlod command reaches is a runtime dependency', () => {
  const { packages, modules } = packagesReachedFrom(`${root}bin/hexlod.js`);
  assert.ok(modules > 10, `only ${modules} modules reached: the import scan is broken`);
  assert.ok(packages.has('playwright-core') && packages.has('fflate'), `the scan sees the regress and loader packages: ${[...packages.keys()]}`);
  for (const [name, from] of packages) {
    if (OPTIONAL.has(name)) continue;
    assert.ok(pkg.dependencies?.[name], `${from} imports ${name}, which is not in package.json "dependencies"`);
  }
});
