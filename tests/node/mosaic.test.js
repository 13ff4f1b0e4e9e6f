// Several tiles make one height field (web/loaders/mosaic.js): real tiles cut from one real DEM
// come back as that DEM, sample for sample, whether they share their edge samples (as adjacent
// SRTM tiles do) or abut; a missing tile is no-data, filled; tiles that cannot be one grid are
// refused with both names and what differs. Fixtures: tests/fixtures/mosaic/README.md.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, mkdtempSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadHeightfield, HeightfieldError } from '../../web/loaders/index.js';
import { loadMosaic } from '../../web/loaders/mosaic.js';
import { probeGeoTiff, decodeGeoTiff } from '../../web/loaders/geotiff.js';
import { loadTerrain } from '../../web/loaders/terrain_source.js';
import { dropRoles } from '../../web/imagery/drop_roles.js';
import { createNodeCore } from '../../lib/node_core.js';
import { globeHgtTiles, TILE_NAMES } from '../../lib/hgt_tiles.js';

const DIR = new URL('../fixtures/mosaic/', import.meta.url);
const tif = (name) => ({ name, bytes: new Uint8Array(readFileSync(new URL(name, DIR))) });
const SHARED = ['shared_nw.tif', 'shared_ne.tif', 'shared_sw.tif', 'shared_se.tif'];
const source = await loadHeightfield([tif('source.tif')]);
const hgt = globeHgtTiles();

/** Indices where two sample arrays differ, beyond `skip(k)`. */
function differences(a, b, skip = () => false) {
  const out = [];
  for (let k = 0; k < a.length; k++) if (!skip(k) && !Object.is(a[k], b[k])) out.push(k);
  return out;
}

test('2 x 2 GeoTIFF tiles that share their edge samples are the source, sample for sample', async () => {
  // Dropped in any order: the mosaic is named after its north-west tile.
  const field = await loadHeightfield([tif('shared_se.tif'), tif('shared_nw.tif'), tif('shared_sw.tif'), tif('shared_ne.tif')]);
  assert.deepEqual([field.width, field.height], [257, 193], 'the shared column and row are kept once (2 x 129 - 1, 2 x 97 - 1)');
  assert.equal(field.source, 'shared_nw.tif + 3 more (mosaic 2 × 2)');
  assert.equal(field.sampleType, 'f32');
  assert.deepEqual(differences(field.samples, source.samples), []);
  assert.deepEqual(field.georef, source.georef, 'the union of the tiles lies where the source does');
  assert.deepEqual([field.spacingX, field.spacingY, field.geographic, field.missing], [source.spacingX, source.spacingY, true, 0]);
});

test('tiles that abut (no shared samples) are the source too', async () => {
  const field = await loadHeightfield([tif('abut_e.tif'), tif('abut_w.tif')]);
  assert.equal(field.source, 'abut_w.tif + 1 more (mosaic 2 × 1)');
  assert.deepEqual([field.width, field.height], [257, 193]);
  assert.deepEqual(differences(field.samples, source.samples), []);
});

test('a missing corner tile is no-data, filled from around it; the rest is exact', async () => {
  const field = await loadHeightfield(SHARED.slice(0, 3).map(tif));
  assert.equal(field.source, 'shared_nw.tif + 2 more (mosaic 2 × 2)', 'an L of three tiles spans two columns and two rows');
  assert.deepEqual([field.width, field.height], [257, 193]);
  const gap = (k) => k % 257 > 128 && Math.floor(k / 257) > 96; // the south-east tile less its shared edges
  assert.equal(field.missing, 128 * 96);
  for (let k = 0; k < field.samples.length; k++) {
    assert.equal((field.missingMask[k >> 3] >> (k & 7)) & 1, gap(k) ? 1 : 0, `sample ${k} is marked as no-data where the tile is missing`);
  }
  assert.deepEqual(differences(field.samples, source.samples, gap), []);
  let lo = Infinity, hi = -Infinity;
  for (let k = 0; k < field.samples.length; k++) {
    if (!gap(k)) continue;
    lo = Math.min(lo, field.samples[k]); hi = Math.max(hi, field.samples[k]);
  }
  const around = [...source.samples].filter((v, k) => !gap(k));
  assert.ok(lo >= Math.min(...around) && hi <= Math.max(...around), `the gap is filled between the heights around it: ${lo}..${hi}`);
});

