// hexlod mesh, run as a user runs it: the OBJ it writes is checked as geometry (inside the data
// rectangle, counter-clockwise from above, watertight, covering the rectangle exactly) and the
// JSON's figures against the settings. Georeferenced fixtures are meshed with --earth flat here,
// in the frame of their samples; the curved Earth's frame is cli_mesh_earth.test.js's.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, copyFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const cli = fileURLToPath(new URL('../../bin/hexlod.js', import.meta.url));
const fixture = (name) => fileURLToPath(new URL(`../fixtures/${name}`, import.meta.url));
const run = (...args) => spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', timeout: 60000 });
const scratch = () => mkdtempSync(join(tmpdir(), 'hexlod-mesh-'));

/**
 * Vertices (x, y, z per vertex), zero-based faces (3 per face), texture coordinates (u, v per
 * `vt` line) and the faces' zero-based texture indices (3 per face, when faces are `f v/vt`) of
 * an OBJ file written by hexlod mesh.
 */
function readObj(path) {
  const vertices = [], faces = [], uv = [], textureFaces = [];
  for (const line of readFileSync(path, 'utf8').split('\n')) {
    if (line.startsWith('v ')) {
      const [x, y, z, extra] = line.slice(2).split(' ');
      assert.equal(extra, undefined, `vertex line '${line}'`);
      vertices.push(Number(x), Number(y), Number(z));
    } else if (line.startsWith('vt ')) {
      const [u, v, extra] = line.slice(3).split(' ');
      assert.equal(extra, undefined, `texture line '${line}'`);
      uv.push(Number(u), Number(v));
    } else if (line.startsWith('f ')) {
      const corners = line.slice(2).split(' ');
      assert.ok(corners.length === 3, `face line '${line}' is a triangle`);
      for (const corner of corners) {
        const [v, vt, extra] = corner.split('/');
        assert.equal(extra, undefined, `face line '${line}': v or v/vt`);
        faces.push(Number(v) - 1);
        if (vt !== undefined) textureFaces.push(Number(vt) - 1);
      }
    }
  }
  return { vertices: Float64Array.from(vertices), faces: Float64Array.from(faces), uv: Float64Array.from(uv), textureFaces };
}

/**
 * Checks an OBJ as a terrain over [0, xMax] x [0, zMax]: every vertex inside, every face
 * counter-clockwise seen from +y (x east, z south: (b - a) x (c - a) has a positive y
 * component), every interior edge shared by exactly two faces in opposite directions, edges
 * of one face only on the rectangle's outline, and the faces' areas adding up to the
 * rectangle's. Returns the number of faces.
 */
