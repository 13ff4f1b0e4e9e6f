// JPEG-compressed GeoTIFF images decoded by the browser's JPEG decoder (web/imagery/
// browser_jpeg.js through tiff_jpeg_band.js), judged against the same satellite scene stored
// with deflate: the colours at known ground points agree within JPEG's loss, the whole image
// agrees with the geotiff library's decoding of the same file within what two decoders differ
// by (rounding, chroma upsampling), for RGB and for YCbCr JPEG, and every tile went through the
// browser's decoder (a stream spliced wrong, or decoded with the wrong colour transform, would
// be off by tens of levels).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { startViewer, openPage, projectDir } from '../../lib/page_harness.js';
import { readDirectory } from '../../web/geo/tiff_directory.js';
import { markerSegments } from '../../web/geo/tiff_jpeg_stream.js';

const FIXTURES = `${projectDir}tests/fixtures/imagery/`;

/**
 * The RGB JPEG fixture with its components numbered 1, 2, 3 (as many writers number them)
 * instead of libtiff's 'R', 'G', 'B', which a decoder takes for RGB by themselves: then only
 * the Adobe marker tells the browser not to convert the colours.
 */
function rgbNumbered() {
  const bytes = new Uint8Array(readFileSync(`${FIXTURES}haiti_rgb_5m_tiled_jpeg.tif`));
  const directory = readDirectory(bytes, (problem) => { throw new Error(problem); });
  const [offsets, counts] = [directory.values(324), directory.values(325)];
  offsets.forEach((offset, i) => {
    const tile = bytes.subarray(offset, offset + counts[i]);
    for (const { marker, at } of markerSegments(tile)) {
      // SOF0: 3 bytes a component after byte 10; SOS: 2 bytes a component after byte 5.
      if (marker === 0xc0) for (let k = 0; k < 3; k++) tile[at + 10 + 3 * k] = k + 1;
      if (marker === 0xda) for (let k = 0; k < 3; k++) tile[at + 5 + 2 * k] = k + 1;
    }
  });
  return Buffer.from(bytes).toString('base64');
}

// Ground points of tests/fixtures/imagery/README.md: UTM 18N centre coordinates.
const POINTS = [[794845.5, 2049299.5], [795190.5, 2049549.5], [795325.5, 2050269.5]];

test('a JPEG GeoTIFF decoded by the browser shows the colours of the deflate one of the same scene', async () => {
  const viewer = await startViewer();
  try {
    // A page of the dev server (a fixture file) to import the modules into, without the viewer.
    // (Its console shows the favicon's 404: what goes wrong in the modules rejects the evaluation.)
    const { page } = await openPage(viewer.browser, `${viewer.url}${viewer.fixturesUrl.slice(1)}imagery/README.md`);
    const result = await page.evaluate(async ({ web, fixtures, points, numbered }) => {
      const { readTiffImage } = await import(`${web}imagery/image_tiff.js`);
      const { browserJpegDecoder } = await import(`${web}imagery/browser_jpeg.js`);
      const { crsToSample } = await import(`${web}geo/georef.js`);
      const files = { 'rgb_numbered.tif': Uint8Array.from(atob(numbered), (c) => c.charCodeAt(0)) };
      const readWhole = async (name, decodeJpeg) => {
        const bytes = files[name] ?? new Uint8Array(await (await fetch(fixtures + name)).arrayBuffer());
        let rgba = null, width = 0;
        const info = await readTiffImage(bytes, name, {
          decodeJpeg,
          begin: (w, h) => { width = w; rgba = new Uint8Array(w * h * 4); },
          onBand: (y, rows, band) => rgba.set(band, y * width * 4),
        });
        return { info, rgba };
      };
      const reference = await readWhole('haiti_rgb_5m_tiled_deflate.tif', null);
      const at = points.map(([x, y]) => crsToSample(reference.info.georef, x, y).map(Math.round));
      const out = {};
      for (const name of ['haiti_rgb_5m_tiled_jpeg.tif', 'haiti_rgb_5m_tiled_jpeg_ycbcr.tif', 'rgb_numbered.tif']) {
        const browser = browserJpegDecoder();
        let decoded = 0;
        const { rgba } = await readWhole(name, (stream) => { decoded++; return browser(stream); });
        const library = (await readWhole(name, null)).rgba;
        let sum = 0, opaque = true;
        for (let i = 0; i < rgba.length; i += 4) {
          for (let k = 0; k < 3; k++) sum += Math.abs(rgba[i + k] - library[i + k]);
          opaque &&= rgba[i + 3] === 255;
        }
        out[name] = {
          decoded, opaque, meanDifference: sum / (rgba.length * 0.75),
          points: at.map(([c, r]) => {
            const i = (r * reference.info.width + c) * 4;
            return { pixel: [c, r], jpeg: Array.from(rgba.subarray(i, i + 3)), deflate: Array.from(reference.rgba.subarray(i, i + 3)) };
          }),
        };
      }

      // Opening the image to drape (open_image.js) hands the browser's decoder in by itself: the
      // bands reaching the GPU are the browser's decoding, not the library's (they differ a little).
      const { openImage } = await import(`${web}imagery/open_image.js`);
      const { crsOfEpsg, makeGeoref } = await import(`${web}geo/georef.js`);
      const haitiField = { width: 150, height: 200, spacingX: 10, spacingY: 10, georef: makeGeoref(crsOfEpsg(32618), 792995, 2050377, 10, -10, 'GeoTIFF') };
      const name = 'haiti_rgb_5m_tiled_jpeg_ycbcr.tif', blob = await (await fetch(fixtures + name)).blob();
      let uploaded = null, width = 0;
      const gpu = {
        limits: () => ({ maxTextureSize: 4096, maxLayers: 256 }),
        begin: (tiling) => { width = tiling.width; uploaded = new Uint8Array(tiling.width * tiling.height * 4); },
        uploadBand: (y, rows, rgba) => uploaded.set(rgba, y * width * 4),
        finish: () => {}, remove: () => {},
      };
      await openImage({ name, blob }, null, haitiField, gpu);
      const browser = await readWhole(name, browserJpegDecoder()), library = await readWhole(name, null);
      const same = (a, b) => a.length === b.length && a.every((v, i) => v === b[i]);
      out.opened = { asBrowser: same(uploaded, browser.rgba), asLibrary: same(uploaded, library.rgba), width };
      return out;
    }, { web: `/@fs${projectDir}web/`, fixtures: `${viewer.fixturesUrl}imagery/`, points: POINTS, numbered: rgbNumbered() });

    const { opened, ...decodings } = result;
    assert.deepEqual(opened, { asBrowser: true, asLibrary: false, width: 515 }, 'open_image.js decodes with the browser');
    for (const [name, { decoded, opaque, meanDifference, points }] of Object.entries(decodings)) {
      assert.equal(decoded, 6, `${name}: each of its 2 x 3 tiles decoded by the browser`);
      assert.ok(opaque, `${name}: every pixel opaque`);
      assert.ok(meanDifference < 2, `${name}: mean difference ${meanDifference.toFixed(2)} from the library's decoding`);
      // JPEG's loss at the fixtures' quality: no ground point further off than the Node test
      // allows the library's decoding (tests/node/imagery_tiff.test.js).
      for (const { pixel, jpeg, deflate } of points) {
        assert.ok(jpeg.every((v, k) => Math.abs(v - deflate[k]) <= 10), `${name} at pixel ${pixel}: ${jpeg}, deflate ${deflate}`);
      }
    }
  } finally {
    await viewer.close();
  }
});
