// Every terrain opens framed (web/cameras/framing.js): its region in view, the eye above the surface
// with nothing between it and the target, at any base height, size, aspect, spacing and
// exaggeration. Fields are made in the WASM core (the page's own) and through the loaders.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { vec4 } from 'gl-matrix';
import { createNodeCore } from '../../lib/node_core.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';
import { createWorld } from '../../web/cameras/ground.js';
import { OrbitCamera } from '../../web/cameras/orbit.js';
import { frameTerrain, openingRegion, regionHeights, meanSlope } from '../../web/cameras/framing.js';

const core = await createNodeCore();
const fixtures = new URL('../fixtures/', import.meta.url);
const read = (name) => ({ name, bytes: new Uint8Array(readFileSync(new URL(name, fixtures))) });

/** A float field of width x height samples, height(i, j) metres, `spacing` metres apart. */
function field(width, height, spacing, heightOf) {
  const terrain = core.createTerrain(width, height, 'f32');
  const samples = terrain.samples();
  for (let i = 0; i < height; ++i) for (let j = 0; j < width; ++j) samples[i * width + j] = heightOf(i, j);
  terrain.setScale({ spacingX: spacing, spacingY: spacing, heightScale: 1, heightOffset: 0, nodata: null });
  terrain.prepare();
  return terrain;
}

/** A smooth relief between `low` and `high` metres. */
const hills = (low, high, period = 17) => (i, j) =>
  low + (high - low) * (0.5 + 0.25 * Math.sin(i / period) + 0.25 * Math.cos(j / (period * 0.7)));

/**
 * Frames a terrain as the page does and checks what a person would see: the opening region's box
 * projects inside the view and fills a good part of it, the eye is above the full-resolution
 * field, and no ground stands between the eye and the target.
 */
function checkFraming(label, terrain, { exaggeration = 1, aspect = 16 / 9, covered = { top: 0, bottom: 0 } } = {}) {
  const extent = { extentX: (terrain.width - 1) * terrain.spacingX, extentZ: (terrain.height - 1) * terrain.spacingY,
    low: terrain.minHeight * exaggeration, high: terrain.maxHeight * exaggeration };
  const world = createWorld(terrain, extent, () => exaggeration, () => 1);
  const orbit = new OrbitCamera();
  orbit.world = world;
  frameTerrain(terrain, world, orbit, exaggeration, aspect, covered);
  orbit.update(aspect);
  const eye = orbit.position;
  for (const value of [...eye, orbit.distance, orbit.near, orbit.far]) assert.ok(Number.isFinite(value), `${label}: finite camera`);

  // The eye above the ground under it (the highest samples around it), when over the field.
  const over = eye[0] >= 0 && eye[2] >= 0 && eye[0] <= extent.extentX && eye[2] <= extent.extentZ;
  if (over) assert.ok(eye[1] > world.ground(eye[0], eye[2]), `${label}: eye ${eye[1]} above ground ${world.ground(eye[0], eye[2])}`);
  assert.ok(eye[1] > orbit.target[1], `${label}: the eye looks down on the target`);

  // Nothing between the eye and the target: every step of the line of sight above the ground.
  for (let k = 1; k < 200; ++k) {
    const t = k / 200 * 0.97;
    const x = eye[0] + (orbit.target[0] - eye[0]) * t, z = eye[2] + (orbit.target[2] - eye[2]) * t;
    if (x < 0 || z < 0 || x > extent.extentX || z > extent.extentZ) continue;
    const y = eye[1] + (orbit.target[1] - eye[1]) * t;
    assert.ok(y >= terrain.heightAt(x, z) * exaggeration, `${label}: ground blocks the view at ${t.toFixed(2)} of the way`);
  }

  // The region's surface (sampled as the framing samples it: every point, corners included)
  // inside the view, in front of the near plane, and large on screen.
  const region = openingRegion(terrain, extent.extentX, extent.extentZ);
  const { points } = regionHeights(terrain, region, exaggeration);
  let reach = 0;
  for (const point of points) {
    const clip = vec4.transformMat4(vec4.create(), [...point, 1], orbit.viewProjection);
    assert.ok(clip[3] > orbit.near, `${label}: (${point}) in front of the near plane`);
    const ndc = [clip[0] / clip[3], clip[1] / clip[3], clip[2] / clip[3]];
    assert.ok(ndc.every((c) => Math.abs(c) <= 1), `${label}: (${point}) in view: ${ndc.map((c) => c.toFixed(3))}`);
    assert.ok(ndc[1] <= 1 - 2 * covered.top && ndc[1] >= -1 + 2 * covered.bottom, `${label}: (${point}) clear of the bars`);
    reach = Math.max(reach, Math.abs(ndc[0]), Math.abs(ndc[1] - (covered.bottom - covered.top)) / (1 - covered.top - covered.bottom));
  }
  assert.ok(reach > 0.85, `${label}: the region fills the view (it reaches ${reach.toFixed(2)} of the half-size)`);

  // The surface faces the camera: its mean plane is seen at a good angle, not edge-on.
  const { east, south } = meanSlope(points);
  const normal = [-east, 1, -south], toEye = [eye[0] - orbit.target[0], eye[1] - orbit.target[1], eye[2] - orbit.target[2]];
  const facing = (normal[0] * toEye[0] + normal[1] * toEye[1] + normal[2] * toEye[2]) / (Math.hypot(...normal) * Math.hypot(...toEye));
  assert.ok(facing > 0.35, `${label}: the surface faces the eye (cosine ${facing.toFixed(2)})`);
  return { orbit, region };
}

