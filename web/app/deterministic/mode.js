// The page's deterministic mode, for headless regression tests (`hexlod regress`): on with
// `?flight=URL` (a flight file, see flight.js). It replaces what varies from run to run:
// - the clock: frame n shows the flight at time n / fps, whatever the wall time;
// - the budget: an operation budget per LOD update, no time budget, no auto tau;
// - the viewport: the canvas has a fixed size in device pixels (the flight's viewport times its
//   dpr, or ?viewport=WxH and ?dpr=N), whatever the window's size and devicePixelRatio;
// - the camera: the flight's path (user input is ignored);
// - frames are drawn only when asked for, through window.hexlod.flight (see install()).
// - the image layers: the flight's, added bottom first once the terrain is shown and before the
//   flight starts.
// URL parameters: flight=URL (required), viewport=WxH (CSS pixels), dpr=N, ops=N (operations
// per LOD update); they override the flight file's values. src=URL picks the terrain as usual;
// imageK=URL and worldK=URL pick the image of layer K (from 0) and its world file (image= and
// world= for the first; with an image given, the world file is the one given or none; without,
// the flight's, relative to the flight file, else one of the image's conventional world file
// names beside it). A flight's track (track=URL, else its "track" file relative to the flight
// file) gives its keyframes once the terrain is shown; its overlays (overlayK=URL, else relative
// to the flight file) are drawn over the image layers.
import { mat4, vec3 } from 'gl-matrix';
import { parseFlight, flightSettings, withKeyframes, FlightCamera, FlightRecord } from './flight.js';
import { flightTrackKeyframes } from './track_keyframes.js';
import { worldFileNames } from '../../geo/index.js';
import { fileNameOf, fetchFile } from '../fetched_file.js';

/** The camera the renderer draws with: posed from FlightCamera every frame (tests pose one the same way). */
export class ScriptedCamera {
  constructor() {
    this.mode = 'flight';
    this.position = new Float64Array(3); // doubles: a float is 4 m apart on a world field
    this.target = new Float64Array(3);
    this.up = vec3.fromValues(0, 1, 0);
    this.fovY = 1;
    this.near = 1;
    this.far = 2;
    this.aspect = 1;
    this.fogDistance = 1;
    this.view = mat4.create();
    this.projection = mat4.create();
    this.viewProjection = mat4.create();
  }

  pose(flightCamera) {
    const lod = flightCamera.lod;
    vec3.set(this.position, lod.eye[0], lod.eye[1], lod.eye[2]);
    vec3.set(this.target, lod.target[0], lod.target[1], lod.target[2]);
    vec3.set(this.up, lod.up[0], lod.up[1], lod.up[2]);
    this.fovY = flightCamera.fovY;
    this.near = lod.near;
    this.far = lod.far;
    this.fogDistance = flightCamera.fogDistance;
  }

  /** Recomputes the matrices for a viewport aspect ratio (width / height). */
  update(aspect) {
    this.aspect = aspect;
    mat4.lookAt(this.view, this.position, this.target, this.up);
    mat4.perspective(this.projection, this.fovY, aspect, this.near, this.far);
    mat4.multiply(this.viewProjection, this.projection, this.view);
  }
}

function parseSize(text) {
  const match = /^(\d+)x(\d+)$/i.exec(text ?? '');
  if (!match || Number(match[1]) < 16 || Number(match[2]) < 16 || Number(match[1]) > 4096 || Number(match[2]) > 4096) {
    throw new Error(`viewport=${text}: expected WIDTHxHEIGHT in CSS pixels, 16 to 4096`);
  }
  return [Number(match[1]), Number(match[2])];
}

/** Base64 of bytes (for pixels handed to Playwright; only capture frames call it). */
function toBase64(bytes) {
  let text = '';
  for (let k = 0; k < bytes.length; k += 0x8000) text += String.fromCharCode.apply(null, bytes.subarray(k, k + 0x8000));
  return btoa(text);
}

/** The deterministic mode when the URL asks for it (?flight=URL), else null. */
export function deterministicMode(params) {
  return params.has('flight') ? new DeterministicMode(params) : null;
}

export class DeterministicMode {
  constructor(params) {
    this.params = params;
    this.flight = null;
    this.settings = null;
    this.camera = new ScriptedCamera();
    this.flightCamera = null;
    this.record = null;
    this.target = -1;            // the last frame asked for
    this.waiting = new Map();    // frame -> [{resolve, pixels}]
    this.pixelFrames = new Set();
    this.pixels = null;          // read-back buffer, allocated once
    this.lastPixels = null;      // {frame, base64} of the last captured frame
    this.ready = new Promise((resolve, reject) => { this.resolveReady = resolve; this.rejectReady = reject; });
    this.ready.catch(() => {});  // a page with no reader of `ready` must not log an unhandled rejection
  }

