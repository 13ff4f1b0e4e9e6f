// WMTS capabilities (web/webtiles/wmts_capabilities.js): the layers of the fixture document that
// are the XYZ pyramid become tile templates whose addresses fetch the right tiles from the test
// server (lib/tile_server.js), by REST and by KVP; the others are named with the reason; a
// document that is not one, or offers nothing usable, gets one message.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { parseWmtsCapabilities, readWmtsCapabilities, capabilitiesUrl } from '../../web/webtiles/wmts_capabilities.js';
import { tileUrl, parseTileSpec, formatTileSpec, TileSpecError } from '../../web/webtiles/tile_template.js';
import { startTileServer } from '../../lib/tile_server.js';

const fixtures = fileURLToPath(new URL('../fixtures/webtiles/', import.meta.url));
const xml = readFileSync(`${fixtures}wmts_capabilities.xml`, 'utf8');
const DOCUMENT = 'http://tiles.example.test/wmts?SERVICE=WMTS&REQUEST=GetCapabilities';
let server;

before(async () => { server = await startTileServer(`${fixtures}bmng`, { capabilities: `${fixtures}wmts_capabilities.xml` }); });
after(() => server.close());

test('the Web Mercator layers of the fixture, by REST and by KVP, with their zooms', () => {
  const service = parseWmtsCapabilities(xml, DOCUMENT);
  assert.equal(service.title, 'hexlod test tiles');
  assert.deepEqual(service.layers.map((l) => [l.identifier, l.encoding, l.tileMatrixSet, l.format, l.tileSize, l.spec.minZoom, l.spec.maxZoom]), [
    ['bmng', 'REST', 'GoogleMapsCompatible', 'image/png', 256, 3, 7],
    ['bmng kvp', 'KVP', 'EPSG:900913', 'image/png', 256, 3, 6],
  ]);
  const [rest, kvp] = service.layers;
  assert.deepEqual(rest.bounds, [72.9333, 20.8, 90, 37.9333]);
  assert.equal(tileUrl(rest.spec, 5, 23, 13), 'http://tiles.example.test/wmts/bmng/default/2004-08/GoogleMapsCompatible/5/13/23.png');
  assert.equal(tileUrl(kvp.spec, 5, 23, 13), 'http://tiles.example.test/wmts?SERVICE=WMTS&REQUEST=GetTile&VERSION=1.0.0' +
    '&LAYER=bmng%20kvp&STYLE=default&TILEMATRIXSET=EPSG%3A900913&FORMAT=image%2Fpng&TILEMATRIX=EPSG%3A900913%3A5&TILEROW=13&TILECOL=23');
  // The page's address carries a layer as its spec.
  for (const layer of service.layers) assert.deepEqual(parseTileSpec(formatTileSpec(layer.spec)), layer.spec);
  assert.deepEqual(service.skipped, [
    { identifier: 'bmng_geographic', reason: 'its tile matrix set WorldCRS84Quad is in urn:ogc:def:crs:OGC:1.3:CRS84, not Web Mercator' },
    { identifier: 'nepal_local', reason: "its tile matrix 0 of NepalGrid is not a zoom of the XYZ pyramid (the world's corner at the top left, 2^z × 2^z tiles)" },
  ]);
});

test('matrices that are not named by their zoom are listed by zoom', () => {
  const names = { 3: 'c', 4: 'd', 5: 'e', 6: 'f' };
  const odd = xml.replace(/<ows:Identifier>EPSG:900913:(\d)</g, (_, z) => `<ows:Identifier>${names[z]}<`);
  const kvp = parseWmtsCapabilities(odd, DOCUMENT).layers[1].spec;
  assert.deepEqual(kvp.matrices, ['', '', '', 'c', 'd', 'e', 'f']);
  assert.match(tileUrl(kvp, 4, 11, 6), /TILEMATRIX=d&TILEROW=6&TILECOL=11$/);
  assert.deepEqual(parseTileSpec(formatTileSpec(kvp)), kvp);
});

test('the templates fetch the tiles of the fixture from the server, by REST and by KVP', async () => {
  const service = await readWmtsCapabilities(`${server.url}/wmts`);
  const expected = readFileSync(`${fixtures}bmng/5/23/13.png`);
  for (const layer of service.layers) {
    const url = tileUrl(layer.spec, 5, 23, 13);
    assert.ok(url.startsWith(server.url), url);
    const response = await fetch(url);
    assert.equal(response.status, 200, url);
    assert.deepEqual(Buffer.from(await response.arrayBuffer()), expected, url);
  }
  assert.deepEqual(server.tilesRequested(), ['5/23/13', '5/23/13']);
});

test('capabilitiesUrl asks a bare endpoint for its capabilities and keeps an address that names them', () => {
  assert.equal(capabilitiesUrl('https://example.org/wmts'), 'https://example.org/wmts?SERVICE=WMTS&REQUEST=GetCapabilities');
  assert.equal(capabilitiesUrl('https://example.org/wmts?key=1'), 'https://example.org/wmts?key=1&SERVICE=WMTS&REQUEST=GetCapabilities');
  assert.equal(capabilitiesUrl('https://example.org/1.0.0/WMTSCapabilities.xml'), 'https://example.org/1.0.0/WMTSCapabilities.xml');
  assert.equal(capabilitiesUrl('https://example.org/w?request=GetCapabilities'), 'https://example.org/w?request=GetCapabilities');
});

test('what is not a usable capabilities document gets one message', async () => {
  const cases = [
    ['<Capabilities><Contents><Layer>', /are not XML/],
    ['<?xml version="1.0"?><html><body>Sign in</body></html>', /is not a WMTS capabilities document \(no <Capabilities> element\)/],
    ['<ows:ExceptionReport xmlns:ows="http://www.opengis.net/ows/1.1"><ows:Exception exceptionCode="InvalidParameterValue">' +
      '<ows:ExceptionText>Unknown layer</ows:ExceptionText></ows:Exception></ows:ExceptionReport>', /answered with an exception: Unknown layer/],
    [xml.replace(/<Layer>[\s\S]*<!-- Only in geographic/, '<!-- Only in geographic'),
      /no layer of the WMTS service at .* is in Web Mercator \(EPSG:3857, GoogleMapsCompatible\) \(bmng_geographic: its tile matrix set WorldCRS84Quad/],
  ];
  for (const [text, message] of cases) {
    assert.throws(() => parseWmtsCapabilities(text, DOCUMENT), (e) => e instanceof TileSpecError && message.test(e.message), String(message));
  }
  await assert.rejects(readWmtsCapabilities(`${server.url}/nothing.xml`), /HTTP 404 for the WMTS capabilities at http:\/\/127\.0\.0\.1:\d+\/nothing\.xml/);
  await assert.rejects(readWmtsCapabilities('not an address'), /'not an address' is not an address of a WMTS service/);
});
