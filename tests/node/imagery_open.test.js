// Opening an image to drape, end to end without a GPU (web/imagery/open_image.js with a
// recording stand-in for the textures): what reaches the GPU, in what order, and that a refused
// image reserves nothing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { openImage } from '../../web/imagery/open_image.js';
import { ImageError } from '../../web/imagery/image_error.js';
import { crsOfEpsg, makeGeoref } from '../../web/geo/georef.js';
import { resolveCrs } from '../../web/geo/index.js';
import { useNodeCrsDefinitions } from '../../lib/crs_definitions.js';

useNodeCrsDefinitions(); // the terrains' CRSs as the loaders give them: with their definitions
const crs = (code, geographic) => resolveCrs(crsOfEpsg(code, geographic));

const DIR = new URL('../fixtures/imagery/', import.meta.url);
const file = (name) => ({ name, blob: new Blob([readFileSync(new URL(name, DIR))]) });
const text = (name, s) => ({ name, blob: new Blob([s]) });

/** Records what the loader asks of the GPU. */
function fakeGpu(maxTextureSize = 4096) {
  const calls = [];
  return {
    calls,
    limits: () => ({ maxTextureSize, maxLayers: 256 }),
    begin: (tiling) => calls.push(['begin', tiling.tilesX, tiling.tilesY]),
    uploadBand: (y, rows) => calls.push(['band', y, rows]),
    uploadBitmap: async (bitmap) => calls.push(['bitmap', bitmap.width, bitmap.height]),
    finish: () => calls.push(['finish']),
    abort: () => calls.push(['abort']),
  };
}

// A 10 m field in UTM 18N over the Haiti image's west half, and the Himalaya (EPSG:4326).
const haitiField = { width: 150, height: 200, spacingX: 10, spacingY: 10, georef: makeGeoref(await crs(32618), 792995, 2050377, 10, -10, 'GeoTIFF') };
const himalaya = { width: 2048, height: 2048, spacingX: 806.9, spacingY: 926, georef: makeGeoref(await crs(4326, true), 72.9375, 37.9125, 1 / 120, -1 / 120, 'sidecar') };
const sidecars = (worldFile, more = {}) => ({ worldFile, prj: null, auxXml: null, ...more });

test('a GeoTIFF image on a field in its CRS: bands to the GPU, then its description', async () => {
  const gpu = fakeGpu();
  const draped = await openImage(file('haiti_rgb_5m_tiled_deflate.tif'), null, haitiField, gpu);
  assert.deepEqual(gpu.calls[0], ['begin', 1, 1]);
  assert.deepEqual(gpu.calls.at(-1), ['finish']);
  assert.equal(gpu.calls.filter((c) => c[0] === 'band').reduce((n, c) => n + c[2], 0), 403, 'every row once');
  assert.equal(draped.metresPerPixel, 5);
  assert.ok(draped.placement.coverage > 0.99, `the field lies inside the image (coverage ${draped.placement.coverage})`);
  assert.equal(draped.note, null);
});

test('a JPEG with its world file on the default terrain, decoded by the browser', async () => {
  const gpu = fakeGpu();
  const draped = await openImage(file('bmng_himalaya_4arcmin.jpg'), sidecars(file('bmng_himalaya_4arcmin.jgw')), himalaya, gpu,
    { decodeBitmap: async () => ({ width: 256, height: 257, close() {} }) });
  assert.deepEqual(gpu.calls, [['begin', 1, 1], ['bitmap', 256, 257]]);
  assert.match(draped.note, /the image names no CRS: taken to be in EPSG:4326/);
  assert.ok(draped.placement.coverage > 0.999);
  assert.ok(draped.metresPerPixel > 6400 && draped.metresPerPixel < 6550, `${draped.metresPerPixel} m a pixel (1/15° at 29° N)`);
});

