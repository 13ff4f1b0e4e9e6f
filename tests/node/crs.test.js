// Any EPSG CRS (web/geo/crs_definitions.js with lib/crs_definitions.js), transforms between CRSs
// (crs_transform.js) and CRSs written as WKT (crs_wkt.js), against GDAL: the latitudes and
// longitudes of tests/fixtures/crs/lonlat_gdal.json are gdaltransform's (GDAL 3.6.2, PROJ
// 9.1.1), made by scripts/make_crs_fixtures.js; the .prj files are gdalsrsinfo's.
//
// Tolerance: 1e-7 degrees (about a centimetre). Each point was transformed twice by GDAL: with
// the PROJ string our definitions give (the same datum shift: proj4 and PROJ do the same sums,
// and agree to 1e-8 degrees or better), and by its EPSG code (the transformation PROJ picks from
// its database). On the machine that made the fixtures PROJ had none of the grids these CRSs'
// best transformations use (OSTN15 for 27700, RDNAPTRANS for 28992), so it picked the same
// 7-parameter shifts our definitions carry and both agree to 1e-7 too. Where PROJ has such a
// grid, its answer moves by up to about 2 m (2e-5 degrees) from any 7-parameter shift: the
// fixtures would then have to be compared at that tolerance.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { crsOfEpsg, resolveCrs, setCrsSource, crsTransform, toLonLat, sameCrs, crsFromWkt, CrsError, parseAuxXml,
  UNKNOWN_CRS } from '../../web/geo/index.js';
import { useNodeCrsDefinitions, crsDefinition } from '../../lib/crs_definitions.js';

const FIXTURES = new URL('../fixtures/crs/', import.meta.url);
const fixture = (name) => readFileSync(new URL(name, FIXTURES), 'utf8');
const GDAL = JSON.parse(fixture('lonlat_gdal.json'));
const DEG = 1e-7;
const near = (a, b, eps, what) => assert.ok(Math.abs(a - b) <= eps, `${what}: ${a} vs ${b} (${Math.abs(a - b).toExponential(2)} > ${eps})`);

useNodeCrsDefinitions();

test('national grids, UTM and Web Mercator: GDAL\'s latitudes and longitudes, datum shifts applied', async () => {
  assert.deepEqual(Object.keys(GDAL.crs).map(Number).sort((a, b) => a - b), [2056, 2193, 3035, 3857, 5070, 27700, 28992, 32633]);
  for (const [code, { name, points }] of Object.entries(GDAL.crs)) {
    const crs = await resolveCrs(crsOfEpsg(Number(code)));
    assert.equal(crs.name, name, code);
    assert.equal(crs.geographic, false, `${code} is projected`);
    const lonLat = toLonLat(crs);
    for (const { x, y, epsg, sameShift } of points) {
      const [lon, lat] = lonLat(x, y);
      near(lon, sameShift[0], DEG, `EPSG:${code} (${x}, ${y}) lon, PROJ on the same string`);
      near(lat, sameShift[1], DEG, `EPSG:${code} (${x}, ${y}) lat, PROJ on the same string`);
      near(lon, epsg[0], DEG, `EPSG:${code} (${x}, ${y}) lon, PROJ by the code`);
      near(lat, epsg[1], DEG, `EPSG:${code} (${x}, ${y}) lat, PROJ by the code`);
    }
  }
  // The shifts are real: without them the Swiss and Dutch grids' latitudes are ~100 m off.
  const bare = { epsg: null, label: 'x', name: null, geographic: false,
    proj4: (await resolveCrs(crsOfEpsg(28992))).proj4.replace(/\+towgs84=\S+/, '') };
  const { x, y, epsg } = GDAL.crs[28992].points[0];
  assert.ok(Math.abs(toLonLat(bare)(x, y)[1] - epsg[1]) > 5e-4, 'Amersfoort on its Bessel ellipsoid alone is far from WGS 84');
});