test('fields at any base height open with the eye above them', () => {
  const cases = [
    ['all below sea level', field(200, 150, 90, hills(-8000, -3000))],
    ['all above 4000 m', field(200, 150, 90, hills(4000, 8800))],
    ['flat at 0 m', field(64, 64, 30, () => 0)],
    ['flat at 5000 m', field(64, 64, 30, () => 5000)],
    ['flat at -400 m', field(64, 64, 30, () => -400)],
    ['a single spike', field(101, 101, 10, (i, j) => (i === 50 && j === 50 ? 3000 : 100))],
    ['a spike at the corner', field(101, 101, 10, (i, j) => (i === 0 && j === 0 ? 3000 : 100))],
  ];
  for (const [label, terrain] of cases) {
    for (const exaggeration of [1, 3]) checkFraming(`${label} ×${exaggeration}`, terrain, { exaggeration });
    terrain.destroy();
  }
});

test('tiny, long and thin fields open framed', () => {
  const cases = [
    ['2x2', field(2, 2, 30, (i, j) => 100 + 10 * i + 5 * j)],
    ['2x2 flat', field(2, 2, 30, () => 0)],
    ['2x2 leaning north', field(2, 2, 30, (i, j) => 100 + 20 * i + 10 * j)],
    ['a plane leaning east', field(50, 40, 10, (i, j) => 8 * j)],
    ['2x300', field(2, 300, 30, hills(200, 600, 9))],
    ['300x2', field(300, 2, 30, hills(200, 600, 9))],
    ['4096x8 strip', field(4096, 8, 5, hills(1000, 1400, 150))],
    ['8x4096 strip', field(8, 4096, 5, hills(1000, 1400, 150))],
    ['2000x600', field(2000, 600, 100, hills(0, 3000, 80))],
  ];
  for (const [label, terrain] of cases) {
    for (const aspect of [16 / 9, 9 / 16]) checkFraming(`${label} at aspect ${aspect.toFixed(2)}`, terrain, { aspect });
    checkFraming(`${label} between bars`, terrain, { covered: { top: 0.12, bottom: 0.08 } });
    terrain.destroy();
  }
});

test('spacings from 0.5 m to 1 km and exaggerations from 1 to 20 open framed', () => {
  for (const spacing of [0.5, 2, 30, 1000]) {
    // A 2 m lidar tile 380-700 m above sea level, scaled to each spacing.
    const terrain = field(300, 300, spacing, hills(380, 380 + 320 * (spacing / 2) ** 0.5, 23));
    for (const exaggeration of [1, 2, 20]) checkFraming(`${spacing} m, ×${exaggeration}`, terrain, { exaggeration });
    terrain.destroy();
  }
});

test('a one-row or one-column file opens as a ribbon, framed', async () => {
  for (const [width, height] of [[1, 400], [400, 1]]) {
    const heights = Float32Array.from({ length: width * height }, (_, k) => 500 + 200 * Math.sin(k / 30));
    const sidecar = new TextEncoder().encode(JSON.stringify({ width, height, cell_size_m: 25 }));
    const { terrain } = await loadTerrain(core, [{ name: 'profile.f32', bytes: new Uint8Array(heights.buffer) },
      { name: 'profile.json', bytes: sidecar }]);
    assert.deepEqual([terrain.width, terrain.height], [Math.max(width, 2), Math.max(height, 2)]);
    assert.equal(terrain.spacingX, 25);
    assert.equal(terrain.spacingY, 25);
    const along = (k) => (width === 1 ? terrain.heightAt(12.5, k * 25) : terrain.heightAt(k * 25, 12.5));
    for (const k of [0, 77, 399]) assert.ok(Math.abs(along(k) - heights[k]) < 1e-3, `sample ${k} kept`);
    checkFraming(`${width}x${height} profile`, terrain);
    terrain.destroy();
  }
});

test('the real DEMs and every format fixture open framed; a large field opens on its relief', async () => {
  const files = [['grandcanyon_512.png', 'grandcanyon_512.json'], ['jacksboro_fault.png', 'jacksboro_fault.json'],
    ['volcano_maungawhau.png', 'volcano_maungawhau.json']];
  const manifest = JSON.parse(readFileSync(new URL('formats/manifest.json', fixtures), 'utf8'));
  for (const entry of manifest) files.push({ names: entry.files.map((n) => `formats/${n}`), options: entry.options });
  assert.ok(files.length >= 15, `format fixtures found: ${files.length}`);
  for (const { names, options } of files.map((f) => (Array.isArray(f) ? { names: f } : f))) {
    const { terrain } = await loadTerrain(core, names.map(read), { guessSpacing: true, ...options });
    for (const exaggeration of [1, 2]) checkFraming(`${names[0]} ×${exaggeration}`, terrain, { exaggeration });
    terrain.destroy();
  }
  // The default terrain (2048²) opens on a region, not the whole field: its front range.
  const { terrain } = await loadTerrain(core, [read('../../public/terrain/globe_himalaya_2048.png'),
    read('../../public/terrain/globe_himalaya_2048.json')]);
  const { region } = checkFraming('Himalaya', terrain, { exaggeration: 2 });
  const extentX = (terrain.width - 1) * terrain.spacingX;
  assert.ok(region.x1 - region.x0 < 0.5 * extentX, 'a region of the field');
  assert.ok(regionHeights(terrain, region, 1).high > 7000, 'the region holds the high peaks');
  terrain.destroy();
});
