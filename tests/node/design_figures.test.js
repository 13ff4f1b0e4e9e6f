// docs/DESIGN.md gives the size of the C ABI; the figures are the headers', so that the document
// cannot drift from the code again: the functions declared in src/api/hexlod.h (the product) and
// src/api/hexlod_diagnostics.h, counted the way build.sh finds what to export.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const read = (path) => readFileSync(new URL(`../../${path}`, import.meta.url), 'utf8');

/** The functions a header declares: a declaration starts a line with its return type. */
function declaredFunctions(header) {
  const code = header.replace(/\/\*[\s\S]*?\*\//g, '');
  return [...code.matchAll(/^[a-z][\w\s*]*?\b(hexlod_\w+)\s*\(/gm)].map((m) => m[1]);
}

test('DESIGN.md counts the functions of the product ABI and of the diagnostics as the headers declare them', () => {
  const product = declaredFunctions(read('src/api/hexlod.h'));
  const diagnostics = declaredFunctions(read('src/api/hexlod_diagnostics.h'));
  assert.ok(product.includes('hexlod_terrain_frame') && diagnostics.includes('hexlod_diag_check_mesh'), 'the headers were read');
  const design = read('docs/DESIGN.md');
  const productFigure = /`hexlod\.h` is the product: (\d+) functions/.exec(design);
  const diagnosticsFigure = /`hexlod_diagnostics\.h` \((\d+) functions/.exec(design);
  assert.ok(productFigure && diagnosticsFigure, 'DESIGN.md states both figures');
  assert.equal(Number(productFigure[1]), product.length, `hexlod.h declares ${product.join(', ')}`);
  assert.equal(Number(diagnosticsFigure[1]), diagnostics.length, `hexlod_diagnostics.h declares ${diagnostics.join(', ')}`);
});
