// Which dropped files are the height field, which the images to drape and which are skipped
// (web/imagery/drop_roles.js), and the table of image formats they follow (web/imagery/image_formats.js).
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
/** The images of a drop as [image, worldFile, prj, auxXml] indices. */
const imagesOf = (r) => r.images.map(({ image, sidecars: s }) => [image, s.worldFile, s.prj, s.auxXml]);
const NO_SIDECARS = { worldFile: null, prj: null, auxXml: null };

test('a DEM and its image, in either order, with or without the world file', () => {
  const dem = ['dem.tif', head('tests/fixtures/formats/everest_i16_strips.tif')];
  assert.deepEqual(roles([dem, ['ortho.jpg', JPEG]]), { field: [0], images: [{ image: 1, sidecars: NO_SIDECARS }], overlays: [], skipped: [] });
  assert.deepEqual(roles([['ortho.jpg', JPEG], ['ortho.jgw', text('1\n0\n0\n-1\n0\n0\n')], dem]),
    { field: [2], images: [{ image: 0, sidecars: { ...NO_SIDECARS, worldFile: 1 } }], overlays: [], skipped: [] });
  // A grey 16-bit PNG with its sidecar and a colour PNG: the colour one is the image.
  assert.deepEqual(roles([['h.png', png(16, 0)], ['h.json', text('{}')], ['photo.png', png(8, 2)]]),
    { field: [0, 1], images: [{ image: 2, sidecars: NO_SIDECARS }], overlays: [], skipped: [] });
  // Two 8-bit grey files: the first is the field, the second the image.
  assert.deepEqual(roles([['dem8.png', png(8, 0)], ['scan.png', png(8, 0)]]), { field: [0], images: [{ image: 1, sidecars: NO_SIDECARS }], overlays: [], skipped: [] });
});

test('a colour PNG alone: heights when it says so or its colours read as heights, else an image', () => {
  assert.deepEqual(roles([['tile.png', png(8, 2)]], { colourPngIsHeight: () => true }), { field: [0], images: [], overlays: [], skipped: [] });
  assert.deepEqual(roles([['photo.png', png(8, 6)]], { colourPngIsHeight: () => false }), { field: [], images: [{ image: 0, sidecars: NO_SIDECARS }], overlays: [], skipped: [] });
  assert.deepEqual(roles([['x_terrarium.png', png(8, 2)]], { colourPngIsHeight: () => false }), { field: [0], images: [], overlays: [], skipped: [] }, 'the name says heights');
  assert.deepEqual(imagesOf(roles([['tile.png', png(8, 2)], ['tile.pgw', text('1\n0\n0\n-1\n0\n0\n')]], { colourPngIsHeight: () => true })),
    [[0, 1, null, null]], 'a world file makes it an image');
  assert.deepEqual(imagesOf(roles([['tile.png', png(8, 2)]], { pngAsImage: 'image', colourPngIsHeight: () => true })), [[0, null, null, null]], 'the menu forces it');
  assert.deepEqual(roles([['photo.png', png(8, 2)]], { pngAsImage: 'height', colourPngIsHeight: () => false }).field, [0]);
});

test('an image alone goes onto the open terrain; a colour GeoTIFF is an image, a grey one a field', () => {
  assert.deepEqual(roles([['ortho.webp', text('RIFF\0\0\0\0WEBPVP8 ')]]), { field: [], images: [{ image: 0, sidecars: NO_SIDECARS }], overlays: [], skipped: [] });
  assert.deepEqual(roles([['dem.tif', head('tests/fixtures/formats/canyon_u16_tiled_deflate.tif')]]).field, [0]);
});

test('several images come in drop order, each with its own world file, .prj and .aux.xml', () => {
  const r = roles([['b.jpg', JPEG], ['a.jpg', JPEG], ['a.jgw', text('1')], ['b.prj', text('PROJCS[]')], ['a.jpg.aux.xml', text('<PAMDataset/>')],
    ['b.aux.xml', text('<PAMDataset/>')], ['b.jgw', text('1')]]);
  assert.deepEqual(imagesOf(r), [[0, 6, 3, 5], [1, 2, null, 4]]);
  assert.deepEqual([r.field, r.skipped], [[], []]);
});

test('a GIS drop: the DEM with its .prj and .aux.xml, the image with its world file and .prj; metadata and strays are skipped with the reason', () => {
  const files = [
    ['dem.tif', head('tests/fixtures/formats/everest_i16_strips.tif')], ['dem.prj', text('PROJCS[]')], ['dem.tif.aux.xml', text('<PAMDataset/>')],
    ['ortho.png', png(8, 2)], ['ortho.pgw', text('1')], ['ortho.prj', text('PROJCS[]')],
    // GDAL's overviews are a TIFF: the name, not the first bytes, says what it is.
    ['dem.tif.ovr', head('tests/fixtures/formats/everest_i16_strips.tif')], ['dem.tif.md5', text('d41d8cd98f00b204e9800998ecf8427e')],
    ['ortho.xml', text('<metadata/>')], ['dem.qmd', text('<qgis/>')], ['roads.cpg', text('UTF-8')], ['README.txt', text('hello')],
    ['other.prj', text('PROJCS[]')], ['other.jgw', text('1')], ['other.json', text('{}')],
  ];
  const r = roles(files);
  assert.deepEqual(r.field, [0, 1, 2]);
  assert.deepEqual(imagesOf(r), [[3, 4, 5, null]]);
  const skipped = Object.fromEntries(r.skipped.map(({ file, why }) => [files[file][0], why]));
  assert.deepEqual(skipped, {
    'dem.tif.ovr': 'GeoTIFF overviews', 'dem.tif.md5': 'checksum', 'ortho.xml': 'metadata', 'dem.qmd': 'QGIS metadata', 'roads.cpg': 'code page',
    'README.txt': 'neither a height field nor an image', 'other.prj': 'a .prj of no height field or image here',
    'other.jgw': 'a world file of no image here: ortho.png\'s is named ortho.pgw or ortho.pngw or ortho.wld',
    'other.json': 'a .json of no height field here',
  });
});

test('a world file or a .prj of another file is skipped; only a drop with nothing to open is refused, by name', () => {
  const dem = ['dem.tif', head('tests/fixtures/formats/everest_i16_strips.tif')];
  assert.deepEqual(roles([dem, ['o.jgw', text('1')]]), { field: [0], images: [], overlays: [], skipped: [{ file: 1, why: 'a world file of no image here' }] });
  assert.deepEqual(roles([['a.jpg', JPEG], ['b.jgw', text('1')]]).skipped,
    [{ file: 1, why: 'a world file of no image here: a.jpg\'s is named a.jgw or a.jpgw or a.wld' }]);
  assert.throws(() => roles([['o.jgw', text('1')]]), (e) => e instanceof ImageError && /^o\.jgw: a world file alone places nothing/.test(e.message));
  assert.throws(() => roles([['x.prj', text('PROJCS[]')], ['x.tif.ovr', text('II*\0')]]),
    (e) => e instanceof ImageError && /^x\.prj: a \.prj of no height field or image here: nothing here to open/.test(e.message));
  // Files no loader takes, alone: the loaders are asked, and say what they take.
  assert.deepEqual(roles([['README', text('hello')], ['x.md5', text('0')]]), { field: [0], images: [], overlays: [], skipped: [{ file: 1, why: 'checksum' }] });
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
