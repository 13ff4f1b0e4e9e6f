// The draped image of the terrain on screen: opened onto it (web/imagery/open_image.js), its
// textures in the renderer, its note or refusal in the status line, its description in the HUD.
// A refused image leaves the one shown before. The files it came from are kept, so that it can
// be draped again when the graphics context comes back.
import { openImage } from '../imagery/open_image.js';
import { ImageError } from '../imagery/image_error.js';

/**
 * @param {{ renderer: object, stage: { current: object|null }, showStatus: (message: string, isError?: boolean) => void,
 *   onChange: (image: object|null) => void, requestRender: () => void }} page
 *   onChange: the image shown changed (the HUD and the panel describe it)
 */
export function createImageStage({ renderer, stage, showStatus, onChange, requestRender }) {
  let current = null;
  let files = null; // { image, worldFile, url } of the image shown

  /** Opens the image onto the terrain on screen; throws ImageError. */
  async function open(image, worldFile) {
    const { terrain, field } = stage.current;
    const ground = { width: terrain.width, height: terrain.height, spacingX: terrain.spacingX, spacingY: terrain.spacingY, georef: field.georef ?? null };
    const opened = await openImage(image, worldFile, ground, renderer.imageTextures);
    renderer.setImagePlacement(opened.placement);
    return opened;
  }

  function changed() {
    onChange(current);
    requestRender();
  }

  return {
    /** The image draped now (DrapedImage of open_image.js), or null. */
    get current() { return current; },

    /** The URL the image shown came from (the address bar's image=), or null. */
    get url() { return files?.url ?? null; },

    /**
     * Drapes an image ({ name, blob }) with its world file (or null) on the terrain on screen.
     * @param {{ url?: string|null, throwRefusal?: boolean }} [options] url: where it came from,
     *   when a link can name it; throwRefusal: a refusal is also thrown (a regression flight
     *   fails with it rather than fly without its image)
     * @returns {Promise<object|null>} the image shown, or null when it was refused (the status line says why)
     */
    async drape(image, worldFile = null, { url = null, throwRefusal = false } = {}) {
      if (!stage.current) return null;
      try {
        current = await open(image, worldFile);
        files = { image, worldFile, url };
        showStatus(current.note ? `${image.name}: ${current.note}` : '');
        changed();
        return current;
      } catch (error) {
        if (!(error instanceof ImageError)) throw error;
        showStatus(`${error.message}${current ? ` (${current.name} stays)` : ''}`, true);
        requestRender();
        if (throwRefusal) throw error;
        return null;
      }
    },

    /** The image goes; the procedural ground shows again. */
    remove() {
      if (!current && !files) return;
      renderer.imageTextures.remove();
      renderer.setImagePlacement(null);
      current = files = null;
      changed();
    },

    /** The graphics context came back without textures: the image shown is draped again. */
    async restore() {
      if (!files || !stage.current) return;
      const { image, worldFile } = files;
      try {
        current = await open(image, worldFile);
      } catch (error) {
        if (!(error instanceof ImageError)) throw error;
        current = files = null;
        showStatus(`${error.message} (after the graphics context came back)`, true);
      }
      changed();
    },
  };
}
