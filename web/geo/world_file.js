// World files (.pgw, .jgw, .tfw, .wld, ...): six numbers that place an image, one a line:
//   A  x step per column          D  y step per column (rotation)
//   B  x step per row (rotation)  E  y step per row (negative for north-up)
//   C  x of the first pixel's centre
//   F  y of the first pixel's centre
// The same convention as our georeference (sample centres), with no CRS: that is the .prj's
// job, so the image is taken to be in the terrain's CRS (georef.js compareCrs: 'assumed').

import { makeGeoref, UNKNOWN_CRS } from './georef.js';

/** Past this a file is no world file (six numbers). */
export const WORLD_FILE_BYTES = 4096;

/** The names a world file of `imageName` may have, lower case: x.pgw for x.png, x.jpgw, x.wld. */
export function worldFileNames(imageName) {
  return worldFileCandidates(imageName).map((n) => n.toLowerCase());
}

/** The same with the image's base name as written (a web server's names are case-sensitive). */
export function worldFileCandidates(imageName) {
  const dot = imageName.lastIndexOf('.');
  if (dot <= 0) return [`${imageName}.wld`];
  const base = imageName.slice(0, dot), ext = imageName.slice(dot + 1).toLowerCase();
  return [...new Set([`${base}.${ext[0]}${ext.at(-1)}w`, `${base}.${ext}w`, `${base}.wld`])];
}

/** True when a file name has a world file's extension. */
export function isWorldFileName(name) {
  return /\.(wld|[a-z]{2}w|[a-z]{3,4}w)$/i.test(name) && !/\.(raw|json)$/i.test(name);
}

/**
 * Parses a world file.
 * @param {Uint8Array} bytes its text
 * @param {(problem: string) => never} fail throws the caller's error for a problem: not six
 *   finite numbers, a rotated image, a zero step
 * @returns {import('./georef.js').Georef}
 */
export function parseWorldFile(bytes, fail) {
  if (bytes.length > WORLD_FILE_BYTES) fail(`${bytes.length} bytes is not a world file (six numbers, one a line)`);
  const lines = new TextDecoder().decode(bytes).split(/\r?\n/).map((l) => l.trim()).filter((l) => l !== '');
  if (lines.length !== 6) fail(`a world file holds six numbers, one a line; this one has ${lines.length} lines`);
  const numbers = lines.map((line, i) => {
    const v = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/.test(line) ? Number(line) : NaN;
    if (!Number.isFinite(v)) fail(`line ${i + 1}: ${JSON.stringify(line.slice(0, 40))} is not a number`);
    return v;
  });
  const [a, d, b, e, c, f] = numbers;
  if (d !== 0 || b !== 0) fail(`the image is rotated or sheared (lines 2 and 3: ${d}, ${b}); only north-up images can be draped`);
  if (!(a > 0)) fail(`line 1: the pixel width ${a} must be positive`);
  if (e === 0) fail('line 4: the pixel height is 0');
  return makeGeoref(UNKNOWN_CRS, c, f, a, e, 'world file');
}
