// Entry point of the height-field loaders: picks the decoder for the files
// given and assembles the Heightfield the rest of the app consumes.
// Plain ES module; runs unchanged in the browser and in Node.

import {
  HeightfieldError, DEFAULT_MAX_SAMPLES, defaultAllocate, describeContent, extensionOf, baseNameOf,
} from './common.js';
import { decodePng, hasPngSignature } from './png.js';
import { decodeF32 } from './f32.js';
import { decodeRaw, SizeNeededError } from './raw.js';
import { decodePgm, hasPgmSignature } from './pgm.js';
import { decodeHgt, probeHgt } from './hgt.js';
import { decodeAsc, hasAscHeader } from './asc.js';
import { decodeGeoTiff, probeGeoTiff } from './geotiff.js';
import { hasTiffSignature, isAuxXmlName, readCrsSidecars, withSidecarCrs, resolveGeoref, sidecarBelongsTo,
  degreesToMetres, metresPerUnit } from '../geo/index.js';
import { loadMosaic } from './mosaic.js';
import { parseSidecar, sidecarGeoref } from './sidecar.js';
import { fillNodata } from './nodata.js';
import { SampleSink } from './pacing.js';

export { HeightfieldError, SizeNeededError, DEFAULT_MAX_SAMPLES, decodePng, decodeF32, parseSidecar };

/** File kinds by extension (a .aux.xml is told by its whole ending). */
const KIND_OF_EXTENSION = {
  png: 'png', f32: 'f32', json: 'json', r16: 'raw', raw: 'raw', pgm: 'pgm', hgt: 'hgt', asc: 'asc',
  tif: 'geotiff', tiff: 'geotiff', prj: 'prj',
};
/** Kinds that are a height field's sidecars, not height fields. */
const SIDECAR_KINDS = new Set(['json', 'prj', 'auxXml']);
/** What the loaders accept, for messages and the file picker. */
export const ACCEPTED = '.png, .tif/.tiff (GeoTIFF), .hgt (SRTM), .asc (ESRI ASCII), .pgm, .r16/.raw, or .f32 with its .json sidecar';
export const ACCEPT_EXTENSIONS = [...Object.keys(KIND_OF_EXTENSION).map((e) => `.${e}`), '.xml'];

/**
 * @typedef {object} Heightfield
 * @property {number} width samples per row
 * @property {number} height rows
 * @property {'u8'|'u16'|'i16'|'f32'} sampleType
 * @property {Uint8Array|Uint16Array|Int16Array|Float32Array} samples the array allocate() returned
 *   (or its latest view, see options.reacquire), row-major, row 0 first (north)
 * @property {number} spacingX metres between neighbouring columns
 * @property {number} spacingY metres between neighbouring rows
 * @property {boolean} spacingFromFile false when the spacing defaulted to 1
 * @property {boolean} geographic the file's grid is in degrees (spacing is metres at its latitude)
 * @property {number} heightScale metres per raw unit: metres = raw*heightScale + heightOffset
 * @property {number} heightOffset metres
 * @property {number|null} nodata raw value meaning "no data", or null. For f32, NaN samples
 *   are always no-data in addition. Missing samples are already filled (see `missing`).
 * @property {number} missing how many no-data samples were filled by interpolation
 * @property {Uint8Array|null} missingMask which (a bit per sample, see nodata.js), or null
 * @property {string|null} encoding 'terrain-rgb' | 'terrarium' for encoded PNGs
 * @property {import('../geo/georef.js').Georef|null} georef where the samples lie on the Earth (the
 *   sidecar's crs and bounds, else the file's own), null when nothing says
 * @property {{ column: number, row: number, width: number, height: number }|null} cropped for a
 *   sparse GeoTIFF whose empty blocks surround its data: where the field starts in the file's
 *   raster, and the raster's declared size; null when the field is the whole raster
 * @property {string[]} notes what the file's .prj or .aux.xml could not give, each naming its file
 * @property {string} source file name of the height field
 * @property {'png'|'f32'|'raw'|'pgm'|'hgt'|'asc'|'geotiff'|'mosaic'} format the tiles' kind for a
 *   mosaic of one kind, 'mosaic' for .hgt and GeoTIFF tiles together
 */