test('adjacent SRTM tiles (mixed-case names) merge their shared edges; voids stay voids, filled', async () => {
  const tiles = [hgt.tiles.se, hgt.tiles.ne, hgt.tiles.sw, hgt.tiles.nw];
  const field = await loadHeightfield(tiles);
  assert.equal(field.source, `${TILE_NAMES.nw} + 3 more (mosaic 2 × 2)`);
  assert.deepEqual([field.width, field.height, field.sampleType], [2401, 2401, 'i16']);
  assert.deepEqual({ ...field.georef, crs: field.georef.crs.label }, { crs: 'EPSG:4326', x0: 86, y0: 28, dx: 1 / 1200, dy: -1 / 1200, from: 'tile name' });
  const isVoid = (k) => hgt.heights[k] === -32768;
  assert.deepEqual(differences(field.samples, hgt.heights, isVoid), [], 'every real sample in its place, no seam');
  assert.equal(field.missing, 2401 * 2401 - 2048 * 2048);
  // The joins: row and column 1200 are each tile's edge, and the rows beside them differ as the DEM does.
  for (const k of [1200 * 2401 + 5, 5 * 2401 + 1200, 1200 * 2401 + 1200]) assert.equal(field.samples[k], hgt.heights[k]);
  // A corner tile missing: its own part (less the shared edges) is filled, the rest exact.
  const three = await loadHeightfield([hgt.tiles.nw, hgt.tiles.ne, hgt.tiles.sw]);
  const corner = (k) => k % 2401 > 1200 && Math.floor(k / 2401) > 1200;
  assert.deepEqual(differences(three.samples, hgt.heights, (k) => isVoid(k) || corner(k)), []);
});

test('mismatched spacing, CRS or grid: a message naming both files and what differs', async () => {
  const refused = (files, pattern) => assert.rejects(loadHeightfield(files.map(tif)), (e) => {
    assert.ok(e instanceof HeightfieldError, e.message);
    assert.match(e.message, pattern);
    return true;
  });
  await refused(['shared_nw.tif', 'coarse_ne.tif'],
    /^shared_nw\.tif and coarse_ne\.tif: different sample spacings \(0\.000833333 x 0\.000833333°, 0\.00165385 x 0\.00164966°\)/);
  await refused(['shared_nw.tif', 'nad83_ne.tif'], /^shared_nw\.tif and nad83_ne\.tif: different coordinate systems \(EPSG:4326, EPSG:4269\)/);
  // Tiles are checked against the first one given.
  await refused(['offgrid_ne.tif', 'shared_nw.tif'],
    /^offgrid_ne\.tif and shared_nw\.tif: not on one grid \(shared_nw\.tif's samples lie 0\.5 of a column and 0 of a row off offgrid_ne\.tif's\)/);
  await refused(['shared_nw.tif', 'shared_nw.tif'], /^shared_nw\.tif and shared_nw\.tif: both lie at the same place/);
  // SRTM1 beside SRTM3, and a tile whose name places it nowhere.
  const srtm1 = { name: 'N27E088.hgt', bytes: new Uint8Array(3601 * 3601 * 2) };
  await assert.rejects(loadHeightfield([hgt.tiles.nw, srtm1]), /: N27E086\.hgt and N27E088\.hgt: different sample spacings \(0\.000833333 x 0\.000833333°, 0\.000277778 x 0\.000277778°\)/);
  await assert.rejects(loadHeightfield([hgt.tiles.nw, { name: 'tile.hgt', bytes: hgt.tiles.ne.bytes }]), /: tile\.hgt: says nowhere where it lies/);
  // A sidecar belongs to one file; a PNG has no place in a mosaic.
  await assert.rejects(loadHeightfield([tif('shared_nw.tif'), tif('shared_ne.tif'), { name: 'shared_nw.json', bytes: new TextEncoder().encode('{}') }]),
    /: shared_nw\.json: a sidecar goes with one height field/);
});

