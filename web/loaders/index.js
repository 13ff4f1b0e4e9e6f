// Entry point of the height-field loaders: picks the decoder for the files
// given and assembles the Heightfield the rest of the app consumes.
// Plain ES module; runs unchanged in the browser and in Node.

import {
  HeightfieldError, DEFAULT_MAX_SAMPLES, defaultAllocate, describeContent, extensionOf, baseNameOf,
} from './common.js';
import { decodePng, hasPngSignature } from './png.js';
import { decodeF32 } from './f32.js';
import { parseSidecar } from './sidecar.js';

export { HeightfieldError, DEFAULT_MAX_SAMPLES, decodePng, decodeF32, parseSidecar };

/**
 * @typedef {object} Heightfield
 * @property {number} width samples per row
 * @property {number} height rows
 * @property {'u8'|'u16'|'i16'|'f32'} sampleType
 * @property {Uint8Array|Uint16Array|Int16Array|Float32Array} samples the array allocate() returned,
 *   row-major, row 0 first
 * @property {number} spacingX metres between neighbouring columns
 * @property {number} spacingY metres between neighbouring rows
 * @property {boolean} spacingFromFile false when the spacing defaulted to 1
 * @property {number} heightScale metres per raw unit: metres = raw*heightScale + heightOffset
 * @property {number} heightOffset metres
 * @property {number|null} nodata raw value meaning "no data", or null. For f32, NaN samples
 *   are always no-data in addition.
 * @property {string} source file name of the height field
 * @property {'png'|'f32'} format
 */

/**
 * Loads a height field from one or more files: a .png (optionally with its
 * .json sidecar, which then supplies spacing), or a .f32 with its .json sidecar.
 * Sidecars pair with a height field by base name (x.png + x.json).
 *
 * @param {Array<{ name: string, bytes: Uint8Array }>} files
 * @param {object} [options]
 * @param {(sampleType: 'u8'|'u16'|'i16'|'f32', width: number, height: number) => ArrayLike<number>} [options.allocate]
 *   returns the typed array (Uint8Array | Uint16Array | Int16Array | Float32Array) of exactly
 *   width*height elements that samples are decoded into; called exactly once, only after the
 *   file has been validated far enough to trust its size. Default: a fresh typed array.
 * @param {number} [options.maxSamples] reject files declaring more than this many samples
 *   (default DEFAULT_MAX_SAMPLES = 32769^2)
 * @returns {Promise<Heightfield>}
 * @throws {HeightfieldError} for any bad, missing, or unsupported input
 */
export async function loadHeightfield(files, options = {}) {
  const allocate = options.allocate ?? defaultAllocate;
  const maxSamples = options.maxSamples ?? DEFAULT_MAX_SAMPLES;
  if (typeof allocate !== 'function') throw new TypeError('options.allocate must be a function');
  if (!(maxSamples > 0)) throw new TypeError('options.maxSamples must be a positive number');

  if (!Array.isArray(files)) throw new HeightfieldError('', 'expected an array of { name, bytes } files');
  if (files.length === 0) throw new HeightfieldError('', 'no files given');
  const entries = files.map(checkFileEntry);
  for (const f of entries) if (f.bytes.length === 0) throw new HeightfieldError(f.name, 'empty file');

  const kinds = entries.map((f) => ({ ...f, kind: kindOf(f) }));
  const fields = kinds.filter((f) => f.kind !== 'json');
  const jsons = kinds.filter((f) => f.kind === 'json');
  if (fields.length === 0) {
    throw new HeightfieldError(jsons[0].name, 'a .json sidecar alone is not a height field; add the .png or .f32 it describes');
  }
  if (fields.length > 1) {
    throw new HeightfieldError('', `several height fields given (${fields.map((f) => f.name).join(', ')}); load one at a time`);
  }
  const main = fields[0];
  const base = baseNameOf(main.name);
  const stray = jsons.find((j) => baseNameOf(j.name) !== base);
  if (stray) throw new HeightfieldError(stray.name, `does not belong to ${main.name} (its sidecar must be named ${base}.json)`);
  if (jsons.length > 1) throw new HeightfieldError('', `several sidecars given for ${main.name} (${jsons.map((j) => j.name).join(', ')})`);
  const sidecar = jsons.length ? parseSidecar(jsons[0].bytes, jsons[0].name) : null;

  let decoded, heightScale = 1, heightOffset = 0, nodata = null;
  if (main.kind === 'png') {
    decoded = decodePng(main.bytes, main.name, allocate, { maxSamples, sidecar });
    ({ heightScale, heightOffset, nodata } = decoded);
  } else {
    if (!sidecar) throw new HeightfieldError(main.name, `missing sidecar ${base}.json (it gives width, height and cell size)`);
    decoded = decodeF32(main.bytes, main.name, sidecar, allocate, { maxSamples });
    nodata = sidecar.nodata;
  }

  const spacingFromFile = !!sidecar && sidecar.spacingX !== null;
  return {
    width: decoded.width,
    height: decoded.height,
    sampleType: decoded.sampleType,
    samples: decoded.samples,
    spacingX: spacingFromFile ? sidecar.spacingX : 1,
    spacingY: spacingFromFile ? sidecar.spacingY : 1,
    spacingFromFile,
    heightScale,
    heightOffset,
    nodata,
    source: main.name,
    format: main.kind,
  };
}

/** Validates one { name, bytes } entry; accepts an ArrayBuffer for bytes too. */
function checkFileEntry(f, i) {
  const label = f && typeof f.name === 'string' && f.name ? f.name : `file ${i + 1}`;
  if (!f || typeof f !== 'object') throw new HeightfieldError(label, 'expected { name, bytes }');
  let bytes = f.bytes;
  if (bytes instanceof ArrayBuffer) bytes = new Uint8Array(bytes);
  if (!(bytes instanceof Uint8Array)) throw new HeightfieldError(label, 'bytes must be a Uint8Array');
  return { name: label, bytes };
}

/** 'png' | 'f32' | 'json', by extension, then by magic bytes; throws for anything else. */
function kindOf({ name, bytes }) {
  const ext = extensionOf(name);
  if (ext === 'png' || ext === 'f32' || ext === 'json') return ext;
  if (hasPngSignature(bytes)) return 'png';
  const what = describeContent(bytes);
  throw new HeightfieldError(name,
    `unsupported file type${what ? ` (looks like ${what})` : ''}; expected a .png, or a .f32 with its .json sidecar`);
}