test('the definitions: a datum shift where the EPSG has one, grids we do not ship left out, no definition for heights', () => {
  assert.match(crsDefinition(2056).proj4, /\+towgs84=674\.374,15\.056,405\.346/);
  assert.match(crsDefinition(27700).proj4, /\+datum=OSGB36/, 'proj4 shifts OSGB36 by its 7 parameters');
  assert.doesNotMatch(crsDefinition(27700).proj4, /nadgrids/);
  assert.match(crsDefinition(28992).proj4, /\+towgs84=565\.4171,50\.3319,465\.5524,-0\.398957,0\.343988,-1\.8774/);
  const nad27 = crsDefinition(6201); // epsg-index names an NTv2 grid for it; proj4 would give NaN
  assert.equal(nad27.name, 'NAD27 / Michigan Central');
  assert.doesNotMatch(nad27.proj4, /nadgrids/);
  assert.deepEqual([crsDefinition(3855).name, crsDefinition(3855).proj4], ['EGM2008 height', null], 'a vertical CRS has a name only');
  assert.equal(crsDefinition(3785).name, null, 'a code only proj4-list knows has a definition without a name');
  assert.match(crsDefinition(3785).proj4, /\+proj=merc/);
  assert.equal(crsDefinition(999999), null);
  assert.equal(crsDefinition(-5), null);
});

test('resolveCrs: geographic from the definition, each code asked once, what the file said without a definition', async () => {
  const asked = [];
  setCrsSource(async (code) => { asked.push(code); return crsDefinition(code); });
  try {
    const [wgs84, etrs89, lv95, again] = await Promise.all([4326, 4258, 2056, 2056].map((code) => resolveCrs(crsOfEpsg(code))));
    assert.deepEqual([wgs84.geographic, etrs89.geographic, lv95.geographic], [true, true, false]);
    assert.deepEqual([etrs89.name, lv95.label], ['ETRS89', 'EPSG:2056']);
    assert.deepEqual(again, lv95);
    assert.deepEqual(asked, [4326, 4258, 2056], 'cached per code');
    // A code nobody knows keeps what the file said; so does a CRS without a code or definition.
    assert.deepEqual(await resolveCrs(crsOfEpsg(999999, true)), { ...crsOfEpsg(999999, true) });
    assert.deepEqual(await resolveCrs(UNKNOWN_CRS), { ...UNKNOWN_CRS });
    // A failed lookup (a network error in the page) gives no definition now and is asked again later.
    let fail = true;
    setCrsSource(async (code) => { if (fail) throw new Error('offline'); return crsDefinition(code); });
    assert.equal((await resolveCrs(crsOfEpsg(3035))).proj4, null);
    fail = false;
    assert.match((await resolveCrs(crsOfEpsg(3035))).proj4, /\+proj=laea/);
    // Without a source, the file's word stands: an SRTM tile's degrees stay degrees.
    setCrsSource(null);
    assert.deepEqual(await resolveCrs(crsOfEpsg(4326, true)), crsOfEpsg(4326, true));
  } finally {
    useNodeCrsDefinitions();
  }
});

test('crsTransform: identity for one CRS, through both definitions otherwise, null without one', async () => {
  const [lv95, lv03, wgs84, mercator] = await Promise.all([2056, 21781, 4326, 3857].map((code) => resolveCrs(crsOfEpsg(code))));
  assert.deepEqual(crsTransform(lv95, lv95)(2600000.5, 1200000.25), [2600000.5, 1200000.25]);
  assert.deepEqual(crsTransform(crsOfEpsg(123456), crsOfEpsg(123456))(1, 2), [1, 2], 'one code needs no definition to be itself');
  // LV95 is LV03 moved by 2 000 km east and 1 000 km north, but for the old network's local
  // distortions (up to about 1.6 m, a grid we do not ship): both go through WGS 84 here.
  const [x, y] = crsTransform(lv95, lv03)(2683000, 1248000);
  near(x, 683000, 2, 'LV03 easting'), near(y, 248000, 2, 'LV03 northing');
  const [lon, lat] = crsTransform(lv95, wgs84)(2600000, 1200000);
  near(lon, GDAL.crs[2056].points[0].epsg[0], DEG, 'lon'), near(lat, GDAL.crs[2056].points[0].epsg[1], DEG, 'lat');
  const [mx, my] = crsTransform(wgs84, mercator)(180, 0);
  near(mx, 20037508.342789244, 1e-6, 'Web Mercator x of 180° E'), near(my, 0, 1e-6, 'y of the equator');
  assert.equal(crsTransform(lv95, UNKNOWN_CRS), null);
  assert.equal(crsTransform(crsOfEpsg(2056), wgs84), null, 'not resolved: no definition yet');
  assert.equal(toLonLat(UNKNOWN_CRS), null);
  assert.ok(sameCrs(lv95, crsOfEpsg(2056)) && !sameCrs(lv95, lv03));
});

