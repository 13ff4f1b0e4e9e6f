// What createViewer() hands back: one viewer's handle. It opens terrains, images and overlays
// (by URL or as File objects), flies the camera, changes settings, takes screenshots, tells its
// events to listeners, and dispose() frees everything the viewer holds: its terrain in the
// WebAssembly core, its GL context, its listeners on the page and its elements.
import { geoCoordinates } from '../geo/index.js';
import { prefersReducedMotion } from '../cameras/camera_flight.js';
import { captureView } from '../app/screenshot.js';
import { checkSettingValue, describe } from './arguments.js';

/** The events a viewer tells: a terrain was shown, a frame drawn, something failed, the ground was clicked. */
export const EVENTS = ['loaded', 'frame', 'error', 'pick'];

export class ViewerHandle {
  /** @param {HTMLElement} root the viewer's element */
  constructor(root) {
    this.root = root;
    this.parts = null;
    this.listeners = new Map(EVENTS.map((type) => [type, new Set()]));
    const handle = this;
    /** The camera: flyTo(), get(), reset(). Positions are metres: x east from the first sample, y up, z south. */
    this.camera = {
      flyTo: (view, options) => handle.flyTo(view, options),
      get: () => handle.cameraPose(),
      reset: () => handle.live().resetView(),
    };
  }

  /** The parts of a viewer that is not disposed (viewer.js assemble()). */
  live() {
    if (!this.parts) throw new Error('this viewer is disposed');
    return this.parts;
  }

  attach(parts) {
    this.parts = parts;
  }

  /** Calls `handler(detail)` on each `type` event; returns a function that stops it. */
  on(type, handler) {
    if (!this.listeners.has(type)) throw new RangeError(`viewer.on: unknown event '${type}' (${EVENTS.join(', ')})`);
    if (typeof handler !== 'function') throw new TypeError(`viewer.on: the handler must be a function, not ${describe(handler)}`);
    this.listeners.get(type).add(handler);
    return () => this.off(type, handler);
  }

  off(type, handler) {
    this.listeners.get(type)?.delete(handler);
  }

  /** Tells the listeners; one that throws does not stop the others or the viewer. */
  emit(type, detail) {
    const handlers = this.listeners.get(type);
    if (handlers.size === 0) return; // the page's frame path: no iterator made when nobody listens
    for (const handler of handlers) {
      try {
        handler(type === 'frame' ? this.frameFigures(detail) : type === 'loaded' ? { terrain: this.terrain } : detail);
      } catch (error) {
        console.error(error);
      }
    }
  }

  /** A frame's figures: { frames, triangles, converged, tau, frameMs } (one object, filled anew each frame). */
  frameFigures(state) {
    const figures = this.figures ??= { frames: 0, triangles: 0, converged: false, tau: 0, frameMs: 0 };
    figures.frames = state.frames;
    figures.triangles = state.triangles;
    figures.converged = state.converged === true;
    figures.tau = state.lod?.tau ?? 0;
    figures.frameMs = state.timing?.frameMs ?? 0;
    return figures;
  }

  /** The terrain shown: { name, width, height, spacingX, spacingY, minHeight, maxHeight, crs, centre, tiled }, or null. */
  get terrain() {
    const loaded = this.parts?.stage.current;
    if (!loaded) return null;
    const { terrain, field } = loaded;
    const georef = field.georef ?? null;
    const centre = geoCoordinates(georef, ((terrain.width - 1) / 2) * terrain.spacingX, ((terrain.height - 1) / 2) * terrain.spacingY,
      terrain.spacingX, terrain.spacingY);
    return { name: field.source, width: terrain.width, height: terrain.height, spacingX: terrain.spacingX, spacingY: terrain.spacingY,
      minHeight: terrain.minHeight, maxHeight: terrain.maxHeight, crs: georef?.crs?.label ?? null,
      centre: centre && centre.lat !== null ? { lon: centre.lon, lat: centre.lat } : null, tiled: field.tiled === true };
  }

  /** A copy of the settings in force. */
  get settings() {
    return { ...this.live().settings };
  }

  /** The canvas the viewer draws into. */
  get canvas() {
    return this.live().dom.byId('view');
  }

  /** Changes a setting live, as the panel does; throws a TypeError or RangeError for a bad value. */
  set(key, value) {
    const parts = this.live();
    const checked = checkSettingValue(key, value, 'viewer.set');
    if (!parts.change(key, checked)) throw new RangeError(`viewer.set: ${parts.state.error ?? `${key} was refused`}`);
  }

  /**
   * Opens a height field (with its sidecars when given several files) instead of the terrain
   * shown. Resolves to the new terrain; rejects with the reason when it is refused (the old
   * terrain and the settings stay).
   * @param {string|File|File[]} source  a URL, or files as if dropped together
   */
  async open(source) {
    const { intake, state } = this.live();
    const outcome = typeof source === 'string' ? await intake.openUrl(source) : await intake.openFiles(filesOf(source, 'open'));
    return this.outcome(outcome, state);
  }

