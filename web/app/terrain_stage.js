// The terrain on stage: shows a loaded terrain (its mesh, core settings, world, opening view)
// and keeps the cameras and the world in step when the heights or the ground spacing change.
// main.js makes one; the setting effects (setting_effects.js) call it.
import { createWorld } from '../cameras/ground.js';
import { frameTerrain } from '../cameras/framing.js';
import { coreSettings } from './settings_table.js';
import { FLAT_EARTH, earthShapeOf } from '../geo/index.js';

export class TerrainStage {
  /**
   * @param {object} parts canvas, renderer, rig, settings, layers (layers.js: the terrain shown is
   *   its terrain layer), pipeline, state, det, and
   *   syncPanel(), requestRender() and onShown(terrain) (the settings and the panel take the new
   *   terrain's cell size)
   */
  constructor(parts) {
    Object.assign(this, parts);
  }

  /** The terrain shown: { terrain, field, loadMs, tiles (a COG's read tile by tile, else absent), world, streamVersion, blendsEnd }. */
  get current() {
    return this.layers.ground;
  }

  /** Shows a loaded terrain; `from`: the URL it came from, null for a file (no URL to share). */
  show(loaded, from) {
    const { terrain, field } = loaded;
    this.fillVoids(terrain);
    this.rebuildMesh(terrain);
    this.current?.tiles?.close(); // its requests stop before its terrain goes
    this.current?.terrain.destroy();
    this.layers.terrain = { loaded, source: from };
    this.placeOnEarth();
    this.makeWorld();
    this.onShown(terrain);
    this.pipeline.forgetFigures(); // the last terrain's "converged" and triangles do not describe this one
    this.state.terrain = { name: field.source, width: terrain.width, height: terrain.height,
      minHeight: terrain.minHeight, maxHeight: terrain.maxHeight, tiled: field.tiled === true };
    this.state.tiles = null; // the frame loop publishes a tiled terrain's figures
    this.layers.changed('terrain'); // the HUD describes it
    // Framed once the HUD and the file bar describe this terrain: their heights bound the view,
    // and R frames it again with them as they are then.
    this.frameDefault();
    this.syncPanel();
    this.det?.setTerrain(terrain, field);
    this.requestRender();
  }

  /** Frees the terrain shown (its tile requests stop first): the viewer is disposed. */
  close() {
    this.current?.tiles?.close();
    this.current?.terrain.destroy();
    this.layers.terrain = null;
  }

  /**
   * A tiled terrain's voids as the no-data setting draws them: pits under holes (their walls make
   * the refinement follow a void's edge), else filled from the surface around them. A terrain
   * held whole was filled by its loader; its holes come from the loader's mask.
   */
  fillVoids(terrain) {
    if (terrain?.tiled) terrain.setVoidsAsPits(this.settings.nodata === 'holes');
  }

  /** A new mesh of the settings' embedding, with every core setting in one call; all uploaded anew. */
  rebuildMesh(terrain) {
    terrain.resetMesh(this.settings.embedding);
    terrain.configure(coreSettings(this.settings));
    this.renderer.invalidate();
  }

  /**
   * The surface the terrain is drawn on (web/geo/earth_shape.js): the curved Earth under a
   * georeferenced terrain unless the settings flatten it. The core refines for it, the renderer
   * and the cameras draw on it (web/cameras/on_the_earth.js).
   */
  placeOnEarth() {
    const loaded = this.current;
    if (!loaded) return;
    const { terrain, field } = loaded;
    const earth = this.settings.earth === 'flat' ? FLAT_EARTH : earthShapeOf(field.georef ?? null, terrain);
    terrain.setEarth(earth);
    loaded.earth = earth;
    if (loaded.world) loaded.world.earth = earth; // picking follows the drawn surface
    this.renderer.setEarth(earth);
    this.requestRender?.();
  }

  /** Heights and extent of the world in drawn metres, for the cameras (ground.js) and the shading. */
  makeWorld() {
    const { settings, rig, renderer } = this, loaded = this.current, { terrain } = loaded;
    const s = settings.exaggeration;
    const extent = { extentX: (terrain.width - 1) * terrain.spacingX, extentZ: (terrain.height - 1) * terrain.spacingY,
      low: terrain.minHeight * s, high: terrain.maxHeight * s };
    loaded.world = createWorld(terrain, extent, () => settings.exaggeration, () => 0.5 * rig.cameras.walk.eyeHeight);
    loaded.world.earth = loaded.earth ?? FLAT_EARTH;
    rig.setWorld(loaded.world);
    renderer.setShading(extent.low, extent.high, extent.extentX, extent.extentZ);
    renderer.setLattice(terrain.spacingX, terrain.spacingY, terrain.width, terrain.height);
    if (renderer.fieldTextures.terrain !== terrain || renderer.fieldTextures.spacing !== terrain.spacingX) {
      renderer.setField(terrain, loaded.field); // normals, shadows, occlusion from the field
    }
  }

  /** The opening view (framing.js): the field, or its region of most relief, in view from above. */
  frameDefault() {
    const { canvas, rig } = this, orbit = rig.cameras.orbit;
    const width = Math.max(canvas.clientWidth, 1), height = Math.max(canvas.clientHeight, 1);
    // The file bar along the top and the HUD along the bottom: the terrain opens between them.
    const bar = this.dom.byId('intake').getBoundingClientRect(), hudBox = this.dom.byId('hud').getBoundingClientRect();
    const covered = {
      top: bar.height > 0 ? Math.min(bar.bottom / height, 0.3) : 0,
      bottom: hudBox.height > 0 ? Math.min((height - hudBox.top) / height, 0.3) : 0,
    };
    frameTerrain(this.current.terrain, this.current.world, orbit, this.settings.exaggeration, width / height, covered);
    rig.active = orbit;
  }

  /** Scales the cameras' heights when the exaggeration changes from `from` to `to`. */
  rescaleHeights(from, to) {
    const k = to / from, cameras = this.rig.cameras;
    cameras.orbit.target[1] *= k;
    cameras.fly.position[1] *= k;
    cameras.walk.position[1] *= k;
  }

  /** Scales the cameras' ground positions when the cell size changes by `k`. */
  rescaleGround(k) {
    const cameras = this.rig.cameras;
    for (const p of [cameras.orbit.target, cameras.fly.position, cameras.walk.position]) {
      p[0] *= k;
      p[2] *= k;
    }
    cameras.orbit.distance *= k;
  }

  /** Lifts the active camera out of the ground after the ground's heights changed. */
  keepCamerasAboveGround() {
    const camera = this.rig.active, margin = this.current.world.spacing * 0.05;
    if (camera.mode === 'walk') camera.settle();
    else camera.keepAboveGround(camera.mode === 'orbit' ? Math.max(margin, 0.01 * camera.distance) : margin);
  }
}