/**
 * Loads a height field from one or more files: one height field (.png, .tif/.tiff, .hgt,
 * .asc, .pgm, .r16/.raw, .f32), optionally with its .json sidecar (required for .f32), which
 * then supplies spacing and, for raw integer formats, the height range. Sidecars pair with a
 * height field by base name (x.png + x.json). Its .prj (x.prj) and GDAL .aux.xml (x.tif.aux.xml
 * or x.aux.xml) give its CRS when the file names none, and the .aux.xml's geotransform places a
 * file that cannot place itself; one that cannot be read, or belongs to another file, is a note.
 * The CRS is resolved (web/geo/crs_definitions.js). Several .hgt or GeoTIFF tiles of one grid,
 * with no sidecar, make one mosaic (mosaic.js): its `source` names the first tile and how many more.
 *
 * @param {Array<{ name: string, bytes: Uint8Array }>} files
 * @param {object} [options]
 * @param {(sampleType: 'u8'|'u16'|'i16'|'f32', width: number, height: number) => ArrayLike<number>} [options.allocate]
 *   returns the typed array (Uint8Array | Uint16Array | Int16Array | Float32Array) of exactly
 *   width*height elements that samples are decoded into; called exactly once, only after the
 *   file has been validated far enough to trust its size. Default: a fresh typed array.
 * @param {() => ArrayLike<number>} [options.reacquire] returns a fresh view on the same samples;
 *   called after every pause of the decoder (needed when they live in memory that may grow)
 * @param {(fraction: number, phase: string) => void} [options.onProgress] 0..1 at every pause, per
 *   phase: 'checking' (a compressed file proving its declared size before anything is
 *   allocated), 'decoding', 'filling no-data'
 * @param {number} [options.maxSamples] reject files declaring more than this many samples
 *   (default DEFAULT_MAX_SAMPLES = 32769^2)
 * @param {number} [options.width] width of a RAW file (else inferred when square, or sidecar)
 * @param {number} [options.height] height of a RAW file
 * @param {'auto'|'terrain-rgb'|'terrarium'} [options.encoding] how an RGB PNG holds heights
 * @returns {Promise<Heightfield>}
 * @throws {HeightfieldError} for any bad, missing, or unsupported input (SizeNeededError when a
 *   RAW file needs its width and height)
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
  const fields = kinds.filter((f) => !SIDECAR_KINDS.has(f.kind));
  const jsons = kinds.filter((f) => f.kind === 'json');
  const crsFiles = kinds.filter((f) => f.kind === 'prj' || f.kind === 'auxXml');
  if (fields.length === 0) {
    const what = jsons.length ? 'a .json sidecar' : crsFiles[0].kind === 'prj' ? 'a .prj' : 'a GDAL .aux.xml';
    throw new HeightfieldError((jsons[0] ?? crsFiles[0]).name, `${what} alone is not a height field; add the file it describes`);
  }
  if (fields.length > 1) return loadTiles(fields, jsons, crsFiles, allocate, maxSamples, options);
  const main = fields[0];
  const base = baseNameOf(main.name);
  const stray = jsons.find((j) => baseNameOf(j.name) !== base);
  if (stray) throw new HeightfieldError(stray.name, `does not belong to ${main.name} (its sidecar must be named ${base}.json)`);
  if (jsons.length > 1) throw new HeightfieldError('', `several sidecars given for ${main.name} (${jsons.map((j) => j.name).join(', ')})`);
  const sidecar = jsons.length ? parseSidecar(jsons[0].bytes, jsons[0].name) : null;

  const progress = options.onProgress;
  const decodeOptions = {
    maxSamples, sidecar, reacquire: options.reacquire,
    onProgress: progress && ((fraction) => progress(fraction, 'decoding')),
    onCheckProgress: progress && ((fraction) => progress(fraction, 'checking')),
    width: options.width, height: options.height, encoding: options.encoding,
  };
  if (main.kind === 'f32' && !sidecar) {
    throw new HeightfieldError(main.name, `missing sidecar ${base}.json (it gives width, height and cell size)`);
  }
  const decoded = await DECODERS[main.kind](main.bytes, main.name, allocate, decodeOptions, sidecar);
  if (sidecar && main.kind !== 'png' && main.kind !== 'pgm' && main.kind !== 'raw' && main.kind !== 'f32' &&
      ((sidecar.width ?? decoded.width) !== decoded.width || (sidecar.height ?? decoded.height) !== decoded.height)) {
    throw new HeightfieldError(main.name, `size ${decoded.width}x${decoded.height} does not match ${sidecar.width ?? '?'}x${sidecar.height ?? '?'} from ${sidecar.name}`);
  }

  const nodata = decoded.nodata ?? (sidecar?.nodata ?? null);
  let missing = 0, missingMask = null;
  if (nodata !== null || decoded.sampleType === 'f32') {
    const sink = SampleSink.over(decoded.samples, { reacquire: options.reacquire,
      onProgress: progress && ((fraction) => progress(fraction, 'filling no-data')) });
    ({ count: missing, mask: missingMask } = await fillNodata(sink, decoded.width, decoded.height, nodata, main.name));
    decoded.samples = sink.samples;
  }

  // Where it lies: the .json sidecar's bounds, else the file's own georeference, else its
  // .aux.xml's geotransform; in the file's CRS, else the .prj's or .aux.xml's.
  const placed = await crsOfSidecars(main.name, crsFiles);
  const { georef: withCrs, note } = withSidecarCrs(sidecarGeoref(sidecar, decoded.width, decoded.height) ?? decoded.georef ?? placed.georef,
    placed.crs, main.name);
  const georef = await resolveGeoref(withCrs);
  const notes = note ? [...placed.notes, note] : placed.notes;

  // Spacing: the sidecar's, else the file's own, else the .aux.xml's geotransform's, else 1 m
  // (the user can change it).
  const sidecarSpacing = sidecar && sidecar.spacingX !== null;
  const fileSpacing = !sidecarSpacing && decoded.spacingX != null && decoded.spacingFromFile !== false;
  // An ASCII grid's cell size is in its CRS's units, which only its .prj says (degrees, feet or
  // metres): where that is not what its numbers suggested (asc.js), the CRS's units win.
  const ascUnits = fileSpacing && main.kind === 'asc' && georef?.crs.proj4 &&
    (georef.crs.geographic !== !!decoded.geographic || metresPerUnit(georef.crs) !== 1);
  const auxPlaced = !sidecarSpacing && !fileSpacing && georef?.from === '.aux.xml';
  const derived = ascUnits || auxPlaced ? gridSpacing(georef, decoded.height) : null;
  const spacingFromFile = sidecarSpacing || fileSpacing || auxPlaced;
  return {
    width: decoded.width,
    height: decoded.height,
    sampleType: decoded.sampleType,
    samples: decoded.samples,
    spacingX: sidecarSpacing ? sidecar.spacingX : derived?.spacingX ?? decoded.spacingX ?? 1,
    spacingY: sidecarSpacing ? sidecar.spacingY : derived?.spacingY ?? decoded.spacingY ?? 1,
    spacingFromFile,
    geographic: derived ? georef.crs.geographic : fileSpacing && !!decoded.geographic,
    heightScale: decoded.heightScale ?? 1,
    heightOffset: decoded.heightOffset ?? 0,
    nodata,
    missing,
    missingMask,
    encoding: decoded.encoding ?? null,
    cropped: decoded.cropped ?? null,
    georef: georef ?? null,
    notes,
    source: main.name,
    format: main.kind,
  };
}

/**
 * The CRS (and perhaps the place) a height field's .prj and .aux.xml give; the ones of another
 * file, and a second of a kind, are notes.
 */
