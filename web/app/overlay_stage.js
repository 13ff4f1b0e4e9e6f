// The vector overlays on the terrain (the layer list's overlays, layers.js): GPX, KML, KMZ and
// GeoJSON files read (overlays/read_overlay.js), placed on the terrain on screen through the
// geography module as images are (overlays/place_overlay.js), and drawn by the renderer
// (render/overlays/). Each keeps its file's contents, so a new terrain (dropped after it, or a
// lost context) places and draws it again. Their colour, width, altitude and visibility, their
// removal, and what they say in the status line (features off the terrain are counted there,
// not drawn in the void). A refused file leaves the terrain and the other overlays as they were.
import { readOverlay } from '../overlays/read_overlay.js';
import { placeOverlay } from '../overlays/place_overlay.js';
import { OverlayError } from '../overlays/overlay_error.js';
import { fieldSampler } from '../measure/field_sampler.js';
import { overlayGeometry } from '../render/overlays/overlay_geometry.js';
import { OverlayDrawing } from '../render/overlays/overlay_drawing.js';
import { polygonFillDrape } from '../render/overlays/polygon_fill.js';
import { fetchFile } from './fetched_file.js';

/** Colours given to overlays in turn: bright, apart from each other and from the measured line's yellow. */
export const OVERLAY_COLORS = ['#ff3d8b', '#2fd4ff', '#7cff4f', '#ff8a1f', '#b68cff', '#ffffff'];
const DEFAULT_HALF_WIDTH = 2;

/** '#rrggbb' -> [r, g, b] in 0..1. */
export function rgbOf(hex) {
  const n = Number.parseInt(hex.slice(1), 16);
  return [(n >> 16) / 255, ((n >> 8) & 255) / 255, (n & 255) / 255];
}

/** What an overlay holds, in words: '1 track, 3 points'. */
export function describeContents(features) {
  const count = { line: 0, polygon: 0, point: 0 };
  for (const f of features) count[f.kind] += f.kind === 'point' ? f.paths.length : 1;
  const words = { line: ['line', 'lines'], polygon: ['polygon', 'polygons'], point: ['point', 'points'] };
  return Object.entries(count).filter(([, n]) => n > 0).map(([kind, n]) => `${n} ${words[kind][n === 1 ? 0 : 1]}`).join(', ');
}

/**
 * @param {{ renderer: object, layers: import('./layers.js').Layers, showStatus: (message: string, isError?: boolean) => void,
 *   requestRender: () => void }} page
 */
