// Which dropped files are the height field and which the image to drape (web/imagery/drop_roles.js),
// and the table of image formats they follow (web/imagery/image_formats.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { dropRoles, IMAGE_EXTENSIONS } from '../../web/imagery/drop_roles.js';
import { IMAGE_FORMATS, DRAPED_FORMATS } from '../../web/imagery/image_formats.js';
import { readImageHeader } from '../../web/imagery/image_header.js';
import { ImageError } from '../../web/imagery/image_error.js';

const ROOT = new URL('../../', import.meta.url);
const head = (path) => new Uint8Array(readFileSync(new URL(path, ROOT))).subarray(0, 65536);
/** A PNG's first 26 bytes with the given bit depth and colour type (only IHDR matters here). */
const png = (bitDepth, colourType) => {
  const b = head('tests/fixtures/formats/everest_16bit.png').slice(0, 26);
  b[24] = bitDepth; b[25] = colourType;
  return b;
};
const JPEG = new Uint8Array([0xff, 0xd8, 0xff, 0xe0, 0, 16]);
const text = (s) => new TextEncoder().encode(s);
const roles = (files, options) => dropRoles(files.map(([name, bytes]) => ({ name, head: bytes })), options);

test('a DEM and its image, in either order, with or without the world file', () => {
  const dem = ['dem.tif', head('tests/fixtures/formats/everest_i16_strips.tif')];
  assert.deepEqual(roles([dem, ['ortho.jpg', JPEG]]), { field: [0], image: 1, worldFile: null });
  assert.deepEqual(roles([['ortho.jpg', JPEG], ['ortho.jgw', text('1\n0\n0\n-1\n0\n0\n')], dem]), { field: [2], image: 0, worldFile: 1 });
  // A grey 16-bit PNG with its sidecar and a colour PNG: the colour one is the image.
  assert.deepEqual(roles([['h.png', png(16, 0)], ['h.json', text('{}')], ['photo.png', png(8, 2)]]), { field: [0, 1], image: 2, worldFile: null });
  // Two 8-bit grey files: the first is the field, the second the image.
  assert.deepEqual(roles([['dem8.png', png(8, 0)], ['scan.png', png(8, 0)]]), { field: [0], image: 1, worldFile: null });
});

test('a colour PNG alone: heights when it says so or its colours read as heights, else an image', () => {
  assert.deepEqual(roles([['tile.png', png(8, 2)]], { colourPngIsHeight: () => true }), { field: [0], image: null, worldFile: null });
  assert.deepEqual(roles([['photo.png', png(8, 6)]], { colourPngIsHeight: () => false }), { field: [], image: 0, worldFile: null });
  assert.deepEqual(roles([['x_terrarium.png', png(8, 2)]], { colourPngIsHeight: () => false }), { field: [0], image: null, worldFile: null }, 'the name says heights');
  assert.deepEqual(roles([['tile.png', png(8, 2)], ['tile.pgw', text('1\n0\n0\n-1\n0\n0\n')]], { colourPngIsHeight: () => true }).image, 0, 'a world file makes it an image');
  assert.deepEqual(roles([['tile.png', png(8, 2)]], { pngAsImage: 'image', colourPngIsHeight: () => true }).image, 0, 'the menu forces it');
  assert.deepEqual(roles([['photo.png', png(8, 2)]], { pngAsImage: 'height', colourPngIsHeight: () => false }).field, [0]);
});

test('an image alone goes onto the open terrain; a colour GeoTIFF is an image, a grey one a field', () => {
  assert.deepEqual(roles([['ortho.webp', text('RIFF\0\0\0\0WEBPVP8 ')]]), { field: [], image: 0, worldFile: null });
  assert.deepEqual(roles([['dem.tif', head('tests/fixtures/formats/canyon_u16_tiled_deflate.tif')]]).field, [0]);
});

test('two images, or a world file without its image, are refused by name', () => {
  assert.throws(() => roles([['a.jpg', JPEG], ['b.jpg', JPEG]]), (e) => e instanceof ImageError && /several images given \(a\.jpg, b\.jpg\); drape one at a time/.test(e.message));
  assert.throws(() => roles([['dem.tif', head('tests/fixtures/formats/everest_i16_strips.tif')], ['o.jgw', text('1')]]),
    (e) => e instanceof ImageError && /^o\.jgw: a world file alone places nothing/.test(e.message));
  assert.throws(() => roles([['a.jpg', JPEG], ['b.jgw', text('1')]]),
    (e) => e instanceof ImageError && /^b\.jgw: does not belong to a\.jpg \(its world file is named a\.jgw or a\.jpgw or a\.wld\)/.test(e.message));
});

test('the image format table: each row knows its own first bytes and no other row\'s, and the picker and messages follow it', () => {
  const heads = {
    png: [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a],
    jpeg: [0xff, 0xd8, 0xff, 0xe0],
    webp: [...'RIFF'].map((c) => c.charCodeAt(0)).concat([0, 0, 0, 0], [...'WEBP'].map((c) => c.charCodeAt(0))),
    tiff: [0x49, 0x49, 0x2a, 0x00, 8, 0, 0, 0],
  };
  assert.deepEqual(IMAGE_FORMATS.map((f) => f.format).sort(), Object.keys(heads).sort());
  for (const [format, bytes] of Object.entries(heads)) {
    const head = new Uint8Array([...bytes, ...new Array(32).fill(0)]);
    assert.deepEqual(IMAGE_FORMATS.filter((f) => f.signature(head)).map((f) => f.format), [format], format);
  }
  assert.deepEqual(IMAGE_EXTENSIONS, ['.jpg', '.jpeg', '.webp', '.pgw', '.jgw', '.tfw', '.wld']);
  assert.equal(DRAPED_FORMATS, 'PNG, JPEG, WebP and 8-bit GeoTIFF');
  const gif = new Uint8Array([...'GIF89a'].map((c) => c.charCodeAt(0)).concat([1, 0, 1, 0, 0, 0, 0]));
  assert.throws(() => readImageHeader(gif, 'a.gif'), /a.gif: a GIF image cannot be draped; PNG, JPEG, WebP and 8-bit GeoTIFF can/);
});