test('.prj: OGC WKT1 and WKT2 name their EPSG code; ESRI WKT is a custom CRS of its own WKT', async () => {
  for (const [code, name] of [[2056, 'CH1903+ / LV95'], [27700, 'OSGB36 / British National Grid'], [28992, 'Amersfoort / RD New']]) {
    for (const flavour of ['wkt1', 'wkt2']) {
      const crs = crsFromWkt(fixture(`prj/epsg${code}_${flavour}.prj`), `epsg${code}_${flavour}.prj`);
      assert.deepEqual([crs.epsg, crs.label, crs.name, crs.geographic], [code, `EPSG:${code}`, name, false], `${code} ${flavour}`);
      // Resolved, it takes the EPSG definitions' datum shift: GDAL's latitude and longitude.
      const { x, y, epsg } = GDAL.crs[code].points[0];
      const [lon, lat] = toLonLat(await resolveCrs(crs))(x, y);
      near(lon, epsg[0], DEG, `${code} ${flavour} lon`), near(lat, epsg[1], DEG, `${code} ${flavour} lat`);
    }
  }
  // ESRI's WKT has no code and no TOWGS84: proj4 knows the CH1903+ and OSGB36 datums by their
  // names and shifts them (within 1e-6 degrees of GDAL: rounded parameters), but not
  // Amersfoort, which stays on its ellipsoid, about 50 m off. That is what such a .prj says.
  for (const [code, esriName, tolerance] of [[2056, 'CH1903+_LV95', 1e-6], [27700, 'British_National_Grid', 1e-6], [28992, 'RD_New', 1e-3]]) {
    const crs = await resolveCrs(crsFromWkt(fixture(`prj/epsg${code}_esri.prj`), 'x.prj'));
    assert.deepEqual([crs.epsg, crs.label, crs.name], [null, `custom (${esriName} from the WKT)`, esriName]);
    assert.equal(crs.proj4, fixture(`prj/epsg${code}_esri.prj`).trim(), 'defined by its own WKT');
    const { x, y, epsg } = GDAL.crs[code].points[0];
    const [lon, lat] = toLonLat(crs)(x, y);
    near(lon, epsg[0], tolerance, `${esriName} lon`), near(lat, epsg[1], tolerance, `${esriName} lat`);
  }
  const amersfoort = await resolveCrs(crsFromWkt(fixture('prj/epsg28992_esri.prj'), 'x.prj'));
  const { x, y, epsg } = GDAL.crs[28992].points[0];
  assert.ok(Math.abs(toLonLat(amersfoort)(x, y)[0] - epsg[0]) > 1e-4, 'no shift from an ESRI .prj of Amersfoort');
});