export function createOverlayStage({ renderer, layers, showStatus, requestRender }) {
  let nextId = 1;
  const terrainHeights = () => layers.ground?.terrain ?? null;
  // The layer list may hold overlays of other kinds (anything with draw()): this stage's are its files.
  const files = () => layers.overlays.filter((layer) => layer.kind === 'overlay');

  function changed() {
    layers.changed('overlays');
    requestRender();
  }

  /** Places the layer's overlay on the terrain on screen and builds what is drawn; throws OverlayError. */
  function place(layer) {
    const ground = layers.ground;
    layer.placed = null;
    layer.geometry = null;
    layer.sampler = null;
    if (!ground) return;
    const { terrain, field } = ground;
    const placed = placeOverlay(layer.overlay, field.georef ?? null,
      { columns: terrain.width, rows: terrain.height, spacingX: terrain.spacingX, spacingY: terrain.spacingY });
    const sampler = fieldSampler(terrain, field.georef ?? null);
    layer.placed = placed;
    layer.sampler = sampler;
    build(layer);
    fill(layer);
  }

  /** What is drawn of a placed overlay, as its altitude and curtain say. */
  function build(layer) {
    layer.geometry = overlayGeometry(layer.placed, layer.sampler, { altitude: layer.altitude, curtain: layer.curtain });
    layer.drawing.setGeometry(layer.geometry);
  }

  /** The polygons' fill, draped on the ground (made again for a new colour or terrain). */
  function fill(layer) {
    layer.fill?.textures.remove();
    layer.fill = layer.placed ? polygonFillDrape(layer.placed, layer.sampler, rgbOf(layer.color), renderer.newImageTextures()) : null;
  }

  function describe(layer) {
    const off = layer.placed?.offTerrain ?? 0;
    const where = !layer.placed ? ' (not placed)' : off === layer.overlay.features.length ? ' (entirely off the terrain)'
      : off > 0 ? ` (${off} off the terrain)` : '';
    layer.description = `overlay: ${layer.name} (${layer.overlay.format}, ${describeContents(layer.overlay.features)})${where}`;
  }

  /** The status line's words on an overlay just placed: what is drawn and what is off the terrain. */
  function report(layer) {
    const placed = layer.placed, total = layer.overlay.features.length;
    const notes = layer.overlay.notes.length ? `; ${layer.overlay.notes.join('; ')}` : '';
    if (placed.offTerrain === total) {
      return `${layer.name}: every feature (${total}) lies off the terrain on screen; it is kept and shows on a terrain that covers it${notes}`;
    }
    const off = placed.offTerrain > 0 ? `; ${placed.offTerrain} of ${total} features lie off the terrain and are not drawn` : '';
    const part = placed.partlyOff > 0 ? `; ${placed.partlyOff} leave it in part` : '';
    return `${layer.name}: ${describeContents(layer.overlay.features)} drawn${off}${part}${notes}`;
  }

  const stage = {
    /** The overlay files, bottom first. */
    get list() { return files(); },

    /**
     * Reads a file and puts it on top of the overlays. A refusal says why in the status line (or
     * throws with throwRefusal) and changes nothing.
     * @param {{name: string, bytes: Uint8Array}} file
     * @returns {Promise<object|null>} the layer, or null when refused
     */
    async add(file, { url = null, color = null, visible = true, halfWidth = DEFAULT_HALF_WIDTH, altitude = 'file', curtain = false,
      throwRefusal = false } = {}) {
      let layer = null;
      try {
        const overlay = await readOverlay(file.name, file.bytes);
        const hex = color ?? OVERLAY_COLORS[(nextId - 1) % OVERLAY_COLORS.length];
        layer = { id: nextId++, kind: 'overlay', name: file.name, url, overlay, color: hex, halfWidth, visible, altitude, curtain,
          drawing: new OverlayDrawing(renderer.groundLines, terrainHeights) };
        layer.drawing.setStyle({ color: rgbOf(hex), halfWidth, visible });
        layer.draw = (gl, camera, width, height, verticalScale) => layer.drawing.draw(gl, camera, width, height, verticalScale);
        layer.createGlObjects = (gl) => {
          layer.drawing.createGlObjects(gl);
          fill(layer); // its textures died with the context
        };
        place(layer);
      } catch (error) {
        layer?.drawing.dispose();
        layer?.fill?.textures.remove();
        if (!(error instanceof OverlayError)) throw error;
        const message = `${file.name}: ${error.message}`;
        if (throwRefusal) throw new OverlayError(message);
        showStatus(message, true);
        return null;
      }
      describe(layer);
      layers.overlays.push(layer);
      showStatus(layer.placed ? report(layer) : `${layer.name}: kept; it is drawn once a terrain is shown`);
      changed();
      return layer;
    },

    /** Fetches an overlay from an address and adds it (the address bar's overlay=). */
    async addUrl(url, options = {}) {
      let file;
      try {
        file = await fetchFile(url);
      } catch (error) {
        const message = `overlay ${url}: cannot fetch it (${error.message})`;
        if (options.throwRefusal) throw new OverlayError(message);
        showStatus(message, true);
        return null;
      }
      return stage.add(file, { ...options, url });
    },

    remove(layer) {
      const at = layers.overlays.indexOf(layer);
      if (at < 0) return;
      layers.overlays.splice(at, 1);
      layer.drawing.dispose();
      layer.fill?.textures.remove();
      changed();
    },

    /** Colour ('#rrggbb'), width (CSS pixels either side) and visibility. */
    setStyle(layer, { color = layer.color, halfWidth = layer.halfWidth, visible = layer.visible } = {}) {
      const recolour = color !== layer.color;
      Object.assign(layer, { color, halfWidth, visible });
      layer.drawing.setStyle({ color: rgbOf(color), halfWidth, visible });
      if (recolour) fill(layer);
      changed();
    },

    /** How lines are drawn: 'file' (as the file says), 'clamp' or 'absolute', and the curtain under lines aloft. */
    setAltitude(layer, { altitude = layer.altitude, curtain = layer.curtain } = {}) {
      Object.assign(layer, { altitude, curtain });
      if (layer.placed) build(layer);
      changed();
    },

    /** A new terrain is on screen: every overlay is placed on it again (or waits, unplaced, on a terrain without a georeference). */
    terrainChanged() {
      if (files().length === 0) return;
      const refused = [];
      for (const layer of files()) {
        try {
          place(layer);
        } catch (error) {
          if (!(error instanceof OverlayError)) throw error;
          layer.drawing.setGeometry(EMPTY_GEOMETRY);
          refused.push(`${layer.name}: ${error.message}`);
        }
        describe(layer);
      }
      const off = stage.offTerrain;
      if (refused.length) showStatus(refused.join('; '), true);
      else if (off > 0) showStatus(`${off} overlay feature${off === 1 ? '' : 's'} lie${off === 1 ? 's' : ''} off this terrain and ${off === 1 ? 'is' : 'are'} not drawn`);
      changed();
    },

    /** Features drawn nowhere: off the terrain, summed over the visible overlays (the status line's count). */
    get offTerrain() {
      return files().reduce((n, layer) => n + (layer.visible && layer.placed ? layer.placed.offTerrain : 0), 0);
    },
  };
  return stage;
}

const EMPTY_GEOMETRY = Object.freeze({ segments: new Float32Array(0), curtain: new Float32Array(0), markers: new Float32Array(0),
  markerNames: [], picks: [], drawnVertices: 0, fileVertices: 0 });
