// The draped image of the terrain on screen, the image layer of the layer list (layers.js; one
// at a time for now): opened onto it (web/imagery/open_image.js), its textures in the renderer,
// its note or refusal in the status line. A refused image leaves the
// one shown before. The layer keeps the files it came from, so that it can be draped again when
// the graphics context comes back.
import { openImage } from '../imagery/open_image.js';
import { ImageError } from '../imagery/image_error.js';
import { describeImage } from '../imagery/describe_image.js';

const NO_SIDECARS = { worldFile: null, prj: null, auxXml: null };

/**
 * @param {{ renderer: object, layers: import('./layers.js').Layers, showStatus: (message: string, isError?: boolean) => void,
 *   onChange: (image: object|null) => void, requestRender: () => void }} page
 *   onChange: the image shown changed (the panel offers to remove it); the layer list tells the HUD
 */
export function createImageStage({ renderer, layers, showStatus, onChange, requestRender }) {
  const shown = () => layers.images.at(-1)?.image ?? null;

  /** Opens the image onto the terrain on screen; throws ImageError. */
  async function open(image, sidecars) {
    const { terrain, field } = layers.ground;
    const ground = { width: terrain.width, height: terrain.height, spacingX: terrain.spacingX, spacingY: terrain.spacingY, georef: field.georef ?? null };
    const opened = await openImage(image, sidecars, ground, renderer.imageTextures);
    renderer.setImagePlacement(opened.placement);
    return opened;
  }

  function changed() {
    layers.changed('images');
    onChange(shown());
    requestRender();
  }

  return {
    /** The image draped now (DrapedImage of open_image.js), or null. */
    get current() { return shown(); },

    /**
     * Drapes an image ({ name, blob }) with its sidecars ({ worldFile, prj, auxXml }, each
     * { name, blob } or null) on the terrain on screen.
     * @param {{ url?: string|null, throwRefusal?: boolean }} [options] url: where it came from,
     *   when a link can name it; throwRefusal: a refusal is also thrown (a regression flight
     *   fails with it rather than fly without its image)
     * @returns {Promise<object|null>} the image shown, or null when it was refused (the status line says why)
     */
    async drape(image, sidecars = NO_SIDECARS, { url = null, throwRefusal = false } = {}) {
      if (!layers.ground) return null;
      try {
        const opened = await open(image, sidecars);
        layers.images = [{ image: opened, files: { image, sidecars, url }, description: describeImage(opened) }];
        showStatus(opened.note ? `${image.name}: ${opened.note}` : '');
        changed();
        return opened;
      } catch (error) {
        if (!(error instanceof ImageError)) throw error;
        showStatus(`${error.message}${shown() ? ` (${shown().name} stays)` : ''}`, true);
        requestRender();
        if (throwRefusal) throw error;
        return null;
      }
    },

    /** The image goes; the procedural ground shows again. */
    remove() {
      if (layers.images.length === 0) return;
      renderer.imageTextures.remove();
      renderer.setImagePlacement(null);
      layers.images = [];
      changed();
    },

    /** The graphics context came back without textures: the image shown is draped again. */
    async restore() {
      const layer = layers.images.at(-1);
      if (!layer || !layers.ground) return;
      const { image, sidecars } = layer.files;
      try {
        layer.image = await open(image, sidecars);
        layer.description = describeImage(layer.image);
      } catch (error) {
        if (!(error instanceof ImageError)) throw error;
        layers.images = [];
        showStatus(`${error.message} (after the graphics context came back)`, true);
      }
      changed();
    },
  };
}

/** What tests read of the image shown (window.hexlod.image): its size, placement and HUD line; null without one. */
export function imageFigures(image, hud) {
  return image && { name: image.name, width: image.width, height: image.height, metresPerPixel: image.metresPerPixel,
    coverage: image.placement.coverage, how: image.placement.how, gpuBytes: image.gpuBytes, hud: hud.layerLines.textContent };
}
