// The WebAssembly build of the core, driven from Node through web/core/core.js exactly as the page
// drives it: real fixtures decoded straight into WASM memory, at native depth.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { createNodeCore, wasmPath, factoryPath } from '../../lib/node_core.js';
import { createCore, ABI_VERSION, CoreError, FRAME } from '../../web/core/core.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';

const fixtures = new URL('../fixtures/', import.meta.url);
const read = (name) => ({ name, bytes: new Uint8Array(readFileSync(new URL(name, fixtures))) });
const sidecar = (base) => JSON.parse(readFileSync(new URL(`${base}.json`, fixtures), 'utf8'));
const floats = (base) => new Float32Array(readFileSync(new URL(`${base}.f32`, fixtures)).buffer.slice(0));

const core = await createNodeCore();
const BASES = ['volcano_maungawhau', 'jacksboro_fault', 'grandcanyon_512'];

test('the WASM core reports the ABI version of src/api/hexlod.h', () => {
  // The header's number, so a stale build (or a header changed without a rebuild) fails here.
  const header = readFileSync(new URL('../../src/api/hexlod.h', import.meta.url), 'utf8');
  const declared = Number(/#define HEXLOD_ABI_VERSION (\d+)/.exec(header)?.[1]);
  assert.ok(declared >= 14, `HEXLOD_ABI_VERSION ${declared} in the header`);
  assert.equal(core.abiVersion, declared);
  assert.equal(ABI_VERSION, declared, 'web/core/core.js ABI_VERSION is the header\'s');
});

test('a core of another ABI version, or one without the version function, is refused with a clear error', async () => {
  // The real diagnostics build, with what it reports about its ABI changed after instantiation.
  const { default: realFactory } = await import(factoryPath.href);
  const wasmBinary = readFileSync(wasmPath);
  const patched = (change) => async (settings) => { const module = await realFactory(settings); change(module); return module; };
  await assert.rejects(createCore({ wasmBinary, factory: patched((m) => { m._hexlod_abi_version = () => ABI_VERSION - 1; }) }),
    (error) => error instanceof CoreError && error.message === `the WebAssembly core has ABI version ${ABI_VERSION - 1}, but web/core/core.js needs ABI version ${ABI_VERSION}: rebuild the core (./build.sh wasm) or install a matching hexlod`);
  await assert.rejects(createCore({ wasmBinary, factory: patched((m) => { m._hexlod_abi_version = () => ABI_VERSION + 1; }) }),
    new RegExp(`has ABI version ${ABI_VERSION + 1}, but web/core/core.js needs ABI version ${ABI_VERSION}`));
  await assert.rejects(createCore({ wasmBinary, factory: patched((m) => { delete m._hexlod_abi_version; }) }),
    new RegExp(`the WebAssembly core exports no hexlod_abi_version, but web/core/core.js needs ABI version ${ABI_VERSION}`));
  // The same factory unchanged is accepted: the refusals above come from the version alone.
  assert.equal((await createCore({ wasmBinary, factory: patched(() => {}) })).abiVersion, ABI_VERSION);
});

for (const base of BASES) {
  test(`${base}.f32 loads into WASM with the sidecar's size, spacing and height range`, async () => {
    const meta = sidecar(base);
    const { terrain, field } = await loadTerrain(core, [read(`${base}.f32`), read(`${base}.json`)]);
    assert.equal(terrain.width, meta.width);
    assert.equal(terrain.height, meta.height);
    assert.equal(field.spacingX, meta.cell_size_x_m ?? meta.cell_size_m);
    assert.equal(field.spacingY, meta.cell_size_y_m ?? meta.cell_size_m);
    assert.ok(Math.abs(terrain.minHeight - meta.min) < 0.5 && Math.abs(terrain.maxHeight - meta.max) < 0.5);
    // Bilinear lookups at sample positions return the samples themselves.
    const raw = floats(base);
    for (const [j, i] of [[0, 0], [meta.width - 1, meta.height - 1], [7, 11], [meta.width >> 1, meta.height >> 1]]) {
      const h = terrain.heightAt(j * field.spacingX, i * field.spacingY);
      assert.ok(Math.abs(h - raw[i * meta.width + j]) < 1e-3, `sample (${j}, ${i})`);
    }
    terrain.destroy();
  });

  test(`${base}.png stays 16-bit in WASM memory and matches the f32 within half a quantum`, async () => {
    const meta = sidecar(base);
    const { terrain } = await loadTerrain(core, [read(`${base}.png`), read(`${base}.json`)]);
    assert.equal(terrain.sampleType, 'u16');
    assert.equal(terrain.sampleBytes, meta.width * meta.height * 2);
    const raw = floats(base);
    const halfQuantum = (meta.max - meta.min) / 65535 / 2 + 1e-3;
    for (let k = 0; k < raw.length; k += 97) {
      const i = Math.floor(k / meta.width), j = k % meta.width;
      const h = terrain.heightAt(j * terrain.spacingX, i * terrain.spacingY);
      assert.ok(Math.abs(h - raw[k]) <= halfQuantum, `sample ${k}: ${h} vs ${raw[k]}`);
    }
    terrain.destroy();
  });
}

test('views are refreshed after memory growth and pointers above 2 GB work (>>> 0)', () => {
  // Fill WASM memory with 512 MB fields until one lies above 2 GB, as a 16k field might.
  const small = core.createTerrain(4, 4, 'u16');
  const before = core.buffer;
  const big = [];
  let high = null;
  while (!high && big.length < 6) {
    const t = core.createTerrain(16385, 16385, 'u16');
    big.push(t);
    if (core.module._hexlod_terrain_samples(t.handle) < 0) high = t;
  }
  assert.ok(high, 'no field was placed above 2 GB');
  assert.notEqual(core.buffer, before, 'memory grew');
  assert.equal(small.samples().length, 16, 'a fresh view works after growth');
  const samples = high.samples();
  samples.fill(1000);
  samples[0] = 7;
  samples[samples.length - 1] = 65535;
  high.setScale({ spacingX: 1, spacingY: 1, heightScale: 0.5, heightOffset: 10, nodata: null });
  high.prepare();
  assert.equal(high.minHeight, 7 * 0.5 + 10);
  assert.equal(high.maxHeight, 65535 * 0.5 + 10);
  for (const t of [...big, small]) t.destroy();
});

test('core failures surface as CoreError with the core message', () => {
  assert.throws(() => core.createTerrain(1, 5, 'u16'), /at least 2x2 samples/);
  assert.throws(() => core.createTerrain(5, 5, 'rgb'), /unknown sample type/);
  const t = core.createTerrain(3, 3, 'f32');
  t.samples().fill(NaN);
  assert.throws(() => t.prepare(), /every sample is nodata/);
  assert.throws(() => t.setScale({ spacingX: 0, spacingY: 1, heightScale: 1, heightOffset: 0, nodata: null }), /spacing must be positive/);
  t.destroy();
  assert.throws(() => t.samples(), /destroyed/);
});

test('the hexagon mesh through the ABI: uniform and local refinement, fans decode to its triangles', async () => {
  const { terrain } = await loadTerrain(core, [read('jacksboro_fault.png'), read('jacksboro_fault.json')]);
  assert.throws(() => terrain.refineUniform(1), /no hexagon mesh yet/);
  assert.throws(() => terrain.resetMesh('sheared'), /unknown embedding/);
  terrain.resetMesh('exact');
  const base = { ...terrain.query() };
  assert.ok(base.cells > 0 && base.maxLevel >= 2);
  assert.ok(terrain.refineUniform(2) > 0);
  const uniform = { ...terrain.query() };
  assert.equal(uniform.triangles, base.triangles * 16, 'two uniform splits are two 1-to-4 splits');
  // A mixed-level mesh: view-independent refinement to 10 m on top of the uniform split.
  terrain.configure({ maxErrorM: 10 });
  assert.ok(terrain.updateLod() > 0);
  terrain.checkMesh();
  const stats = { ...terrain.query() };
  terrain.updateStream();
  const stream = terrain.stream();
  // One slot of 9 per cell record: a fan, then restarts (free records: restarts only).
  assert.equal(stream.indices.length % 9, 0);
  let triangles = 0, fans = 0;
  for (let slot = 0; slot < stream.indices.length; slot += 9) {
    let length = 0;
    while (length < 9 && stream.indices[slot + length] !== 0xffffffff) {
      assert.ok(stream.indices[slot + length] < stream.vertexCount);
      length += 1;
    }
    assert.ok(length < 9, 'every slot ends with a restart');
    for (let k = length; k < 9; k++) assert.equal(stream.indices[slot + k], 0xffffffff);
    if (length > 0) {
      triangles += length - 2;
      fans += 1;
    }
  }
  assert.equal(triangles, stats.triangles);
  assert.equal(fans, stats.cells);
  const level = terrain.levelView(false);
  assert.equal(level.levelOffsets.at(-1), level.indices.length);
  assert.ok(stats.memoryBytes / stats.triangles < 100, `${stats.memoryBytes / stats.triangles} bytes per triangle`);
  terrain.destroy();
});

test('terrain.frame is one core call that returns the same stats object every frame, whose figures the queries read', async () => {
  const { terrain } = await loadTerrain(core, [read('jacksboro_fault.png'), read('jacksboro_fault.json')]);
  terrain.resetMesh('exact');
  terrain.configure({ budgetMs: 0, maxOperations: 300 });
  const camera = { eye: [15000, 3000, 33000], target: [15000, 400, 9000], fovY: 0.9, aspect: 1.6, viewportHeight: 600, near: 1, far: 1e6 };
  const first = terrain.frame(camera);
  const operations = first.operations, version = first.version;
  assert.ok(operations > 0 && first.splits > 0 && first.cellsTested > 0);
  assert.ok(first.dirtyVertexPairs > 0 && first.dirtyIndexPairs > 0, 'a new mesh is all dirty');
  terrain.acknowledgeStream();
  const second = terrain.frame(camera);
  assert.equal(second, first, 'the same object every frame: the frame loop makes no garbage');
  assert.ok(second.version > version, 'the stream moved');
  const stream = terrain.stream();
  assert.equal(stream.indices.length, second.indexCount);
  assert.equal(stream.dirtyIndices.length, 2 * second.dirtyIndexPairs);
  assert.equal(terrain.query(FRAME.hash).hash(), terrain.meshHash());
  const cells = second.cells;
  const kinds = terrain.cellKinds();
  assert.equal(kinds.full + kinds.semi + kinds.boundarySemi, cells);
  terrain.destroy();
});

test('the product build (the page\'s) exports the product ABI only; the diagnostics build adds the diagnostics', async () => {
  const product = await createCore({ wasmBinary: readFileSync(new URL('../../build/wasm/hexlod_core.wasm', import.meta.url)) });
  assert.equal(product.hasDiagnostics, false);
  assert.equal(core.hasDiagnostics, true);
  const exported = (c) => Object.keys(c.module).filter((k) => k.startsWith('_hexlod_')).sort();
  const productAbi = exported(product);
  // Exactly the functions hexlod.h declares: nothing of the diagnostics, nothing missing.
  const header = readFileSync(new URL('../../src/api/hexlod.h', import.meta.url), 'utf8');
  const declared = [...new Set([...header.matchAll(/\b(hexlod_[a-z_]+)\(/g)].map((m) => `_${m[1]}`))].sort();
  assert.deepEqual(productAbi, declared);
  assert.deepEqual(exported(core).filter((k) => !k.startsWith('_hexlod_diag_')), productAbi);
  const t = product.createTerrain(4, 4, 'f32');
  t.samples().set(Array.from({ length: 16 }, (_, k) => k));
  t.setScale({ spacingX: 1, spacingY: 1, heightScale: 1, heightOffset: 0, nodata: null });
  t.prepare();
  t.resetMesh('exact');
  assert.throws(() => t.checkMesh(), /diagnostics build/);
  assert.ok(t.frame(null).triangles > 0);
  t.destroy();
});
