// The view in the address bar, so that a link shares it and a reload restores it exactly:
//   tau, budget, exag, ...     the settings with a URL key (settings_table.js)
//   cam=orbit,x,y,z,distance,yaw,pitch   or   cam=fly|walk,x,y,z,yaw,pitch   metres, radians
//   src=URL                    the data source, when it came from a URL
//   image=URL, tiles=TEMPLATE  the image layers draped on it that came from an address, bottom
//                              first (each repeatable, in any order: the order is the layers')
//   overlay=URL                GPX, KML, KMZ or GeoJSON overlays from an address, bottom first (repeatable)
//   measure=p:x,z;x,z;...      the measured path (a: for an area), metres (web/ui/measure_tool.js)
//   timeout, maxmb, layout     only when not the defaults
// Other parameters (timing, flight, test) are kept as they are. Every value is checked: a bad one
// gets a message and its default.
import { SETTINGS, URL_KEYS, checkSetting } from './settings_table.js';
import { MIN_PITCH, MAX_PITCH } from '../cameras/orbit.js';
import { parseMeasureParam } from '../ui/measure_tool.js';

const WRITE_EVERY_MS = 300;
const LAYER_KEYS = { image: 'image', tiles: 'tiles' }; // parameter -> the kind of image layer it adds
const LIMIT = 1e9; // metres: past this a position is not a place on any terrain

/**
 * Reads the view from a query string.
 * @returns {{settings: object, camera: object|null, src: string|null,
 *   layers: Array<{kind: 'image'|'tiles', url: string}>, overlays: string[], measure: {kind: string, points: number[][]}|null,
 *   errors: string[]}}
 */
export function parseUrlState(search) {
  const params = new URLSearchParams(search);
  const layers = [...params].filter(([key, value]) => LAYER_KEYS[key] && value !== '').map(([key, url]) => ({ kind: LAYER_KEYS[key], url }));
  const overlays = params.getAll('overlay').filter((url) => url !== '');
  const result = { settings: {}, camera: null, src: params.get('src'), layers, overlays, measure: null, errors: [] };
  if (params.has('measure')) {
    const measure = parseMeasureParam(params.get('measure'));
    if (measure instanceof Error) result.errors.push(measure.message);
    else result.measure = measure;
  }
  for (const [key, name] of URL_KEYS) {
    if (!params.has(name)) continue;
    const value = checkSetting(key, params.get(name));
    if (value instanceof Error) result.errors.push(value.message);
    else result.settings[key] = value;
  }
  if (params.has('cam')) {
    const camera = parseCamera(params.get('cam'));
    if (camera instanceof Error) result.errors.push(camera.message);
    else result.camera = camera;
  }
  return result;
}

function parseCamera(text) {
  const [mode, ...rest] = text.split(',');
  const numbers = rest.map(Number);
  const bad = (why) => new Error(`cam=${text}: ${why}; expected orbit,x,y,z,distance,yaw,pitch or fly|walk,x,y,z,yaw,pitch`);
  if (!['orbit', 'fly', 'walk'].includes(mode)) return bad(`unknown camera '${mode}'`);
  const count = mode === 'orbit' ? 6 : 5;
  if (numbers.length !== count || numbers.some((n, k) => rest[k].trim() === '' || !Number.isFinite(n))) {
    return bad(`${count} numbers needed`);
  }
  if (numbers.slice(0, 3).some((n) => Math.abs(n) > LIMIT)) return bad('a position beyond a million kilometres');
  const [x, y, z] = numbers;
  if (mode === 'orbit') {
    const [, , , distance, yaw, pitch] = numbers;
    if (!(distance > 0 && distance < LIMIT)) return bad('the distance must be positive');
    if (pitch < MIN_PITCH || pitch > MAX_PITCH) return bad(`the pitch must be from ${MIN_PITCH} to ${MAX_PITCH}`);
    return { mode, target: [x, y, z], distance, yaw, pitch };
  }
  const [, , , yaw, pitch] = numbers;
  if (Math.abs(pitch) > 1.55) return bad('the pitch must be from -1.55 to 1.55');
  return { mode, position: [x, y, z], yaw, pitch };
}