async function crsOfSidecars(fieldName, crsFiles) {
  const notes = [];
  const pick = (kind) => {
    const mine = crsFiles.filter((f) => f.kind === kind && sidecarBelongsTo(f.name, fieldName));
    for (const f of mine.slice(1)) notes.push(`${f.name}: a second ${kind === 'prj' ? '.prj' : '.aux.xml'} of ${fieldName}; not used`);
    return mine[0] ?? null;
  };
  const prj = pick('prj'), auxXml = pick('auxXml');
  for (const f of crsFiles) {
    if (!sidecarBelongsTo(f.name, fieldName)) notes.push(`${f.name}: belongs to no height field here (${fieldName} is not its grid); not used`);
  }
  const read = await readCrsSidecars({ prj, auxXml });
  return { ...read, notes: [...notes, ...read.notes] };
}

/** Metres between columns and rows of a grid whose steps are in its (resolved) CRS's units. */
function gridSpacing(georef, height) {
  if (georef.crs.geographic) return degreesToMetres(georef.dx, Math.abs(georef.dy), georef.y0 + (georef.dy * (height - 1)) / 2);
  const unit = metresPerUnit(georef.crs);
  return { spacingX: georef.dx * unit, spacingY: Math.abs(georef.dy) * unit };
}

/** Kinds whose tiles say where they lie, so that several make one mosaic (mosaic.js). */
const PROBES = {
  hgt: async (tile) => probeHgt(tile.bytes, tile.name),
  geotiff: (tile, maxSamples) => probeGeoTiff(tile.bytes, tile.name, { maxSamples }),
};

