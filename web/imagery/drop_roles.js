// Which of the files a person opens at once are a height field (with its sidecar) and which are
// an image to drape (with its world file), from their names and first bytes:
//   - JPEG and WebP are always images (image_formats.js); so is a colour (RGB, palette, YCbCr)
//     8-bit TIFF;
//   - a colour PNG is an image when a world file comes with it, when a height field comes with
//     it, or when its colours are no height encoding (loaders/terrain_rgb.js); else it is a
//     Terrain-RGB or Terrarium height field, as before ('image' in the PNG colours menu forces it);
//   - an 8-bit grey PNG or TIFF is a height field, unless another height field comes with it;
//   - everything else is for the height-field loaders, which say what they do not take.

import { extensionOf } from '../loaders/common.js';
import { hasPngSignature } from '../loaders/png.js';
import { hasTiffSignature, readDirectory, isWorldFileName, worldFileNames } from '../geo/index.js';
import { encodingFromName } from '../loaders/terrain_rgb.js';
import { ImageError } from './image_error.js';
import { IMAGE_FORMATS, alwaysImageFormat } from './image_formats.js';

/** What the file picker offers beside the height fields: images and their world files. */
export const IMAGE_EXTENSIONS = [...IMAGE_FORMATS.filter((f) => f.alwaysImage).flatMap((f) => f.extensions),
  'pgw', 'jgw', 'tfw', 'wld'].map((extension) => `.${extension}`);
const PHOTOMETRIC = 262, SAMPLES_PER_PIXEL = 277, BITS_PER_SAMPLE = 258;

/**
 * @param {Array<{ name: string, head: Uint8Array }>} files each file's name and first bytes
 *   (64 KB are plenty: a TIFF's first directory usually lies at its start; one that does not
 *   is taken for a height field)
 * @param {{ pngAsImage?: 'auto'|'image'|'height', colourPngIsHeight?: (file) => boolean }} [options]
 *   pngAsImage: the PNG colours menu ('image' forces colour PNGs to be images, 'height' to be
 *   heights); colourPngIsHeight: whether a colour PNG's first row reads as heights (asked only
 *   when nothing else decides)
 * @returns {{ field: number[], image: number|null, worldFile: number|null }} indices into files
 * @throws {ImageError} for two images, or a world file without its image
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

  const images = kinds.flatMap((k, i) => (k === 'image' ? [i] : []));
  if (images.length > 1) {
    throw new ImageError('', `several images given (${images.map((i) => files[i].name).join(', ')}); drape one at a time`);
  }
  const image = images[0] ?? null;
  const worldFile = image === null ? null : worldFiles.find((w) => worldFileNames(files[image].name).includes(files[w].name.toLowerCase())) ?? null;
  const stray = worldFiles.find((w) => w !== worldFile);
  if (stray !== undefined) {
    throw new ImageError(files[stray].name, image === null
      ? 'a world file alone places nothing; open it with its image'
      : `does not belong to ${files[image].name} (its world file is named ${worldFileNames(files[image].name).join(' or ')})`);
  }
  const field = kinds.flatMap((k, i) => (k === 'height' ? [i] : []));
  return { field, image, worldFile };
}

/** 'world' | 'image' (surely) | 'colourPng' | 'grey' (8-bit single channel) | 'height' (the loaders' to judge). */
function kindOf({ name, head }) {
  const extension = extensionOf(name);
  if (isWorldFileName(name) && !['png', 'tif', 'tiff', 'hgt', 'asc', 'pgm', 'f32', 'json', 'r16', 'raw'].includes(extension)) return 'world';
  if (alwaysImageFormat(extension, head)) return 'image';
  if (hasPngSignature(head) && head.length >= 26) {
    const bitDepth = head[24], colourType = head[25];
    if (colourType === 2 || colourType === 6 || colourType === 3) return bitDepth === 8 ? 'colourPng' : 'height';
    return bitDepth === 8 && colourType === 0 ? 'grey' : 'height';
  }
  if (hasTiffSignature(head)) return tiffKind(head);
  return 'height';
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

