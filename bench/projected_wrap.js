#!/usr/bin/env node
// How far the curved Earth puts a projected grid's samples from where they are. A projected
// field is drawn on a sphere of the mean radius at its centre, distances and directions from the
// centre kept (web/geo/earth_shape.js), not through its CRS. Here each sample of a 65 x 65 grid
// over a field goes through its CRS (proj4, the page's definitions) to longitude and latitude,
// then onto WGS 84 in the field centre's east-up-south frame (web/geo/earth_frame.js); the
// table gives the largest distance between that and the drawn point, in metres and as a share
// of the sample's distance from the centre; then the turn about the centre that brings the drawn
// field closest to the true one (a projected grid's north is not true north away from its
// central meridian: the CRS's convergence), and the largest offset left after that turn (how
// far the shape itself is off, the CRS's scale against the wrap's). Figures printed, never
// asserted.
//
//   node bench/projected_wrap.js
import { useNodeCrsDefinitions } from '../lib/crs_definitions.js';
import { crsOfEpsg, makeGeoref, resolveGeoref, earthShapeOf, drawnPoint } from '../web/geo/index.js';
import { geoCoordinates } from '../web/geo/coordinates.js';
import { eastUpSouthAt } from '../web/geo/earth_frame.js';

useNodeCrsDefinitions();
const STEPS = 64;

// Fields as people bring them: [what, EPSG code, west, north (CRS metres), width, height (km), spacing (m)].
const FIELDS = [
  ['lidar tile, UTM 33N on its central meridian', 32633, 495000, 5210000, 10, 10, 1],
  ['regional DEM, UTM 33N at the zone edge', 32633, 200000, 5250000, 100, 100, 10],
  ['Switzerland, LV95', 2056, 2480000, 1300000, 360, 230, 25],
  ['Europe, LCC (EPSG:3034)', 3034, 2500000, 4500000, 3000, 2500, 500],
  ['Scandinavia, Web Mercator 55-64 N', 3857, 1000000, 9100000, 1000, 1700, 100],
];

const rows = [];
for (const [what, epsg, west, north, widthKm, heightKm, spacing] of FIELDS) {
  const georef = await resolveGeoref(makeGeoref(crsOfEpsg(epsg), west, north, spacing, -spacing, 'bench'));
  const width = Math.round((widthKm * 1000) / spacing) + 1, height = Math.round((heightKm * 1000) / spacing) + 1;
  const terrain = { width, height, spacingX: spacing, spacingY: spacing };
  const earth = earthShapeOf(georef, terrain);
  const centre = geoCoordinates(georef, earth.originX, earth.originZ, spacing, spacing);
  const frame = eastUpSouthAt(centre.lon, centre.lat);
  const pairs = []; // [drawn, true], each relative to the centre
  let worst = 0, worstShare = 0;
  for (let i = 0; i <= STEPS; i++) {
    for (let j = 0; j <= STEPS; j++) {
      const x = ((width - 1) * spacing * j) / STEPS, z = ((height - 1) * spacing * i) / STEPS;
      const { lon, lat } = geoCoordinates(georef, x, z, spacing, spacing);
      const truth = frame(lon, lat, 0), drawn = drawnPoint(earth, x, 0, z);
      const distance = Math.hypot(drawn[0] - truth[0], drawn[1] - truth[1], drawn[2] - truth[2]);
      const fromCentre = Math.hypot(x - earth.originX, z - earth.originZ);
      worst = Math.max(worst, distance);
      if (fromCentre > 0) worstShare = Math.max(worstShare, distance / fromCentre);
      pairs.push([drawn, truth]);
    }
  }
  // The turn about the vertical through the centre that best lays the drawn points on the true
  // ones (least squares in the east-south plane), and what is left after it.
  let cross = 0, dot = 0;
  for (const [d, t] of pairs) cross += d[0] * t[2] - d[2] * t[0], dot += d[0] * t[0] + d[2] * t[2];
  const turn = Math.atan2(cross, dot), c = Math.cos(turn), s = Math.sin(turn);
  let shape = 0;
  for (const [d, t] of pairs) shape = Math.max(shape, Math.hypot(c * d[0] - s * d[2] - t[0], d[1] - t[1], s * d[0] + c * d[2] - t[2]));
  rows.push({ what, epsg, extent: `${widthKm} x ${heightKm} km`, worst, worstShare, turn, shape });
}

const metres = (m) => (m < 10 ? `${m.toFixed(3)} m` : m < 10000 ? `${m.toFixed(0)} m` : `${(m / 1000).toFixed(1)} km`);
console.log('| field | CRS | extent | largest offset | of the distance from the centre | best turn | offset after it |');
console.log('|---|---|---|---|---|---|---|');
for (const r of rows) {
  const turn = ((Math.abs(r.turn) * 180) / Math.PI).toFixed(3);
  console.log(`| ${r.what} | EPSG:${r.epsg} | ${r.extent} | ${metres(r.worst)} | ${(100 * r.worstShare).toFixed(2)} % | ${turn}° | ${metres(r.shape)} |`);
}
