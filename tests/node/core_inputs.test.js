// What the WebAssembly core refuses (src/api/hexlod.h: the ranges of hexlod_camera,
// hexlod_settings and hexlod_scale), driven from Node as the page drives it, on the product
// build the page loads (build/wasm): non-finite, non-positive and absurd numbers are refused with
// a message naming the field, and a refused call leaves the mesh, the stream, the camera and the
// settings as they were. Settings the JS facade cleans up itself (budgets) are also written
// straight into the C struct, to reach the core's own checks. The fixtures' float32 samples go
// straight into the core (no loader), so that only the core is under test.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { createCore, CoreError } from '../../web/core/core.js';
import { SETTINGS as PAGE_SETTINGS, defaultSettings, coreSettings } from '../../web/app/settings_table.js';

const root = new URL('../../', import.meta.url);
const fixtures = new URL('tests/fixtures/', root);
const product = new URL('build/wasm/', root);
if (!existsSync(fileURLToPath(new URL('hexlod_core.wasm', product)))) throw new Error('build/wasm is not built: run ./build.sh wasm');
const { default: factory } = await import(new URL('hexlod_core.mjs', product).href);
const core = await createCore({ wasmBinary: readFileSync(fileURLToPath(new URL('hexlod_core.wasm', product))), factory });

/** A fixture's .f32 samples in a new terrain, scaled by its .json sidecar and prepared. */
async function load(base) {
  const meta = JSON.parse(readFileSync(new URL(`${base}.json`, fixtures), 'utf8'));
  const samples = new Float32Array(readFileSync(new URL(`${base}.f32`, fixtures)).buffer.slice(0));
  const terrain = core.createTerrain(meta.width, meta.height, 'f32');
  terrain.samples().set(samples);
  terrain.setScale({ spacingX: meta.cell_size_x_m ?? meta.cell_size_m, spacingY: meta.cell_size_y_m ?? meta.cell_size_m,
    heightScale: 1, heightOffset: 0, nodata: null });
  terrain.prepare();
  return terrain;
}

// Jacksboro fault (403 x 344 samples, 30 x 32 km), from 2.5 km up south of the field, looking
// north: 1920 x 1080, 60 degrees.
const GOOD = Object.freeze({ eye: [15000, 2500, 40000], target: [15000, 500, 15000], up: [0, 1, 0], fovY: Math.PI / 3,
  aspect: 16 / 9, viewportHeight: 1080, near: 1, far: 1e7 });

function converge(terrain, camera) {
  let stats = terrain.frame(camera);
  for (let n = 0; !stats.converged; n++) {
    assert.ok(n < 500, 'converges within 500 frames');
    stats = terrain.frame(null);
  }
}

/** What a refused call must leave: the same mesh and stream, and nothing to do at the next frame. */
function snapshot(terrain) {
  return { hash: terrain.meshHash(), version: terrain.query().version, triangles: terrain.query().triangles };
}
function assertUnchanged(terrain, before, what) {
  assert.deepEqual(snapshot(terrain), before, `${what}: the mesh and stream are as before`);
  const stats = terrain.frame(null);
  assert.equal(stats.operations, 0, `${what}: the previous camera and settings still hold`);
  assert.equal(stats.converged, true, what);
  assert.equal(terrain.meshHash(), before.hash, what);
}

