// The folders depend on each other in one direction only (design guide, section 7: the tools
// share helpers through one library folder and never import each other):
//   bin/, bench/, scripts/, tests/  entry points (commands, benchmarks, tests): they import
//                                   lib/ and web/, and nothing imports them
//   lib/                            the tools' shared library: imports lib/ and web/
//   web/, public/                   the page: imports web/ (and its GLSL text in shaders/), and
//                                   every folder may import it
// build/ (the generated WebAssembly module factories) and npm packages may be imported by all,
// and tests/fixtures/ is data that anything but the page may read.
// Every .js and .mjs file of those folders is parsed with acorn (comments and strings are not
// code, so a JSDoc `import('...')` type or a usage text is no edge). Edges are static imports
// and re-exports, dynamic import() of a literal, and `new URL('./x.js', import.meta.url)`, the
// way a module names a worker; a URL to a file that starts with `#!` names a program that is
// run as a process (a test running bin/hexlod.js), not imported.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, readdirSync, existsSync, statSync } from 'node:fs';
import { dirname, join, relative, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parse } from 'acorn';

const root = fileURLToPath(new URL('../../', import.meta.url));
const FOLDERS = ['bin', 'bench', 'lib', 'public', 'scripts', 'tests', 'web'];
const SKIP = new Set(['node_modules', 'out']); // tests/out: what the browser tests write

// What each folder may import, besides itself for lib/ and web/ (build/ and npm: everyone).
const ALLOWED = {
  bin: ['lib', 'web'],
  bench: ['lib', 'web'],
  scripts: ['lib', 'web'],
  tests: ['lib', 'web'],
  lib: ['lib', 'web'],
  web: ['web', 'shaders'],
  public: ['web'],
};

function sourceFiles(folder) {
  const dir = join(root, folder);
  if (!existsSync(dir)) return [];
  const files = [];
  for (const entry of readdirSync(dir, { withFileTypes: true })) {
    if (SKIP.has(entry.name)) continue;
    const path = join(dir, entry.name);
    if (entry.isDirectory()) files.push(...sourceFiles(relative(root, path)));
    else if (/\.m?js$/.test(entry.name)) files.push(relative(root, path));
  }
  return files;
}

/** The literal string of a node, or null (a template literal without expressions counts). */
function literal(node) {
  if (node?.type === 'Literal' && typeof node.value === 'string') return node.value;
  if (node?.type === 'TemplateLiteral' && node.expressions.length === 0) return node.quasis[0].value.cooked;
  return null;
}

const isImportMetaUrl = (node) => node?.type === 'MemberExpression' && node.object.type === 'MetaProperty' &&
  node.object.meta.name === 'import' && node.property.name === 'url';

/** Every module a file names: [{ specifier, line, how: 'import' | 'url' }]. */
function edgesOf(file) {
  const text = readFileSync(join(root, file), 'utf8');
  const ast = parse(text, { ecmaVersion: 'latest', sourceType: 'module', allowHashBang: true, locations: true });
  const edges = [];
  const visit = (node) => {
    if (!node || typeof node.type !== 'string') return;
    const line = node.loc.start.line;
    if (node.type === 'ImportDeclaration' || node.type === 'ExportNamedDeclaration' || node.type === 'ExportAllDeclaration') {
      if (node.source) edges.push({ specifier: node.source.value, line, how: 'import' });
    } else if (node.type === 'ImportExpression' && literal(node.source) !== null) {
      edges.push({ specifier: literal(node.source), line, how: 'import' });
    } else if (node.type === 'NewExpression' && node.callee.type === 'Identifier' && node.callee.name === 'URL' &&
      literal(node.arguments[0]) !== null && isImportMetaUrl(node.arguments[1]) && /\.[mc]?js$/.test(literal(node.arguments[0]))) {
      edges.push({ specifier: literal(node.arguments[0]), line, how: 'url' });
    }
    for (const value of Object.values(node)) {
      if (Array.isArray(value)) value.forEach(visit);
      else if (value && typeof value === 'object' && value !== node.loc) visit(value);
    }
  };
  visit(ast);
  return edges;
}

const folderOf = (path) => path.split(sep)[0];
const isProgram = (path) => statSync(path).isFile() && readFileSync(path, 'utf8').startsWith('#!');

/** The project-relative file a relative specifier of `file` names (Vite's `?raw` dropped), or null for a package. */
function targetOf(file, specifier) {
  if (!specifier.startsWith('./') && !specifier.startsWith('../')) return null;
  return relative(root, resolve(root, dirname(file), specifier.replace(/\?.*$/, '')));
}

