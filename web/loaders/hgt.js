// SRTM .hgt tiles: 1201 x 1201 (3 arc-seconds) or 3601 x 3601 (1 arc-second) big-endian int16
// metres, no header, voids = -32768. A tile spans one degree; its name gives its south-west
// corner (N27E086.hgt), hence the latitude that turns arc-seconds into metres.

import { HeightfieldError, fileNameOf } from './common.js';
import { degreesToMetres, crsOfEpsg, makeGeoref } from '../geo/index.js';
import { SampleSink } from './pacing.js';
import { copyRows } from './copy_rows.js';

export const HGT_VOID = -32768;
const SIDES = [1201, 3601];

/** The south-west corner of a tile from its name like N27E086 / s12w077 ({ lat, lon } in
 *  degrees), or null (also for a name no tile has, such as N95E000, whose cosine would make
 *  the spacing absurd). */
export function tileCorner(name) {
  const m = /^([NS])(\d{2})([EW])(\d{3})/i.exec(fileNameOf(name));
  if (!m) return null;
  const lat = m[1].toUpperCase() === 'N' ? Number(m[2]) : -Number(m[2]);
  const lon = m[3].toUpperCase() === 'E' ? Number(m[4]) : -Number(m[4]);
  return lat >= -90 && lat <= 89 && lon >= -180 && lon <= 179 ? { lat, lon } : null;
}

/** Latitude of the south edge from a tile name, or null (see tileCorner). */
export function tileLatitude(name) {
  return tileCorner(name)?.lat ?? null;
}

/**
 * A tile's size (from its byte count) and where it lies (from its name), before any sample is
 * read: what a mosaic needs of a tile (mosaic.js).
 * @returns {{ width: number, height: number, sampleType: 'i16', georef: import('../geo/georef.js').Georef|null }}
 */
export function probeHgt(bytes, name) {
  const side = SIDES.find((n) => n * n * 2 === bytes.length);
  if (!side) {
    const near = bytes.length < SIDES[0] * SIDES[0] * 2 ? 'truncated' : 'wrong size';
    throw new HeightfieldError(name, `${near}: ${bytes.length} bytes, but an SRTM tile has ` +
      `${SIDES.map((n) => `${n}x${n}`).join(' or ')} 16-bit samples (${SIDES.map((n) => n * n * 2).join(' or ')} bytes)`);
  }
  // Samples lie on whole arc-seconds, the first row on the tile's north edge, the first column on its west edge (WGS 84).
  const corner = tileCorner(name);
  const step = 1 / (side - 1); // degrees between samples
  const georef = corner && makeGeoref(crsOfEpsg(4326, true), corner.lon, corner.lat + 1, step, -step, 'tile name');
  return { width: side, height: side, sampleType: 'i16', georef };
}

/**
 * @returns {Promise<{ width, height, sampleType: 'i16', samples: Int16Array, nodata: number,
 *   spacingX: number, spacingY: number, spacingFromFile: boolean, georef }>} spacing in metres; without a
 *   tile name the spacing is the equator's and spacingFromFile is false
 */
export async function decodeHgt(bytes, name, allocate, options = {}) {
  const { width: side, georef } = probeHgt(bytes, name);
  const south = tileLatitude(name);
  const step = 1 / (side - 1);
  const { spacingX, spacingY } = degreesToMetres(step, step, south === null ? 0 : south + 0.5);
  const sink = new SampleSink(allocate, 'i16', side, side, options);
  await copyRows(bytes, 0, sink, side, side, false);
  return { width: side, height: side, sampleType: 'i16', samples: sink.samples, nodata: HGT_VOID,
    spacingX, spacingY, spacingFromFile: south !== null, georef };
}