const CAMERAS = [
  ['viewport_height_px', { viewportHeight: Infinity }],
  ['viewport_height_px', { viewportHeight: NaN }],
  ['viewport_height_px', { viewportHeight: 0 }],
  ['viewport_height_px', { viewportHeight: -600 }],
  ['viewport_height_px', { viewportHeight: 1e6 }],
  ['eye\\[0\\]', { eye: [NaN, 2500, 40000] }],
  ['eye\\[1\\]', { eye: [15000, Infinity, 40000] }],
  ['eye\\[2\\]', { eye: [15000, 2500, -1e13] }],
  ['target\\[1\\]', { target: [15000, -Infinity, 15000] }],
  ['up\\[2\\]', { up: [0, 1, NaN] }],
  ['tan_half_fov_y', { fovY: Math.PI }], // tan(pi / 2): 1.6e16
  ['tan_half_fov_y', { tanHalfFovY: 0 }],
  ['tan_half_fov_y', { tanHalfFovY: -1 }],
  ['tan_half_fov_y', { fovY: NaN }],
  ['aspect', { aspect: Infinity }],
  ['aspect', { aspect: 0 }],
  ['aspect', { aspect: -16 / 9 }],
  ['near_m', { near: 0 }],
  ['near_m', { near: -1 }],
  ['near_m', { near: 1e7 }], // = far
  ['near_m', { near: NaN }],
  ['far_m', { far: Infinity }],
  ['far_m', { far: 1e13 }],
  ['eye on the target', { target: [15000, 2500, 40000] }],
  ['along the view', { target: [15000, 0, 40000] }], // straight down with +y up
];

test('cameras with non-finite, non-positive or absurd fields are refused naming the field; the mesh and camera stay', async () => {
  const terrain = await load('jacksboro_fault');
  terrain.resetMesh('exact');
  converge(terrain, GOOD);
  const before = snapshot(terrain);
  assert.ok(before.triangles > 1000);
  for (const [field, change] of CAMERAS) {
    const camera = { ...GOOD, ...change };
    assert.throws(() => terrain.frame(camera), (error) => error instanceof CoreError &&
      new RegExp(`^invalid camera: degenerate camera: .*${field}`).test(error.message), `${field} ${JSON.stringify(change)}`);
    assertUnchanged(terrain, before, `${field} ${JSON.stringify(change)}`);
  }
  terrain.destroy();
});

test('viewportHeight = Infinity is refused, not refined to full resolution', async () => {
  const terrain = await load('grandcanyon_512');
  terrain.resetMesh('exact');
  const camera = { eye: [15000, 5000, 40000], target: [15000, 1000, 15000], fovY: Math.PI / 3, aspect: 16 / 9, viewportHeight: 1080,
    near: 1, far: 1e7 };
  converge(terrain, camera);
  const triangles = terrain.query().triangles;
  assert.throws(() => terrain.setLodCamera({ ...camera, viewportHeight: Infinity }),
    /viewport_height_px is inf; it must be a finite number of device pixels from 1 to 100000/);
  converge(terrain, null);
  assert.equal(terrain.query().triangles, triangles);
  terrain.destroy();
});

// hexlod_settings written as given (configure() hands every value to the core unchanged, in
// one call); the core's message, or null when it accepted them.
function setRawSettings(terrain, fields) {
  try {
    terrain.configure({ tauPx: 1, maxErrorM: 0, verticalScale: 1, budgetMs: 0, maxOperations: 0, maxTriangles: 0, autoTau: 0,
      noFrustumCulling: 0, noBackfaceCulling: 0, morphFrames: 0, layout: 0, noNormals: 0, ...fields });
    return null;
  } catch (error) {
    if (!(error instanceof CoreError)) throw error;
    return error.message.replace(/^invalid settings: /, '');
  }
}

const SETTINGS = [
  ['tau_px', { tauPx: -1 }], ['tau_px', { tauPx: NaN }], ['tau_px', { tauPx: Infinity }], ['tau_px', { tauPx: 0.001 }], ['tau_px', { tauPx: 2e4 }],
  ['max_error_m', { maxErrorM: -5 }], ['max_error_m', { maxErrorM: Infinity }], ['max_error_m', { maxErrorM: 1e-9 }],
  ['vertical_scale', { verticalScale: -2 }], ['vertical_scale', { verticalScale: NaN }], ['vertical_scale', { verticalScale: 5000 }],
  ['budget_ms', { budgetMs: -4 }], ['budget_ms', { budgetMs: Infinity }], ['budget_ms', { budgetMs: NaN }], ['budget_ms', { budgetMs: 1e6 }],
  ['max_operations', { maxOperations: -100 }], ['max_triangles', { maxTriangles: -1 }],
  ['morph_frames', { morphFrames: -1 }], ['morph_frames', { morphFrames: 1001 }], ['layout', { layout: 2 }],
];

