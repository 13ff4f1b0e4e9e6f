// The image layers of the terrain on screen (the layer list's images, layers.js): image files
// opened onto it (web/imagery/open_image.js), each with textures of its own, and the web map
// tile layers (web_tile_stage.js) beside them; their order, visibility, opacity and removal; and
// their notes and refusals in the status line. A refused image leaves every layer as it was.
// Each file layer keeps the files it came from, so that it can be draped again when the
// graphics context comes back.
import { openImage } from '../imagery/open_image.js';
import { ImageError } from '../imagery/image_error.js';
import { describeImage } from '../imagery/describe_image.js';
import { MAX_DRAPES } from './layers.js';

const NO_SIDECARS = { worldFile: null, prj: null, auxXml: null };
const ADDED_HIDDEN = `added hidden; at most ${MAX_DRAPES} image layers show at once (hide one to show it)`;

/**
 * @param {{ renderer: object, layers: import('./layers.js').Layers, showStatus: (message: string, isError?: boolean) => void,
 *   requestRender: () => void }} page
 */
export function createImageStage({ renderer, layers, showStatus, requestRender }) {
  let nextId = 1;
  const topImage = () => layers.images.findLast((layer) => layer.kind === 'image') ?? null;
  const byId = (id) => layers.images.find((layer) => layer.id === id) ?? null;
  const visibleCount = () => layers.images.filter((layer) => layer.visible).length;

  /** Opens the image onto the terrain on screen into new textures; throws ImageError. */
  async function open(image, sidecars) {
    const { terrain, field } = layers.ground;
    const ground = { width: terrain.width, height: terrain.height, spacingX: terrain.spacingX, spacingY: terrain.spacingY, georef: field.georef ?? null };
    const textures = renderer.newImageTextures();
    const opened = await openImage(image, sidecars, ground, textures);
    return { opened, textures };
  }

  function changed() {
    layers.changed('images');
    requestRender();
  }

  /** A file layer's record from its opening. */
  function fileLayer(layer, { opened, textures }) {
    layer.image = opened;
    layer.name = opened.name;
    layer.description = describeImage(opened);
    layer.drape = { kind: 'image', warp: opened.placement.warp, opacity: layer.opacity, textures };
    layer.dispose = () => textures.remove();
    return layer;
  }

  const stage = {
    /** The top image file draped now (DrapedImage of open_image.js), or null. */
    get current() { return topImage()?.image ?? null; },

    /**
     * Puts a layer on top of the others (visible unless MAX_DRAPES already are: then hidden,
     * and the status line says why).
     * @param {object} layer { kind, name, description, url, drape, dispose?, restore? }
     * @returns {object} the layer, with its id
     */
    add(layer) {
      layer.id = nextId++;
      layer.opacity ??= 1;
      layer.visible = visibleCount() < MAX_DRAPES;
      if (layer.drape) layer.drape.opacity = layer.opacity;
      layers.images.push(layer);
      if (!layer.visible) showStatus(`${layer.name}: ${ADDED_HIDDEN}`);
      changed();
      return layer;
    },

    /**
     * Drapes an image file ({ name, blob }) with its sidecars ({ worldFile, prj, auxXml }, each
     * { name, blob } or null) over the layers of the terrain on screen.
     * @param {{ url?: string|null, throwRefusal?: boolean, opacity?: number, visible?: boolean }} [options]
     *   url: where it came from, when a link can name it; throwRefusal: a refusal is also thrown
     *   (a regression flight fails with it rather than fly without its image); opacity and
     *   visible: the layer's, from the start
     * @returns {Promise<object|null>} the image shown (its note telling also when it was added
     *   hidden), or null when it was refused (the status line says why)
     */
    async drape(image, sidecars = NO_SIDECARS, { url = null, throwRefusal = false, opacity = 1, visible = true } = {}) {
      if (!layers.ground) return null;
      try {
        const layer = fileLayer({ kind: 'image', url, opacity, files: { image, sidecars } }, await open(image, sidecars));
        stage.add(layer);
        if (!visible) stage.setVisible(layer.id, false);
        const note = [layer.image.note, visible && !layer.visible ? ADDED_HIDDEN : null].filter(Boolean).join('; ') || null;
        showStatus(note ? `${image.name}: ${note}` : '');
        return note === layer.image.note ? layer.image : { ...layer.image, note }; // a drop's status line says it too
      } catch (error) {
        if (!(error instanceof ImageError)) throw error;
        const top = topImage();
        showStatus(`${error.message}${top ? ` (${top.name} stays)` : ''}`, true);
        requestRender();
        if (throwRefusal) throw error;
        return null;
      }
    },

    /** A layer goes (the top image file when no id is given). */
    remove(id = topImage()?.id) {
      const layer = byId(id);
      if (!layer) return;
      layers.images.splice(layers.images.indexOf(layer), 1);
      layer.dispose?.();
      changed();
    },

    /** Every image file goes (a new terrain: they belonged to the old ground); web map tiles stay. */
    removeFiles() {
      for (const layer of layers.images.filter((l) => l.kind === 'image')) stage.remove(layer.id);
    },

    /** Shows or hides a layer; refuses to show more than MAX_DRAPES at once. */
    setVisible(id, visible) {
      const layer = byId(id);
      if (!layer || layer.visible === visible) return true;
      if (visible && visibleCount() >= MAX_DRAPES) {
        showStatus(`${layer.name}: at most ${MAX_DRAPES} image layers show at once; hide one first`, true);
        return false;
      }
      layer.visible = visible;
      changed();
      return true;
    },

    /** A layer's opacity, 0..1. */
    setOpacity(id, opacity) {
      const layer = byId(id);
      if (!layer) return;
      layer.opacity = Math.min(1, Math.max(0, opacity));
      if (layer.drape) layer.drape.opacity = layer.opacity;
      requestRender();
    },

    /** Moves a layer up (+1, over the next) or down (-1) the order. */
    move(id, step) {
      const layer = byId(id);
      if (!layer) return;
      const from = layers.images.indexOf(layer), to = Math.min(layers.images.length - 1, Math.max(0, from + step));
      if (from === to) return;
      layers.images.splice(from, 1);
      layers.images.splice(to, 0, layer);
      changed();
    },

    /** The graphics context came back without textures: every layer is draped again. */
    async restore() {
      if (!layers.ground) return;
      for (const layer of [...layers.images]) {
        if (layer.kind !== 'image') {
          layer.restore?.();
          continue;
        }
        try {
          fileLayer(layer, await open(layer.files.image, layer.files.sidecars));
        } catch (error) {
          if (!(error instanceof ImageError)) throw error;
          layers.images.splice(layers.images.indexOf(layer), 1);
          showStatus(`${error.message} (after the graphics context came back)`, true);
        }
      }
      changed();
    },
  };
  return stage;
}

/** What tests read of the top image file (window.hexlod.image): its size, placement and the HUD's layer lines; null without one. */
export function imageFigures(image, hud) {
  return image && { name: image.name, width: image.width, height: image.height, metresPerPixel: image.metresPerPixel,
    coverage: image.placement.coverage, how: image.placement.how, maxWarpError: image.placement.warp.maxError,
    gpuBytes: image.gpuBytes, hud: hud.layerLines.textContent };
}

/** What tests read of the image layers (window.hexlod.imageLayers), bottom first; a tile layer's figures too (webtiles/web_tile_layer.js). */
export function layerFigures(layers) {
  return layers.images.map(({ id, kind, name, visible, opacity, url, tiles }) =>
    ({ id, kind, name, visible, opacity, url, ...(tiles && { tiles: { ...tiles.figures } }) }));
}
