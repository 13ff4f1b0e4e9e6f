// Overlays read and placed as a user's files are: GPX 1.1 and 1.0, KML, KMZ and GeoJSON made
// with GDAL from the real Everest DEM's coordinates (tests/fixtures/overlays/, scripts/
// make_overlay_fixtures.py), each fault with its message, and the placement on the UTM DEM
// against the pixels GDAL computed for the track's vertices.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { readOverlay } from '../../web/overlays/read_overlay.js';
import { placeOverlay } from '../../web/overlays/place_overlay.js';
import { OverlayError } from '../../web/overlays/overlay_error.js';
import { overlayKind } from '../../web/overlays/overlay_kind.js';
import { crsOfEpsg, makeGeoref, resolveGeoref } from '../../web/geo/index.js';
import { useNodeCrsDefinitions } from '../../lib/crs_definitions.js';
import { lissajousGpx } from '../../lib/track_files.js';

useNodeCrsDefinitions();
const dir = new URL('../fixtures/overlays/', import.meta.url);
const bytes = (name) => new Uint8Array(readFileSync(new URL(name, dir)));
const read = (name) => readOverlay(name, bytes(name));
const expected = JSON.parse(readFileSync(new URL('expected.json', dir), 'utf8'));
const gt = expected.dem.geotransform;
// The DEM's georeference as the loaders make it: the first sample's centre, 1000 m steps.
const demGeoref = () => resolveGeoref(makeGeoref(crsOfEpsg(32645), gt[0] + gt[1] / 2, gt[3] + gt[5] / 2, gt[1], gt[5], 'GeoTIFF'));
const DEM = { columns: expected.dem.width, rows: expected.dem.height, spacingX: 1000, spacingY: 1000 };
const summary = (overlay) => overlay.features.map((f) => `${f.kind}:${f.name}:${f.altitude}:${f.paths.length}`);

test('a GPX 1.1 track, route and waypoints: elevations and times on every track point', async () => {
  const o = await read('everest_trek.gpx');
  assert.equal(o.format, 'GPX');
  assert.equal(o.crs.epsg, 4326);
  assert.deepEqual(summary(o), ['line:Everest Base Camp trek:clamp:1', 'line:Kala Patthar:clamp:1', 'point:Lukla:clamp:1',
    'point:Namche Bazaar:clamp:1', 'point:Tengboche:clamp:1', 'point:Everest Base Camp:clamp:1']);
  const [track] = o.features[0].paths;
  assert.equal(track.x.length, expected.track.points);
  assert.equal(o.features[0].source, 'track');
  assert.equal(o.features[1].source, 'route');
  assert.equal(o.features[2].source, 'waypoint');
  assert.ok(track.z.every(Number.isFinite) && track.t.every(Number.isFinite));
  assert.equal(track.t[1] - track.t[0], 90000, 'a fix every 90 s');
  const v = expected.track.vertices[3];
  assert.equal(track.x[v.vertex], v.lon);
  assert.equal(track.y[v.vertex], v.lat);
  assert.equal(o.features[1].paths[0].z, null, 'a route without elevations has none');
});

test('GPX 1.0, KML, KMZ and GeoJSON: every geometry, names, properties and altitude modes', async () => {
  assert.deepEqual(summary(await read('gokyo_gpx10.gpx')), ['line:Gokyo approach:clamp:1']);
  const kml = await read('everest_places.kml');
  assert.deepEqual(summary(kml), ['point:Mount Everest:clamp:1', 'point:Lhotse:clamp:1', 'point:Makalu:clamp:1', 'point:Cho Oyu:clamp:1',
    'point:Ama Dablam:clamp:1', 'line:Khumbu valley trail:clamp:1', 'line:Flight to Everest:absolute:1', 'polygon:Base camp area:clamp:1',
    'point:Gokyo:clamp:1', 'line:Gokyo:clamp:1']);
  assert.equal(kml.features[0].paths[0].z[0], 8849);
  assert.equal(kml.features[6].paths[0].z[0], 9500, 'the absolute line keeps its altitudes');
  assert.deepEqual(kml.features[7].polygons, [[0]]);
  const kmz = await read('everest_places.kmz');
  assert.equal(kmz.format, 'KMZ');
  assert.deepEqual(summary(kmz), summary(kml));
  const geojson = await read('everest_features.geojson');
  assert.deepEqual(summary(geojson), ['point:Mount Everest:clamp:1', 'point:Lhotse and Makalu:clamp:1', 'line:Lukla to Tengboche:clamp:1',
    'line:two paths:clamp:2', 'polygon:Sagarmatha core:clamp:2', 'polygon:two fields:clamp:2', 'point:Ama Dablam:clamp:1', 'line:Ama Dablam:clamp:1']);
  assert.equal(geojson.features[0].properties.first_ascent, 1953);
  assert.equal(geojson.features[1].paths[0].x.length, 2, 'a MultiPoint is one path of two points');
  assert.deepEqual(geojson.features[4].polygons, [[0, 1]], 'a polygon with a hole: outer ring, then the hole');
  assert.deepEqual(geojson.features[5].polygons, [[0], [1]]);
});

