// The pointer over the overlays: hovering a feature shows its name and properties beside the
// pointer; clicking a line shows its profile in the measuring panel (overlay_tracks.js). The
// ground point under the pointer (cameras/picking.js) finds the feature (overlays/
// nearest_feature.js) within a few pixels at that distance, so a line is as easy to hit near
// as far.
import { pickGround } from '../cameras/picking.js';
import { nearestFeature } from '../overlays/nearest_feature.js';

const HOVER_EVERY_MS = 50;
const REACH_PX = 8;      // how near the pointer must come to a line or point, in CSS pixels
const CLICK_PX = 6;      // a press that moves farther is a drag (the camera's), not a click
const MAX_PROPERTIES = 10;

/**
 * @param {HTMLCanvasElement} canvas
 * @param {{ rig: object, settings: object, terrain: () => object|null, layers: import('./layers.js').Layers,
 *   tip: HTMLElement, measuring: () => boolean, showTrack: (layer: object, feature: number, path: number) => void }} page
 *   measuring: whether the measuring tool takes clicks (it asks lineAt itself then)
 * @returns {{ lineAt(clientX: number, clientY: number): boolean }}
 */
export function installOverlayPointer(canvas, { rig, settings, terrain, layers, tip, measuring, showTrack }) {
  /** The feature under client (x, y), or null. */
  function featureAt(clientX, clientY) {
    const loaded = terrain();
    if (!loaded || layers.overlays.length === 0) return null;
    const rect = canvas.getBoundingClientRect();
    const camera = rig.active;
    const point = pickGround(camera, clientX - rect.left, clientY - rect.top, rect.width, rect.height, loaded.terrain, loaded.world,
      settings.exaggeration);
    if (!point) return null;
    const p = camera.position, distance = Math.hypot(point.x - p[0], point.height * settings.exaggeration - p[1], point.z - p[2]);
    const metresPerPixel = (2 * Math.tan(camera.fovY / 2) * distance) / Math.max(1, rect.height);
    const found = nearestFeature(layers.overlays, point.x, point.z, REACH_PX * metresPerPixel); // other kinds have no geometry
    return found ? { ...found, layer: layers.overlays[found.overlay] } : null;
  }

  function showTip(found, clientX, clientY) {
    if (!found) {
      tip.hidden = true;
      return;
    }
    const feature = found.layer.overlay.features[found.feature];
    const title = document.createElement('strong');
    title.textContent = feature.name ?? `${feature.kind} ${found.feature + 1}`;
    const lines = Object.entries(feature.properties ?? {}).filter(([key, value]) => key !== 'name' && value !== null && typeof value !== 'object')
      .slice(0, MAX_PROPERTIES).map(([key, value]) => `${key}: ${String(value).slice(0, 80)}`);
    lines.push(`${found.layer.name}${feature.kind === 'line' ? ' · click for its profile' : ''}`);
    tip.replaceChildren(title, document.createTextNode(lines.join('\n')));
    tip.hidden = false;
    const x = Math.min(clientX + 14, window.innerWidth - tip.offsetWidth - 4), y = Math.min(clientY + 14, window.innerHeight - tip.offsetHeight - 4);
    tip.style.transform = `translate(${Math.max(0, x)}px, ${Math.max(0, y)}px)`;
  }

  /** Shows the profile of the line under client (x, y); false when there is none. */
  function lineAt(clientX, clientY) {
    const found = featureAt(clientX, clientY);
    if (!found || found.kind !== 'line') return false;
    showTrack(found.layer, found.feature, found.path);
    return true;
  }

  let last = 0;
  canvas.addEventListener('pointermove', (e) => {
    if (e.pointerType === 'touch' || e.buttons !== 0 || e.timeStamp - last < HOVER_EVERY_MS) return;
    last = e.timeStamp;
    showTip(featureAt(e.clientX, e.clientY), e.clientX, e.clientY);
  });
  canvas.addEventListener('pointerleave', () => showTip(null));
  let press = null;
  canvas.addEventListener('pointerdown', (e) => { press = e.button === 0 ? { x: e.clientX, y: e.clientY } : null; });
  canvas.addEventListener('pointerup', (e) => {
    const click = press && Math.hypot(e.clientX - press.x, e.clientY - press.y) <= CLICK_PX;
    press = null;
    if (click && !measuring()) lineAt(e.clientX, e.clientY);
  });
  return { lineAt };
}
