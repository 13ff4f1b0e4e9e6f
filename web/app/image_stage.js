// The draped image of the terrain on screen: opened onto it (web/imagery/open_image.js), its
// textures in the renderer, its note or refusal in the status line. A refused image leaves the
// one shown before.
import { openImage } from '../imagery/open_image.js';
import { ImageError } from '../imagery/image_error.js';

/**
 * @param {{ renderer: object, stage: { current: object|null }, showStatus: (message: string, isError?: boolean) => void,
 *   requestRender: () => void }} page
 */
export function createImageStage({ renderer, stage, showStatus, requestRender }) {
  let current = null;
  return {
    /** The image draped now (DrapedImage of open_image.js), or null. */
    get current() { return current; },

    /**
     * Drapes an image ({ name, blob }) with its world file (or null) on the terrain on screen.
     * @param {{ throwRefusal?: boolean }} [options] throwRefusal: a refusal is also thrown (a
     *   regression flight fails with it rather than fly without its image)
     * @returns {Promise<object|null>} the image shown, or null when it was refused (the status line says why)
     */
    async drape(image, worldFile = null, { throwRefusal = false } = {}) {
      const loaded = stage.current;
      if (!loaded) return null;
      const { terrain, field } = loaded;
      const ground = { width: terrain.width, height: terrain.height, spacingX: terrain.spacingX, spacingY: terrain.spacingY, georef: field.georef ?? null };
      try {
        current = await openImage(image, worldFile, ground, renderer.imageTextures);
        renderer.setImagePlacement(current.placement);
        showStatus(current.note ? `${image.name}: ${current.note}` : '');
      } catch (error) {
        if (!(error instanceof ImageError)) throw error;
        showStatus(error.message, true);
        if (!renderer.imageTextures.ready) { current = null; renderer.setImagePlacement(null); }
        if (throwRefusal) throw error;
      }
      requestRender();
      return current;
    },

    /** The image goes; the procedural ground shows again. */
    remove() {
      renderer.imageTextures.remove();
      renderer.setImagePlacement(null);
      current = null;
      requestRender();
    },
  };
}
