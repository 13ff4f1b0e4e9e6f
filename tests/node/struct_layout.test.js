// The struct layouts JS reads and writes come from the core (hexlod_struct_layout), and they are
// the header's: every field src/api/hexlod.h declares is listed, at the size its comment gives,
// and web/core/core.js reads every field of a frame into FrameStats.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { createNodeCore } from '../../lib/node_core.js';
import { camelCase, FrameStats } from '../../web/core/core.js';

const core = await createNodeCore();
const header = readFileSync(new URL('../../src/api/hexlod.h', import.meta.url), 'utf8');

/** The header's structs: {name: {bytes (from the comment before it, or null), fields: [names]}}. */
function headerStructs() {
  const structs = {};
  const pattern = /\/\*((?:(?!\*\/)[\s\S])*)\*\/\s*typedef struct hexlod_(\w+) \{([\s\S]*?)\} hexlod_\w+;/g;
  for (const [, comment, name, body] of header.matchAll(pattern)) {
    const bytes = /(\d+) bytes/.exec(comment);
    const code = body.replace(/\/\*[\s\S]*?\*\//g, '');
    const fields = [];
    for (const declaration of code.split(';')) {
      const names = declaration.trim().replace(/^(const\s+)?\w+\*?\s*\*?\s*/, '').split(',');
      for (const n of names) {
        const field = n.trim().replace(/\[\d+\]$/, '');
        if (field && field !== 'reserved') fields.push(field);
      }
    }
    structs[name] = { bytes: bytes ? Number(bytes[1]) : null, fields };
  }
  return structs;
}

test('the core reports every struct and field of src/api/hexlod.h, at the sizes the header gives', () => {
  const declared = headerStructs();
  assert.deepEqual(Object.keys(core.layout).sort(), Object.keys(declared).sort());
  for (const [name, { bytes, fields }] of Object.entries(declared)) {
    const reported = core.layout[name];
    if (bytes !== null) assert.equal(reported.size, bytes, `hexlod_${name} is ${bytes} bytes in the header`);
    assert.deepEqual(Object.keys(reported.fields).filter((f) => f !== 'reserved'), fields, `hexlod_${name}'s fields`);
  }
});

test('every field lies inside its struct, aligned to its type, and fields do not overlap', () => {
  const bytesOf = { f64: 8, i32: 4, u32: 4, ptr: 4 };
  for (const [name, struct] of Object.entries(core.layout)) {
    const used = new Uint8Array(struct.size);
    for (const [field, { offset, type, count }] of Object.entries(struct.fields)) {
      const size = bytesOf[type];
      assert.ok(size, `hexlod_${name}.${field} has a known type (${type})`);
      assert.equal(offset % size, 0, `hexlod_${name}.${field} is aligned`);
      assert.ok(offset + size * count <= struct.size, `hexlod_${name}.${field} lies inside the struct`);
      for (let b = offset; b < offset + size * count; b++) {
        assert.equal(used[b], 0, `hexlod_${name}.${field} overlaps another field`);
        used[b] = 1;
      }
    }
  }
});

test('a frame fills one FrameStats, a property per hexlod_frame field, the same object every frame', () => {
  const terrain = core.createTerrain(65, 65, 'f32');
  terrain.samples().fill(3);
  terrain.setScale({ spacingX: 10, spacingY: 10, heightScale: 1, heightOffset: 0, nodata: null });
  terrain.prepare();
  terrain.resetMesh('exact');
  const camera = { eye: [320, 400, 900], target: [320, 0, 320], fovY: 1, aspect: 1, viewportHeight: 600, near: 1, far: 1e4 };
  const first = terrain.frame(camera);
  assert.ok(first instanceof FrameStats);
  assert.equal(terrain.frame(camera), first, 'the same object');
  const renamed = { tau_px: 'tau', vertices_ptr: 'vertexPointer', indices_ptr: 'indexPointer',
    dirty_vertices_ptr: 'dirtyVerticesPointer', dirty_indices_ptr: 'dirtyIndicesPointer', normals_ptr: 'normalsPointer' };
  const keys = Object.keys(core.layout.frame.fields).map((f) => renamed[f] ?? camelCase(f));
  assert.deepEqual(Object.keys(first).sort(), keys.sort());
  assert.ok(first.triangles > 0 && first.cells > 0 && first.indexCount > 0 && first.vertexPointer > 0);
  assert.equal(first.tau, 1, 'the default tau');
  assert.equal(typeof first.converged, 'boolean');
  terrain.destroy();
});
