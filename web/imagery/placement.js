// Where an image lies on the terrain: the map from the field's sample coordinates (column, row;
// the terrain's own grid) to the image's texture coordinates (u, v in 0..1 over the image),
// and how much of the field it covers.
//
// Both grids map sample centres to CRS coordinates (georef.js), so in one CRS the map is affine
// per axis: u = column * scaleU + offsetU, v = row * scaleV + offsetV. Without georeferences on
// both sides, the image is stretched over the field: its outer pixel edges on the field's outer
// samples.

import { compareCrs } from '../geo/index.js';
import { ImageError } from './image_error.js';

/**
 * @typedef {object} Placement
 * @property {number} scaleU texture u per field column
 * @property {number} offsetU texture u at column 0
 * @property {number} scaleV texture v per field row
 * @property {number} offsetV texture v at row 0
 * @property {number} coverage share of the field's area under the image, 0..1
 * @property {'georeferenced'|'stretched'} how
 * @property {string|null} note for the status line: why it is stretched, or the CRS assumed
 */

/**
 * @param {{ width: number, height: number, georef: import('../geo/georef.js').Georef|null }} field
 * @param {{ name: string, width: number, height: number, georef: import('../geo/georef.js').Georef|null }} image
 * @returns {Placement}
 * @throws {ImageError} when the CRSs differ or the image misses the field
 */
export function placeImage(field, image) {
  if (!image.georef || !field.georef) {
    const why = !image.georef ? 'the image has no georeference' : 'the terrain has no georeference';
    const span = (n) => Math.max(n - 1, 1);
    // The image's outer pixel edges on the field's outer samples: u = column / (width - 1).
    return { scaleU: 1 / span(field.width), offsetU: 0, scaleV: 1 / span(field.height), offsetV: 0, coverage: 1,
      how: 'stretched', note: `${why}: stretched over the whole field` };
  }
  const f = field.georef, g = image.georef;
  const relation = compareCrs(f.crs, g.crs);
  if (relation === 'different') {
    throw new ImageError(image.name, `it is in ${g.crs.label} and the terrain in ${f.crs.label}; ` +
      'reproject it to the terrain\'s CRS first (e.g. gdalwarp -t_srs ' + f.crs.label + ')');
  }
  // column -> x = f.x0 + column * f.dx -> image pixel p = (x - g.x0) / g.dx -> u = (p + 0.5) / width
  const scaleU = f.dx / g.dx / image.width, offsetU = ((f.x0 - g.x0) / g.dx + 0.5) / image.width;
  const scaleV = f.dy / g.dy / image.height, offsetV = ((f.y0 - g.y0) / g.dy + 0.5) / image.height;
  const coverage = coverageOf(field, { scaleU, offsetU, scaleV, offsetV });
  if (coverage === 0) {
    throw new ImageError(image.name, `it lies outside the terrain (the image spans ${extentText(g, image)}, ` +
      `the terrain ${extentText(f, field)}${relation === 'assumed' ? `, taking the image to be in ${f.crs.label}` : ''})`);
  }
  const crsUnknown = g.crs.epsg === null ? 'the image' : 'the terrain';
  return { scaleU, offsetU, scaleV, offsetV, coverage, how: 'georeferenced',
    note: relation === 'assumed' ? `${crsUnknown} names no CRS: taken to be in ${(g.crs.epsg === null ? f : g).crs.label}` : null };
}

/**
 * The share of the field's area (the rectangle of its sample centres) whose texture coordinates
 * fall inside the image.
 */
export function coverageOf(field, p) {
  const overlap = (scale, offset, last) => {
    // The columns c in [0, last] with 0 <= c * scale + offset <= 1.
    const a = (0 - offset) / scale, b = (1 - offset) / scale;
    const lo = Math.max(0, Math.min(a, b)), hi = Math.min(last, Math.max(a, b));
    return last > 0 ? Math.max(0, hi - lo) / last : (lo <= hi ? 1 : 0);
  };
  return overlap(p.scaleU, p.offsetU, field.width - 1) * overlap(p.scaleV, p.offsetV, field.height - 1);
}

/** "x 10..20, y 40..50 (EPSG:4326)": a grid's outer edges, for messages. */
function extentText(georef, grid) {
  const xs = [georef.x0 - georef.dx / 2, georef.x0 + (grid.width - 0.5) * georef.dx];
  const ys = [georef.y0 - georef.dy / 2, georef.y0 + (grid.height - 0.5) * georef.dy];
  const fmt = (v) => Number(v.toPrecision(7)).toString();
  return `x ${fmt(Math.min(...xs))}..${fmt(Math.max(...xs))}, y ${fmt(Math.min(...ys))}..${fmt(Math.max(...ys))}`;
}
