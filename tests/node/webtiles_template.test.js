// Tile layer templates as people paste them (web/webtiles/tile_template.js): the addresses of
// tiles, the options of the page's `tiles=` value, and one clear message for each mistake.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseTileSpec, parseTemplate, tileUrl, formatTileSpec, layerHost, TileSpecError } from '../../web/webtiles/tile_template.js';

test('an XYZ template gives the address of each tile, the same subdomain for the same tile', () => {
  const layer = parseTemplate('https://{s}.tile.example.org/{z}/{x}/{y}.png');
  assert.deepEqual([layer.minZoom, layer.maxZoom, layer.subdomains, layer.attribution], [0, 19, ['a', 'b', 'c'], '']);
  assert.equal(tileUrl(layer, 7, 98, 55), 'https://a.tile.example.org/7/98/55.png'); // (98 + 55) % 3 = 0
  assert.equal(tileUrl(layer, 7, 99, 55), 'https://b.tile.example.org/7/99/55.png');
  assert.equal(tileUrl(layer, 7, 99, 55), tileUrl(layer, 7, 99, 55));
  assert.equal(layerHost(layer), '{s}.tile.example.org');
});

test('{-y} counts rows from the south (TMS), {r} is empty, WMTS names stand for z, x, y', () => {
  assert.equal(tileUrl(parseTemplate('http://tms.example.org/1.0.0/map/{z}/{x}/{-y}.jpg'), 3, 5, 1), 'http://tms.example.org/1.0.0/map/3/5/6.jpg');
  assert.equal(tileUrl(parseTemplate('https://example.org/{z}/{x}/{y}{r}.png'), 2, 1, 3), 'https://example.org/2/1/3.png');
  assert.equal(tileUrl(parseTemplate('https://example.org/wmts/{TileMatrix}/{TileRow}/{TileCol}.png'), 5, 23, 13),
    'https://example.org/wmts/5/13/23.png');
});

test('options after the template: zooms, subdomains, attribution with escapes, matrices', () => {
  const layer = parseTileSpec('https://{s}.example.org/{z}/{x}/{y}.png|zoom=3-7|subdomains=otile1,otile2|attribution=© Example %7C NASA');
  assert.deepEqual([layer.minZoom, layer.maxZoom], [3, 7]);
  assert.deepEqual(layer.subdomains, ['otile1', 'otile2']);
  assert.equal(layer.attribution, '© Example | NASA');
  assert.equal(tileUrl(layer, 4, 1, 0), 'https://otile2.example.org/4/1/0.png');
  assert.deepEqual(parseTileSpec('https://{s}.example.org/{z}/{x}/{y}.png|subdomains=1234').subdomains, ['1', '2', '3', '4']);
  assert.deepEqual([parseTileSpec('https://example.org/{z}/{x}/{y}.png|zoom=5').minZoom, parseTileSpec('https://example.org/{z}/{x}/{y}.png|zoom=5').maxZoom], [5, 5]);
  const wmts = parseTileSpec('https://example.org/w/{z}/{y}/{x}.png|zoom=0-2|matrices=a:0,a%2C1,a:2');
  assert.equal(tileUrl(wmts, 1, 0, 0), 'https://example.org/w/a,1/0/0.png');
});

test('formatTileSpec gives back what parseTileSpec reads', () => {
  for (const text of [
    'https://{s}.tile.example.org/{z}/{x}/{y}.png',
    'https://{s}.example.org/{z}/{x}/{-y}.png|zoom=2-12|subdomains=xyz|attribution=© 100%25 Example %7C NASA',
    'https://example.org/w/{z}/{y}/{x}.png|zoom=0-1|subdomains=s1,s2|matrices=m%7C0,m%2C1',
  ]) {
    const layer = parseTileSpec(text);
    assert.deepEqual(parseTileSpec(formatTileSpec(layer)), layer, text);
  }
  assert.equal(formatTileSpec(parseTileSpec('https://a.org/{z}/{x}/{y}.png|zoom=0-19|subdomains=abc')), 'https://a.org/{z}/{x}/{y}.png');
});

test('every mistake gets one message that says what is wrong', () => {
  const cases = [
    ['', /the tile template is empty/],
    ['   ', /the tile template is empty/],
    ['ftp://example.org/{z}/{x}/{y}.png', /must be an http:\/\/ or https:\/\/ address, not 'ftp:\/\/example\.org/],
    ['example.org/{z}/{x}/{y}.png', /must be an http:\/\/ or https:\/\/ address/],
    ['https://example.org/{x}/{y}.png', /has no \{z\} \(the zoom\)/],
    ['https://example.org/{z}/{y}.png', /has no \{x\} \(the column\)/],
    ['https://example.org/{z}/{x}.png', /has no \{y\} or \{-y\} \(the row\)/],
    ['https://example.org/{z}/{x}/{y}/{q}.png', /unknown placeholder \{q\} in the tile template \(known: \{z\} \{x\} \{y\} \{-y\} \{s\} \{r\}\)/],
    ['https://example.org/{Z}/{x}/{y}.png', /unknown placeholder \{Z\}/],
    ['https://example.org/{Style}/{z}/{x}/{y}.png', /unknown placeholder \{Style\}/],
    ['https://example.org/{z}/{x}/{y}.png|maxzoom=3', /unknown tile layer option 'maxzoom' after the template \(known: zoom, subdomains, attribution, matrices\)/],
    ['https://example.org/{z}/{x}/{y}.png|zoom=7-3', /zoom must be MIN-MAX with whole numbers 0 <= MIN <= MAX <= 24, not '7-3'/],
    ['https://example.org/{z}/{x}/{y}.png|zoom=0-30', /not '0-30'/],
    ['https://example.org/{z}/{x}/{y}.png|zoom=a', /not 'a'/],
    ['https://example.org/{z}/{x}/{y}.png|subdomains=', /subdomains must be letters or names separated by commas, not ''/],
    ['https://example.org/{z}/{x}/{y}.png|subdomains=a,,b', /not 'a,,b'/],
    ['https://example.org/{z}/{x}/{y}.png|zoom=0-3|matrices=a,b', /matrices= names 2 TileMatrix identifiers, one for each zoom 0\.\.3 is needed/],
  ];
  for (const [text, message] of cases) {
    assert.throws(() => parseTileSpec(text), (error) => error instanceof TileSpecError && message.test(error.message), text);
  }
});
