// Which tiles a view needs (web/webtiles/tile_selection.js), for a Himalaya-sized terrain placed
// on its real longitudes and latitudes: a camera looking at one corner asks for tiles there and
// none elsewhere, the nearest first and the finest near it, texels about a pixel where they
// fall; the base level covers the whole terrain in a few tiles and comes first; nothing finer
// than the table's zoom; a view away from the terrain asks for the base level alone.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mat4 } from 'gl-matrix';
import { TileSelection, BASE_TILES } from '../../web/webtiles/tile_selection.js';
import { terrainBounds, tableRange } from '../../web/webtiles/table_range.js';
import { lonLatToWorld, tileLonLatBounds } from '../../web/webtiles/web_mercator.js';

// The default terrain's extent (72.93-90.0 E, 20.8-37.93 N) in ground metres as the page makes
// them from degrees (a degree of longitude shortened by the cosine of the middle latitude);
// heights times an exaggeration of 2.
const WEST = 72.9333, EAST = 90.0, NORTH = 37.9333, SOUTH = 20.8;
const EXTENT_X = (EAST - WEST) * 111320 * Math.cos((((NORTH + SOUTH) / 2) * Math.PI) / 180), EXTENT_Z = (NORTH - SOUTH) * 110574;
const terrain = { extentX: EXTENT_X, extentZ: EXTENT_Z, low: 0, high: 2 * 8752 };
const scratch = [0, 0];
const toMercator = (x, z) => lonLatToWorld(WEST + (x / EXTENT_X) * (EAST - WEST), NORTH - (z / EXTENT_Z) * (NORTH - SOUTH), scratch);
const bounds = terrainBounds(EXTENT_X, EXTENT_Z, toMercator);
const table = tableRange(bounds, 19);
const FOV = (50 * Math.PI) / 180, HEIGHT = 600;

function view(eye, target, { maxZoom = table.zoom, minZoom = 0, height = HEIGHT } = {}) {
  const viewMatrix = mat4.lookAt(mat4.create(), eye, target, [0, 1, 0]);
  const projection = mat4.perspective(mat4.create(), FOV, 1.6, 10, 4e6);
  return { position: eye, viewProjection: mat4.multiply(mat4.create(), projection, viewMatrix), viewportHeight: height, fovY: FOV,
    terrain, toMercator, bounds, tileSize: 256, minZoom, maxZoom };
}

/** [west, south, east, north] of a tile in terrain metres (x east, z south). */
function groundOf(t) {
  const [w, s, e, n] = tileLonLatBounds(t.z, t.x, t.y);
  const x = (lon) => ((lon - WEST) / (EAST - WEST)) * EXTENT_X, z = (lat) => ((NORTH - lat) / (NORTH - SOUTH)) * EXTENT_Z;
  return [x(w), z(s), x(e), z(n)];
}

test('the table zoom: the finest whose tiles over the terrain fit 1024 a side', () => {
  // 17.07° of longitude: 777 tiles of zoom 14, 1554 of zoom 15.
  assert.deepEqual(table, { zoom: 14, x0: Math.floor((WEST / 360 + 0.5) * 2 ** 14), y0: Math.floor(lonLatToWorld(0, NORTH)[1] * 2 ** 14),
    width: table.width, height: table.height });
  assert.ok(table.width <= 1024 && table.height <= 1024 && table.width > 512);
  assert.equal(tableRange(bounds, 9).zoom, 9, 'no finer than the layer');
});

test('a camera looking down at the north-west corner asks for tiles there and none elsewhere', () => {
  const selection = new TileSelection({ maxTiles: 400 });
  const tiles = selection.select(view([100000, 150000, 100000], [100000, 0, 100001]));
  const base = tiles.filter((t) => t.base), near = tiles.filter((t) => !t.base);
  assert.ok(base.length >= 1 && base.length <= BASE_TILES && base.every((t) => t.z === selection.baseZoom), 'a few base tiles');
  assert.deepEqual(tiles.slice(0, base.length), base, 'the base level first');
  assert.ok(near.length > 10, `${near.length} tiles in view`);
  for (const t of near) {
    const [w, , , n] = groundOf(t);
    assert.ok(w < 400000 && n < 400000, `tile ${t.z}/${t.x}/${t.y} lies within 400 km of the corner`);
  }
  // The corner itself is covered: the tiles over the ground straight below.
  const below = lonLatToWorld(WEST + (100000 / EXTENT_X) * (EAST - WEST), NORTH - (100000 / EXTENT_Z) * (NORTH - SOUTH));
  const finest = near[0];
  assert.ok(near.some((t) => t.z === finest.z && t.x === Math.floor(below[0] * 2 ** t.z) && t.y === Math.floor(below[1] * 2 ** t.z)));
});

