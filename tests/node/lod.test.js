// View-dependent refinement (src/hexlod.h, "View-dependent refinement") through web/core/core.js,
// on real fixtures decoded straight into WASM memory, as the page and the CLI drive it. The
// mesh invariants are checked after every update.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { createNodeCore } from '../../lib/node_core.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';
import { CoreError } from '../../web/core/core.js';

const fixtures = new URL('../fixtures/', import.meta.url);
const read = (name) => ({ name, bytes: new Uint8Array(readFileSync(new URL(name, fixtures))) });
const core = await createNodeCore();
const load = async (base, ext = 'png') => (await loadTerrain(core, [read(`${base}.${ext}`), read(`${base}.json`)])).terrain;

/** The camera of a 1920 x 1080 viewport with a 60 degree vertical field of view. */
const camera = (eye, target) => ({ eye, target, fovY: Math.PI / 3, aspect: 16 / 9, viewportHeight: 1080, near: 1, far: 1e7 });
// Jacksboro fault (403 x 344 samples, 30 x 32 km): from 2.5 km up south of the field, looking north.
const NEAR = camera([15000, 2500, 40000], [15000, 500, 15000]);
const FAR = camera([15000, 300000, 200000], [15000, 500, 15000]);

/**
 * Updates until converged (at most `limit` updates), checking the invariants after each.
 * @returns {{updates: number, operations: number, splits: number, merges: number, perUpdate: object[]}}
 */
function converge(terrain, limit = 1000) {
  const run = { updates: 0, operations: 0, splits: 0, merges: 0, perUpdate: [] };
  while (run.updates < limit) {
    const operations = terrain.updateLod();
    terrain.checkMesh();
    const figures = { ...terrain.query() };
    run.updates += 1;
    run.operations += operations;
    run.splits += figures.splits;
    run.merges += figures.merges;
    run.perUpdate.push({ operations, ...figures });
    if (figures.converged) return run;
  }
  assert.fail(`no convergence after ${limit} updates`);
}

for (const [base, ext, maxError] of [['volcano_maungawhau', 'f32', 1], ['jacksboro_fault', 'png', 5], ['grandcanyon_512', 'png', 5]]) {
  test(`max-error mode on ${base}.${ext} converges with every sample within ${maxError} m (measured by the core)`, async () => {
    const terrain = await load(base, ext);
    terrain.resetMesh('exact');
    terrain.configure({ maxErrorM: maxError });
    terrain.configure({ budgetMs: 0, maxOperations: 0 });
    const run = converge(terrain);
    assert.ok(run.splits > 0);
    assert.equal(terrain.query().converged, true);
    for (const againstStored of [true, false]) {
      const error = terrain.measureError(againstStored);
      assert.ok(error.max <= maxError + 1e-6, `max error ${error.max} m (against ${againstStored ? 'stored' : 'original'} samples)`);
      assert.ok(error.p99 <= error.max && error.mean <= error.p99 + 1e-12, JSON.stringify(error));
      assert.equal(error.uncovered, 0);
    }
    // A looser error needs fewer triangles, and coarsening to it converges too.
    const fine = terrain.query().triangles;
    terrain.configure({ maxErrorM: maxError * 4 });
    const coarsening = converge(terrain);
    assert.ok(coarsening.merges > 0);
    assert.ok(terrain.query().triangles < fine);
    assert.ok(terrain.measureError(false).max <= maxError * 4 + 1e-6);
    terrain.destroy();
  });
}

test('max-error mode with the shifted embedding keeps every sample of the stored field within the error', async () => {
    const terrain = await load('jacksboro_fault');
    terrain.resetMesh('shifted');
    terrain.configure({ maxErrorM: 5 });
    terrain.configure({ budgetMs: 0, maxOperations: 0 });
    converge(terrain);
    assert.ok(terrain.measureError(true).max <= 5 + 1e-6, `${terrain.measureError(true).max} m`);
    terrain.destroy();
  });

test('moving the camera far away coarsens the mesh (merges, fewer triangles); coming back refines it again', async () => {
  const terrain = await load('jacksboro_fault');
  terrain.resetMesh('exact');
  terrain.configure({ budgetMs: 0, maxOperations: 0 });
  terrain.setLodCamera(NEAR);
  terrain.configure({ tauPx: 1, maxErrorM: 0 });
  const first = converge(terrain);
  assert.ok(first.splits > 0);
  const near = terrain.query().triangles;
  terrain.setLodCamera(FAR);
  const away = converge(terrain);
  const far = terrain.query().triangles;
  assert.ok(away.merges > 0, 'merges happened');
  assert.ok(far < near / 10, `${far} triangles far away, ${near} near`);
  terrain.setLodCamera(NEAR);
  const back = converge(terrain);
  assert.ok(back.splits > 0);
  assert.equal(terrain.query().triangles, near, 'the same view gives as many triangles again');
  terrain.destroy();
});