/**
 * Several height fields at once: tiles of one mosaic, each placed by its own georeference (a
 * .prj or .aux.xml beside a tile is a note: the tiles say where they lie). Its CRS is resolved.
 */
async function loadTiles(fields, jsons, crsFiles, allocate, maxSamples, options) {
  if (jsons.length) {
    throw new HeightfieldError(jsons[0].name, `a sidecar goes with one height field; the tiles of a mosaic (${fields.map((f) => f.name).join(', ')}) are placed by their own georeferences`);
  }
  const other = fields.find((f) => !PROBES[f.kind]);
  if (other) {
    throw new HeightfieldError(other.name, `several height fields make a mosaic only of .hgt (SRTM) and GeoTIFF tiles; open ${other.name} on its own`);
  }
  const progress = options.onProgress;
  const mosaic = await loadMosaic(fields, {
    probe: (tile) => PROBES[tile.kind](tile, maxSamples),
    decode: (tile, tileAllocate, onProgress) => DECODERS[tile.kind](tile.bytes, tile.name, tileAllocate,
      { maxSamples, onProgress, onCheckProgress: progress && ((fraction) => progress(fraction, 'checking')) }),
    allocate, reacquire: options.reacquire, onProgress: progress, maxSamples,
  });
  const notes = crsFiles.map((f) => `${f.name}: the tiles of a mosaic are placed by their own georeferences; not used`);
  return { ...mosaic, georef: await resolveGeoref(mosaic.georef), notes };
}

/** Decoders by kind: (bytes, name, allocate, options, sidecar) -> decoded field. */
const DECODERS = {
  png: (bytes, name, allocate, options) => decodePng(bytes, name, allocate, options),
  f32: async (bytes, name, allocate, options, sidecar) => decodeF32(bytes, name, sidecar, allocate, options),
  raw: (bytes, name, allocate, options) => decodeRaw(bytes, name, allocate, options),
  pgm: (bytes, name, allocate, options) => decodePgm(bytes, name, allocate, options),
  hgt: (bytes, name, allocate, options) => decodeHgt(bytes, name, allocate, options),
  asc: (bytes, name, allocate, options) => decodeAsc(bytes, name, allocate, options),
  geotiff: (bytes, name, allocate, options) => decodeGeoTiff(bytes, name, allocate, options),
};

/** Validates one { name, bytes } entry; accepts an ArrayBuffer for bytes too. */
function checkFileEntry(f, i) {
  const label = f && typeof f.name === 'string' && f.name ? f.name : `file ${i + 1}`;
  if (!f || typeof f !== 'object') throw new HeightfieldError(label, 'expected { name, bytes }');
  let bytes = f.bytes;
  if (bytes instanceof ArrayBuffer) bytes = new Uint8Array(bytes);
  if (!(bytes instanceof Uint8Array)) throw new HeightfieldError(label, 'bytes must be a Uint8Array');
  return { name: label, bytes };
}

/** The file's kind by extension, then by magic bytes; throws for anything else. */
function kindOf({ name, bytes }) {
  const kind = heightFieldKind({ name, head: bytes });
  if (kind) return kind;
  const what = describeContent(bytes);
  throw new HeightfieldError(name, `unsupported file type${what ? ` (looks like ${what})` : ''}; expected ${ACCEPTED}`);
}

/**
 * What the loaders make of a file, from its name and first bytes: a height field's kind ('png',
 * 'geotiff', ...), a sidecar's ('json', 'prj', 'auxXml'), or null for a file they do not take.
 * @param {{ name: string, head: Uint8Array }} file
 */
export function heightFieldKind({ name, head }) {
  if (isAuxXmlName(name)) return 'auxXml';
  const kind = KIND_OF_EXTENSION[extensionOf(name)];
  if (kind) return kind;
  if (hasPngSignature(head)) return 'png';
  if (hasTiffSignature(head)) return 'geotiff';
  if (hasPgmSignature(head)) return 'pgm';
  if (hasAscHeader(head)) return 'asc';
  return null;
}