  /** Fetches and checks the flight file; applies the URL's overrides. */
  async load() {
    const url = this.params.get('flight');
    const name = fileNameOf(url);
    let json;
    try {
      const response = await fetch(url);
      if (!response.ok) throw new Error(`HTTP ${response.status}`);
      json = JSON.parse(await response.text());
    } catch (error) {
      throw new Error(`${name}: cannot read the flight (${error.message})`);
    }
    const flight = parseFlight(json, name);
    if (this.params.has('viewport')) flight.viewport = parseSize(this.params.get('viewport'));
    if (this.params.has('dpr')) {
      const dpr = Number(this.params.get('dpr'));
      if (!(dpr >= 0.25 && dpr <= 4)) throw new Error(`dpr=${this.params.get('dpr')}: expected a number from 0.25 to 4`);
      flight.dpr = dpr;
    }
    if (this.params.has('ops')) {
      const ops = Number(this.params.get('ops'));
      if (!Number.isInteger(ops) || ops < 1) throw new Error(`ops=${this.params.get('ops')}: expected a positive integer`);
      flight.settings.operations = ops;
    }
    this.flight = flight;
    this.settings = flightSettings(flight);
    const here = new URL(url, location.href);
    // Each image layer's file, by the page's parameters (image0=, world0=, ...; image= and world=
    // for the first) or relative to the flight file.
    const given = (name, k) => this.params.get(`${name}${k}`) ?? (k === 0 ? this.params.get(name) : null);
    this.layers = flight.layers.map((layer, k) => {
      if (layer.kind !== 'image') return layer;
      const url = given('image', k);
      return url ? { ...layer, url, world: given('world', k), findWorld: false }
        : { ...layer, url: new URL(layer.image, here).href, world: layer.worldFile && new URL(layer.worldFile, here).href, findWorld: !layer.worldFile };
    });
    if (this.layers.length === 0 && this.params.has('image')) {
      this.layers = [{ kind: 'image', url: this.params.get('image'), world: this.params.get('world'), findWorld: false, opacity: 1, visible: true }];
    }
    this.overlays = flight.overlays.map((file, k) => given('overlay', k) ?? new URL(file, here).href);
    this.trackUrl = flight.track ? this.params.get('track') ?? new URL(flight.track.file, here).href : null;
    this.width = Math.round(flight.viewport[0] * flight.dpr);
    this.height = Math.round(flight.viewport[1] * flight.dpr);
    return flight;
  }

  /** Fixes the canvas's size and puts the API on window.hexlod.flight. */
  install(state, canvas, gl, requestRender, addLayer, addOverlay) {
    this.gl = gl;
    this.addLayer = addLayer; // (layer, image, sidecars) => the image stage's, which throws a refusal
    this.addOverlay = addOverlay; // (url) => the overlay stage's, which throws a refusal
    this.requestRender = requestRender;
    canvas.style.width = `${this.flight.viewport[0]}px`;
    canvas.style.height = `${this.flight.viewport[1]}px`;
    canvas.width = this.width;
    canvas.height = this.height;
    this.pixels = new Uint8Array(this.width * this.height * 4);
    const mode = this;
    state.flight = {
      /** Resolves with {frames, fps, captures, width, height} once the terrain is shown. */
      ready: this.ready,
      /** The parsed flight (defaults filled in). */
      get spec() { return mode.flight; },
      /** Frames drawn so far. */
      get done() { return mode.record?.done ?? 0; },
      /**
       * Draws frames up to `frame` and resolves with its figures; with {pixels: true} also
       * {pixels: {width, height, base64}}: the canvas as drawn (RGBA, bottom row first).
       */
      frame: (frame, options = {}) => this.request(frame, !!options.pixels),
      /** The figures of every frame drawn so far. */
      stats: () => this.record?.toArray() ?? [],
    };
  }

  /** The terrain on screen is ready: the flight starts from its first frame (its track's keyframes made first). */
  setTerrain(terrain, field) {
    this.trackKeyframes(terrain, field).then(() => {
      this.flightCamera = new FlightCamera(this.flight, terrain, this.width, this.height);
      this.record = new FlightRecord(this.flight.frames);
      return this.addLayers();
    }).then(() => {
      const { frames, fps, captures } = this.flight;
      this.resolveReady({ frames, fps, captures, width: this.width, height: this.height });
      this.requestRender();
    }, (error) => this.fail(error.message));
  }