test('a budget of N operations does at most N per update, and repeated updates still converge', async () => {
  const terrain = await load('jacksboro_fault');
  const N = 150;
  // View-dependent: refine from the base mesh, then coarsen for a far camera, N at a time.
  terrain.resetMesh('exact');
  terrain.configure({ budgetMs: 0, maxOperations: N });
  terrain.setLodCamera(NEAR);
  terrain.configure({ tauPx: 1, maxErrorM: 0 });
  for (const view of [NEAR, FAR]) {
    terrain.setLodCamera(view);
    const run = converge(terrain, 5000);
    assert.ok(run.updates > 2, `${run.updates} updates: the budget split the work`);
    for (const [i, u] of run.perUpdate.entries()) {
      assert.ok(u.operations <= N, `update ${i}: ${u.operations} operations`);
      assert.ok(u.splits + u.merges <= N, `update ${i}: ${u.splits} splits + ${u.merges} merges`);
      if (!u.converged) assert.ok(u.operations >= 1, `update ${i} made progress`);
    }
  }
  // Max-error mode under the same budget ends within the error.
  terrain.resetMesh('exact');
  terrain.configure({ maxErrorM: 10 });
  const run = converge(terrain, 5000);
  assert.ok(run.perUpdate.every((u) => u.operations <= N));
  assert.ok(terrain.measureError(false).max <= 10 + 1e-6);
  terrain.destroy();
});

test('every LOD setting reaches the core: vertical scale, culling, triangle cap with auto tau', async () => {
  const terrain = await load('jacksboro_fault');
  terrain.resetMesh('exact');
  terrain.configure({ budgetMs: 0, maxOperations: 0 });
  terrain.setLodCamera(NEAR);
  terrain.configure({ tauPx: 1, maxErrorM: 0 });
  converge(terrain);
  const base = terrain.query().triangles;
  const stats = { ...terrain.query() };
  assert.equal(stats.tau, 1);
  assert.ok(stats.updateMs > 0 && stats.updateMs < 60000, `the update was timed: ${stats.updateMs} ms`);

  terrain.configure({ verticalScale: 3 });
  converge(terrain);
  assert.ok(terrain.query().triangles > base, 'exaggerated heights need more triangles');
  terrain.configure({ verticalScale: 1 });
  converge(terrain);

  terrain.configure({ noFrustumCulling: true });
  converge(terrain);
  assert.ok(terrain.query().triangles > base, 'without culling, cells outside the view are refined too');
  terrain.configure({ noFrustumCulling: false });
  converge(terrain);

  // From the base mesh with a cap far below what tau 1 needs: the cap holds splits back and
  // auto tau raises tau above the tolerance that was set.
  terrain.resetMesh('exact');
  terrain.configure({ maxTriangles: 5000, autoTau: true });
  for (let i = 0; i < 50; i++) {
    terrain.updateLod();
    terrain.checkMesh();
    if (terrain.query().converged) break;
  }
  assert.ok(terrain.query().triangles < base / 2, `${terrain.query().triangles} triangles under a cap of 5000`);
  assert.ok(terrain.query().tau > 1, `tau rose to ${terrain.query().tau}`);
  terrain.configure({ maxTriangles: 0, autoTau: false });
  terrain.destroy();
});

test('bad LOD settings throw a CoreError with the core message', async () => {
  const terrain = await load('volcano_maungawhau');
  assert.throws(() => terrain.updateLod(), /no hexagon mesh yet/);
  terrain.resetMesh('exact');
  assert.throws(() => terrain.configure({ tauPx: 0.001 }), CoreError);
  assert.throws(() => terrain.configure({ tauPx: -1 }), /tau must be a positive/);
  assert.throws(() => terrain.configure({ maxErrorM: -1 }), /maximum error must be a positive/);
  assert.throws(() => terrain.configure({ verticalScale: -1 }), /vertical scale must be a positive/);
  assert.throws(() => terrain.configure({ tau: 1 }), /unknown core setting 'tau'/);
  assert.throws(() => terrain.setLodCamera(camera([100, 200, 300], [100, 200, 300])), /degenerate camera/);
  assert.throws(() => terrain.setLodCamera({ ...camera([0, 500, 0], [400, 100, 300]), near: 0 }), /degenerate camera/);
  terrain.destroy();
  assert.throws(() => terrain.updateLod(), /destroyed/);
});

test('the mesh hash repeats for the same calls and changes with the mesh', async () => {
  const hashes = [];
  for (let run = 0; run < 2; run++) {
    const terrain = await load('volcano_maungawhau');
    terrain.resetMesh('exact');
    const base = terrain.meshHash();
    terrain.configure({ maxErrorM: 2 });
    converge(terrain);
    assert.notEqual(terrain.meshHash(), base);
    assert.match(terrain.meshHash(), /^[0-9a-f]{16}$/);
    hashes.push(terrain.meshHash());
    terrain.destroy();
  }
  assert.equal(hashes[0], hashes[1]);
});
