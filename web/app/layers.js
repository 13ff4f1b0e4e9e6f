// What the page shows, in drawing order: the terrain, the image layers draped on it, and (next)
// the vector overlays over both. The one answer to "what is shown": the frame pipeline draws the
// terrain it holds, the address bar names its sources, the HUD describes its layers (told by
// onChange), and a drop replaces its terrain or adds a layer over it (ui/picked_files.js). The
// terrain stage (terrain_stage.js) and the image stage (image_stage.js) fill it and say what
// changed; nothing else keeps a copy.

export class Layers {
  constructor() {
    /** The terrain shown: { loaded: { terrain, field, loadMs, world, tiles, ... }, source: its URL or null }, or null. */
    this.terrain = null;
    /**
     * Image layers, bottom first: [{ image: the DrapedImage (imagery/open_image.js), files:
     * { image, worldFile, url }, description: its HUD line }]. Every layer over the terrain
     * carries its description: the HUD lists them as they are.
     */
    this.images = [];
    /**
     * Overlays drawn over the terrain, bottom first: [{ description: its HUD line, draw(gl,
     * camera, width, height, verticalScale), createGlObjects(gl) }]; the renderer draws them
     * each frame (render/renderer.js draw). None yet.
     */
    this.overlays = [];
    this.listeners = [];
  }

  /** Calls listener(layers, part) after each change; part: 'terrain', 'images' or 'overlays'. */
  onChange(listener) {
    this.listeners.push(listener);
  }

  /** Tells the listeners `part` changed: 'terrain' (a new one, or its scale), 'images' or 'overlays'. */
  changed(part) {
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

  /** The URL of the top image layer (the address bar's image), or null. */
  get imageUrl() {
    return this.images.at(-1)?.files.url ?? null;
  }
}