test('a GeoJSON with a legacy crs member is read in that CRS, and says so', async () => {
  const o = await read('legacy_crs_utm45.geojson');
  assert.equal(o.crs.epsg, 32645);
  assert.ok(o.crs.proj4);
  assert.deepEqual(o.notes, ['its legacy "crs" member (EPSG:32645) was honoured']);
  // Placed on the UTM DEM it lands where its WGS 84 twin does (GDAL's lon/lat of its first point).
  const georef = await demGeoref();
  const placed = placeOverlay(o, georef, DEM);
  const first = expected.track.vertices[0];
  assert.ok(Math.abs(placed.features[0].paths[0].x[0] - first.column * 1000) < 60, 'Lukla, as the track starts');
  assert.ok(Math.abs(placed.features[0].paths[0].z[0] - first.row * 1000) < 60);
});

test('every fault is refused with a message that says what is wrong', async () => {
  const refused = async (name, pattern, data = bytes(name)) => {
    await assert.rejects(readOverlay(name, data), (error) => error instanceof OverlayError && pattern.test(error.message), name);
  };
  await refused('bad_empty.gpx', /the file is empty/);
  await refused('bad_malformed.gpx', /^malformed XML: the document ends with <gpx>, <trk>, <trkseg>.* still open \(a file cut short\?\)$/);
  await refused('bad_malformed.geojson', /^malformed JSON at line 1: /);
  await refused('bad_no_kml.kmz', /a KMZ without a KML document inside \(it holds readme\.txt, images\/icon\.png\)/);
  await refused('bad_projected.geojson', /coordinates \(473514\.5, 3062515\.08\) are not WGS 84 longitude and latitude.*RFC 7946/);
  const text = (s) => new TextEncoder().encode(s);
  await refused('x.gpx', /^malformed XML at line 2, column \d+: Expected closing tag 'a'/, text('<gpx>\n<a></gpx>'));
  await refused('x.geojson', /not GeoJSON/, text('[1, 2]'));
  await refused('x.gpx', /^track 1, segment 1: <trkpt> 2 has lon="east", not a number$/,
    text('<gpx><trk><trkseg><trkpt lat="1" lon="2"/><trkpt lat="1" lon="east"/></trkseg></trk></gpx>'));
  await refused('x.kml', /^placemark 1 \("P"\): coordinate 2 "86\.95,north" is not longitude,latitude\[,altitude\] numbers$/,
    text('<kml><Placemark><name>P</name><LineString><coordinates>86.9,27.9 86.95,north</coordinates></LineString></Placemark></kml>'));
  await refused('x.geojson', /legacy "crs" member names EPSG:999999, which has no definition/,
    text('{"type":"Feature","crs":{"type":"name","properties":{"name":"EPSG:999999"}},"properties":{},"geometry":{"type":"Point","coordinates":[1,2]}}'));
  await refused('x.geojson', /position 2 is not a pair of numbers/, text('{"type":"LineString","coordinates":[[1,2],["a",3]]}'));
  await refused('x.geojson', /unknown geometry type "Circle"/, text('{"type":"Feature","properties":{},"geometry":{"type":"Circle","coordinates":[1,2]}}'));
  await refused('x.gpx', /not a GPX document: its root element is <kml>/, text('<kml><Document/></kml>'));
  await refused('x.kml', /no features with a geometry/, text('<kml xmlns="http://www.opengis.net/kml/2.2"><Document><Placemark><name>a</name></Placemark></Document></kml>'));
  await refused('x.kmz', /not a readable KMZ/, text('PK\u0003\u0004 broken'));
  await refused('notes.txt', /not an overlay/, text('hello'));
});