function checkTerrainObj(path, xMax, zMax) {
  const { vertices: v, faces } = readObj(path);
  const n = v.length / 3, faceCount = faces.length / 3;
  assert.ok(faceCount > 0, 'the OBJ has faces');
  for (let i = 0; i < n; i++) {
    const x = v[3 * i], y = v[3 * i + 1], z = v[3 * i + 2];
    if (!(Number.isFinite(y) && x >= 0 && x <= xMax && z >= 0 && z <= zMax)) {
      assert.fail(`vertex ${i + 1} (${x}, ${y}, ${z}) must lie in [0, ${xMax}] x [0, ${zMax}]`);
    }
  }
  const used = new Uint8Array(n);
  const edges = new Float64Array(faces.length); // directed edge a -> b as a * n + b
  let area = 0;
  for (let f = 0; f < faceCount; f++) {
    const a = faces[3 * f], b = faces[3 * f + 1], c = faces[3 * f + 2];
    for (const i of [a, b, c]) {
      if (!(Number.isInteger(i) && i >= 0 && i < n)) assert.fail(`face ${f + 1} indexes vertex ${i + 1} of ${n}`);
      used[i] = 1;
    }
    const crossY = (v[3 * b + 2] - v[3 * a + 2]) * (v[3 * c] - v[3 * a]) - (v[3 * b] - v[3 * a]) * (v[3 * c + 2] - v[3 * a + 2]);
    if (!(crossY > 0)) assert.fail(`face ${f + 1} must be counter-clockwise seen from +y (cross y = ${crossY})`);
    area += crossY / 2;
    edges[3 * f] = a * n + b;
    edges[3 * f + 1] = b * n + c;
    edges[3 * f + 2] = c * n + a;
  }
  assert.ok(used.every((u) => u === 1), 'every vertex is used by a face');
  edges.sort();
  const has = (key) => { // binary search in the sorted edges
    let lo = 0, hi = edges.length - 1;
    while (lo <= hi) {
      const mid = (lo + hi) >> 1;
      if (edges[mid] === key) return true;
      if (edges[mid] < key) lo = mid + 1;
      else hi = mid - 1;
    }
    return false;
  };
  const tolerance = 1e-3;
  const onOutline = (a, b) => {
    const x1 = v[3 * a], z1 = v[3 * a + 2], x2 = v[3 * b], z2 = v[3 * b + 2];
    return (x1 <= tolerance && x2 <= tolerance) || (x1 >= xMax - tolerance && x2 >= xMax - tolerance) ||
      (z1 <= tolerance && z2 <= tolerance) || (z1 >= zMax - tolerance && z2 >= zMax - tolerance);
  };
  let boundary = 0;
  for (let k = 0; k < edges.length; k++) {
    const a = Math.floor(edges[k] / n), b = edges[k] - a * n;
    if (k > 0 && edges[k] === edges[k - 1]) assert.fail(`edge ${a + 1}-${b + 1} is used twice in the same direction`);
    if (!has(b * n + a)) {
      boundary += 1;
      if (!onOutline(a, b)) {
        assert.fail(`edge ${a + 1}-${b + 1} belongs to one face only, so it must lie on the rectangle's outline: ` +
          `(${v[3 * a]}, ${v[3 * a + 2]}) to (${v[3 * b]}, ${v[3 * b + 2]})`);
      }
    }
  }
  assert.ok(boundary > 0, 'the mesh has an outline');
  const rectangle = xMax * zMax;
  assert.ok(Math.abs(area - rectangle) <= 1e-6 * rectangle, `faces cover the rectangle exactly: ${area} vs ${rectangle}`);
  return faceCount;
}

const FIXTURES = [
  ['volcano_maungawhau.png', 87, 61, 10, 10],
  ['jacksboro_fault.f32', 403, 344, 74.4, 92.6],
  ['grandcanyon_512.png', 512, 512, 61.7, 61.7],
];

for (const [file, width, height, dx, dy] of FIXTURES) {
  test(`mesh --max-error 5 on ${file}: the OBJ is a watertight counter-clockwise terrain over the data rectangle, within 5 m`, () => {
    const dir = scratch();
    const obj = join(dir, 'mesh.obj'), json = join(dir, 'mesh.json');
    const r = run('mesh', fixture(file), '--max-error', '5', '--earth', 'flat', '--obj', obj, '--json', json);
    assert.equal(r.status, 0, r.stderr);
    assert.equal(r.stderr, '');
    assert.match(r.stdout, /converged after \d+ update/);
    const report = JSON.parse(readFileSync(json, 'utf8'));
    const xMax = (width - 1) * dx, zMax = (height - 1) * dy;
    assert.ok(Math.abs(report.rectangle.xMax - xMax) < 1e-9 && Math.abs(report.rectangle.zMax - zMax) < 1e-9);
    assert.equal(report.converged, true);
    assert.equal(report.settings.embedding, 'exact');
    assert.ok(report.error.original.max <= 5 + 1e-6, `max error vs original samples ${report.error.original.max} m`);
    assert.ok(report.error.stored.max <= 5 + 1e-6, `max error vs stored field ${report.error.stored.max} m`);
    assert.equal(report.error.original.uncovered, 0);
    const faces = checkTerrainObj(obj, xMax, zMax);
    assert.equal(faces, report.triangles.afterClipping);
    // Figures agree with each other.
    const { cells } = report;
    assert.equal(cells.fullHexagons + cells.boundarySemiHexagons + cells.interiorSemiHexagons + cells.other, cells.total);
    assert.ok(report.triangles.drawn >= report.triangles.keptWhole + report.triangles.cut);
    assert.ok(report.maxLevel >= 0 && report.maxLevel <= report.finestLevel);
    assert.equal(report.levels.reduce((s, l) => s + l.triangles, 0), report.triangles.drawn);
    assert.ok(report.bytes > 0 && Math.abs(report.bytesPerTriangle - report.bytes / report.triangles.drawn) < 0.01);
    assert.match(report.hash, /^[0-9a-f]{16}$/);
  });
}

