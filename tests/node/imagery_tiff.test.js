// GeoTIFF images to drape (web/imagery/image_tiff.js), on a real 5 m satellite image in the
// layouts and codecs people have: bands of whole rows, each once, in order; the colours at
// known ground points; the georeference; and refusals before anything is reserved.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { readTiffImage } from '../../web/imagery/image_tiff.js';
import { ImageError } from '../../web/imagery/image_error.js';
import { crsToSample } from '../../web/geo/georef.js';

const DIR = new URL('../fixtures/imagery/', import.meta.url);
const read = (name) => new Uint8Array(readFileSync(new URL(name, DIR)));

/** Reads an image whole through the bands, checking their order; returns { info, rgba, begun }. */
async function readWhole(bytes, name) {
  let rgba = null, next = 0, width = 0, begun = false;
  const info = await readTiffImage(bytes, name, {
    begin: (w, h) => { begun = true; width = w; rgba = new Uint8Array(w * h * 4); },
    onBand: (y, rows, band) => {
      assert.equal(y, next, 'bands in order, none skipped');
      assert.equal(band.length, width * rows * 4);
      rgba.set(band, y * width * 4);
      next = y + rows;
    },
  });
  assert.equal(next, info.height, 'every row');
  return { info, rgba, begun };
}

// Ground points (tests/fixtures/imagery/README.md): UTM 18N centre coordinates and the colour there.
const POINTS = [[794845.5, 2049299.5, [211, 224, 223]], [795190.5, 2049549.5, [44, 43, 33]], [795325.5, 2050269.5, [77, 100, 72]]];

test('a real satellite GeoTIFF in every layout and codec: its size, place and colours', async () => {
  for (const [name, tolerance] of [['haiti_rgb_5m_tiled_deflate.tif', 0], ['haiti_rgb_5m_strips_lzw_pred2.tif', 0],
    ['haiti_rgb_5m_tiled_jpeg.tif', 10], ['haiti_rgb_5m_tiled_jpeg_ycbcr.tif', 10]]) {
    const { info, rgba } = await readWhole(read(name), name);
    assert.deepEqual([info.width, info.height, info.georef.crs.label, info.georef.dx, info.georef.dy], [515, 403, 'EPSG:32618', 5, -5], name);
    for (const [x, y, colour] of POINTS) {
      const [c, r] = crsToSample(info.georef, x, y).map(Math.round);
      const got = Array.from(rgba.subarray((r * 515 + c) * 4, (r * 515 + c) * 4 + 4));
      assert.ok(colour.every((v, k) => Math.abs(got[k] - v) <= tolerance) && got[3] === 255, `${name} at ${x}, ${y} (pixel ${c}, ${r}): ${got} vs ${colour}`);
    }
  }
});

test('what is no drapeable image is refused with a message naming it, before anything is reserved', async () => {
  const refused = async (bytes, name, problem) => {
    let begun = false;
    await assert.rejects(readTiffImage(bytes, name, { begin: () => { begun = true; }, onBand: () => {} }),
      (e) => e instanceof ImageError && e.message.startsWith(`${name}: `) && problem.test(e.message));
    assert.equal(begun, false, `${name}: nothing reserved`);
  };
  await refused(new Uint8Array(readFileSync(new URL('../fixtures/formats/everest_i16_strips.tif', import.meta.url))), 'dem.tif',
    /unsupported TIFF image: 16-bit samples \(8-bit images can be draped; a height field is dropped on its own\)/);
  const good = read('haiti_rgb_5m_tiled_deflate.tif');
  await refused(good.subarray(0, 200000), 'cut.tif', /^cut\.tif: truncated: /);
  await refused(new TextEncoder().encode('not a tiff'), 'x.tif', /not a TIFF file/);
  // The width forged to 60000 (ImageWidth is the directory's first entry): the tiles no longer cover it.
  const forged = good.slice(), v = new DataView(forged.buffer), ifd = v.getUint32(4, true);
  assert.equal(v.getUint16(ifd + 2, true), 256);
  v.setUint16(ifd + 2 + 8, 60000, true);
  await refused(forged, 'wide.tif', /bad TIFF: \d+ tiles listed, \d+ needed/);
});