/** Why an edge breaks the rule, or null when it keeps it. */
function violation(file, target) {
  const from = folderOf(file), to = folderOf(target);
  if (target === file || to === 'build' || to === 'node_modules') return null;
  if (target.startsWith(`tests${sep}fixtures${sep}`) && from !== 'web' && from !== 'public') return null; // data
  if (ALLOWED[from]?.includes(to)) return null;
  if (to === 'bin' || to === 'bench' || to === 'tests' || to === 'scripts') return `nothing imports ${to}/`;
  return `${from}/ imports only ${ALLOWED[from]?.map((f) => `${f}/`).join(' and ') ?? 'nothing'} (and build/, npm)`;
}

/** [{ file, line, target, how }] of every relative edge in the scanned folders. */
function allEdges() {
  const edges = [];
  for (const file of FOLDERS.flatMap(sourceFiles)) {
    for (const { specifier, line, how } of edgesOf(file)) {
      const target = targetOf(file, specifier);
      if (target !== null) edges.push({ file, line, target, how });
    }
  }
  return edges;
}

const edges = allEdges();

test('the folders are scanned and their imports found', () => {
  // A parser that found nothing would pass the rule below on any tree.
  assert.ok(edges.length > 200, `only ${edges.length} imports found`);
  assert.ok(edges.some((e) => folderOf(e.file) === 'bin'), 'no import found in bin/');
  assert.ok(edges.some((e) => folderOf(e.file) === 'tests'), 'no import found in tests/');
  assert.ok(edges.some((e) => e.how === 'url'), 'no worker module (new URL) found');
});

test('tools import only lib/ and web/, lib/ only lib/ and web/, the page only web/', () => {
  const broken = edges.flatMap(({ file, line, target, how }) => {
    if (how === 'url' && existsSync(join(root, target)) && isProgram(join(root, target))) return []; // run, not imported
    const why = violation(file, target);
    return why ? [`${file}:${line} -> ${target}${how === 'url' ? ' (new URL)' : ''}: ${why}`] : [];
  });
  assert.equal(broken.length, 0, `${broken.length} forbidden imports:\n  ${broken.join('\n  ')}`);
});

test('every relative import names a file that exists', () => {
  // Scripts that no test runs (most of bench/) would otherwise keep a path that a move broke.
  const missing = edges.filter(({ target }) => folderOf(target) !== 'build' && !existsSync(join(root, target)))
    .map(({ file, line, target }) => `${file}:${line} -> ${target}`);
  assert.equal(missing.length, 0, `${missing.length} imports of missing files:\n  ${missing.join('\n  ')}`);
});

test('the page reaches geography and TIFF reading only through web/geo/index.js', () => {
  // web/geo/ is the one home of CRSs, georeferences and the TIFF reader; its files are its own.
  const geo = `web${sep}geo${sep}`;
  const broken = edges.filter(({ file, target }) => file.startsWith(`web${sep}`) && !file.startsWith(geo) &&
    target.startsWith(geo) && target !== `${geo}index.js`).map(({ file, line, target }) => `${file}:${line} -> ${target}`);
  assert.ok(edges.some(({ file, target }) => !file.startsWith(geo) && target === `${geo}index.js`), 'no import of web/geo/index.js found');
  assert.equal(broken.length, 0, `${broken.length} imports of web/geo/ internals:\n  ${broken.join('\n  ')}`);
});

test('the geotiff library is opened in one place, which registers our decoders once', () => {
  // Who imports the library's ways to open a file (or its registry of decoders).
  const OPENERS = new Set(['default', 'fromArrayBuffer', 'fromSource', 'fromBlob', 'fromUrl', 'addDecoder']);
  const opened = FOLDERS.flatMap(sourceFiles).filter((file) => file.startsWith(`web${sep}`) &&
    parse(readFileSync(join(root, file), 'utf8'), { ecmaVersion: 'latest', sourceType: 'module' }).body.some((node) =>
      node.type === 'ImportDeclaration' && node.source.value === 'geotiff' &&
      node.specifiers.some((s) => OPENERS.has(s.type === 'ImportDefaultSpecifier' ? 'default' : s.imported?.name))));
  assert.deepEqual(opened.sort(), [`web${sep}geo${sep}tiff_decoders.js`, `web${sep}geo${sep}tiff_open.js`]);
});

test('web/app/ wires the parts: web/ui/ never imports web/app/', () => {
  const app = `web${sep}app${sep}`, ui = `web${sep}ui${sep}`;
  const upward = edges.filter(({ file, target }) => file.startsWith(ui) && target.startsWith(app))
    .map(({ file, line, target }) => `${file}:${line} -> ${target}`);
  assert.ok(edges.some(({ file, target }) => file.startsWith(app) && target.startsWith(ui)), 'app/ imports ui/');
  assert.equal(upward.length, 0, `ui/ imports app/:\n  ${upward.join('\n  ')}`);
});
