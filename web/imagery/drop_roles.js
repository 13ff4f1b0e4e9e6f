// Which of the files a person opens at once (a drop, the picker, a dropped folder's files) are a
// height field (with its sidecars), which are images to drape (each with its sidecars), and
// which are skipped, from their names and first bytes:
//   - JPEG and WebP are always images (image_formats.js); so is a colour (RGB, palette, YCbCr)
//     8-bit TIFF;
//   - a colour PNG is an image when a world file comes with it, when a height field comes with
//     it, or when its colours are no height encoding (loaders/terrain_rgb.js); else it is a
//     Terrain-RGB or Terrarium height field, as before ('image' in the PNG colours menu forces it);
//   - an 8-bit grey PNG or TIFF is a height field, unless another height field comes with it;
//   - sidecars go with the file they are named after: a world file with its image
//     (world_file.js), a .prj or GDAL .aux.xml with its image or height field
//     (geo/sidecar_names.js), a .json with its height field (the loaders pair those);
//   - GPX, KML, KMZ and GeoJSON files are overlays (overlays/overlay_kind.js), drawn over the
//     terrain the drop shows or the one on screen;
//   - a sidecar of no file in the drop, metadata (.ovr, .xml, .md5, ...), and any file the
//     loaders do not take are skipped, each with the reason: they never stop the drop. Only when
//     nothing is left to open does the drop fail (an unknown file alone goes to the loaders,
//     whose message says what they take).

import { extensionOf, baseNameOf } from '../loaders/common.js';
import { hasPngSignature } from '../loaders/png.js';
import { heightFieldKind } from '../loaders/index.js';
import { hasTiffSignature, readDirectory, isWorldFileName, worldFileNames, isPrjName, isAuxXmlName, sidecarBelongsTo,
  metadataKind } from '../geo/index.js';
import { encodingFromName } from '../loaders/terrain_rgb.js';
import { ImageError } from './image_error.js';
import { overlayKind } from '../overlays/overlay_kind.js';
import { IMAGE_FORMATS, alwaysImageFormat } from './image_formats.js';

/** What the file picker offers beside the height fields: images and their sidecars. */
export const IMAGE_EXTENSIONS = [...IMAGE_FORMATS.filter((f) => f.alwaysImage).flatMap((f) => f.extensions),
  'pgw', 'jgw', 'tfw', 'wld'].map((extension) => `.${extension}`);
const PHOTOMETRIC = 262, SAMPLES_PER_PIXEL = 277, BITS_PER_SAMPLE = 258;
const HEIGHT_EXTENSIONS = ['png', 'tif', 'tiff', 'hgt', 'asc', 'pgm', 'f32', 'json', 'r16', 'raw'];

/**
 * @typedef {object} DropRoles
 * @property {number[]} field the height field's files (or a mosaic's tiles), with its .json, .prj and .aux.xml
 * @property {Array<{ image: number, sidecars: { worldFile: number|null, prj: number|null, auxXml: number|null } }>} images
 *   in the order they came
 * @property {number[]} overlays GPX, KML, KMZ and GeoJSON files, in the order they came
 * @property {Array<{ file: number, why: string }>} skipped files that are not opened, and why
 */

/**
 * @param {Array<{ name: string, head: Uint8Array }>} files each file's name and first bytes
 *   (64 KB are plenty: a TIFF's first directory usually lies at its start; one that does not
 *   is taken for a height field)
 * @param {{ pngAsImage?: 'auto'|'image'|'height', colourPngIsHeight?: (file) => boolean }} [options]
 *   pngAsImage: the PNG colours menu ('image' forces colour PNGs to be images, 'height' to be
 *   heights); colourPngIsHeight: whether a colour PNG's first row reads as heights (asked only
 *   when nothing else decides)
 * @returns {DropRoles} indices into files
 * @throws {ImageError} when nothing in the drop can be opened (only sidecars or metadata)
 */
