// A mosaic: several tiles of one grid (adjacent SRTM .hgt tiles, GeoTIFFs cut from one raster)
// made into one height field. Each tile is placed by its georeference (an .hgt tile's name, a
// GeoTIFF's geotransform); where tiles overlap (adjacent .hgt tiles repeat their border rows and
// columns) the samples fall on the same cells, so a shared edge is kept once, not doubled; cells
// no tile covers (a missing corner tile) are no-data and filled like a void inside a tile.
//
// Memory: the tiles are probed first (size, sample type, place: no samples read), the mosaic is
// allocated once, then each tile is decoded into an array of its own size, copied in and
// dropped: the mosaic and one decoded tile are held at a time, never every tile.

import { HeightfieldError, defaultAllocate } from './common.js';
import { degreesToMetres, makeGeoref } from '../geo/index.js';
import { SampleSink } from './pacing.js';
import { fillNodata } from './nodata.js';

/** How far (in samples) a tile's offset may lie from a whole number of steps: rounding in the files' doubles, not a shifted grid. */
const GRID_TOLERANCE = 1e-3;
/** How far two tiles' steps may differ, relative: over 32768 samples the drift stays within GRID_TOLERANCE. */
const STEP_TOLERANCE = 1e-8;

/** The sample type that holds both tiles' values exactly ('f32' holds every 16-bit integer). */
function widerType(a, b) {
  if (a === b) return a;
  const pair = new Set([a, b]);
  if (pair.has('f32')) return 'f32';
  if (pair.has('u8')) return pair.has('u16') ? 'u16' : 'i16';
  return 'f32'; // u16 with i16: neither holds the other
}

const stepText = (g) => `${Number(g.dx.toPrecision(6))} x ${Number((-g.dy).toPrecision(6))}${g.crs.geographic ? '°' : ''}`;

/**
 * Checks that tile b can join tile a's grid and says where: b's first sample in a's columns and
 * rows (whole numbers).
 * @throws {HeightfieldError} naming both files and what differs
 */
function placeOnGrid(a, b) {
  const pair = `${a.name} and ${b.name}`;
  const ga = a.georef, gb = b.georef;
  if (ga.crs.epsg !== gb.crs.epsg || ga.crs.label !== gb.crs.label) {
    throw new HeightfieldError('', `${pair}: different coordinate systems (${ga.crs.label}, ${gb.crs.label}); a mosaic's tiles share one`);
  }
  const close = (u, v) => Math.abs(u - v) <= STEP_TOLERANCE * Math.max(Math.abs(u), Math.abs(v));
  if (!close(ga.dx, gb.dx) || !close(ga.dy, gb.dy)) {
    throw new HeightfieldError('', `${pair}: different sample spacings (${stepText(ga)}, ${stepText(gb)}); a mosaic's tiles share one`);
  }
  const column = (gb.x0 - ga.x0) / ga.dx, row = (gb.y0 - ga.y0) / ga.dy;
  const offColumn = Math.abs(column - Math.round(column)), offRow = Math.abs(row - Math.round(row));
  if (offColumn > GRID_TOLERANCE || offRow > GRID_TOLERANCE) {
    throw new HeightfieldError('', `${pair}: not on one grid (${b.name}'s samples lie ${Number(offColumn.toFixed(3))} of a column and ` +
      `${Number(offRow.toFixed(3))} of a row off ${a.name}'s)`);
  }
  return { column: Math.round(column), row: Math.round(row) };
}

/**
 * @param {Array<{ name: string, bytes: Uint8Array, kind: string }>} tiles two or more
 * @param {object} io
 * @param {(tile) => Promise<{ width, height, sampleType, georef }>} io.probe a tile's size, sample type and place
 * @param {(tile, allocate, onProgress) => Promise<object>} io.decode a tile's samples, no-data not filled
 *   (a decoder of index.js: { width, height, samples, nodata, georef, spacingX, spacingY })
 * @param {Function} [io.allocate] as loadHeightfield's: called once, for the whole mosaic
 * @param {() => ArrayLike<number>} [io.reacquire] as loadHeightfield's
 * @param {(fraction: number, phase: string) => void} [io.onProgress] as loadHeightfield's
 * @param {number} io.maxSamples the cap on the mosaic's samples
 * @returns {Promise<import('./index.js').Heightfield>} source: "N27E086.hgt + 3 more (mosaic 2 × 2)"
 * @throws {HeightfieldError} for a tile without a georeference, tiles not on one grid, twice the
 *   same place, a mosaic past the cap, and every error of a tile's decoder
 */