/** The camera as its `cam` parameter. */
export function cameraParam(camera) {
  const fixed = (v, digits) => Number(v.toFixed(digits));
  const values = camera.mode === 'orbit'
    ? [...camera.target, camera.distance].map((v) => fixed(v, 3)).concat([camera.yaw, camera.pitch].map((v) => fixed(v, 6)))
    : [...camera.position].map((v) => fixed(v, 3)).concat([camera.yaw, camera.pitch].map((v) => fixed(v, 6)));
  return [camera.mode, ...values].join(',');
}

/** Puts a parsed camera state on the rig's camera of that mode, and makes it active. */
export function applyCameraState(rig, state) {
  const camera = rig.cameras[state.mode];
  if (state.mode === 'orbit') {
    camera.target.set(state.target);
    Object.assign(camera, { distance: state.distance, yaw: state.yaw, pitch: state.pitch });
  } else {
    camera.position.set(state.position);
    Object.assign(camera, { yaw: state.yaw, pitch: state.pitch });
  }
  rig.active = camera;
}

/**
 * Writes the view into the address bar with history.replaceState, at most every WRITE_EVERY_MS.
 * write() runs every frame: it only notes what to write (no object, no closure per call).
 */
export class UrlWriter {
  /** @param {{ addressBar?: boolean }} [options] addressBar: false for a viewer in someone else's page, whose address is theirs */
  constructor({ addressBar = true } = {}) {
    this.addressBar = addressBar;
    this.timer = null;
    this.pending = false;
    this.settings = null;
    this.camera = null;
    this.src = null;
    this.layerUrls = [];
    this.overlayUrls = [];
    this.measure = null; // the measured line's `measure` value, set by the measuring tool when it changes
    this.flushLater = () => this.flush();
  }

  /**
   * @param {object} settings @param {object} camera the active camera @param {string|null} src the data's URL
   * @param {Array<{kind: 'image'|'tiles', url: string}>} [layerUrls] the image layers that came from an address, bottom first
   * @param {string[]} [overlayUrls] the overlays that came from an address, bottom first
   */
  write(settings, camera, src, layerUrls = [], overlayUrls = []) {
    if (!this.addressBar) return;
    this.settings = settings;
    this.camera = camera;
    this.src = src;
    this.layerUrls = layerUrls;
    this.overlayUrls = overlayUrls;
    this.pending = true;
    if (this.timer === null) this.timer = setTimeout(this.flushLater, WRITE_EVERY_MS);
  }

  flush() {
    clearTimeout(this.timer);
    this.timer = null;
    if (!this.pending) return;
    const { settings, camera, src, layerUrls, overlayUrls } = this;
    this.pending = false;
    const params = new URLSearchParams(location.search);
    for (const [key, name] of URL_KEYS) {
      if (SETTINGS[key].urlIfChanged && settings[key] === SETTINGS[key].default) params.delete(name);
      else params.set(name, String(settings[key]));
    }
    params.set('cam', cameraParam(camera));
    if (src) params.set('src', src); else params.delete('src');
    for (const key of Object.keys(LAYER_KEYS)) params.delete(key);
    for (const { kind, url } of layerUrls) params.append(kind, url);
    params.delete('overlay');
    for (const url of overlayUrls) params.append('overlay', url);
    params.delete('measure');
    // The measured line goes last and as it is (digits and , ; : need no escaping): readable.
    const measure = this.measure ? `&measure=${this.measure}` : '';
    const url = `${location.pathname}?${params.toString().replace(/%2C/g, ',')}${measure}${location.hash}`;
    history.replaceState(null, '', url);
  }
}