test('an oblique view: nearest first, finer near than far, none finer than the table', () => {
  const selection = new TileSelection({ maxTiles: 1000 });
  const near = selection.select(view([-20000, 20000, -20000], [60000, 0, 60000])).filter((t) => !t.base);
  assert.ok(near.length > 20, `${near.length} tiles in view`);
  for (let i = 1; i < near.length; i++) assert.ok(near[i].distance >= near[i - 1].distance, 'nearest first');
  assert.ok(near[0].z >= near[near.length - 1].z + 3, `finer near (${near[0].z}) than far (${near[near.length - 1].z})`);
  assert.ok(near.every((t) => t.z <= table.zoom));
});

test('texels are about a screen pixel where they fall', () => {
  const selection = new TileSelection({ maxTiles: 2000 });
  // Straight down from 40 km over the middle: every tile's texel within a factor 1.5 of the pixel at its distance.
  const eye = [EXTENT_X / 2, 40000 + terrain.high, EXTENT_Z / 2];
  const tiles = selection.select(view(eye, [eye[0], 0, eye[2] + 1]));
  const near = tiles.filter((t) => !t.base);
  assert.ok(near.length > 0);
  for (const t of near) {
    const [w, s, e, n] = groundOf(t);
    const texel = Math.min(e - w, s - n) / 256, pixel = (t.distance * 2 * Math.tan(FOV / 2)) / HEIGHT;
    assert.ok(texel <= pixel * 1.5 && texel >= pixel / 1.5, `zoom ${t.z}: texel ${texel.toFixed(0)} m, pixel ${pixel.toFixed(0)} m`);
    assert.ok(s > n);
  }
  // Twice the viewport height: one zoom finer.
  const fine = new TileSelection({ maxTiles: 2000 }).select(view(eye, [eye[0], 0, eye[2] + 1], { height: 2 * HEIGHT })).filter((t) => !t.base);
  assert.equal(Math.max(...fine.map((t) => t.z)), Math.max(...near.map((t) => t.z)) + 1);
});

test('zooms stay within the layer\'s and the table\'s; a view away from the terrain wants the base level alone', () => {
  const selection = new TileSelection({ maxTiles: 400 });
  const low = selection.select(view([60000, 3000, 60000], [120000, 0, 120000], { maxZoom: 9, minZoom: 6 }));
  assert.ok(low.every((t) => t.z >= 6 && t.z <= 9), 'within 6..9');
  assert.ok(low.some((t) => t.z === 9));
  const away = selection.select(view([-10000, 5000, -10000], [-20000, 5000, -20000]));
  assert.ok(away.length > 0 && away.every((t) => t.base), 'only the base level');
});

test('the farthest are left out past maxTiles; the records and the list are reused', () => {
  const selection = new TileSelection({ maxTiles: 20 });
  const v = view([60000, 30000, 60000], [120000, 5000, 120000]);
  const first = selection.select(v);
  assert.equal(first.length, 20);
  const records = [...first];
  const again = selection.select(v);
  assert.equal(again, first, 'the same array');
  assert.deepEqual(again, records);
  assert.ok(again.every((t, i) => t === records[i]), 'the same records');
  const all = new TileSelection({ maxTiles: 5000 }).select(v);
  assert.deepEqual(again.map((t) => t.key), all.slice(0, 20).map((t) => t.key), 'the most wanted 20');
});

test('a height range per patch culls what lies below the view and finds the ground nearer', () => {
  const v = view([-20000, 20000, -20000], [60000, 0, 60000]);
  const whole = new TileSelection({ maxTiles: 5000 }).select(v).filter((t) => !t.base);
  // A flat terrain at 0..100 m: patches far away sink below the view's lower edge.
  const flat = new TileSelection({ maxTiles: 5000 }).select({ ...v, heightRange: (x0, z0, x1, z1, out) => { out[0] = 0; out[1] = 100; return out; } })
    .filter((t) => !t.base);
  assert.ok(flat.length < whole.length, `${flat.length} tiles over flat ground, ${whole.length} with the whole range`);
  // Over the terrain, 10 m above a ridge that the whole range (up to 17.5 km) does not reach:
  // the nearest ground is nearer, the finest tile finer.
  const over = view([20000, 20000, 20000], [60000, 0, 60000], { maxZoom: 20 });
  const below = new TileSelection({ maxTiles: 5000 }).select(over).filter((t) => !t.base);
  const ridge = new TileSelection({ maxTiles: 5000 }).select({ ...over, heightRange: (x0, z0, x1, z1, out) => { out[0] = 0; out[1] = 19990; return out; } })
    .filter((t) => !t.base);
  assert.ok(ridge[0].z > below[0].z, `finest ${ridge[0].z} near a ridge, ${below[0].z} without`);
});
