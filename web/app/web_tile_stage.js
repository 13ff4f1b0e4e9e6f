// Web map tile layers (XYZ, TMS, WMTS in Web Mercator: web/webtiles/) draped on the terrain on
// screen, as image layers of the layer list beside the image files (image_stage.js keeps their
// order, visibility, opacity and removal). Each maps the terrain's ground to tile coordinates
// through its CRS (web/geo/) and a control grid the drape shader interpolates, fetches the tiles
// the view needs, and follows a new terrain: a tile layer belongs to the world, not to one file.
import { WebTileLayer } from '../webtiles/web_tile_layer.js';
import { TileSpecError, layerHost, formatTileSpec } from '../webtiles/tile_template.js';
import { readWmtsCapabilities } from '../webtiles/wmts_capabilities.js';
import { lonLatToWorld } from '../webtiles/web_mercator.js';
import { toLonLat, makeWarpGrid, sampleToCrs } from '../geo/index.js';

// Layers of one WMTS service added at once (the first shown, the others hidden until asked for).
const MAX_WMTS_LAYERS = 8;
// The control grid's largest error, in tiles of the table's zoom: a quarter of a texel of a 512² tile.
const WARP_TOLERANCE_TILES = 0.25 / 512;

/**
 * @param {{ gl: WebGL2RenderingContext, layers: import('./layers.js').Layers, images: object,
 *   showStatus: (message: string, isError?: boolean) => void, requestRender: () => void }} page
 *   images: the image stage, which adds the layer to the list and keeps its order and look;
 *   deterministic: a flight's page, whose layers choose tiles for every view (no time between choices)
 */
