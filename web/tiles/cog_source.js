// A Cloud-Optimized GeoTIFF opened to be read tile by tile: from a URL by HTTP Range requests, or from a
// Blob or dropped File by slice, reading only the header and the image directories at open,
// then one tile at a time, its entries of the tile tables read with it (tile_tables.js). The
// levels are the full-resolution image and its overviews (GDAL's reduced-resolution images in
// the same file), each tiled alike.
//
// The geotiff library parses the directories (header_source.js feeds it); the tiles are read
// byte-exact by offset and count and decoded by the same decoders and block checks as a whole
// file (web/geo/tiff_blocks.js, tiff_decoders.js), so a tile read this way equals the same
// window of the file loaded whole.

import { hasTiffSignature, parseNodata, heightScaling, sampleTypeOf, spacingOf, blockLayout, measurer, georefOfTiff, libraryGuard, openTiffSource,
  TYPED_ARRAYS, GETTERS, LITTLE_ENDIAN_HOST } from '../geo/index.js';
import { SAMPLE_ARRAYS } from '../loaders/common.js';
import { TileError, checkAborted } from './tile_error.js';
import { urlReader, blobReader } from './range_reader.js';
import { headerSource } from './header_source.js';
import { readTileTables } from './tile_tables.js';

const TILE_OFFSETS = 324, TILE_BYTE_COUNTS = 325;
const REDUCED_IMAGE = 1, MASK_IMAGE = 4; // NewSubfileType bits
export const MAKE_COG = 'gdal_translate -of COG in.tif out.tif';

/**
 * @typedef {object} CogLevel
 * @property {number} width samples
 * @property {number} height samples
 * @property {number} scale full-resolution samples per sample of this level, across (1 for the
 *   full resolution, 2 for the first overview of a usual COG)
 * @property {number} tileWidth samples
 * @property {number} tileHeight samples
 * @property {number} tilesAcross
 * @property {number} tilesDown
 */

/**
 * @param {string|URL|Blob} input a URL (read with Range requests) or a Blob or File (read by slice)
 * @param {{ signal?: AbortSignal, retries?: number, backoffMs?: number, fetch?: typeof fetch,
 *   name?: string }} [options] retries and backoffMs: see range_reader.js urlReader
 * @returns {Promise<CogSource>}
 * @throws {TileError} kinds 'http', 'network', 'no-range', 'not-cog', 'bad-tiff', 'aborted'
 */
