// The page's API for headless tests, benchmarks and regression flights, on window.hexlod. It is
// installed only in test mode: when a browser automation tool drives the page
// (navigator.webdriver, as Playwright, Puppeteer and WebDriver set it) or with ?test=1. A person's
// page publishes nothing.
import { FLAT_EARTH, drawnPoint } from '../geo/index.js';

/** True when the page publishes window.hexlod. */
export function isTestMode(params) {
  return navigator.webdriver === true || params.get('test') === '1';
}

/**
 * Publishes `state` (status, error, terrain, frames, triangles, mesh, lod, timing, hud, eye,
 * cursor, tiles (a tiled terrain's waiting, bytesFetched, fileBytes, heldBytes, tilesIn,
 * failures), ... kept up to date by the page) as window.hexlod, with the handles tests use to drive
 * the page: the camera rig, the settings and the view, setSetting(key, value) as the panel sets
 * one, requestRender(), glError(), screenshot(scale), terrainObject() (the core's Terrain),
 * flushUrl(), openUrl(url) (as ?src= opens a file, in this page), setLayout('fans' | 'triangles') (the same mesh drawn with the other index layout)
 * drawnPoint(x, y, z) (a flat point where it is drawn, on the curved Earth too)
 * and memory() ({ wasmBytes, liveTerrains }: the size of the core's WebAssembly memory, which
 * never shrinks, and the terrains the core holds: created and not yet destroyed). The measuring
 * tool is window.hexlod.measure (web/ui/measure_tool.js: points, result, pick(x, y), restore(),
 * overlay), published by web/app/measuring.js.
 */

export function installTestApi(state, { gl, core, rig, settings, view, requestRender, setSetting, screenshot, terrain, urlWriter, setLayout, openUrl }) {
  Object.assign(state, { rig, settings, view, requestRender, setSetting, screenshot, setLayout, openUrl,
    glError: () => gl.getError(), terrainObject: terrain, flushUrl: () => urlWriter.flush(),
    memory: () => ({ wasmBytes: core.buffer.byteLength, liveTerrains }) });
  // Counts the terrains the page makes and frees (a load that fails or is cancelled must free its own).
  let liveTerrains = 0;
  for (const method of ['createTerrain', 'createTiledTerrain']) {
    const create = core[method].bind(core);
    core[method] = (...args) => {
      const terrain = create(...args);
      liveTerrains += 1;
      const destroy = terrain.destroy.bind(terrain);
      terrain.destroy = () => {
        if (terrain.handle !== 0) liveTerrains -= 1;
        destroy();
      };
      return terrain;
    };
  }
  Object.defineProperty(state, 'camera', { get: () => rig.active, enumerable: true });
  // Where a flat point (x east, height times the exaggeration, z south) is drawn now: on the
  // curved Earth its place in the drawn frame (web/geo/earth_shape.js), for tests that project
  // ground points with the camera's matrix.
  state.drawnPoint = (x, y, z) => drawnPoint(state.camera.earth ?? FLAT_EARTH, x, y, z);
  window.hexlod = state;
}