test('mesh --max-error is deterministic: the same hash and OBJ twice', () => {
  const dir = scratch();
  const outputs = [1, 2].map((k) => {
    const r = run('mesh', fixture('volcano_maungawhau.png'), '--max-error', '2', '--obj', join(dir, `${k}.obj`), '--json', join(dir, `${k}.json`));
    assert.equal(r.status, 0, r.stderr);
    return [JSON.parse(readFileSync(join(dir, `${k}.json`), 'utf8')).hash, readFileSync(join(dir, `${k}.obj`), 'utf8')];
  });
  assert.deepEqual(outputs[0], outputs[1]);
});

test('mesh with a camera converges, reports its triangles and writes a valid OBJ', () => {
  const dir = scratch();
  const obj = join(dir, 'view.obj'), json = join(dir, 'view.json');
  // Over the north-west corner of the Grand Canyon, 2.5 km up, looking south-east and down.
  const r = run('mesh', fixture('grandcanyon_512.png'), '--earth', 'flat', '--camera', '-500,3000,-500', '--target', '15000,1000,15000',
    '--fov', '50', '--viewport', '1280x720', '--tau', '2', '--obj', obj, '--json', json);
  assert.equal(r.status, 0, r.stderr);
  const report = JSON.parse(readFileSync(json, 'utf8'));
  assert.equal(report.converged, true);
  assert.equal(report.settings.mode, 'view');
  assert.deepEqual(report.settings.camera, [-500, 3000, -500]);
  assert.deepEqual(report.settings.viewport, [1280, 720]);
  assert.equal(report.settings.tau, 2);
  assert.ok(report.settings.near > 0 && report.settings.far > report.settings.near);
  assert.ok(report.triangles.drawn > 1000, `${report.triangles.drawn} triangles`);
  assert.match(r.stdout, new RegExp(`${report.triangles.drawn} triangles drawn`));
  assert.equal(checkTerrainObj(obj, 511 * 61.7, 511 * 61.7), report.triangles.afterClipping);
});

test('mesh --budget-splits N stops after one update of at most N operations and still writes a valid mesh', () => {
  const dir = scratch();
  const obj = join(dir, 'budget.obj'), json = join(dir, 'budget.json');
  const r = run('mesh', fixture('jacksboro_fault.f32'), '--earth', 'flat', '--camera', '15000,2500,40000', '--target', '15000,500,15000',
    '--budget-splits', '40', '--obj', obj, '--json', json);
  assert.equal(r.status, 0, r.stderr);
  const report = JSON.parse(readFileSync(json, 'utf8'));
  assert.equal(report.updates, 1);
  assert.equal(report.settings.budgetSplits, 40);
  assert.ok(report.operations >= 1 && report.operations <= 40, `${report.operations} operations`);
  assert.ok(report.splits + report.merges <= 40, `${report.splits} splits, ${report.merges} merges`);
  assert.equal(report.converged, false, '40 operations do not converge for this view');
  assert.match(r.stdout, /budget 40 operations/);
  assert.equal(checkTerrainObj(obj, 402 * 74.4, 343 * 92.6), report.triangles.afterClipping);
});