export async function openCog(input, options = {}) {
  const reader = input instanceof Blob ? blobReader(input) : urlReader(String(input), options);
  const name = options.name ?? reader.name;
  const source = headerSource(reader);
  const fail = (problem) => { throw new TileError('bad-tiff', `${name}: ${problem}`); };
  // A structure that points past the end of the file is a truncated file, not a bad one.
  const failInStructure = (problem) => {
    if (source.pastEnd) {
      throw new TileError('truncated', `${name}: the file ends at byte ${reader.size ?? '?'}, inside its image directories ` +
        `(${problem}): it is truncated`, { size: reader.size });
    }
    throw new TileError('bad-tiff', `${name}: ${problem}`);
  };
  const guard = libraryGuard(failInStructure, TileError);
  const signal = options.signal;

  const head = new Uint8Array((await source.fetch([{ offset: 0, length: 16 }], signal))[0]);
  if (head.length < 8) fail(head.length === 0 ? 'empty file' : `truncated: ${head.length} bytes, no TIFF header`);
  if (!hasTiffSignature(head)) fail('not a TIFF file (bad signature)');
  const tiff = await guard('bad TIFF structure', () => openTiffSource(source, signal));
  const count = await guard('bad TIFF image directories', () => tiff.getImageCount());

  // Where each directory's tile tables lie; their entries are read as tiles are wanted (tile_tables.js).
  const tables = await guard('bad TIFF image directories', () => readTileTables(source, count, failInStructure, signal));
  const levels = [], layouts = [];
  let full = null;
  for (let index = 0; index < count; index++) {
    const image = await guard(`bad TIFF image directory ${index}`, () => tiff.getImage(index));
    const dir = image.fileDirectory;
    const subfile = (await guard('bad TIFF subfile type', () => dir.loadValue('NewSubfileType'))) ?? 0;
    if (subfile & MASK_IMAGE) continue; // a transparency mask, not heights
    if (full && !(subfile & REDUCED_IMAGE)) continue; // another page, not an overview of this one
    const width = image.getWidth(), height = image.getHeight();
    if (!image.isTiled) {
      throw new TileError('not-cog', `${name} is not a Cloud-Optimized GeoTIFF: image ${index} is stored in strips, ` +
        `so any view needs whole rows of the file; convert it with: ${MAKE_COG}`);
    }
    // The block checks of a whole-file load read the tile tables whole; here only their lengths
    // are checked at open, and each entry when its tile is read.
    const table = tables[index];
    const tags = { [TILE_OFFSETS]: table?.offsets, [TILE_BYTE_COUNTS]: table?.counts };
    const layout = await guard('bad TIFF layout', () => blockLayout(image, { values: (tag) => tags[tag] }, { width, height }, fail));
    if (!full) {
      const [format, bits] = await guard('bad TIFF sample type', async () =>
        [(await dir.loadValue('SampleFormat'))?.[0] ?? 1, (await dir.loadValue('BitsPerSample'))?.[0] ?? 1]);
      const sampleType = sampleTypeOf(format, bits);
      if (!sampleType) fail(`unsupported TIFF sample type: ${['', 'unsigned', 'signed', 'float'][format] ?? `format ${format}`} ${bits}-bit`);
      full = { image, width, height, format, bits, sampleType,
        nodata: parseNodata(await guard('bad TIFF no-data tag (42113)', () => dir.loadValue('GDAL_NODATA')), fail) };
    } else if (layout.bytesPerPixel !== layouts[0].bytesPerPixel) {
      fail(`overview ${levels.length} has ${layout.bytesPerPixel} bytes a sample, the full resolution ${layouts[0].bytesPerPixel}`);
    }
    layouts.push({ ...layout, littleEndian: image.littleEndian, measure: measurer(layout) });
    levels.push({
      width, height, scale: full.width / width, tileWidth: layout.blockWidth, tileHeight: layout.blockHeight,
      tilesAcross: Math.ceil(width / layout.blockWidth), tilesDown: Math.ceil(height / layout.blockHeight),
    });
  }
  // Coarsest last, whatever order the file keeps them in.
  const order = levels.map((_, i) => i).sort((a, b) => levels[b].width - levels[a].width);
  const metadata = await guard('bad TIFF metadata tag (42112)', () => full.image.getGDALMetadata(0));
  full.scaling = heightScaling(metadata, fail);
  full.statistics = statisticsOf(metadata);
  return new CogSource(name, reader, full, order.map((i) => levels[i]), order.map((i) => layouts[i]));
}

/**
 * The lowest and highest sample of the whole file when GDAL wrote its statistics
 * (STATISTICS_MINIMUM and STATISTICS_MAXIMUM of band 1, e.g. `gdal_translate -stats`), else null:
 * what the tiles read so far cannot show.
 * @param {Record<string, unknown>|null} items the band's GDAL metadata items, read once at open
 */
function statisticsOf(items) {
  const min = Number(items?.STATISTICS_MINIMUM), max = Number(items?.STATISTICS_MAXIMUM);
  return Number.isFinite(min) && Number.isFinite(max) && min <= max ? { min, max } : null;
}

/** An open COG: what it holds, and its tiles on demand. */
export class CogSource {
  constructor(name, reader, full, levels, layouts) {
    this.name = name;
    /** full-resolution samples */
    this.width = full.width;
    this.height = full.height;
    /** 'i16', 'u16', 'u8' or 'f32' (int32 and float64 files come as f32, as web/loaders/geotiff.js loads them) */
    this.sampleType = full.sampleType;
    /** raw value of a missing sample, or null */
    this.nodata = full.nodata;
    /** @type {import('../geo/georef.js').Georef|null} sample centres to model coordinates */
    this.georef = georefOfTiff(full.image);
    /** {min, max} raw sample range of the whole file from GDAL's statistics, or null */
    this.statistics = full.statistics;
    /** metres = raw x heightScale + heightOffset (GDAL's scale and offset; 1 and 0 without) */
    this.heightScale = full.scaling.heightScale;
    this.heightOffset = full.scaling.heightOffset;
    /** metres between columns and rows, or nulls without a geotransform (see web/loaders/geotiff.js) */
    const spacing = spacingOf(full.image, full.height / 2);
    this.spacingX = spacing.spacingX;
    this.spacingY = spacing.spacingY;
    /** tile size of the full resolution, in samples */
    this.tileWidth = levels[0].tileWidth;
    this.tileHeight = levels[0].tileHeight;
    /** @type {CogLevel[]} full resolution first, then each overview, coarser each time */
    this.levels = levels;
    /** false for a COG without overviews: a distant view then needs full-resolution tiles */
    this.hasOverviews = levels.length > 1;
    /** what was fetched so far: requests made and body bytes received (header and tiles) */
    this.stats = reader.stats;
    this._reader = reader;
    this._layouts = layouts;
    this._format = full.format;
    this._bits = full.bits;
  }

