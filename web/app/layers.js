// What the page shows, in drawing order: the terrain, the image layers draped on it, and (next)
// the vector overlays over both. The one answer to "what is shown": the frame pipeline draws the
// terrain it holds, the address bar names its sources, the HUD and the panel describe its
// layers, and a drop replaces the terrain or adds a layer to it. The terrain stage
// (terrain_stage.js) and the image stage (image_stage.js) fill it; nothing else keeps a copy.

export class Layers {
  constructor() {
    /** The terrain shown: { loaded: { terrain, field, loadMs, world, tiles, ... }, source: its URL or null }, or null. */
    this.terrain = null;
    /** Image layers, bottom first: [{ image: the DrapedImage (imagery/open_image.js), files: { image, worldFile, url } }]. */
    this.images = [];
    /** Vector overlays, bottom first (none yet). */
    this.overlays = [];
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