test('mesh --embedding shifted and --cell-size are applied', () => {
  const dir = scratch();
  const obj = join(dir, 'shifted.obj'), json = join(dir, 'shifted.json');
  const r = run('mesh', fixture('volcano_maungawhau.png'), '--max-error', '3', '--embedding', 'shifted',
    '--cell-size', '12,8', '--obj', obj, '--json', json);
  assert.equal(r.status, 0, r.stderr);
  const report = JSON.parse(readFileSync(json, 'utf8'));
  assert.equal(report.settings.embedding, 'shifted');
  assert.equal(report.spacingX, 12);
  assert.equal(report.spacingY, 8);
  assert.equal(checkTerrainObj(obj, 86 * 12, 60 * 8), report.triangles.afterClipping);
});

test('a PNG without a cell size warns on stderr and uses 1 m, unless --cell-size is given', () => {
  const dir = scratch();
  copyFileSync(fixture('volcano_maungawhau.png'), join(dir, 'alone.png'));
  const warned = run('mesh', join(dir, 'alone.png'), '--max-error', '5', '--json', join(dir, 'a.json'));
  assert.equal(warned.status, 0, warned.stderr);
  assert.equal(warned.stderr, 'hexlod: warning: alone.png has no cell size; using 1 m, set --cell-size\n');
  assert.equal(JSON.parse(readFileSync(join(dir, 'a.json'), 'utf8')).spacingX, 1);
  const quiet = run('mesh', join(dir, 'alone.png'), '--max-error', '5', '--cell-size', '10', '--json', join(dir, 'b.json'));
  assert.equal(quiet.status, 0, quiet.stderr);
  assert.equal(quiet.stderr, '');
  assert.equal(JSON.parse(readFileSync(join(dir, 'b.json'), 'utf8')).rectangle.xMax, 860);
});

test('bad arguments and bad files exit 2 or 1 with one clear line on stderr', () => {
  const dir = scratch();
  const png = fixture('volcano_maungawhau.png');
  const truncated = join(dir, 'cut.png');
  writeFileSync(truncated, readFileSync(png).subarray(0, 3000));
  const camera = ['--camera', '100,300,100', '--target', '400,100,300'];
  for (const [args, status, pattern] of [
    [[join(dir, 'missing.png'), '--max-error', '5'], 1, /missing\.png: no such file/],
    [[truncated, '--max-error', '5'], 1, /cut\.png/],
    [[png, '--max-error', '5', '--frobnicate'], 2, /unknown option '--frobnicate'/],
    [[png, ...camera, '--tau', '-1'], 2, /--tau must be greater than 0/],
    [[png, '--camera', '1,2', '--target', '3,4,5'], 2, /--camera must be three numbers/],
    [[png, '--max-error', '5', ...camera], 2, /either --max-error or --camera, not both/],
    [[png], 2, /give --max-error M or --camera/],
    [[png, '--camera', '1,2,3'], 2, /--camera needs --target/],
    [[png, ...camera, '--viewport', '0x5'], 2, /--viewport must be WIDTHxHEIGHT/],
    [[png, '--max-error', '5', '--embedding', 'foo'], 2, /--embedding must be 'shifted' or 'exact'/],
    [[png, '--max-error', '5', '--cell-size', 'abc'], 2, /--cell-size must be DX or DX,DY/],
    [[png, '--max-error', '0'], 2, /--max-error must be greater than 0/],
    [[png, '--max-error', '5', '--budget-splits', '2.5'], 2, /--budget-splits must be an integer/],
    [[png, '--max-error', '5', '--tau', '2'], 2, /--tau goes with --camera/],
    [[png, '--camera', '1,2,3', '--target', '1,2,3'], 2, /the same point/],
    [[], 2, /mesh needs a height field file/],
  ]) {
    const r = run('mesh', ...args);
    assert.equal(r.status, status, `${args.join(' ')}: ${r.stderr}`);
    const lines = r.stderr.trim().split('\n');
    assert.equal(lines.length, 1, `one line for ${args.join(' ')}: ${r.stderr}`);
    assert.match(lines[0], /^hexlod: /);
    assert.match(lines[0], pattern);
    assert.doesNotMatch(r.stderr, /\n\s+at /, 'no stack trace');
    assert.equal(r.stdout, '');
  }
  const help = run('mesh', '--help');
  assert.equal(help.status, 0);
  assert.match(help.stdout, /usage: hexlod mesh <heightfield>/);
});