export async function loadMosaic(tiles, io) {
  const probed = [];
  for (const tile of tiles) {
    const shape = await io.probe(tile);
    if (!shape.georef) {
      throw new HeightfieldError(tile.name, 'says nowhere where it lies (no geotransform, or not an SRTM tile name like N27E086.hgt): a mosaic places its tiles by that');
    }
    probed.push({ ...tile, ...shape });
  }
  const first = probed[0];
  let sampleType = first.sampleType;
  for (const tile of probed) {
    Object.assign(tile, placeOnGrid(first, tile));
    sampleType = widerType(sampleType, tile.sampleType);
  }
  const left = Math.min(...probed.map((t) => t.column)), top = Math.min(...probed.map((t) => t.row));
  const width = Math.max(...probed.map((t) => t.column + t.width)) - left;
  const height = Math.max(...probed.map((t) => t.row + t.height)) - top;
  for (const tile of probed) { tile.column -= left; tile.row -= top; }
  // North-west first (by rows, then columns), whatever order the files came in: the name and any
  // message then do not depend on how the person picked them.
  probed.sort((a, b) => a.row - b.row || a.column - b.column);
  for (let i = 1; i < probed.length; i++) {
    const twin = probed.slice(0, i).find((t) => t.row === probed[i].row && t.column === probed[i].column);
    if (twin) throw new HeightfieldError('', `${twin.name} and ${probed[i].name}: both lie at the same place; a mosaic takes each tile once`);
  }
  const columns = new Set(probed.map((t) => t.column)).size, rows = new Set(probed.map((t) => t.row)).size;
  const label = `${probed[0].name} + ${probed.length - 1} more (mosaic ${columns} × ${rows})`;
  if (width * height > io.maxSamples) {
    throw new HeightfieldError(label, `${width}x${height} samples (${width * height}) are past the limit of ${io.maxSamples}`);
  }

  const progress = io.onProgress;
  const sink = new SampleSink(io.allocate ?? defaultAllocate, sampleType, width, height, {
    reacquire: io.reacquire, onProgress: progress && ((fraction) => progress(fraction, 'decoding')) });
  const valid = new Uint8Array(Math.ceil((width * height) / 8)); // one bit a cell: a tile gave it a height
  let spacing = null; // a projected grid's metres: the decoders know its units
  let scaling = null; // [scale, offset] of the tiles' raw values
  for (let i = 0; i < probed.length; i++) {
    const tile = probed[i];
    const decoded = await io.decode(tile, defaultAllocate, progress && ((fraction) => progress((i + fraction / 2) / probed.length, 'decoding')));
    if (io.reacquire) sink.samples = io.reacquire();
    spacing ??= decoded;
    // The samples are copied raw, so every tile must turn raw values into metres alike (GDAL's scale and offset).
    const scale = [decoded.heightScale ?? 1, decoded.heightOffset ?? 0];
    scaling ??= scale;
    if (scale[0] !== scaling[0] || scale[1] !== scaling[1]) {
      throw new HeightfieldError(label, `${tile.name} stores heights as raw x ${scale[0]} + ${scale[1]} m, ${probed[0].name} as raw x ` +
        `${scaling[0]} + ${scaling[1]} m: a mosaic needs one scale and offset (gdal_translate -unscale -ot Float32 makes metres)`);
    }
    await copyTile(decoded, tile, first.georef, left, top, sink, valid, width, (fraction) => (i + 0.5 + fraction / 2) / probed.length);
  }

  let covered = 0;
  for (let k = 0; k < valid.length; k++) covered += popcount(valid[k]);
  const missing = width * height - covered;
  let missingMask = null;
  if (missing > 0) {
    const fill = SampleSink.over(sink.samples, { reacquire: io.reacquire,
      onProgress: progress && ((fraction) => progress(fraction, 'filling no-data')) });
    ({ mask: missingMask } = await fillNodata(fill, width, height, null, label, (k) => !((valid[k >> 3] >> (k & 7)) & 1)));
    sink.samples = fill.samples;
  }

  const g = first.georef;
  const georef = makeGeoref(g.crs, g.x0 + left * g.dx, g.y0 + top * g.dy, g.dx, g.dy, g.from);
  const metres = g.crs.geographic ? degreesToMetres(g.dx, g.dy, georef.y0 + (georef.dy * (height - 1)) / 2)
    : { spacingX: spacing.spacingX ?? g.dx, spacingY: spacing.spacingY ?? Math.abs(g.dy) };
  const kinds = new Set(probed.map((t) => t.kind));
  return {
    width, height, sampleType, samples: sink.samples,
    ...metres, spacingFromFile: true, geographic: g.crs.geographic,
    heightScale: scaling[0], heightOffset: scaling[1],
    nodata: probed.map((t) => t.nodata).find((v) => v != null) ?? null,
    missing, missingMask, encoding: null, cropped: null, georef,
    source: label,
    format: kinds.size === 1 ? probed[0].kind : 'mosaic',
  };
}

/**
 * Copies a decoded tile's valid samples into the mosaic, where its georeference puts them (a
 * sparse GeoTIFF comes back cropped to its data, with its georeference moved to match), and
 * marks them valid. A tile's no-data never overwrites a neighbour's height in an overlap.
 */
async function copyTile(decoded, tile, grid, left, top, sink, valid, width, fraction) {
  const at = placeOnGrid({ name: tile.name, georef: grid }, { name: tile.name, georef: decoded.georef ?? tile.georef });
  const column = at.column - left, row = at.row - top;
  const nodata = decoded.nodata === null || decoded.nodata === undefined ? null
    : decoded.samples instanceof Float32Array ? Math.fround(decoded.nodata) : decoded.nodata;
  const from = decoded.samples;
  for (let y = 0; y < decoded.height; y++) {
    const samples = sink.samples;
    const base = (row + y) * width + column;
    for (let x = 0, s = y * decoded.width; x < decoded.width; x++, s++) {
      const v = from[s];
      if (v !== v || v === nodata) continue; // NaN, or the tile's no-data
      const k = base + x;
      samples[k] = v;
      valid[k >> 3] |= 1 << (k & 7);
    }
    await sink.pace(fraction((y + 1) / decoded.height));
  }
}

function popcount(byte) {
  let n = 0;
  for (let b = byte; b; b &= b - 1) n++;
  return n;
}
