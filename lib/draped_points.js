// Known ground points of the Blue Marble image draped on the default terrain
// (tests/fixtures/imagery/README.md), for the browser tests that judge a draped image by its
// pixels: where a point lies on the field, where a camera's view-projection puts it on screen,
// and the colour a screenshot has there; and the view from straight above that the tests judge
// it from.

/** Ground points: lon, lat and the image's colour there (its pixel's RGB). */
export const BLUE_MARBLE_POINTS = {
  'Bay of Bengal': [89.5, 21.0333, [24, 71, 127]],
  'Taklamakan': [81.9667, 37.7, [163, 143, 110]],
  'Ganges plain': [84.9667, 25.6333, [113, 105, 69]],
};

// The default terrain's sidecar (public/terrain/globe_himalaya_2048.json): 2048 x 2048 cells
// whose outer edges are these bounds.
const WEST = 72.93333333333334, EAST = 90, SOUTH = 20.85, NORTH = 37.916666666666664, CELLS = 2048;

/**
 * A longitude and latitude on the default terrain as the page's ground metres: x east of the
 * first column's centre, z south of the first row's, at height 0.
 * @returns {number[]} [x, y, z]
 */
export function groundPoint(lon, lat, spacingX, spacingY) {
  const dx = (EAST - WEST) / CELLS, dy = (NORTH - SOUTH) / CELLS;
  const column = (lon - (WEST + dx / 2)) / dx, row = ((NORTH - dy / 2) - lat) / dy;
  return [column * spacingX, 0, row * spacingY];
}

/**
 * Where a point lands on a screen of width x height pixels (top-left origin, rounded), given a
 * column-major view-projection matrix (gl-matrix's layout).
 * @returns {number[]} [x, y]
 */
export function screenPoint(m, [x, y, z], width, height) {
  const w = m[3] * x + m[7] * y + m[11] * z + m[15];
  const sx = ((m[0] * x + m[4] * y + m[8] * z + m[12]) / w * 0.5 + 0.5) * width;
  const sy = (1 - ((m[1] * x + m[5] * y + m[9] * z + m[13]) / w * 0.5 + 0.5)) * height;
  return [Math.round(sx), Math.round(sy)];
}

/**
 * The RGB of an image's pixel: { width, data, channels } with rows top first (a decoded PNG,
 * or `hexlod regress`'s captures with channels 3).
 */
export function colourAt({ width, data, channels }, [x, y]) {
  const i = (y * width + x) * channels;
  return Array.from(data.subarray(i, i + 3));
}

/** True when each channel of `got` is within `tolerance` of `expected`. */
export const coloursMatch = (got, expected, tolerance) => expected.every((v, k) => Math.abs(got[k] - v) <= tolerance);

/**
 * Points the page's orbit camera straight down on the middle of the terrain from `distance`
 * metres, with the image unlit (its own colours, no sun), and draws.
 */
export function lookStraightDown(page, distance = 3.2e6) {
  return page.evaluate((distance) => {
    const h = window.hexlod, t = h.terrainObject(), orbit = h.rig.cameras.orbit;
    h.setSetting('imageUnlit', true);
    h.setSetting('camera', 'orbit');
    orbit.target[0] = ((t.width - 1) * t.spacingX) / 2; orbit.target[1] = 0; orbit.target[2] = ((t.height - 1) * t.spacingY) / 2;
    orbit.yaw = 0; orbit.pitch = 1.55; orbit.distance = distance;
    h.requestRender();
  }, distance);
}

/** Screen pixels of ground points { name: [lon, lat] } on the default terrain (sea level), in the page's current view. */
export async function projectLonLat(page, points) {
  const spacing = await page.evaluate(() => { const t = window.hexlod.terrainObject(); return [t.spacingX, t.spacingY]; });
  const ground = Object.values(points).map(([lon, lat]) => groundPoint(lon, lat, ...spacing));
  // Where the page draws them (on the curved Earth too), and its camera's matrix.
  const view = await page.evaluate((ground) => {
    const h = window.hexlod;
    return { m: Array.from(h.camera.viewProjection), drawn: ground.map((p) => h.drawnPoint(...p)), width: innerWidth, height: innerHeight };
  }, ground);
  return Object.fromEntries(Object.keys(points).map((name, k) => [name, screenPoint(view.m, view.drawn[k], view.width, view.height)]));
}