test('tiles with GDAL\'s scale and offset keep them; a tile whose raw values mean other metres is refused by name', async () => {
  const field = await loadHeightfield([tif('scaled_ne.tif'), tif('scaled_nw.tif')]);
  assert.deepEqual([field.width, field.height, field.heightScale, field.heightOffset], [257, 97, 0.5, 10]);
  assert.deepEqual(differences(field.samples, source.samples.subarray(0, 257 * 97)), [], 'the raw samples, as the source\'s top rows');
  await assert.rejects(loadHeightfield([tif('shared_nw.tif'), tif('scaled_ne.tif')]), (e) => {
    assert.ok(e instanceof HeightfieldError);
    assert.match(e.message, /scaled_ne\.tif stores heights as raw x 0\.5 \+ 10 m, shared_nw\.tif as raw x 1 \+ 0 m: a mosaic needs one scale and offset/);
    return true;
  });
});

test('a mosaic past the sample cap is refused before anything is allocated', async () => {
  let allocated = 0;
  await assert.rejects(loadHeightfield(SHARED.map(tif), { maxSamples: 257 * 193 - 1, allocate: () => { allocated++; } }),
    /: shared_nw\.tif \+ 3 more \(mosaic 2 × 2\): 257x193 samples \(49601\) are past the limit of 49600$/);
  assert.equal(allocated, 0);
});

test('the mosaic is allocated once, after every tile is probed and before any is decoded', async () => {
  const events = [];
  const field = await loadMosaic(SHARED.map(tif).map((t) => ({ ...t, kind: 'geotiff' })), {
    probe: (tile) => { events.push(`probe ${tile.name}`); return probeGeoTiff(tile.bytes, tile.name); },
    decode: (tile, allocate) => { events.push(`decode ${tile.name}`); return decodeGeoTiff(tile.bytes, tile.name, allocate); },
    allocate: (type, w, h) => { events.push(`allocate ${w}x${h}`); return new Float32Array(w * h); },
    maxSamples: 1e9,
  });
  assert.deepEqual(events.slice(0, 5), [...SHARED.map((n) => `probe ${n}`), 'allocate 257x193']);
  assert.deepEqual(events.slice(5), SHARED.map((n) => `decode ${n}`), 'each tile decoded once, after the allocation');
  assert.deepEqual(differences(field.samples, source.samples), []);
});

test('dropped together, tiles are one height field: dropRoles and loadTerrain', async () => {
  const head = (f) => ({ name: f.name, head: f.bytes.subarray(0, 65536) });
  assert.deepEqual(dropRoles(SHARED.map(tif).map(head)), { field: [0, 1, 2, 3], images: [], overlays: [], skipped: [] });
  assert.deepEqual(dropRoles(Object.values(hgt.tiles).map(head)), { field: [0, 1, 2, 3], images: [], overlays: [], skipped: [] });
  const core = await createNodeCore();
  const loaded = await loadTerrain(core, SHARED.map(tif));
  try {
    assert.deepEqual([loaded.terrain.width, loaded.terrain.height], [257, 193]);
    assert.equal(loaded.field.source, 'shared_nw.tif + 3 more (mosaic 2 × 2)');
    const lo = Math.min(...source.samples), hi = Math.max(...source.samples);
    assert.ok(Math.abs(loaded.terrain.minHeight - lo) < 1e-3 && Math.abs(loaded.terrain.maxHeight - hi) < 1e-3,
      `the terrain's heights are the source's: ${loaded.terrain.minHeight}..${loaded.terrain.maxHeight} vs ${lo}..${hi}`);
  } finally {
    loaded.terrain.destroy();
  }
  // A refused mosaic leaves nothing allocated and says why.
  await assert.rejects(loadTerrain(core, ['shared_nw.tif', 'nad83_ne.tif'].map(tif)), /different coordinate systems/);
});

test('hexlod mesh takes the tiles of a mosaic as its files', () => {
  const json = join(mkdtempSync(join(tmpdir(), 'hexlod-mosaic-')), 'mesh.json');
  const paths = ['shared_ne.tif', 'shared_nw.tif'].map((name) => fileURLToPath(new URL(name, DIR)));
  const run = spawnSync(process.execPath, [fileURLToPath(new URL('../../bin/hexlod.js', import.meta.url)), 'mesh', ...paths,
    '--max-error', '5', '--json', json], { encoding: 'utf8', timeout: 60000 });
  assert.equal(run.status, 0, run.stderr);
  const report = JSON.parse(readFileSync(json, 'utf8'));
  assert.deepEqual([report.file, report.width, report.height], ['shared_nw.tif + 1 more (mosaic 2 × 1)', 257, 97]);
  assert.ok(report.error.original.max <= 5 + 1e-6, `within 5 m of the samples: ${report.error.original.max}`);
});
