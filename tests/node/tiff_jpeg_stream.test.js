// JPEG-compressed TIFF blocks as complete JPEG streams (web/geo/tiff_jpeg_stream.js), and
// images read through a JPEG decoder given from outside (web/imagery/tiff_jpeg_band.js), on the
// real 5 m satellite image stored as RGB and as YCbCr JPEG. The outside decoder here is the
// geotiff library's, with the colour rules of a JFIF decoder such as the browser's: three
// components are YCbCr unless an Adobe marker says transform 0.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { getDecoder, fromArrayBuffer } from 'geotiff';
import { tiffJpegStream, jpegFrame, markerSegments } from '../../web/geo/tiff_jpeg_stream.js';
import { readTiffImage } from '../../web/imagery/image_tiff.js';
import { ImageError } from '../../web/imagery/image_error.js';
import { readDirectory } from '../../web/geo/tiff_directory.js';

const DIR = new URL('../fixtures/imagery/', import.meta.url);
const read = (name) => new Uint8Array(readFileSync(new URL(name, DIR)));
const FIXTURES = { 'haiti_rgb_5m_tiled_jpeg.tif': { rgb: true }, 'haiti_rgb_5m_tiled_jpeg_ycbcr.tif': { rgb: false } };
const TILE_OFFSETS = 324, TILE_BYTE_COUNTS = 325;

/** The tiles of a fixture, as the file holds them. */
function tilesOf(bytes) {
  const directory = readDirectory(bytes, (problem) => { throw new Error(problem); });
  const [offsets, counts] = [directory.values(TILE_OFFSETS), directory.values(TILE_BYTE_COUNTS)];
  return Array.from(offsets, (o, i) => bytes.subarray(o, o + counts[i]));
}

/** The JPEGTables tag's bytes, as the library reads them. */
async function tablesOf(bytes) {
  const image = await (await fromArrayBuffer(bytes.slice().buffer)).getImage(0);
  return image.fileDirectory.loadValue('JPEGTables');
}

/** A JFIF decoder's reading of a complete stream: RGBA, YCbCr converted unless Adobe transform 0. */
async function jfifDecode(stream) {
  const frame = jpegFrame(stream);
  const raw = new Uint8Array(await (await getDecoder(7, {})).decodeBlock(stream.slice().buffer));
  let rgbAsStored = false;
  for (const { marker, at } of markerSegments(stream)) {
    if (marker === 0xee && String.fromCharCode(...stream.subarray(at + 4, at + 9)) === 'Adobe') rgbAsStored = stream[at + 15] === 0;
  }
  const n = frame.components, rgba = new Uint8ClampedArray(frame.width * frame.height * 4);
  for (let i = 0, j = 0; j < rgba.length; i += n, j += 4) {
    if (n === 1) { rgba.fill(raw[i], j, j + 3); } else if (rgbAsStored) { rgba.set(raw.subarray(i, i + 3), j); } else {
      const [y, cb, cr] = [raw[i], raw[i + 1] - 128, raw[i + 2] - 128];
      rgba[j] = y + 1.402 * cr; rgba[j + 1] = y - 0.344136 * cb - 0.714136 * cr; rgba[j + 2] = y + 1.772 * cb; // rounded and clamped by the array
    }
    rgba[j + 3] = 255;
  }
  return { width: frame.width, height: frame.height, rgba };
}

/** Reads an image whole through its bands. */
async function readWhole(bytes, name, decodeJpeg) {
  let rgba = null, width = 0;
  const info = await readTiffImage(bytes, name, {
    decodeJpeg,
    begin: (w, h) => { width = w; rgba = new Uint8Array(w * h * 4); },
    onBand: (y, rows, band) => { rgba.set(band, y * width * 4); },
  });
  return { info, rgba };
}

const count = (bytes, a, b) => bytes.reduce((n, v, i) => n + (v === a && bytes[i + 1] === b ? 1 : 0), 0);

test('a tile spliced with JPEGTables is one complete stream: SOI, the tables, one frame, one scan, EOI', async () => {
  for (const [name, { rgb }] of Object.entries(FIXTURES)) {
    const bytes = read(name);
    const tableBytes = await tablesOf(bytes);
    assert.ok(tableBytes instanceof Uint8Array && tableBytes.length > 4, `${name} has JPEGTables`);
    for (const tile of tilesOf(bytes)) {
      const stream = tiffJpegStream(tableBytes, tile, { rgb });
      assert.deepEqual([stream[0], stream[1], stream.at(-2), stream.at(-1)], [0xff, 0xd8, 0xff, 0xd9], `${name}: SOI first, EOI last`);
      assert.equal(count(stream, 0xff, 0xd8), 1, `${name}: one SOI (the tile's and the tables' dropped)`);
      assert.equal(count(stream, 0xff, 0xda), 1, `${name}: one scan`);
      const markers = Array.from(markerSegments(stream), (s) => s.marker);
      assert.equal(markers.filter((m) => m === 0xdb).length, count(tableBytes, 0xff, 0xdb), `${name}: the tables' quantisation tables`);
      const dqt = tableBytes.subarray(2, tableBytes.length - 2);
      assert.ok(Buffer.from(stream).includes(Buffer.from(dqt)), `${name}: the tables' segments whole`);
      assert.equal(markers.includes(0xee), rgb, `${name}: an Adobe marker exactly when the samples are RGB`);
      assert.deepEqual(jpegFrame(stream), { width: 256, height: 256, components: 3 }, `${name}: a full-size frame`);
    }
  }
});

