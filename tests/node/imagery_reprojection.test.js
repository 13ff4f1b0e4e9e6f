// An image in another CRS than the terrain is reprojected onto it (web/imagery/placement.js):
// every sample of a real UTM DEM lands within one texel of where gdalwarp puts it, for the
// Blue Marble image in EPSG:4326 and in Web Mercator (EPSG:3857), through the exact map and
// through the control grid the shader interpolates. The expected positions are GDAL's own
// (scripts/make_reprojection_fixtures.py numbers each image pixel and warps the numbers with
// nearest-neighbour onto the DEM's grid).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { gunzipSync } from 'node:zlib';
import { placeImage, WARP_TOLERANCE_PX } from '../../web/imagery/placement.js';
import { crsOfEpsg, makeGeoref, parseEpsg, interpolate, resolveGeoref } from '../../web/geo/index.js';
import { useNodeCrsDefinitions } from '../../lib/crs_definitions.js';

useNodeCrsDefinitions(); // the grids' CRSs as the loaders give them: with their EPSG definitions

const dir = new URL('../fixtures/reprojection/', import.meta.url);
const expected = JSON.parse(readFileSync(new URL('expected.json', dir), 'utf8'));
const grid = (g) => resolveGeoref(makeGeoref(crsOfEpsg(parseEpsg(g.crs)), g.x0, g.y0, g.dx, g.dy, 'GeoTIFF'));
const dem = expected.dem;
const field = { width: dem.width, height: dem.height, georef: await grid(dem) };

for (const [code, source] of Object.entries(expected.images)) {
  test(`a UTM DEM's image in EPSG:${code} lands within one texel of where gdalwarp puts it`, async () => {
    const image = { name: source.file, width: source.width, height: source.height, georef: await grid(source) };
    const placement = placeImage(field, image);
    assert.equal(placement.how, 'reprojected');
    assert.match(placement.note, new RegExp(`reprojected from EPSG:${code} to EPSG:32645`));
    assert.ok(placement.warp.maxError <= WARP_TOLERANCE_PX, `the control grid is within ${WARP_TOLERANCE_PX} px (${placement.warp.maxError})`);
    const picked = new Uint16Array(gunzipSync(readFileSync(new URL(source.index, dir))).buffer.slice(0));
    let compared = 0, sameTexel = 0, worst = 0, worstGrid = 0, sumX = 0, sumY = 0;
    for (let row = 0; row < dem.height; row++) {
      for (let column = 0; column < dem.width; column++) {
        const k = 2 * (row * dem.width + column);
        if (picked[k] === 65535) continue; // gdalwarp put no pixel there
        const [x, y] = placement.toImage(column, row);
        const [gx, gy] = interpolate(placement.warp, column, row);
        // gdalwarp's nearest pixel is the one containing the point: its centre is (i + 0.5, j + 0.5).
        const off = Math.max(Math.abs(x - (picked[k] + 0.5)), Math.abs(y - (picked[k + 1] + 0.5)));
        const offGrid = Math.max(Math.abs(gx - (picked[k] + 0.5)), Math.abs(gy - (picked[k + 1] + 0.5)));
        worst = Math.max(worst, off);
        worstGrid = Math.max(worstGrid, offGrid);
        compared++;
        sumX += x - (picked[k] + 0.5);
        sumY += y - (picked[k + 1] + 0.5);
        if (Math.floor(x) === picked[k] && Math.floor(y) === picked[k + 1]) sameTexel++;
      }
    }
    assert.ok(compared > 0.9 * dem.width * dem.height, `most samples compared (${compared})`);
    // Inside the texel gdalwarp picked (with its exact transformer): within half a texel of its
    // centre, give or take proj4's and PROJ's rounding; through the control grid, within one texel.
    assert.ok(worst <= 0.5 + 1e-4, `exact map: inside gdalwarp's texel (worst ${worst.toFixed(4)} from its centre)`);
    assert.ok(worstGrid <= 0.5 + WARP_TOLERANCE_PX, `control grid: within one texel (worst ${worstGrid.toFixed(4)})`);
    // No bias: a half-pixel convention error would shift every sample by 0.5.
    assert.ok(Math.abs(sumX / compared) < 0.02 && Math.abs(sumY / compared) < 0.02, `no bias (${(sumX / compared).toFixed(4)}, ${(sumY / compared).toFixed(4)} px)`);
    assert.ok(sameTexel / compared > 0.9999, `the same texel (${sameTexel} of ${compared})`);
    assert.ok(placement.coverage > 0.99, `the image covers the DEM (${placement.coverage})`);
  });
}

test('an image off the terrain is refused, given in its own CRS; one in an unnamed CRS is taken to be in the terrain\'s', async () => {
  const off = { name: 'off.tif', width: 10, height: 10, georef: await resolveGeoref(makeGeoref(crsOfEpsg(4326), 10, 50, 0.1, -0.1, 'GeoTIFF')) };
  assert.throws(() => placeImage(field, off), /^ImageError: off\.tif: it lies outside the terrain \(the image spans x 9\.95\.\.10\.95/);
  const custom = { name: 'c.tif', width: 10, height: 10, georef: makeGeoref({ epsg: null, label: 'user-defined', name: null, proj4: null, geographic: false }, 300000, 3000000, 1000, -1000, 'GeoTIFF') };
  assert.deepEqual(placeImage(field, custom).how, 'georeferenced', 'a CRS nobody named is taken to be the terrain\'s, as GIS programs do');
});