test('hexlod bench flies a short scripted flight, compares with martini and writes every figure as JSON', () => {
  const dir = scratch();
  const json = join(dir, 'bench.json');
  const r = run('bench', fixture('volcano_maungawhau.png'), '--frames', '8', '--budget-ops', '50', '--max-error', '2', '--json', json);
  assert.equal(r.status, 0, r.stderr);
  assert.match(r.stdout, /update\s+p50 [\d.]+ ms, p95 [\d.]+ ms/);
  assert.match(r.stdout, /ratio\s+triangles ours \/ martini [\d.]+/);
  const report = JSON.parse(readFileSync(json, 'utf8'));
  assert.equal(report.frames.length, 8);
  assert.ok(report.frames.every((f) => f.operations <= 50 && f.triangles > 0));
  // Within tau and fades pending are told apart: converged is exactly both settled.
  const counts = r.stdout.match(/within tau in (\d+) of 8 frames, fades pending in (\d+), both settled in (\d+)/);
  assert.ok(counts, r.stdout);
  assert.deepEqual(counts.slice(1).map(Number), [report.flight.withinTauFrames, report.flight.fadingFrames, report.flight.convergedFrames]);
  for (const f of report.frames) assert.equal(f.converged, f.refined && !f.fading, `frame ${f.frame}`);
  assert.ok(report.firstFrame.warm.converged);
  assert.ok(report.maxError.error.max <= 2 + 1e-6);
  assert.ok(report.martini.error.max <= report.maxError.error.max + 1e-6, 'martini matched at no more than our error');
  assert.ok(report.martini.triangles > 0 && report.ratios.trianglesOursOverMartini > 0);
  assert.ok(report.native.missing || report.native.ratios.updateP50 > 0, 'a WASM/native ratio, or why there is none');
  const bad = run('bench', fixture('volcano_maungawhau.png'), '--frames', '0');
  assert.equal(bad.status, 2);
  assert.match(bad.stderr, /^hexlod: --frames must be at least 1/);
});

// The Blue Marble image over the default terrain (tests/fixtures/imagery/README.md): texture
// coordinates are checked against the world file's and the sidecar's numbers, worked out here
// from their definitions rather than by the placement code under test.
const DEFAULT_TERRAIN = fileURLToPath(new URL('../../public/terrain/globe_himalaya_2048.png', import.meta.url));
const BLUE_MARBLE = fixture('imagery/bmng_himalaya_4arcmin.jpg');