test('settings outside their ranges are refused by the core naming the field; the settings and mesh stay', async () => {
  const terrain = await load('jacksboro_fault');
  terrain.resetMesh('exact');
  terrain.configure({ tauPx: 2, maxErrorM: 0 });
  converge(terrain, GOOD);
  assert.equal(setRawSettings(terrain, { tauPx: 2 }), null, 'the same settings, written raw, are accepted');
  const before = snapshot(terrain);
  for (const [field, change] of SETTINGS) {
    const message = setRawSettings(terrain, { tauPx: 2, ...change });
    assert.match(message ?? 'accepted', new RegExp(`^settings: ${field} is `), `${field} ${JSON.stringify(change)}`);
    assertUnchanged(terrain, before, `${field} ${JSON.stringify(change)}`);
  }
  // Through configure(): the core's message reaches the caller and the facade keeps its copy of
  // the settings.
  assert.throws(() => terrain.configure({ tauPx: 0.001 }), /invalid settings: settings: tau_px is 0.001; tau must be a positive number of pixels from 0.01 to 10000/);
  assert.throws(() => terrain.configure({ verticalScale: 5000 }), /vertical_scale is 5000/);
  assert.throws(() => terrain.configure({ maxErrorM: 5e9 }), /max_error_m is 5e\+09/);
  assert.throws(() => terrain.configure({ morphFrames: 1001 }), /morph_frames is 1001/);
  assert.equal(terrain.settings.tauPx, 2);
  assert.equal(terrain.settings.verticalScale, 1);
  assert.equal(terrain.settings.morphFrames, 0);
  assertUnchanged(terrain, before, 'configure');
  terrain.destroy();
});

test('a scale that puts heights beyond 1e9 m is refused and the terrain stays', async () => {
  const terrain = await load('volcano_maungawhau');
  terrain.resetMesh('exact');
  converge(terrain, { ...GOOD, eye: [430, 300, 900], target: [430, 120, 300], far: 1e5 });
  const before = snapshot(terrain);
  const height = terrain.heightAt(430, 300);
  const scale = { spacingX: 10, spacingY: 10, heightScale: 1, heightOffset: 0, nodata: null };
  assert.throws(() => terrain.setScale({ ...scale, heightOffset: 2e9 }), /height offset must be between -1e9 m and 1e9 m/);
  assert.throws(() => terrain.setScale({ ...scale, heightScale: 1e8 }), /heights must lie between -1e9 m and 1e9 m/);
  assert.throws(() => terrain.setScale({ ...scale, spacingX: Infinity }), /must be finite/);
  assert.equal(terrain.heightAt(430, 300), height);
  assert.ok(Number.isNaN(terrain.heightAt(NaN, 300)), 'a NaN position has no height');
  assertUnchanged(terrain, before, 'scale');
  terrain.destroy();
});

test("the page's setting ranges (web/app/settings_table.js) lie within what the core accepts, at both ends", async () => {
  const terrain = await load('volcano_maungawhau');
  terrain.resetMesh('exact');
  let applied = 0;
  for (const key of ['tau', 'budgetMs', 'maxOperations', 'maxTriangles', 'exaggeration']) {
    for (const value of [PAGE_SETTINGS[key].min, PAGE_SETTINGS[key].max]) {
      const settings = { ...defaultSettings(), [key]: value };
      assert.doesNotThrow(() => terrain.configure(coreSettings(settings)), `${key} = ${value}`);
      applied++;
    }
  }
  assert.equal(applied, 10);
  terrain.frame({ ...GOOD, eye: [430, 300, 900], target: [430, 120, 300], far: 1e5 });
  terrain.destroy();
});