  /** The file's length in bytes, once known (a server tells it with its first answer). */
  get size() {
    return this._reader.size;
  }

  /**
   * One tile's samples, decoded.
   * @param {number} level index into levels (0 is the full resolution)
   * @param {number} tx tile column, 0 at the west
   * @param {number} ty tile row, 0 at the north
   * @param {AbortSignal} [signal]
   * @returns {Promise<Int16Array|Uint16Array|Uint8Array|Float32Array>} tileWidth x tileHeight
   *   samples of sampleType, row by row; tiles at the right and bottom edges hold what the file
   *   stores past the image (GDAL writes zeros or no-data): only the level's width and height count
   * @throws {TileError} kinds 'http', 'network', 'truncated', 'decode', 'aborted'
   */
  async readTile(level, tx, ty, signal) {
    const info = this.levels[level];
    if (!info) throw new RangeError(`level ${level} does not exist (this COG has ${this.levels.length})`);
    if (!(tx >= 0 && tx < info.tilesAcross && ty >= 0 && ty < info.tilesDown && Number.isInteger(tx) && Number.isInteger(ty))) {
      throw new RangeError(`tile (${tx}, ${ty}) is outside level ${level}'s ${info.tilesAcross} x ${info.tilesDown} tiles`);
    }
    const layout = this._layouts[level];
    const i = ty * info.tilesAcross + tx;
    const where = `${this.name}: tile (${tx}, ${ty}) of level ${level}`;
    const [offset, count] = await Promise.all([layout.offsets.get(i), layout.counts.get(i)]);
    checkAborted(signal, where);
    if (Number.isNaN(offset) || Number.isNaN(count)) {
      throw new TileError('truncated', `${where}: the file ends inside its tile tables (${this._reader.size ?? '?'} bytes): it is truncated`,
        { size: this._reader.size });
    }
    const samples = new SAMPLE_ARRAYS[this.sampleType](info.tileWidth * info.tileHeight);
    if (count === 0) return samples.fill(this.nodata ?? 0); // a sparse file's empty tile (GDAL SPARSE_OK)

    const truncated = (had) => new TileError('truncated', `${where} lies at bytes ${offset}..${offset + count - 1}, ` +
      `past the end of the file (${had} bytes): the file is truncated`, { size: had });
    const size = this._reader.size;
    if (size !== null && offset + count > size) throw truncated(size);
    const bytes = await this._reader.read(offset, count, signal);
    if (bytes.length < count) throw truncated(this._reader.size ?? offset + bytes.length);
    checkAborted(signal, where);

    // Measured before decoding, as a whole-file load checks every block: our decoders pad a
    // block cut short with zeros, which would pass for samples.
    const needed = samples.length * layout.bytesPerPixel;
    let decoded;
    try {
      const length = await layout.measure(bytes, needed);
      if (length !== needed) throw new Error(`${length > needed ? `more than ${needed}` : length} bytes, its ${info.tileWidth}x${info.tileHeight} samples need ${needed}`);
      decoded = await layout.decoder.decode(bytes.slice().buffer);
    } catch (e) {
      throw new TileError('decode', `${where} does not decode (${String(e?.message ?? e).split('\n')[0].slice(0, 120)})`, { cause: e });
    }
    copySamples(decoded, samples, this._format, this._bits, layout);
    return samples;
  }
}

/** The first sample of each pixel of a decoded tile into samples, converted to their type. */
function copySamples(decoded, samples, format, bits, { bytesPerPixel, littleEndian }) {
  const sampleBytes = bits / 8;
  if (bytesPerPixel === sampleBytes && littleEndian === LITTLE_ENDIAN_HOST) {
    samples.set(new TYPED_ARRAYS[format][bits](decoded, 0, samples.length));
    return;
  }
  const view = new DataView(decoded), getter = GETTERS[format][bits];
  for (let k = 0; k < samples.length; k++) samples[k] = view[getter](k * bytesPerPixel, littleEndian);
}
