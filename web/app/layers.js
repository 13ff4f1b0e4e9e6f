// What the page shows, in drawing order: the terrain, the image layers draped on it (image
// files and web map tiles), and the vector overlays over both. The one answer to "what is
// shown": the frame pipeline draws the terrain and the visible image layers it holds, the
// address bar names its sources, the HUD and the panel list its layers (told by onChange), and
// a drop replaces its terrain or adds layers over it (ui/picked_files.js). The terrain stage
// (terrain_stage.js) and the image stage (image_stage.js) fill it and say what changed;
// nothing else keeps a copy.
import { MAX_DRAPES } from '../render/shading/drape_layers.js';

export { MAX_DRAPES };

export class Layers {
  constructor() {
    /** The terrain shown: { loaded: { terrain, field, loadMs, world, tiles, ... }, source: its URL or null }, or null. */
    this.terrain = null;
    /**
     * Image layers, bottom first: [{ id, kind: 'image'|'tiles', name, description (its HUD
     * line), visible, opacity, url (where it came from, for the address bar; null for a file),
     * drape (what the renderer draws: render/shading/drape_layers.js Drape), ... its stage's own }].
     */
    this.images = [];
    /**
     * Overlays drawn over the terrain, bottom first: [{ description: its HUD line, draw(gl,
     * camera, width, height, verticalScale), createGlObjects(gl), fill (its polygons' drape, or
     * null), url }]; the renderer draws them each frame (render/renderer.js draw).
     */
    this.overlays = [];
    /** The visible image layers' drapes, then the overlays' polygon fills, bottom first, at most MAX_DRAPES: made again at each change, read each frame. */
    this.drapes = [];
    /** The image layers that came from an address, bottom first, as the address bar names them: [{ kind, url }]. */
    this.layerUrls = [];
    /** The overlays that came from an address, bottom first (the address bar's overlay=). */
    this.overlayUrls = [];
    this.listeners = [];
  }

  /** Calls listener(layers, part) after each change; part: 'terrain', 'images' or 'overlays'. */
  onChange(listener) {
    this.listeners.push(listener);
  }

  /** Tells the listeners `part` changed: 'terrain' (a new one, or its scale), 'images' or 'overlays'. */
  changed(part) {
    if (part === 'images' || part === 'overlays') {
      // The overlays' polygon fills lie on the ground over the images.
      const fills = this.overlays.filter((layer) => layer.visible && layer.fill).map((layer) => layer.fill);
      this.drapes = [...this.images.filter((layer) => layer.visible && layer.drape).slice(0, MAX_DRAPES).map((layer) => layer.drape), ...fills]
        .slice(0, MAX_DRAPES);
    }
    if (part === 'images') {
      this.layerUrls = this.images.filter((layer) => layer.url).map((layer) => ({ kind: layer.kind, url: layer.url }));
    }
    if (part === 'overlays') this.overlayUrls = this.overlays.filter((layer) => layer.url).map((layer) => layer.url);
    for (const listener of this.listeners) listener(this, part);
  }

  /** The loaded terrain on screen ({ terrain, field, loadMs, world, tiles, ... }), or null. */
  get ground() {
    return this.terrain?.loaded ?? null;
  }

  /** The URL the terrain came from (the address bar's src), or null for a file. */
  get source() {
    return this.terrain?.source ?? null;
  }

}
