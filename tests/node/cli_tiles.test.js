// hexlod mesh on a Cloud-Optimized GeoTIFF, as a user runs it: from a path and from a URL on a
// range server, only part of the file is read, and the mesh is the one of the same file read
// whole (its cells; with the same heights where the full resolution was read).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, copyFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { createNodeCore } from '../../lib/node_core.js';
import { cameraFor } from '../../lib/cli_common.js';
import { startRangeServer } from '../../lib/range_server.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';

const cli = fileURLToPath(new URL('../../bin/hexlod.js', import.meta.url));
const cogs = fileURLToPath(new URL('../fixtures/cog/', import.meta.url));
const HIMALAYA = 'himalaya_1024_i16.tif';
// Looking down on the south-west from high up: about a tenth of the field in view.
const EYE = [165000, 99000, 758000], TARGET = [165000, 0, 741000];
const VIEW = ['--earth', 'flat', '--camera', EYE.join(','), '--target', TARGET.join(','), '--viewport', '1280x720'];
let server, dir;

before(async () => {
  server = await startRangeServer(cogs, { latencyMs: 5 });
  dir = mkdtempSync(join(tmpdir(), 'hexlod-cog-cli-'));
});
after(() => server.close());

/** Runs the CLI without blocking this process (the range server lives here). */
function run(...args) {
  return new Promise((resolve) => {
    const child = spawn(process.execPath, [cli, ...args]);
    let stdout = '', stderr = '';
    child.stdout.on('data', (d) => (stdout += d));
    child.stderr.on('data', (d) => (stderr += d));
    child.on('close', (status) => resolve({ status, stdout, stderr }));
  });
}

async function wholeTriangles() {
  const core = await createNodeCore();
  const { terrain } = await loadTerrain(core, [{ name: HIMALAYA, bytes: new Uint8Array(readFileSync(cogs + HIMALAYA)) }]);
  terrain.resetMesh('exact');
  terrain.setLodCamera(cameraFor(terrain, EYE, TARGET, 60, [1280, 720]));
  terrain.configure({ tauPx: 1, maxErrorM: 0, budgetMs: 0 });
  let stats;
  for (let k = 0; k < 200 && !stats?.converged; k++) stats = terrain.frame(null);
  return stats.triangles;
}

test('hexlod mesh streams a COG from a path and from a URL: part of the file read, the whole file\'s cells', async () => {
  const whole = await wholeTriangles();
  const size = readFileSync(cogs + HIMALAYA).length;
  copyFileSync(cogs + HIMALAYA, join(dir, HIMALAYA));
  for (const input of [join(dir, HIMALAYA), `${server.url}/${HIMALAYA}`]) {
    const json = join(dir, 'mesh.json');
    const result = await run('mesh', input, ...VIEW, '--json', json);
    assert.equal(result.status, 0, result.stderr);
    assert.match(result.stdout, /^streamed  \d+ tiles; [\d.]+ of 1\.5 MB of the file read/m);
    const report = JSON.parse(readFileSync(json, 'utf8'));
    assert.ok(report.converged);
    assert.ok(report.streamed.tiles > 0);
    assert.equal(report.streamed.fileBytes, size);
    assert.ok(report.streamed.bytesFetched < 0.5 * size, `${report.streamed.bytesFetched} of ${size} bytes`);
    assert.equal(report.triangles.drawn, whole, input);
  }
});

test('hexlod mesh on a COG URL that is gone says so in one line', async () => {
  const result = await run('mesh', `${server.url}/missing.tif`, ...VIEW);
  assert.notEqual(result.status, 0);
  assert.match(result.stderr, /missing\.tif.*404/);
});
