// A draped image on an exported mesh: OBJ texture coordinates of every vertex from the image's
// placement on the field (web/imagery/placement.js, the map the page's shader uses), and the
// material file that names the image, for Blender, MeshLab and other OBJ readers.
import { writeFileSync } from 'node:fs';
import { basename, dirname, join, relative, resolve, isAbsolute, sep } from 'node:path';

/**
 * Texture coordinates (u, v per vertex) of vertices at x metres east of the first column and z
 * metres south of the first row. The placement's v runs down from the image's first (top) row,
 * as the page uploads it; an OBJ's v runs up from the image's bottom, hence 1 - v. Vertices
 * off the image get coordinates outside 0..1 (readers repeat or clamp the image there).
 * @param {Float64Array} vertices x, y, z per vertex
 * @param {import('../web/imagery/placement.js').Placement} placement
 * @param {number} spacingX metres between columns
 * @param {number} spacingY metres between rows
 * @returns {Float64Array}
 */
export function textureCoordinates(vertices, placement, spacingX, spacingY) {
  const n = vertices.length / 3;
  const uv = new Float64Array(2 * n);
  for (let i = 0; i < n; i++) {
    const column = vertices[3 * i] / spacingX, row = vertices[3 * i + 2] / spacingY;
    const [u, v] = placement.uvAt(column, row) ?? [-1, -1]; // off the CRSs' map: off the image
    uv[2 * i] = u;
    uv[2 * i + 1] = 1 - v;
  }
  return uv;
}

/**
 * The image as a material file names it: relative to the OBJ's folder (so the three files can
 * move together), or absolute when no relative path exists (another drive). Forward slashes:
 * OBJ readers on every system accept them.
 */
export function materialImagePath(objPath, imagePath) {
  const from = dirname(resolve(objPath)), to = resolve(imagePath);
  const rel = relative(from, to);
  return (isAbsolute(rel) ? to : rel).split(sep).join('/');
}

/** NAME.mtl beside NAME.obj (the OBJ's name without its extension). */
export function materialPathOf(objPath) {
  const base = basename(objPath).replace(/\.obj$/i, '');
  return join(dirname(objPath), `${base}.mtl`);
}

export const MATERIAL_NAME = 'draped_image';

/**
 * Writes a material file with one material whose diffuse colour is the image. Unlit-looking
 * defaults (white diffuse, no specular) so the image's colours show as they are.
 */
export function writeMaterial(path, imageRef, comments) {
  writeFileSync(path, [
    ...comments.map((line) => `# ${line}`),
    `newmtl ${MATERIAL_NAME}`,
    'Ka 1 1 1',
    'Kd 1 1 1',
    'Ks 0 0 0',
    'd 1',
    'illum 1',
    `map_Kd ${imageRef}`,
    '',
  ].join('\n'));
}