test('mesh --image: every vertex gets the texture coordinate of its ground point in the georeferenced image, and NAME.mtl names the image', () => {
  const dir = scratch();
  const obj = join(dir, 'draped.obj'), json = join(dir, 'draped.json');
  const r = run('mesh', DEFAULT_TERRAIN, '--max-error', '1500', '--earth', 'flat', '--obj', obj, '--json', json, '--image', BLUE_MARBLE);
  assert.equal(r.status, 0, r.stderr);
  assert.equal(r.stderr, '', 'a georeferenced image gives no warning');
  assert.match(r.stdout, /image +bmng_himalaya_4arcmin\.jpg: 256 x 257 pixels, georeferenced by bmng_himalaya_4arcmin\.jgw/);

  const sidecar = JSON.parse(readFileSync(DEFAULT_TERRAIN.replace(/\.png$/, '.json'), 'utf8'));
  const [A, , , E, C, F] = readFileSync(BLUE_MARBLE.replace(/\.jpg$/, '.jgw'), 'utf8').trim().split(/\s+/).map(Number);
  const [imageWidth, imageHeight] = [256, 257];
  const { west, north } = sidecar.bounds_deg, cell = sidecar.cell_size_deg;
  const dx = sidecar.cell_size_x_m, dy = sidecar.cell_size_y_m;
  // Ground point x (metres east of the first column's centre), z (south of the first row's):
  // the samples' centres lie half a cell inside the sidecar's bounds; the world file gives the
  // first pixel's centre, so the image's left edge is C - A / 2 and its top edge F - E / 2.
  // OBJ v runs up from the image's bottom.
  const expected = (x, z) => {
    const lon = west + (x / dx + 0.5) * cell, lat = north - (z / dy + 0.5) * cell;
    const px = (lon - (C - A / 2)) / A, py = (lat - (F - E / 2)) / E;
    return [px / imageWidth, 1 - py / imageHeight];
  };

  const { vertices, faces, uv, textureFaces } = readObj(obj);
  const n = vertices.length / 3;
  assert.equal(uv.length / 2, n, 'a texture coordinate per vertex');
  assert.deepEqual(textureFaces, Array.from(faces), 'each face corner names its own vertex\'s texture coordinate');
  const text = readFileSync(obj, 'utf8');
  assert.match(text, /^mtllib draped\.mtl$/m);
  assert.match(text, /^usemtl (\S+)$/m);
  const material = /^usemtl (\S+)$/m.exec(text)[1];
  assert.ok(text.indexOf('usemtl') < text.indexOf('\nf '), 'the material is set before the faces');
  let worst = 0, corners = 0;
  const xMax = 2047 * dx, zMax = 2047 * dy;
  for (let i = 0; i < n; i++) {
    const x = vertices[3 * i], z = vertices[3 * i + 2];
    const [u, v] = expected(x, z);
    worst = Math.max(worst, Math.abs(uv[2 * i] - u) * imageWidth, Math.abs(uv[2 * i + 1] - v) * imageHeight);
    if ((x === 0 || Math.abs(x - xMax) < 1e-3) && (z === 0 || Math.abs(z - zMax) < 1e-3)) corners += 1;
  }
  assert.equal(corners, 4, 'the four corners of the field are vertices');
  assert.ok(worst < 1e-3, `texture coordinates within a thousandth of a pixel of the expected ones (worst ${worst} pixels)`);
  // The north-west corner's sample centre is a sixteenth of a pixel right of the image's left
  // edge and 0.3125 pixels below its top edge (4 arc minutes a pixel, half a 30" cell inside).
  const nw = Array.from({ length: n }, (_, i) => i).find((i) => vertices[3 * i] === 0 && vertices[3 * i + 2] === 0);
  assert.ok(Math.abs(uv[2 * nw] - 0.0625 / 256) < 1e-6 && Math.abs(uv[2 * nw + 1] - (1 - 0.3125 / 257)) < 1e-6,
    `north-west corner at (${uv[2 * nw]}, ${uv[2 * nw + 1]})`);

  const mtl = readFileSync(join(dir, 'draped.mtl'), 'utf8');
  assert.match(mtl, new RegExp(`^newmtl ${material}$`, 'm'));
  const map = /^map_Kd (.+)$/m.exec(mtl);
  assert.ok(map, 'the material has a diffuse map');
  assert.ok(!map[1].startsWith('/'), `a relative path: ${map[1]}`);
  assert.equal(readFileSync(join(dir, map[1])).compare(readFileSync(BLUE_MARBLE)), 0, 'map_Kd leads from the OBJ\'s folder to the image');
  const report = JSON.parse(readFileSync(json, 'utf8'));
  assert.equal(report.image.placement, 'georeferenced');
  assert.equal(report.image.worldFile, 'bmng_himalaya_4arcmin.jgw');
  assert.equal(report.image.coverage, 1);
});

test('mesh --image without a world file stretches the image over the field and says so', () => {
  const dir = scratch();
  const image = join(dir, 'plain.jpg'), obj = join(dir, 'plain.obj');
  copyFileSync(BLUE_MARBLE, image);
  const r = run('mesh', DEFAULT_TERRAIN, '--max-error', '3000', '--earth', 'flat', '--obj', obj, '--image', image);
  assert.equal(r.status, 0, r.stderr);
  assert.match(r.stderr, /^hexlod: warning: plain\.jpg: the image has no georeference: stretched over the whole field$/m);
  assert.match(r.stdout, /image +plain\.jpg: .*STRETCHED over the whole field/);
  const { vertices, uv } = readObj(obj);
  const xMax = Math.max(...vertices.filter((_, k) => k % 3 === 0)), zMax = Math.max(...vertices.filter((_, k) => k % 3 === 2));
  for (let i = 0; i < vertices.length / 3; i++) {
    const u = vertices[3 * i] / xMax, v = 1 - vertices[3 * i + 2] / zMax;
    assert.ok(Math.abs(uv[2 * i] - u) < 1e-6 && Math.abs(uv[2 * i + 1] - v) < 1e-6, `vertex ${i + 1}: (${uv[2 * i]}, ${uv[2 * i + 1]}) vs (${u}, ${v})`);
  }
  assert.match(readFileSync(join(dir, 'plain.mtl'), 'utf8'), /^map_Kd plain\.jpg$/m);
});

