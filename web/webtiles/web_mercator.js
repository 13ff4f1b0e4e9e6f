// Web Mercator (EPSG:3857) as web map tiles use it: "world" coordinates 0..1 across the whole
// map, x east from 180° W, y south from the top edge at about 85.05° N (so that the world is a
// square), and tile (z, x, y) the square [x, x+1] × [y, y+1] / 2^z of it. The sphere's radius is
// WGS 84's semi-major axis, as every tile service uses.

/** Metres of the sphere's equator: 2π × 6378137. */
export const EQUATOR_METRES = 2 * Math.PI * 6378137;
/** The latitude of the map's top and bottom edges, degrees: atan(sinh(π)). */
export const MAX_LATITUDE = (Math.atan(Math.sinh(Math.PI)) * 180) / Math.PI;
/** The finest zoom we handle: tile keys stay exact doubles, and no service goes finer. */
export const MAX_ZOOM = 24;

const RADIANS = Math.PI / 180;

/**
 * World coordinates of a longitude and latitude (degrees); latitudes beyond MAX_LATITUDE land on
 * the map's edge. Writes into `out` when given.
 * @returns {number[]} [x, y], 0..1, y down
 */
export function lonLatToWorld(lon, lat, out = [0, 0]) {
  const phi = Math.max(-MAX_LATITUDE, Math.min(MAX_LATITUDE, lat)) * RADIANS;
  out[0] = lon / 360 + 0.5;
  out[1] = 0.5 - Math.log(Math.tan(Math.PI / 4 + phi / 2)) / (2 * Math.PI);
  return out;
}

/** Longitude and latitude (degrees) of world coordinates. */
export function worldToLonLat(x, y, out = [0, 0]) {
  out[0] = (x - 0.5) * 360;
  out[1] = Math.atan(Math.sinh(Math.PI * (1 - 2 * y))) / RADIANS;
  return out;
}

/** World coordinates of EPSG:3857 metres (easting, northing). */
export function metresToWorld(easting, northing, out = [0, 0]) {
  out[0] = easting / EQUATOR_METRES + 0.5;
  out[1] = 0.5 - northing / EQUATOR_METRES;
  return out;
}

/** The tile of zoom z holding a world point (edges go to the tile east and south of them, clamped to the map). */
export function worldToTile(x, y, z, out = [0, 0]) {
  const n = 2 ** z;
  out[0] = Math.min(n - 1, Math.max(0, Math.floor(x * n)));
  out[1] = Math.min(n - 1, Math.max(0, Math.floor(y * n)));
  return out;
}

/** The tile of zoom z holding a longitude and latitude. */
export function lonLatToTile(lon, lat, z, out = [0, 0]) {
  lonLatToWorld(lon, lat, out);
  return worldToTile(out[0], out[1], z, out);
}

/** West, south, east and north edges of a tile in degrees. */
export function tileLonLatBounds(z, x, y) {
  const n = 2 ** z;
  const [west, north] = worldToLonLat(x / n, y / n);
  const [east, south] = worldToLonLat((x + 1) / n, (y + 1) / n);
  return [west, south, east, north];
}

/**
 * Ground metres a texel of zoom z spans at a latitude (degrees), on the sphere: Mercator
 * stretches by 1 / cos(latitude).
 * @param {number} tileSize texels a tile side (256 for most services)
 */
export function groundResolution(z, lat, tileSize = 256) {
  return (EQUATOR_METRES * Math.cos(lat * RADIANS)) / (tileSize * 2 ** z);
}