export function createWebTileStage({ gl, layers, images, showStatus, requestRender, deterministic = false }) {
  const viewport = { height: 0 };

  /**
   * The terrain on screen as a tile layer needs it: its world (extent and drawn heights), the
   * map from its ground metres to Web Mercator, and the same as sample -> tile coordinates.
   * @returns {{ world: object, toMercator: Function, ground: object }|string} a reason when tiles cannot go on it
   */
  function placeOnTerrain() {
    const ground = layers.ground;
    if (!ground) return 'no terrain is shown';
    const georef = ground.field.georef;
    if (!georef) return 'the terrain has no georeference to place web map tiles by';
    const lonLat = toLonLat(georef.crs);
    if (!lonLat) return `the terrain's CRS (${georef.crs.label}) has no definition to place web map tiles by`;
    const { spacingX, spacingY } = ground.terrain;
    const toMercator = (x, z, out = [0, 0]) => {
      const [cx, cy] = sampleToCrs(georef, x / spacingX, z / spacingY);
      const [lon, lat] = lonLat(cx, cy);
      return lonLatToWorld(lon, lat, out);
    };
    return { world: ground.world, toMercator, ground };
  }

  /** The control grid from the terrain's samples to the layer's tile table (tile coordinates at its zoom, from its first tile). */
  function warpOf(tiles, { toMercator, ground }) {
    const { zoom, x0, y0 } = tiles.table, scale = 2 ** zoom;
    const { width, height, spacingX, spacingY } = ground.terrain;
    return makeWarpGrid(width, height, (column, row) => {
      const [mx, my] = toMercator(column * spacingX, row * spacingY);
      return [mx * scale - x0, my * scale - y0];
    }, WARP_TOLERANCE_TILES);
  }

  /** "tiles tile.example.org  Web Mercator, zooms 0–14 over this terrain" */
  function describe(name, tiles) {
    return `tiles ${name}  Web Mercator, zooms ${tiles.spec.minZoom}–${tiles.table.zoom} over this terrain`;
  }

  const stage = {
    /**
     * Adds a web map tile layer over the others from its spec (the ?tiles= value: a template
     * with its options, see webtiles/tile_template.js). Refused with a message when the spec
     * is wrong or the terrain cannot take tiles (and the refusal thrown with throwRefusal: a
     * regression flight fails with it).
     * @returns {object|null} the layer, or null
     */
    add(spec, { opacity = 1, visible = true, throwRefusal = false, name = null } = {}) {
      const refuse = (message) => {
        showStatus(message, true);
        if (throwRefusal) throw new Error(message);
        return null;
      };
      const placed = placeOnTerrain();
      if (typeof placed === 'string') return refuse(`tiles=${spec}: ${placed}`);
      let tiles;
      try {
        tiles = new WebTileLayer(gl, spec, { toMercator: placed.toMercator, terrain: placed.world, onChange: requestRender,
          ...(deterministic && { selectEveryMs: 0 }),
          onMessage: (message) => showStatus(`${layerHost(tiles?.spec ?? { template: spec })}: ${message}`, true) });
      } catch (error) {
        if (!(error instanceof TileSpecError)) throw error;
        return refuse(error.message);
      }
      const layer = {
        kind: 'tiles', name: name ?? layerHost(tiles.spec), url: spec, attribution: tiles.attribution, opacity, tiles,
        drape: { kind: 'tiles', warp: warpOf(tiles, placed), opacity, textures: tiles.textures },
        description: describe(name ?? layerHost(tiles.spec), tiles),
        update: (camera, width, height) => {
          viewport.height = height;
          tiles.update(camera, viewport);
        },
        get settled() { return tiles.settled; },
        dispose: () => tiles.dispose(),
        restore: () => tiles.forgetGl(),
      };
      images.add(layer);
      if (!visible) images.setVisible(layer.id, false);
      return layer;
    },

    /**
     * Adds what a person gives in the panel's field or ?tiles=: a tile template (add), or the
     * address of a WMTS service or its capabilities document (no placeholder in it), whose
     * layers usable in Web Mercator are added, the first shown and the others hidden.
     * @returns {Promise<object[]>} the layers added
     */
    async addFrom(text, look = {}) {
      const address = String(text).split('|')[0];
      if (/[{}]/.test(address) || !/^https?:\/\//i.test(address)) {
        const layer = stage.add(text, look);
        return layer ? [layer] : [];
      }
      let service;
      try {
        service = await readWmtsCapabilities(address);
      } catch (error) {
        if (!(error instanceof TileSpecError)) throw error;
        showStatus(`${address}: not a tile template (it has no {z}, {x} and {y}), and as a WMTS service: ${error.message}`, true);
        return [];
      }
      const added = [];
      for (const offered of service.layers.slice(0, MAX_WMTS_LAYERS)) {
        const layer = stage.add(formatTileSpec(offered.spec), { ...look, name: offered.title, visible: added.length === 0 && look.visible !== false });
        if (layer) added.push(layer);
      }
      const more = service.layers.length - added.length;
      const skipped = service.skipped.length ? `; not in Web Mercator: ${service.skipped.map((s) => s.identifier).join(', ')}` : '';
      if (added.length > 0) {
        showStatus(`${service.title || address}: ${added.length} layer${added.length > 1 ? 's' : ''} added (${added.map((l) => l.name).join(', ')})` +
          `${added.length > 1 ? ', the first shown' : ''}${more > 0 ? `; ${more} more not added` : ''}${skipped}`);
      }
      return added;
    },

    /** A new terrain on screen: every tile layer follows it (or goes, with a message, when it cannot take tiles). */
    terrainChanged() {
      const tileLayers = layers.images.filter((layer) => layer.kind === 'tiles');
      if (tileLayers.length === 0) return;
      const placed = placeOnTerrain();
      for (const layer of tileLayers) {
        if (typeof placed === 'string') {
          showStatus(`${layer.name}: ${placed}; the tile layer goes`, true);
          images.remove(layer.id);
          continue;
        }
        layer.tiles.setTerrain(placed.world, placed.toMercator);
        layer.drape.warp = warpOf(layer.tiles, placed);
        layer.description = describe(layer.name, layer.tiles);
      }
      layers.changed('images');
    },
  };
  return stage;
}