test('WKT: the code must stand at the top level; compound CRSs give their horizontal part; geographic ones are geographic', () => {
  const wkt2 = fixture('prj/epsg2056_wkt2.prj');
  const withoutId = wkt2.trim().replace(/,\s*ID\["EPSG",2056\]\]$/, ']');
  assert.notEqual(withoutId, wkt2.trim());
  const custom = crsFromWkt(withoutId, 'lv95.prj');
  assert.deepEqual([custom.epsg, custom.label], [null, 'custom (CH1903+ / LV95 from the WKT)'], 'its base CRS\'s ID[4150] is not its code');
  const compound = `COMPD_CS["CH1903+ / LV95 + LN02 height",${fixture('prj/epsg2056_wkt1.prj').trim()},VERT_CS["LN02 height",VERT_DATUM["Landesnivellement 1902",2005],UNIT["metre",1],AXIS["Gravity-related height",UP]]]`;
  assert.equal(crsFromWkt(compound, 'c.prj').epsg, 2056);
  const wgs84 = crsFromWkt('GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433],AUTHORITY["EPSG","4326"]]', 'g.prj');
  assert.deepEqual([wgs84.epsg, wgs84.geographic], [4326, true]);
  const esriGeographic = crsFromWkt('GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]]', 'e.prj');
  assert.deepEqual([esriGeographic.epsg, esriGeographic.geographic, esriGeographic.label], [null, true, 'custom (GCS_WGS_1984 from the WKT)']);
  assert.equal(crsFromWkt('\uFEFFEPSG:3035\n', 'code.prj').epsg, 3035, 'a code alone, as some tools write it');
});

test('a .prj that is not a CRS, or one proj4 cannot read, is an error naming the file and the CRS', () => {
  const refused = (text, name, problem) => assert.throws(() => crsFromWkt(text, name),
    (e) => e instanceof CrsError && e.message.startsWith(`${name}: `) && problem.test(e.message), `${name}: ${problem}`);
  refused('PROJCS["Lambert Azimuthal of my own",GEOGCS["GCS_Mine",DATUM["D_Mine",SPHEROID["Mine",6378000,300]],PRIMEM["Greenwich",0],' +
    'UNIT["Degree",0.0174532925199433]],PROJECTION["Space_Oblique_Mercator"],UNIT["Meter",1]]', 'site.prj',
  /proj4 cannot read the CRS "Lambert Azimuthal of my own" in it \(PROJCS\[\.\.\.\] without an EPSG code\)/);
  refused('', 'empty.prj', /empty, where a CRS in WKT was expected/);
  refused('Projection    UTM\nZone          32\nDatum         WGS84\n', 'arcinfo.prj', /not a CRS in WKT \(it starts with "Projection/);
  refused('<html>not found</html>', 'page.prj', /not a CRS in WKT/);
});

test('.aux.xml: GDAL\'s SRS gives the CRS and its GeoTransform the sample centres; broken ones are errors naming the file', async () => {
  const aux = await parseAuxXml(fixture('jacksboro_5070_png.png.aux.xml'), 'jacksboro_5070_png.png.aux.xml');
  assert.deepEqual([aux.crs.epsg, aux.crs.name], [5070, 'NAD83 / Conus Albers']);
  const { x, y } = JSON.parse(fixture('expected.json')).dems['jacksboro_5070_png.png'].samples[0];
  assert.deepEqual([aux.georef.x0, aux.georef.y0, aux.georef.dx, aux.georef.dy, aux.georef.from, aux.georef.crs.epsg], [x, y, 100, -100, '.aux.xml', 5070]);
  const srsOnly = await parseAuxXml('<PAMDataset><SRS>EPSG:4326</SRS><Metadata><MDI key="a">b</MDI></Metadata></PAMDataset>', 's.aux.xml');
  assert.deepEqual([srsOnly.crs.epsg, srsOnly.georef], [4326, null]);
  const refused = async (text, problem) => assert.rejects(parseAuxXml(text, 'x.tif.aux.xml'),
    (e) => e instanceof CrsError && e.message.startsWith('x.tif.aux.xml: ') && problem.test(e.message), String(problem));
  await refused('<PAMDataset><SRS>PROJCS[</PAMDataset>', /not XML/);
  await refused('<Other/>', /not a GDAL \.aux\.xml \(no <PAMDataset>\)/);
  await refused('<PAMDataset><GeoTransform>1, 2, 3</GeoTransform></PAMDataset>', /<GeoTransform> is not six numbers/);
  await refused('<PAMDataset><GeoTransform>0, 1, 0.5, 0, 0, -1</GeoTransform></PAMDataset>', /is rotated/);
  await refused('<PAMDataset><SRS>PROJCS["Mine",PROJECTION["Nope"]]</SRS></PAMDataset>', /proj4 cannot read the CRS "Mine"/);
});