test('a .prj or .aux.xml beside the image gives its CRS; one that cannot be read is a note, not a refusal', async () => {
  const decodeBitmap = async () => ({ width: 256, height: 257, close() {} });
  const wgs84 = text('bmng_himalaya_4arcmin.prj', 'GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],' +
    'PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433],AUTHORITY["EPSG","4326"]]');
  const named = await openImage(file('bmng_himalaya_4arcmin.jpg'), sidecars(file('bmng_himalaya_4arcmin.jgw'), { prj: wgs84 }), himalaya, fakeGpu(), { decodeBitmap });
  assert.equal(named.note, null, 'in the terrain\'s CRS by its .prj: nothing assumed');
  // GDAL's record of the image: its SRS names the CRS, and its geotransform would place it (the world file wins).
  const aux = text('bmng_himalaya_4arcmin.jpg.aux.xml', '<PAMDataset><SRS dataAxisToSRSAxisMapping="2,1">' +
    'GEOGCS[&quot;WGS 84&quot;,DATUM[&quot;WGS_1984&quot;,SPHEROID[&quot;WGS 84&quot;,6378137,298.257223563]],PRIMEM[&quot;Greenwich&quot;,0],' +
    'UNIT[&quot;degree&quot;,0.0174532925199433],AUTHORITY[&quot;EPSG&quot;,&quot;4326&quot;]]</SRS>' +
    '<GeoTransform>0, 1, 0, 0, 0, -1</GeoTransform></PAMDataset>');
  const recorded = await openImage(file('bmng_himalaya_4arcmin.jpg'), sidecars(file('bmng_himalaya_4arcmin.jgw'), { auxXml: aux }), himalaya, fakeGpu(), { decodeBitmap });
  assert.equal(recorded.note, null);
  assert.ok(recorded.placement.coverage > 0.999, 'placed by the world file, not the .aux.xml\'s geotransform');
  // Without the world file, the .aux.xml's geotransform places it (here off the terrain: refused for that).
  await assert.rejects(openImage(file('bmng_himalaya_4arcmin.jpg'), sidecars(null, { auxXml: aux }), himalaya, fakeGpu(), { decodeBitmap }),
    (e) => e instanceof ImageError && /lies outside the terrain/.test(e.message));
  const garbage = text('bmng_himalaya_4arcmin.prj', 'PROJCS["My grid",GEOGCS["x"],PROJECTION["No_Such_Projection"]]');
  const noted = await openImage(file('bmng_himalaya_4arcmin.jpg'), sidecars(file('bmng_himalaya_4arcmin.jgw'), { prj: garbage }), himalaya, fakeGpu(), { decodeBitmap });
  assert.match(noted.note, /the image names no CRS: taken to be in EPSG:4326; bmng_himalaya_4arcmin\.prj: proj4 cannot read the CRS "My grid" in it .*; not used/);
});

test('refused images reserve nothing: off the field (in another CRS or its own), too big, broken, a lying header', async () => {
  const refused = async (image, world, field, gpu, problem, options) => {
    await assert.rejects(openImage(image, sidecars(world), field, gpu, options), (e) => e instanceof ImageError && problem.test(e.message));
    assert.ok(!gpu.calls.some((c) => c[0] === 'begin') || gpu.calls.at(-1)[0] === 'abort', `nothing left reserved: ${JSON.stringify(gpu.calls)}`);
  };
  await refused(file('haiti_rgb_5m_tiled_deflate.tif'), null, himalaya, fakeGpu(), /lies outside the terrain \(the image spans x 792988\.\.795563/);
  await refused(file('bmng_everest_4arcmin.jpg'), file('bmng_everest_4arcmin.jgw'), haitiField, fakeGpu(), /lies outside the terrain/,
    { decodeBitmap: async () => ({ width: 26, height: 26, close() {} }) });
  await refused(file('haiti_rgb_5m_tiled_deflate.tif'), null, haitiField, fakeGpu(), /more than the 0\.0 GB an image may take/, { budgetBytes: 1000 });
  await refused(text('broken.jpg', new Uint8Array([0xff, 0xd8, 0xff, 0xe0, 0, 16, 1, 2, 3])), null, himalaya, fakeGpu(), /^broken\.jpg: /);
  await refused(file('bmng_himalaya_4arcmin.jpg'), text('bmng_himalaya_4arcmin.jgw', '1\n0\n0\n-1\nx\n0\n'), himalaya, fakeGpu(),
    /^bmng_himalaya_4arcmin\.jgw: line 5: "x" is not a number/);
  await refused(file('bmng_himalaya_4arcmin.jpg'), file('bmng_himalaya_4arcmin.jgw'), himalaya, fakeGpu(), /its header says 256 × 257 but it decodes to 10 × 10/,
    { decodeBitmap: async () => ({ width: 10, height: 10, close() {} }) });
  await refused(file('bmng_himalaya_4arcmin.jpg'), null, himalaya, fakeGpu(), /the browser cannot decode it \(EncodingError: bad data\)/,
    { decodeBitmap: async () => { throw new Error('EncodingError: bad data'); } });
});
