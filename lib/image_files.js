// An image to drape and its world file, read whole for a command (hexlod mesh --image, a
// regression flight's "image"), from disk or by http(s). Without a world file named, the first
// of its conventional names beside the image (x.jgw, x.jpgw, x.wld: web/geo/world_file.js)
// is taken, as the page pairs files dropped together; from disk, its .prj and GDAL .aux.xml
// beside it too (x.prj, x.jpg.aux.xml: web/geo/sidecar_names.js), which give its CRS.
import { readFileSync, existsSync, statSync } from 'node:fs';
import { basename } from 'node:path';
import { worldFileNames } from '../web/geo/world_file.js';
import { crsSidecarNames } from '../web/geo/sidecar_names.js';
import { isUrl, urlFileName, fetchBytes } from './dem_source.js';
import { besideFile } from './cli_common.js';

/**
 * @typedef {{ name: string, bytes: Uint8Array }} NamedBytes
 * @typedef {{ image: NamedBytes, worldFile: NamedBytes|null, prj: NamedBytes|null, auxXml: NamedBytes|null }} ImageFiles
 */

/**
 * Reads an image and its world file from disk.
 * @param {string} imagePath
 * @param {string|null} worldFilePath null: look for one beside the image
 * @returns {ImageFiles}
 * @throws {Error} one line naming a file that is missing
 */
export function readImageFiles(imagePath, worldFilePath = null) {
  const read = readLocalFile;
  const image = read(imagePath, 'image file');
  const beside = besideFile(imagePath);
  const worldPath = worldFilePath ?? beside(worldFileNames(basename(imagePath)));
  const { prj, auxXml } = crsSidecarNames(basename(imagePath));
  const optional = (path) => (path === null ? null : read(path, 'file'));
  return { image, worldFile: worldPath === null ? null : read(worldPath, 'world file'), prj: optional(beside(prj)), auxXml: optional(beside(auxXml)) };
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
  const files = { image: await fetched(image), worldFile: null, prj: null, auxXml: null };
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

/**
 * Reads one file whole from a path or an http(s) URL, as { name, bytes } (a flight's overlay or track).
 * @param {string} path
 * @param {string} what the file's role, for the message
 * @returns {Promise<NamedBytes>}
 * @throws {Error} one line naming the file
 */
export async function readNamedFile(path, what) {
  return isUrl(path) ? { name: urlFileName(path), bytes: await fetchBytes(path) } : readLocalFile(path, `${what} file`);
}

/** One file from disk as { name, bytes }; throws one line naming it when it is missing or a folder. */
function readLocalFile(path, what) {
  if (!existsSync(path)) throw new Error(`${path}: no such ${what}`);
  if (!statSync(path).isFile()) throw new Error(`${path}: not a file`);
  return { name: basename(path), bytes: new Uint8Array(readFileSync(path)) };
}