test('placed on the UTM DEM, the track\'s vertices land on the pixels GDAL computed', async () => {
  const o = await read('everest_trek.gpx');
  const placed = placeOverlay(o, await demGeoref(), DEM);
  assert.equal(placed.offTerrain, 0);
  const path = placed.features[0].paths[0];
  for (const v of expected.track.vertices) {
    // 7 decimals of a degree in the file are 1 cm; the rest is proj4 against PROJ.
    assert.ok(Math.abs(path.x[v.vertex] - v.column * 1000) < 0.05, `vertex ${v.vertex} x ${path.x[v.vertex]} vs ${v.column * 1000}`);
    assert.ok(Math.abs(path.z[v.vertex] - v.row * 1000) < 0.05, `vertex ${v.vertex} z`);
    assert.equal(path.inside[v.vertex], 1);
  }
  // On the default terrain (EPSG:4326 itself) nothing is reprojected: lon/lat to samples directly.
  const geographic = await resolveGeoref(makeGeoref(crsOfEpsg(4326, true), 72.9375, 37.9125, 0.0125, -0.0125, 'json'));
  const direct = placeOverlay(o, geographic, { columns: 2048, rows: 2048, spacingX: 1000, spacingY: 1000 }).features[0].paths[0];
  assert.ok(Math.abs(direct.x[0] - ((o.features[0].paths[0].x[0] - 72.9375) / 0.0125) * 1000) < 1e-6);
});

test('a track entirely off the terrain is counted, not refused; a terrain without georeference is', async () => {
  const georef = await demGeoref();
  const alps = placeOverlay(await read('off_terrain_alps.gpx'), georef, DEM);
  assert.equal(alps.offTerrain, 1);
  assert.equal(alps.features[0].onTerrain, 'none');
  const geojson = placeOverlay(await read('everest_features.geojson'), georef, DEM);
  assert.equal(geojson.offTerrain, 0);
  assert.throws(() => placeOverlay(alps.overlay, null, DEM), (e) => e instanceof OverlayError && /has no georeference/.test(e.message));
});

test('a GPX point without a time keeps the others\' times on their own points', async () => {
  const o = await readOverlay('t.gpx', new TextEncoder().encode('<gpx><trk><trkseg><trkpt lat="1" lon="2"/>' +
    '<trkpt lat="1.1" lon="2"><time>2020-01-01T00:01:00Z</time></trkpt><trkpt lat="1.2" lon="2"><time>2020-01-01T00:02:00Z</time></trkpt></trkseg></trk></gpx>'));
  const { t } = o.features[0].paths[0];
  assert.ok(Number.isNaN(t[0]));
  assert.deepEqual([t[1], t[2]], [Date.UTC(2020, 0, 1, 0, 1), Date.UTC(2020, 0, 1, 0, 2)]);
});

test('files are told apart from height fields by name and first bytes', () => {
  const text = (s) => new TextEncoder().encode(s);
  assert.equal(overlayKind('a.GPX', text('')), 'gpx');
  assert.equal(overlayKind('a.kmz', text('PK')), 'kmz');
  assert.equal(overlayKind('trails.json', text('{ "type": "FeatureCollection", "features": [] }')), 'geojson');
  assert.equal(overlayKind('dem.json', text('{ "width": 512, "height": 512 }')), null, "a height field's sidecar");
  assert.equal(overlayKind('dem.tif', text('II*')), null);
});

test('a 500 000-point GPX is read whole, every point kept', async () => {
  const big = new TextEncoder().encode(lissajousGpx(500000, { west: 86.5, east: 87.5, south: 27.5, north: 28.5 }));
  const o = await readOverlay('big.gpx', big);
  const [path] = o.features[0].paths;
  assert.equal(path.x.length, 500000);
  assert.ok(path.t.every(Number.isFinite) && path.z.every(Number.isFinite));
  const placed = placeOverlay(o, await demGeoref(), DEM);
  assert.equal(placed.features[0].onTerrain, 'all');
});
