// Where an image lies on the terrain: the map from the field's sample coordinates (column, row;
// the terrain's own grid) to the image's pixel coordinates (x, y; pixel k spans k..k+1, so
// texture u = x / width), and how much of the field it covers.
//
// Both grids map sample centres to CRS coordinates (georef.js). In one CRS the map is affine;
// across CRSs it goes field CRS -> image CRS through the CRSs' definitions (geo/coordinates.js),
// and the drape shader interpolates it over a control grid (geo/warp_grid.js) refined until it
// is within a quarter of an image pixel of the exact map. Without georeferences on both sides,
// the image is stretched over the field: its outer pixel edges on the field's outer samples.

import { compareCrs, crsTransform, sampleToCrs, crsToSample, makeWarpGrid } from '../geo/index.js';
import { ImageError } from './image_error.js';

/** The interpolation error a reprojected image may have, in its pixels. */
export const WARP_TOLERANCE_PX = 0.25;
// Points per axis where the coverage of a reprojected image is counted.
const COVERAGE_SAMPLES = 128;

/**
 * @typedef {object} Placement
 * @property {(column: number, row: number) => [number, number]|null} toImage the exact map from a
 *   field position to image pixel coordinates (null where the CRSs' map has no value)
 * @property {(column: number, row: number) => [number, number]|null} uvAt the same as texture
 *   coordinates (u = x / width, v = y / height; 0..1 over the image)
 * @property {import('../geo/warp_grid.js').WarpGrid} warp the same as the shader interpolates it
 * @property {number} coverage share of the field's area under the image, 0..1
 * @property {'georeferenced'|'reprojected'|'stretched'} how
 * @property {string|null} note for the status line: why it is stretched, or the CRS assumed
 */

/**
 * @param {{ width: number, height: number, georef: import('../geo/georef.js').Georef|null }} field
 * @param {{ name: string, width: number, height: number, georef: import('../geo/georef.js').Georef|null }} image
 * @returns {Placement}
 * @throws {ImageError} when the image misses the field, or its CRS cannot be mapped onto the terrain's
 */
export function placeImage(field, image) {
  if (!image.georef || !field.georef) {
    const why = !image.georef ? 'the image has no georeference' : 'the terrain has no georeference';
    const span = (n) => Math.max(n - 1, 1);
    const sx = image.width / span(field.width), sy = image.height / span(field.height);
    return placement(field, image, (column, row) => [column * sx, row * sy], 'stretched', `${why}: stretched over the whole field`, true);
  }
  const f = field.georef, g = image.georef;
  const relation = compareCrs(f.crs, g.crs);
  let toImage, how = 'georeferenced';
  if (relation === 'different') {
    const transform = crsTransform(f.crs, g.crs);
    if (!transform) {
      throw new ImageError(image.name, `it is in ${g.crs.label} and the terrain in ${f.crs.label}, and ` +
        `${crsDefinitionMissing(f.crs, g.crs)} has no definition to reproject with; reproject it to the terrain's CRS first (gdalwarp -t_srs)`);
    }
    toImage = (column, row) => {
      const [x, y] = sampleToCrs(f, column, row);
      const p = transform(x, y);
      if (!p || !Number.isFinite(p[0]) || !Number.isFinite(p[1])) return null;
      const [px, py] = crsToSample(g, p[0], p[1]);
      return [px + 0.5, py + 0.5];
    };
    how = 'reprojected';
  } else {
    // column -> x = f.x0 + column * f.dx -> image sample (x - g.x0) / g.dx -> pixel edge coordinate + 0.5
    const sx = f.dx / g.dx, ox = (f.x0 - g.x0) / g.dx + 0.5, sy = f.dy / g.dy, oy = (f.y0 - g.y0) / g.dy + 0.5;
    toImage = (column, row) => [column * sx + ox, row * sy + oy];
  }
  const crsUnknown = g.crs.epsg === null ? 'the image' : 'the terrain';
  const note = relation === 'assumed' ? `${crsUnknown} names no CRS: taken to be in ${(g.crs.epsg === null ? f : g).crs.label}`
    : how === 'reprojected' ? `reprojected from ${g.crs.label} to ${f.crs.label}` : null;
  const placed = placement(field, image, toImage, how, note, how !== 'reprojected');
  if (placed.coverage === 0) {
    throw new ImageError(image.name, `it lies outside the terrain (the image spans ${extentText(g, image)}, ` +
      `the terrain ${extentText(f, field)}${relation === 'assumed' ? `, taking the image to be in ${f.crs.label}` : ''})`);
  }
  return placed;
}

function placement(field, image, toImage, how, note, affine) {
  const warp = makeWarpGrid(field.width, field.height, toImage, WARP_TOLERANCE_PX);
  const coverage = affine ? affineCoverage(field, image, toImage) : sampledCoverage(field, image, toImage);
  const uvAt = (column, row) => {
    const p = toImage(column, row);
    return p && [p[0] / image.width, p[1] / image.height];
  };
  return { toImage, uvAt, warp, coverage, how, note };
}

/** Which of the terrain's CRS (a) and the image's (b) lacks a definition, for the message. */
function crsDefinitionMissing(a, b) {
  return b.proj4 ? a.label : b.label;
}

/**
 * The share of the field's area (the rectangle of its sample centres) that an affine map puts
 * inside the image.
 */
function affineCoverage(field, image, toImage) {
  const [ox, oy] = toImage(0, 0), [ax] = toImage(1, 0), [, by] = toImage(0, 1);
  const overlap = (scale, offset, size, last) => {
    // The columns c in [0, last] with 0 <= c * scale + offset <= size.
    const a = (0 - offset) / scale, b = (size - offset) / scale;
    const lo = Math.max(0, Math.min(a, b)), hi = Math.min(last, Math.max(a, b));
    return last > 0 ? Math.max(0, hi - lo) / last : (lo <= hi ? 1 : 0);
  };
  return overlap(ax - ox, ox, image.width, field.width - 1) * overlap(by - oy, oy, image.height, field.height - 1);
}

/** The share of points spread over the field whose image position falls inside the image. */
function sampledCoverage(field, image, toImage) {
  let inside = 0;
  for (let j = 0; j < COVERAGE_SAMPLES; j++) {
    for (let i = 0; i < COVERAGE_SAMPLES; i++) {
      const p = toImage(((i + 0.5) / COVERAGE_SAMPLES) * (field.width - 1), ((j + 0.5) / COVERAGE_SAMPLES) * (field.height - 1));
      if (p && p[0] >= 0 && p[0] <= image.width && p[1] >= 0 && p[1] <= image.height) inside++;
    }
  }
  return inside / COVERAGE_SAMPLES ** 2;
}

/** "x 10..20, y 40..50 (EPSG:4326)": a grid's outer edges, for messages. */
function extentText(georef, grid) {
  const xs = [georef.x0 - georef.dx / 2, georef.x0 + (grid.width - 0.5) * georef.dx];
  const ys = [georef.y0 - georef.dy / 2, georef.y0 + (grid.height - 0.5) * georef.dy];
  const fmt = (v) => Number(v.toPrecision(7)).toString();
  return `x ${fmt(Math.min(...xs))}..${fmt(Math.max(...xs))}, y ${fmt(Math.min(...ys))}..${fmt(Math.max(...ys))}`;
}
