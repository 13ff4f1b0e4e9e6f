// What the mouse pointer does besides the cameras' drags: the readout of the ground under it
// (x, z, height and slope in the HUD, at most every 50 ms) and a double click, which orbits
// around the point under the pointer.
import { pickGround } from '../cameras/picking.js';

const READOUT_INTERVAL_MS = 50;

/**
 * @param {HTMLCanvasElement} canvas
 * @param {{ rig: import('../cameras/rig.js').CameraRig, terrain: () => object | null, settings: object,
 *   onCursor: (pick: object | null) => void, onOrbit: () => void }} page `terrain()` is the loaded
 *   terrain ({ terrain, world }) or null; onCursor gets each readout; onOrbit follows a double click.
 */
export function installPointerReadout(canvas, { rig, terrain, settings, onCursor, onOrbit }) {
  const pick = (e) => {
    const loaded = terrain();
    if (!loaded) return null;
    const rect = canvas.getBoundingClientRect();
    return pickGround(rig.active, e.clientX - rect.left, e.clientY - rect.top, rect.width, rect.height,
      loaded.terrain, loaded.world, settings.exaggeration);
  };
  let lastPick = 0;
  canvas.addEventListener('pointermove', (e) => {
    if (!terrain() || e.pointerType === 'touch' || e.timeStamp - lastPick < READOUT_INTERVAL_MS) return;
    lastPick = e.timeStamp;
    onCursor(pick(e));
  });
  canvas.addEventListener('dblclick', (e) => {
    const point = pick(e);
    if (!point) return;
    if (rig.mode !== 'orbit') rig.setMode('orbit');
    rig.cameras.orbit.lookAround(point.x, point.height * settings.exaggeration, point.z);
    onOrbit();
  });
}