test('mesh --image refuses an image in another CRS, a garbage world file and a missing image, with one line and exit 1; misuse exits 2', () => {
  const dir = scratch();
  const obj = join(dir, 'x.obj');
  const garbage = join(dir, 'garbage.jgw');
  writeFileSync(garbage, 'this is\nnot a world file\n');
  const cut = join(dir, 'cut.jpg');
  writeFileSync(cut, readFileSync(BLUE_MARBLE).subarray(0, 40));
  const base = [DEFAULT_TERRAIN, '--max-error', '3000', '--obj', obj];
  for (const [args, status, pattern] of [
    [[...base, '--image', fixture('imagery/haiti_rgb_5m_tiled_deflate.tif')], 1,
      /haiti_rgb_5m_tiled_deflate\.tif: it lies outside the terrain/],
    [[...base, '--image', BLUE_MARBLE, '--world-file', garbage], 1, /garbage\.jgw: a world file holds six numbers/],
    [[...base, '--image', join(dir, 'missing.jpg')], 1, /missing\.jpg: no such image file/],
    [[...base, '--image', cut], 1, /cut\.jpg: not an image hexlod can drape/],
    [[...base, '--image', BLUE_MARBLE, '--world-file', join(dir, 'missing.jgw')], 1, /missing\.jgw: no such world file/],
    [[...base, '--world-file', garbage], 2, /--world-file goes with --image/],
    [[DEFAULT_TERRAIN, '--max-error', '3000', '--image', BLUE_MARBLE], 2, /--image needs --obj/],
  ]) {
    const r = run('mesh', ...args);
    assert.equal(r.status, status, `${args.join(' ')}: ${r.stderr}`);
    const lines = r.stderr.trim().split('\n');
    assert.equal(lines.length, 1, `one line: ${r.stderr}`);
    assert.match(lines[0], /^hexlod: /);
    assert.match(lines[0], pattern);
    assert.equal(r.stdout, '');
  }
  assert.throws(() => readFileSync(obj), 'no OBJ is written for a refused image');
});

test('mesh --image with a GeoTIFF on a terrain without georeference: stretched with a warning, and the material names the TIFF', () => {
  const dir = scratch();
  const obj = join(dir, 'volcano.obj');
  const tiff = fixture('imagery/haiti_rgb_5m_strips_lzw_pred2.tif');
  const r = run('mesh', fixture('volcano_maungawhau.png'), '--max-error', '5', '--obj', obj, '--image', tiff);
  assert.equal(r.status, 0, r.stderr);
  assert.match(r.stderr, /warning: haiti_rgb_5m_strips_lzw_pred2\.tif: the terrain has no georeference: stretched over the whole field/);
  assert.match(r.stdout, /515 x 403 pixels, STRETCHED/);
  const { vertices, uv } = readObj(obj);
  const corner = Array.from({ length: vertices.length / 3 }, (_, i) => i).find((i) => vertices[3 * i] === 860 && vertices[3 * i + 2] === 600);
  assert.deepEqual([uv[2 * corner], uv[2 * corner + 1]], [1, 0], 'the south-east corner is the image\'s bottom right');
  const map = /^map_Kd (.+)$/m.exec(readFileSync(join(dir, 'volcano.mtl'), 'utf8'))[1];
  assert.equal(readFileSync(join(dir, map)).compare(readFileSync(tiff)), 0);
});