test('a spliced tile decodes to the colours the library reads from the file, edge tiles cropped', async () => {
  for (const name of Object.keys(FIXTURES)) {
    const bytes = read(name);
    const library = await readWhole(bytes, name, null);
    // The decoder inverts its colours, so that a band read by the library instead (after an
    // error of ours) shows.
    let decoded = 0;
    const inverting = async (stream) => {
      decoded++;
      const pixels = await jfifDecode(stream);
      for (let j = 0; j < pixels.rgba.length; j += 4) for (let k = 0; k < 3; k++) pixels.rgba[j + k] = 255 - pixels.rgba[j + k];
      return pixels;
    };
    const spliced = await readWhole(bytes, name, inverting);
    assert.equal(decoded, 6, `${name}: each of the 2 x 3 tiles through the given decoder`);
    let largest = 0;
    for (let i = 0; i < library.rgba.length; i++) {
      const expected = i % 4 === 3 ? library.rgba[i] : 255 - library.rgba[i];
      largest = Math.max(largest, Math.abs(expected - spliced.rgba[i]));
    }
    assert.ok(largest <= 2, `${name}: largest difference ${largest}`);
  }
});

test('what the given decoder refuses the library reads; what neither can is an ImageError', async () => {
  const name = 'haiti_rgb_5m_tiled_jpeg.tif', bytes = read(name);
  const library = await readWhole(bytes, name, null);
  const refusing = async () => { throw new Error('EncodingError: the source image cannot be decoded'); };
  assert.deepEqual((await readWhole(bytes, name, refusing)).rgba, library.rgba);

  // Tile 0's first Huffman table marker garbled: its frame header still says 256 x 256 x 3.
  const broken = bytes.slice(), tiles = tilesOf(broken);
  const dht = Buffer.from(tiles[0]).indexOf(Buffer.from([0xff, 0xc4]));
  broken[tiles[0].byteOffset + dht + 1] = 0x02;
  await assert.rejects(readWhole(broken, 'broken.tif', refusing),
    (e) => e instanceof ImageError && /^broken\.tif: corrupt image data: /.test(e.message));
});

test('a JPEG tile whose frame says another size is refused before anything is reserved', async () => {
  const bytes = read('haiti_rgb_5m_tiled_jpeg.tif'), tiles = tilesOf(bytes);
  const sof = Buffer.from(tiles[2]).indexOf(Buffer.from([0xff, 0xc0]));
  bytes[tiles[2].byteOffset + sof + 7] = 0; bytes[tiles[2].byteOffset + sof + 8] = 128; // width 256 -> 128
  let begun = false;
  await assert.rejects(readTiffImage(bytes, 'narrow.tif', { begin: () => { begun = true; }, onBand: () => {}, decodeJpeg: jfifDecode }),
    (e) => e instanceof ImageError && /^narrow\.tif: bad TIFF: tile 2 decodes to 98304 bytes, but its 256x256 samples need 196608/.test(e.message));
  assert.equal(begun, false);
});

test('streams that are not what TIFF JPEG blocks are: clear errors', () => {
  assert.throws(() => tiffJpegStream(null, Uint8Array.of(0, 1, 2)), /does not start with a JPEG SOI marker/);
  assert.throws(() => tiffJpegStream(Uint8Array.of(1, 2), Uint8Array.of(0xff, 0xd8, 0xff, 0xd9)), /JPEGTables does not start with/);
  assert.deepEqual(tiffJpegStream(null, Uint8Array.of(0xff, 0xd8, 0xff, 0xd9)), Uint8Array.of(0xff, 0xd8, 0xff, 0xd9), 'no tables: the block alone');
  assert.throws(() => jpegFrame(Uint8Array.of(0xff, 0xd8, 0xff, 0xc0, 0, 40, 8)), /runs past the end/);
  assert.equal(jpegFrame(Uint8Array.of(0xff, 0xd8, 0xff, 0xda, 0, 2)), null, 'a scan before any frame');
});