  /** Drapes an image (a URL, or a File with its world file and .prj as further Files) over the terrain. */
  async drape(source) {
    const { intake, state } = this.live();
    const before = state.error;
    const outcome = typeof source === 'string' ? await intake.openImageUrl(source) : await intake.openFiles(filesOf(source, 'drape'));
    if (outcome === 'shown' && state.error !== before && state.error) throw new Error(state.error);
    return this.outcome(outcome, state);
  }

  /** Adds a GPX, KML, KMZ or GeoJSON overlay (a URL or a File); resolves to its name and feature count. */
  async addOverlay(source) {
    const { overlays } = this.live();
    let layer;
    if (typeof source === 'string') layer = await overlays.addUrl(source, { throwRefusal: true });
    else {
      const [file] = filesOf(source, 'addOverlay');
      layer = await overlays.add({ name: file.name, bytes: new Uint8Array(await file.arrayBuffer()) }, { throwRefusal: true });
    }
    return { name: layer.name, features: layer.overlay.features.length };
  }

  outcome(outcome, state) {
    if (outcome === 'shown') return this.terrain;
    if (outcome === 'cancelled') throw new DOMException('the load was cancelled by a newer one', 'AbortError');
    throw new Error(state.error ?? 'the file was refused');
  }

  /**
   * Flies the camera to look at `target` from `position` (metres) in `seconds` (default 2; at
   * once when the person prefers reduced motion). Resolves to whether it arrived.
   */
  flyTo(view, { seconds = 2 } = {}) {
    const { rig } = this.live();
    const point = (name) => {
      const p = view?.[name];
      if (!Array.isArray(p) && !ArrayBuffer.isView(p)) throw new TypeError(`camera.flyTo: ${name} must be [x, y, z] in metres, not ${describe(p)}`);
      if (p.length !== 3 || ![...p].every(Number.isFinite)) throw new RangeError(`camera.flyTo: ${name} must be three finite numbers`);
      return [...p];
    };
    const position = point('position'), target = point('target');
    if (Math.hypot(position[0] - target[0], position[1] - target[1], position[2] - target[2]) < 1e-3) {
      throw new RangeError('camera.flyTo: the position and the target are the same point');
    }
    if (typeof seconds !== 'number' || !(seconds >= 0) || seconds > 600) throw new RangeError('camera.flyTo: seconds must be a number from 0 to 600');
    const flight = rig.flyTo({ position, target }, prefersReducedMotion() ? 0 : seconds);
    this.parts.syncPanel();
    return flight;
  }

  /** The camera as it is: { mode, position, target } in metres. */
  cameraPose() {
    const { rig } = this.live();
    const camera = rig.active;
    camera.update(camera.aspect ?? 1);
    return { mode: camera.mode, position: [...camera.position], target: [...camera.target] };
  }

  /** The view as a PNG Blob at `scale` × the canvas's size. */
  async screenshot({ scale = 1 } = {}) {
    const { gl, rig, renderer, view, layers, requestRender } = this.live();
    if (![1, 2, 3, 4].includes(scale)) throw new RangeError('viewer.screenshot: scale must be 1, 2, 3 or 4');
    const camera = rig.active;
    const blob = await captureView(gl, scale, (width, height) => {
      camera.update(width / height);
      renderer.draw(camera, width, height, view, layers);
    });
    requestRender();
    return blob;
  }

  /** The WebAssembly core's memory in bytes (it grows with the terrain and never shrinks). */
  memory() {
    return { wasmBytes: this.live().core.buffer.byteLength };
  }

  /** Frees the viewer: its terrain and layers, the WebAssembly memory, the GL context, every listener, its elements. */
  dispose() {
    const parts = this.parts;
    if (!parts) return;
    this.parts = null;
    const { pipeline, rig, dom, stage, images, overlays, layers, gl } = parts;
    pipeline.stop();
    rig.stopFlight();
    dom.dispose();
    for (const layer of [...layers.overlays]) overlays.remove(layer);
    for (const layer of [...layers.images]) images.remove(layer.id); // image files and web map tiles
    stage.close();
    gl.getExtension('WEBGL_lose_context')?.loseContext(); // the GPU's memory now, not when the canvas is collected
    this.root.remove();
    this.root = null; // a handle kept by the page must not keep the elements, whose listeners reach the core
    for (const set of this.listeners.values()) set.clear();
  }
}

/** The File objects of an API call's source, or a TypeError. */
function filesOf(source, caller) {
  const list = Array.isArray(source) ? source : [source];
  if (list.length === 0 || !list.every((f) => typeof File !== 'undefined' && f instanceof File)) {
    throw new TypeError(`viewer.${caller}: give a URL string, a File or an array of Files, not ${describe(source)}`);
  }
  return list;
}