  /** A flight along a track: its keyframes from the track file on this terrain. */
  async trackKeyframes(terrain, field) {
    if (!this.flight.track) return;
    let file;
    try {
      file = await fetchFile(this.trackUrl);
    } catch (error) {
      throw new Error(`${fileNameOf(this.trackUrl)}: cannot read the flight's track (${error.message})`);
    }
    const keyframes = await flightTrackKeyframes(this.flight.track, file, terrain, field.georef ?? null);
    this.flight = withKeyframes(this.flight, keyframes);
  }

  /** Adds the flight's layers, bottom first, fetching each image (and world file); throws a refusal's message. */
  async addLayers() {
    for (const layer of this.layers) {
      if (layer.kind === 'image') await this.drapeImage(layer);
      else await this.addLayer(layer, null, null);
    }
    for (const url of this.overlays) await this.addOverlay(url);
  }

  /** Fetches an image layer's image (and world file) and drapes it. */
  async drapeImage(layer) {
    const named = async (url, optional = false) => {
      const name = fileNameOf(url);
      let response;
      try {
        response = await fetch(url);
      } catch (error) {
        throw new Error(`${name}: cannot read the flight's image (${error.message})`);
      }
      if (optional && response.status === 404) return null;
      if (!response.ok) throw new Error(`${name}: cannot read the flight's image (HTTP ${response.status})`);
      return { name, blob: await response.blob() };
    };
    const image = await named(layer.url);
    let world = layer.world ? await named(layer.world) : null;
    if (layer.findWorld) {
      for (const name of worldFileNames(image.name)) {
        world = await named(new URL(name, new URL(layer.url, location.href)).href, true);
        if (world) break;
      }
    }
    await this.addLayer(layer, image, { worldFile: world, prj: null, auxXml: null });
  }

  /** The page could not start (its message), e.g. the terrain did not load. */
  fail(message) {
    this.rejectReady(new Error(message));
  }

  request(frame, pixels) {
    return this.ready.then(() => new Promise((resolve, reject) => {
      if (!Number.isInteger(frame) || frame < 0 || frame >= this.flight.frames) {
        reject(new Error(`frame ${frame} is not in the flight (0 to ${this.flight.frames - 1})`));
      } else if (frame < this.record.done) {
        if (!pixels) resolve({ stats: this.record.frame(frame) });
        else if (this.lastPixels?.frame === frame) resolve({ stats: this.record.frame(frame), pixels: this.lastPixels.image });
        else reject(new Error(`frame ${frame} was drawn already: ask for its pixels before it is drawn`));
      } else {
        if (!this.waiting.has(frame)) this.waiting.set(frame, []);
        this.waiting.get(frame).push({ resolve, pixels });
        if (pixels) this.pixelFrames.add(frame);
        this.target = Math.max(this.target, frame);
        this.requestRender();
      }
    }));
  }

  // --- Hooks of the frame loop (web/app/main.js) ----------------------------------------------

  /** True when the next frame of the flight should be drawn now; poses the camera for it. */
  beginFrame() {
    if (!this.record || this.record.done > this.target || this.record.done >= this.flight.frames) return false;
    this.flightCamera.at(this.record.done);
    this.camera.pose(this.flightCamera);
    return true;
  }

  /** The camera of the LOD update (Terrain.setLodCamera), as Node replays compute it. */
  get lodCamera() {
    return this.flightCamera.lod;
  }

  /** After the LOD update: records the frame's figures. */
  afterLod(terrain, operations) {
    this.record.record(terrain, operations);
  }

  /** After drawing: reads the pixels if asked, settles promises, asks for the next frame. */
  endFrame() {
    const frame = this.record.done - 1;
    if (this.pixelFrames.has(frame)) {
      const gl = this.gl;
      gl.readPixels(0, 0, this.width, this.height, gl.RGBA, gl.UNSIGNED_BYTE, this.pixels);
      this.lastPixels = { frame, image: { width: this.width, height: this.height, base64: toBase64(this.pixels) } };
      this.pixelFrames.delete(frame);
    }
    const waiting = this.waiting.get(frame);
    if (waiting) {
      this.waiting.delete(frame);
      const stats = this.record.frame(frame);
      for (const w of waiting) w.resolve(w.pixels ? { stats, pixels: this.lastPixels.image } : { stats });
    }
    if (this.record.done <= this.target && this.record.done < this.flight.frames) this.requestRender();
  }
}
