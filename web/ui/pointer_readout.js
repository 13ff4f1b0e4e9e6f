// What the mouse pointer does besides the cameras' drags: the readout of the ground under it
// (x, z, height and slope in the HUD, at most every 50 ms) and a double click, which orbits
// around the point under the pointer (not while the measuring tool takes the clicks). The readout
// carries the point's real coordinates when the field has a georeference (web/geo/coordinates.js).
import { pickGround } from '../cameras/picking.js';
import { geoCoordinates, formatCoordinates } from '../geo/index.js';

const READOUT_INTERVAL_MS = 50;
const CLICK_SLOP_PX = 4; // a press that moved further was a drag, not a click

/**
 * @param {HTMLCanvasElement} canvas
 * @param {{ rig: import('../cameras/rig.js').CameraRig, terrain: () => object | null, settings: object,
 *   onCursor: (pick: object | null) => void, onPick?: (pick: object) => void, onOrbit: () => void, measuring: () => boolean }} page
 *   `terrain()` is the loaded terrain ({ terrain, field, world }) or null; onCursor gets each
 *   readout (with `place`, the coordinates as text); onPick the ground under a click; onOrbit
 *   follows a double click.
 */
export function installPointerReadout(canvas, { rig, terrain, settings, onCursor, onPick = null, onOrbit, measuring }) {
  const pick = (e) => {
    const loaded = terrain();
    if (!loaded) return null;
    const rect = canvas.getBoundingClientRect();
    const point = pickGround(rig.active, e.clientX - rect.left, e.clientY - rect.top, rect.width, rect.height,
      loaded.terrain, loaded.world, settings.exaggeration);
    if (point) {
      const t = loaded.terrain;
      point.place = formatCoordinates(geoCoordinates(loaded.field.georef ?? null, point.x, point.z, t.spacingX, t.spacingY));
    }
    return point;
  };
  let lastPick = 0;
  canvas.addEventListener('pointermove', (e) => {
    if (!terrain() || e.pointerType === 'touch' || e.timeStamp - lastPick < READOUT_INTERVAL_MS) return;
    lastPick = e.timeStamp;
    onCursor(pick(e));
  });
  // A click (not the end of a drag) picks the ground under it: the JS API's 'pick' event.
  let pressedAt = null;
  canvas.addEventListener('pointerdown', (e) => { pressedAt = [e.clientX, e.clientY]; });
  canvas.addEventListener('click', (e) => {
    if (!onPick || !pressedAt || Math.hypot(e.clientX - pressedAt[0], e.clientY - pressedAt[1]) > CLICK_SLOP_PX) return;
    const point = pick(e);
    if (point) onPick(point);
  });
  canvas.addEventListener('dblclick', (e) => {
    if (measuring()) return; // the measuring tool's double click ends its line
    const point = pick(e);
    if (!point) return;
    if (rig.mode !== 'orbit') rig.setMode('orbit');
    rig.cameras.orbit.lookAround(point.x, point.height * settings.exaggeration, point.z);
    onOrbit();
  });
}
