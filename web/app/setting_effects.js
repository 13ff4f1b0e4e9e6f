// What applying a setting does, one handler per effect of the settings table
// (settings_table.js): applying one is a lookup of its effect, never a chain of key tests.
// SettingsOwner calls apply() after checking the value; a handler throws when it cannot apply,
// and the owner then keeps the previous value.
import { SETTINGS, coreSettings } from './settings_table.js';

/**
 * @param {import('./terrain_stage.js').TerrainStage} stage the terrain on stage and its cameras
 * @param {{ rescaleMeasure: (k: number) => void, showSpacing: (terrain: object) => void }} hooks
 *   a new cell size moves the measured line with the ground (the measuring tool) and shows the
 *   spacing in the file bar (the file intake)
 * @returns {(key: string, value: any, previous: any) => void}
 */
export function settingEffects(stage, { rescaleMeasure, showSpacing }) {
  const { settings, rig, renderer, layers } = stage;
  const terrain = () => stage.current?.terrain;
  const EFFECTS = {
    // Every core setting in one call: the core keeps its previous settings when it refuses.
    core() {
      terrain()?.configure(coreSettings(settings));
    },
    // No mesh rebuild: the shader scales the heights; the cameras and the world follow.
    heights(key, value, previous) {
      stage.rescaleHeights(previous, value);
      if (!terrain()) return;
      terrain().configure(coreSettings(settings));
      stage.makeWorld();
      stage.keepCamerasAboveGround(); // taller hills may now stand where the eye is
    },
    camera(key, value) {
      if (key === 'eyeHeight') rig.cameras.walk.eyeHeight = value;
    },
    view() {}, // deriveView (view_state.js) picks it up after every change
    nodata() { // and the view, as for every change
      stage.fillVoids(terrain());
    },
    mesh() {
      if (terrain()) stage.rebuildMesh(terrain());
    },
    // The value as typed between columns, rows in ratio; the ground positions scale with it.
    ground(key, value) {
      const t = terrain();
      if (!t) return;
      const loaded = stage.current, k = value / t.spacingX;
      t.setScale({ ...loaded.field, spacingX: value, spacingY: t.spacingY * k });
      stage.rescaleGround(k);
      stage.makeWorld();
      rescaleMeasure(k); // the measured line stays on the same samples
      stage.keepCamerasAboveGround();
      renderer.invalidate();
      layers.changed('terrain'); // the HUD describes the new spacing
      stage.placeOnEarth(); // a geographic grid's metres per degree changed
      showSpacing(t);
    },
    earth() {
      stage.placeOnEarth();
    },
    tiles(key, value) {
      stage.current?.tiles?.setCapBytes(value * 2 ** 20);
    },
    none() {},
  };
  return (key, value, previous) => EFFECTS[SETTINGS[key].effect](key, value, previous);
}