export function dropRoles(files, options = {}) {
  const kinds = files.map((f) => kindOf(f));
  const worldFiles = kinds.flatMap((k, i) => (k === 'world' ? [i] : []));
  const named = (i) => worldFiles.some((w) => worldFileNames(files[i].name).includes(files[w].name.toLowerCase()));

  // A colour PNG: its world file, another height field beside it, or the menu decide; then its colours.
  const choice = options.pngAsImage ?? 'auto';
  for (let i = 0; i < files.length; i++) {
    if (kinds[i] !== 'colourPng') continue;
    const beside = kinds.some((k, j) => j !== i && (k === 'height' || k === 'grey'));
    if (choice === 'height') kinds[i] = 'height';
    else if (choice === 'image' || named(i) || beside) kinds[i] = 'image';
    else kinds[i] = encodingFromName(files[i].name) || options.colourPngIsHeight?.(files[i]) !== false ? 'height' : 'image';
  }
  // 8-bit grey files: the first is the height field unless another one is; the rest are images.
  const firm = kinds.includes('height'), firstGrey = kinds.indexOf('grey');
  kinds.forEach((k, i) => {
    if (k === 'grey') kinds[i] = !firm && i === firstGrey ? 'height' : 'image';
  });

  const indices = (kind) => kinds.flatMap((k, i) => (k === kind ? [i] : []));
  const imageIndices = indices('image'), heights = indices('height'), overlays = indices('overlay');
  const skipped = [];
  const owned = new Set();
  const ownerOf = (sidecar, owners) => {
    const owner = owners.find((i) => sidecarBelongsTo(files[sidecar].name, files[i].name));
    if (owner !== undefined) owned.add(sidecar);
    return owner;
  };

  const images = imageIndices.map((image) => {
    const worldFile = worldFiles.find((w) => !owned.has(w) && worldFileNames(files[image].name).includes(files[w].name.toLowerCase())) ?? null;
    if (worldFile !== null) owned.add(worldFile);
    const mine = (kind) => {
      const found = indices(kind).find((i) => sidecarBelongsTo(files[i].name, files[image].name));
      if (found !== undefined) owned.add(found);
      return found ?? null;
    };
    return { image, sidecars: { worldFile, prj: mine('prj'), auxXml: mine('auxXml') } };
  });
  // The height field's .json, .prj and .aux.xml go to the loaders with it (a .prj may serve an image too).
  const crsOfField = [...indices('prj'), ...indices('auxXml')].filter((i) => ownerOf(i, heights) !== undefined);
  const jsons = indices('json').filter((j) => heights.some((h) => baseNameOf(files[h].name) === baseNameOf(files[j].name)));
  for (const j of jsons) owned.add(j);
  const field = [...heights, ...jsons, ...crsOfField].sort((a, b) => a - b);

  kinds.forEach((kind, i) => {
    if (owned.has(i)) return;
    if (kind === 'world') {
      const only = imageIndices.length === 1 ? `: ${files[imageIndices[0]].name}'s is named ${worldFileNames(files[imageIndices[0]].name).join(' or ')}` : '';
      skipped.push({ file: i, why: `a world file of no image here${only}` });
    } else if (kind === 'json') {
      skipped.push({ file: i, why: 'a .json of no height field here' });
    } else if (kind === 'prj' || kind === 'auxXml') {
      skipped.push({ file: i, why: `${kind === 'prj' ? 'a .prj' : 'a GDAL .aux.xml'} of no height field or image here` });
    } else if (kind === 'metadata') {
      skipped.push({ file: i, why: metadataKind(files[i].name) });
    } else if (kind === 'other') {
      skipped.push({ file: i, why: 'neither a height field nor an image' });
    }
  });

  if (heights.length === 0 && images.length === 0 && overlays.length === 0) {
    // Files the loaders do not take, alone: the loaders say what they take. Only sidecars or
    // metadata: there is nothing to open.
    const others = skipped.filter((s) => kinds[s.file] === 'other' || kinds[s.file] === 'json').map((s) => s.file);
    if (others.length) return { field: others, images: [], overlays: [], skipped: skipped.filter((s) => !others.includes(s.file)) };
    const first = skipped[0];
    if (!first) throw new ImageError('', 'no files given');
    throw new ImageError(files[first.file].name, kinds[first.file] === 'world' ? 'a world file alone places nothing; open it with its image'
      : `${first.why}: nothing here to open; open it with the height field or image it belongs to`);
  }
  return { field, images, overlays, skipped };
}

/**
 * 'world' | 'prj' | 'auxXml' | 'json' | 'overlay' | 'metadata' | 'image' (surely) | 'colourPng' | 'grey' (8-bit
 * single channel) | 'height' (the loaders' to judge) | 'other' (no file the loaders or the
 * drape take).
 */
function kindOf({ name, head }) {
  const extension = extensionOf(name);
  if (isWorldFileName(name) && !HEIGHT_EXTENSIONS.includes(extension)) return 'world';
  if (isPrjName(name)) return 'prj';
  if (isAuxXmlName(name)) return 'auxXml';
  if (metadataKind(name)) return 'metadata'; // before the first bytes: an .ovr is a TIFF
  if (overlayKind(name, head)) return 'overlay'; // before the loaders: a GeoJSON may be named .json
  if (alwaysImageFormat(extension, head)) return 'image';
  if (hasPngSignature(head) && head.length >= 26) {
    const bitDepth = head[24], colourType = head[25];
    if (colourType === 2 || colourType === 6 || colourType === 3) return bitDepth === 8 ? 'colourPng' : 'height';
    return bitDepth === 8 && colourType === 0 ? 'grey' : 'height';
  }
  if (hasTiffSignature(head)) return tiffKind(head);
  const kind = heightFieldKind({ name, head });
  return kind === 'json' ? 'json' : kind ? 'height' : 'other';
}

/** A TIFF's kind from its first directory, when it lies in `head`. */
function tiffKind(head) {
  let directory;
  try {
    directory = readDirectory(head, (problem) => { throw new Error(problem); });
  } catch {
    return 'height'; // its directory lies further on, or is damaged: the height-field loader says which
  }
  const photometric = directory.values(PHOTOMETRIC)?.[0];
  const samples = directory.values(SAMPLES_PER_PIXEL)?.[0] ?? 1;
  const bits = directory.values(BITS_PER_SAMPLE) ?? [1];
  const eightBit = bits.every((b) => b === 8);
  if (eightBit && (photometric === 2 || photometric === 3 || photometric === 6 || samples >= 3)) return 'image';
  return eightBit && samples === 1 ? 'grey' : 'height';
}
