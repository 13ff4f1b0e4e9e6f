// An image to drape and its world file, read whole for a command (hexlod mesh --image, a
// regression flight's "image"), from disk or by http(s). Without a world file named, the first
// of its conventional names beside the image (x.jgw, x.jpgw, x.wld: web/geo/world_file.js)
// is taken, as the page pairs files dropped together.
import { readFileSync, readdirSync, existsSync, statSync } from 'node:fs';
import { basename, dirname, join } from 'node:path';
import { worldFileNames } from '../web/geo/world_file.js';
import { isUrl, urlFileName, fetchBytes } from './dem_source.js';

/**
 * @typedef {{ name: string, bytes: Uint8Array }} NamedBytes
 * @typedef {{ image: NamedBytes, worldFile: NamedBytes|null }} ImageFiles
 */

/**
 * Reads an image and its world file from disk.
 * @param {string} imagePath
 * @param {string|null} worldFilePath null: look for one beside the image
 * @returns {ImageFiles}
 * @throws {Error} one line naming a file that is missing
 */
export function readImageFiles(imagePath, worldFilePath = null) {
  const read = (path, what) => {
    if (!existsSync(path)) throw new Error(`${path}: no such ${what}`);
    if (!statSync(path).isFile()) throw new Error(`${path}: not a file`);
    return { name: basename(path), bytes: new Uint8Array(readFileSync(path)) };
  };
  const image = read(imagePath, 'image file');
  let worldPath = worldFilePath;
  if (worldPath === null) {
    // The conventional names are lower case; a file written elsewhere may be X.JGW: match any case.
    const folder = dirname(imagePath);
    const present = new Map(readdirSync(folder).map((n) => [n.toLowerCase(), n]));
    const found = worldFileNames(basename(imagePath)).map((n) => present.get(n)).find((n) => n !== undefined);
    if (found !== undefined) worldPath = join(folder, found);
  }
  return { image, worldFile: worldPath === null ? null : read(worldPath, 'world file') };
}

/**
 * Reads an image and its world file from a path or an http(s) URL (the world file likewise).
 * @param {string} image
 * @param {string|null} worldFile null: look for one beside the image
 * @returns {Promise<ImageFiles>}
 */
export async function loadImageFiles(image, worldFile = null) {
  if (!isUrl(image)) return readImageFiles(image, worldFile);
  const fetched = async (url, optional = false) => {
    const bytes = await fetchBytes(url, { optional });
    return bytes && { name: urlFileName(url), bytes };
  };
  const files = { image: await fetched(image), worldFile: null };
  if (worldFile !== null) {
    files.worldFile = await fetched(worldFile);
  } else {
    for (const name of worldFileNames(urlFileName(image))) {
      files.worldFile = await fetched(new URL(name, image).href, true);
      if (files.worldFile) break;
    }
  }
  return files;
}
