// Scripted flights of the deterministic mode, shared by the page (web/app/deterministic/mode.js) and
// Node (`hexlod regress`, lib/regress.js), so that both give the core the same camera, the same
// settings and the same sequence of calls, and so the same mesh hashes, frame by frame.
//
// A flight file (JSON):
//   {
//     "dem": "../fixtures/grandcanyon_512.png",  optional: the height field, relative to this file
//     "image": "../fixtures/ortho.jpg",            optional: an image draped before the first frame,
//     "worldFile": "../fixtures/ortho.jgw",          and its world file (default: ortho.jgw ... beside it)
//     "layers": [ { "image": "a.tif", "worldFile": "a.tfw", "opacity": 0.5, "visible": true },
//                 { "tiles": "http://host/{z}/{x}/{y}.png" } ],  optional, instead of "image": image
//                                                  layers, bottom first (worldFile, opacity, visible optional)
//     "fps": 30,                                   frame clock: frame n shows time n / fps seconds
//     "viewport": [400, 225], "dpr": 1,            canvas size in CSS pixels, device pixel ratio
//     "settings": { "tau": 1, "exaggeration": 2, "operations": 1000, "geomorph": true,
//                   "embedding": "exact", "culling": true, "backfaceCulling": true,
//                   "imageOpacity": 1, "imageUnlit": false,         these two for an image
//                   "contours": true, "contourInterval": 50,        contour lines; the interval in metres or "auto"
//                   "earth": "curved" },                            or "flat": the surface a georeferenced field is drawn on
//     "captures": [0, 30, 59],                     frames to screenshot
//     "keyframes": [ { "time": 0, "position": [x, y, z], "target": [x, y, z], "fov": 50 }, ... ],
//     "track": "route.gpx",                         instead of "keyframes": fly along a track of a GPX, KML,
//       or { "file": "route.gpx", "height": 300,    KMZ or GeoJSON file (relative to this file): metres above
//            "speed": 50, "lookAhead": 600,         the ground, metres a second ("times": the track's own),
//            "line": 1 },                           metres ahead it looks, which line (track_keyframes.js)
//     "overlays": ["places.kml", ...],              optional: vector overlays drawn over the terrain
//     "tolerance": { "threshold": 0.004, "maxDiffPixelRatio": 0.002, ... }  optional: see tolerance.js
//   }
// Positions are metres of the height field: x east from the first column, z south from the first
// row, y the height above the field's zero (not exaggerated: the exaggeration is applied here).
// On the curved Earth they are placed on it as the page's cameras are (web/cameras/on_the_earth.js).
// Between keyframes, position, target and fov follow a cubic Hermite spline with Catmull-Rom
// tangents for uneven times (C1: no jumps in velocity). Only +, -, *, / and sqrt enter the path
// (exact in IEEE arithmetic) and one Math.tan of the fov (fdlibm in V8 both in Chromium and
// Node), so the page and Node compute bit-identical cameras.
import { defaultSettings, coreSettings, EARTH_SHAPES } from '../settings_table.js';
import { FLAT_EARTH, earthShapeOf } from '../../geo/index.js';
import { lodCameraOnEarth } from '../../cameras/on_the_earth.js';
import { FRAME } from '../../core/core.js';
import { parseTolerance } from './tolerance.js';
import { parseContourInterval } from '../../measure/contour_levels.js';

export const DEFAULT_FPS = 30;
export const DEFAULT_VIEWPORT = [400, 225];
export const DEFAULT_FOV_DEG = 50; // the page's cameras (cameras/clip_planes.js FOV_Y)
export const DEFAULT_OPERATIONS = 1000;
export const MAX_FRAMES = 100000;
const LIMIT = 1e9; // metres: past this a coordinate is not a place on any terrain
const MAX_DEPTH_RATIO = 1e6; // far / near, as the page's cameras (24-bit depth buffer)

/** A flight file that cannot be used; the message names the key. */
export class FlightError extends Error {}

const SETTING_KINDS = {
  tau: { min: 0.05, max: 64 },
  exaggeration: { min: 0.01, max: 100 },
  operations: { min: 1, max: 1e7, integer: true },
  geomorph: 'boolean',
  culling: 'boolean',
  backfaceCulling: 'boolean',
  embedding: ['exact', 'shifted'],
  // The draped image's (settings_table.js); kept in the settings only when the flight sets
  // them, so the references of flights without an image record what they did.
  imageOpacity: { min: 0, max: 1 },
  imageUnlit: 'boolean',
  // Contour lines (settings_table.js), likewise kept only when set: the interval in metres or 'auto'.
  contours: 'boolean',
  contourInterval: 'contourInterval',
  // The surface (settings_table.js): curved (the default) or flat, kept only when set.
  earth: EARTH_SHAPES,
};

/**
 * Checks a parsed flight file and fills its defaults.
 * @param {unknown} json the parsed file
 * @param {string} name the file's name, for messages
 * @returns {{dem: string|null, layers: object[], overlays: string[], fps: number, frames: number, viewport: number[], dpr: number,
 *   settings: object, captures: number[], keyframes: {time: number, position: number[], target: number[], fov: number}[]|null,
 *   track: {file: string, height: number, speed: number|null, lookAhead: number, line: number}|null,
 *   tolerance: {flight: object, captures: Record<number, object>}}} a flight with a track has no keyframes
 *   (nor frames, captures, tolerance) until withKeyframes gives it those made from the track
 * @throws FlightError naming the key that is wrong
 */
export function parseFlight(json, name = 'flight') {
  const fail = (key, why) => { throw new FlightError(`${name}: ${key} ${why}`); };
  if (json === null || typeof json !== 'object' || Array.isArray(json)) fail('the file', 'must hold a JSON object');
  const known = ['dem', 'image', 'worldFile', 'layers', 'overlays', 'fps', 'viewport', 'dpr', 'settings', 'captures', 'keyframes', 'track',
    'tolerance', 'description'];
  for (const key of Object.keys(json)) if (!known.includes(key)) fail(`"${key}"`, `is not a flight key (${known.join(', ')})`);
  const { number } = checkers(fail);
  for (const key of ['dem', 'image', 'worldFile']) {
    if (json[key] !== undefined && (typeof json[key] !== 'string' || json[key] === '')) fail(`"${key}"`, 'must be a file path or an http(s) URL');
  }
  if (json.worldFile !== undefined && json.image === undefined) fail('"worldFile"', 'goes with "image"');
  if (json.layers !== undefined && json.image !== undefined) fail('"image"', 'goes into "layers" when a flight has them');
  const layers = json.image !== undefined ? [{ kind: 'image', image: json.image, worldFile: json.worldFile ?? null, opacity: 1, visible: true }]
    : parseLayers(json.layers, fail, number);
  const fps = json.fps === undefined ? DEFAULT_FPS : number('"fps"', json.fps, { min: 1, max: 1000 });
  let viewport = DEFAULT_VIEWPORT;
  if (json.viewport !== undefined) {
    if (!Array.isArray(json.viewport) || json.viewport.length !== 2) fail('"viewport"', 'must be [width, height] in CSS pixels');
    viewport = json.viewport.map((v, k) => number(`"viewport"[${k}]`, v, { min: 16, max: 4096, integer: true }));
  }
  const dpr = json.dpr === undefined ? 1 : number('"dpr"', json.dpr, { min: 0.25, max: 4 });
  const settings = { tau: 1, exaggeration: defaultSettings().exaggeration, operations: DEFAULT_OPERATIONS,
    geomorph: true, culling: true, backfaceCulling: true, embedding: 'exact' };
  if (json.settings !== undefined) {
    if (json.settings === null || typeof json.settings !== 'object' || Array.isArray(json.settings)) fail('"settings"', 'must be an object');
    for (const [key, value] of Object.entries(json.settings)) {
      const kind = SETTING_KINDS[key];
      const label = `"settings"."${key}"`;
      if (!kind) fail(label, `is not a setting (${Object.keys(SETTING_KINDS).join(', ')})`);
      if (kind === 'contourInterval') {
        try {
          settings[key] = parseContourInterval(value);
        } catch (error) {
          fail(label, `${error.message}, got ${JSON.stringify(value)}`);
        }
      } else if (kind === 'boolean') {
        if (typeof value !== 'boolean') fail(label, `must be true or false, got ${JSON.stringify(value)}`);
        settings[key] = value;
      } else if (Array.isArray(kind)) {
        if (!kind.includes(value)) fail(label, `must be one of ${kind.join(', ')}, got ${JSON.stringify(value)}`);
        settings[key] = value;
      } else {
        settings[key] = number(label, value, kind);
      }
    }
  }
  const overlays = parseOverlays(json.overlays, fail);
  const base = { dem: json.dem ?? null, layers, overlays, fps, viewport, dpr, settings };
  if (json.track !== undefined) {
    if (json.keyframes !== undefined) fail('"track"', 'comes instead of "keyframes": a flight takes one or the other');
    // The keyframes come from the track on the terrain (withKeyframes, once both are read).
    return { ...base, track: parseTrack(json.track, fail, number), keyframes: null, frames: 0, captures: [], tolerance: null,
      pending: { captures: json.captures, tolerance: json.tolerance, name } };
  }
  if (!Array.isArray(json.keyframes) || json.keyframes.length === 0) fail('"keyframes"', 'must be a non-empty array');
  return withKeyframes({ ...base, track: null, pending: { captures: json.captures, tolerance: json.tolerance, name } }, json.keyframes);
}

/**
 * A flight with its keyframes: checked, and the frames, captures and tolerances that follow
 * from them. For a flight file's own keyframes, and for those made from its track.
 * @throws FlightError naming the key that is wrong
 */
export function withKeyframes(flight, keyframesJson) {
  const { name, captures: capturesJson, tolerance: toleranceJson } = flight.pending;
  const fps = flight.fps;
  const fail = (key, why) => { throw new FlightError(`${name}: ${key} ${why}`); };
  const { number, point } = checkers(fail);
  const keyframes = keyframesJson.map((k, i) => {
    const key = `"keyframes"[${i}]`;
    if (k === null || typeof k !== 'object' || Array.isArray(k)) fail(key, 'must be an object {time, position, target, fov?}');
    for (const field of Object.keys(k)) if (!['time', 'position', 'target', 'fov'].includes(field)) fail(`${key}.${field}`, 'is not a keyframe key (time, position, target, fov)');
    for (const field of ['time', 'position', 'target']) if (k[field] === undefined) fail(`${key}.${field}`, 'is missing');
    const frame = {
      time: number(`${key}.time`, k.time, { min: 0, max: MAX_FRAMES / fps }),
      position: point(`${key}.position`, k.position),
      target: point(`${key}.target`, k.target),
      fov: k.fov === undefined ? DEFAULT_FOV_DEG : number(`${key}.fov`, k.fov, { min: 1, max: 170 }),
    };
    const d = frame.target.map((v, a) => v - frame.position[a]);
    if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] === 0) fail(`${key}.target`, 'must differ from its position');
    return frame;
  });
  for (let i = 1; i < keyframes.length; i++) {
    if (!(keyframes[i].time > keyframes[i - 1].time)) fail(`"keyframes"[${i}].time`, `must be later than the keyframe before (${keyframes[i - 1].time} s)`);
  }
  const frames = Math.floor(keyframes[keyframes.length - 1].time * fps + 1e-9) + 1;
  let captures = [0, Math.floor((frames - 1) / 2), frames - 1].filter((f, i, a) => a.indexOf(f) === i);
  if (capturesJson !== undefined) {
    if (!Array.isArray(capturesJson)) fail('"captures"', 'must be an array of frame numbers');
    captures = capturesJson.map((c, i) => number(`"captures"[${i}]`, c, { min: 0, max: frames - 1, integer: true }));
    captures = [...new Set(captures)].sort((a, b) => a - b);
  }
  const tolerance = parseTolerance(toleranceJson, captures, fail);
  return { ...flight, frames, captures, keyframes, tolerance };
}

/** The checks of a flight's numbers and points; `fail(key, why)` throws. */
function checkers(fail) {
  const number = (key, value, { min = -Infinity, max = Infinity, integer = false } = {}) => {
    if (typeof value !== 'number' || !Number.isFinite(value) || (integer && !Number.isInteger(value)) || value < min || value > max) {
      fail(key, `must be ${integer ? 'an integer' : 'a number'} from ${min} to ${max}, got ${JSON.stringify(value)}`);
    }
    return value;
  };
  const point = (key, value) => {
    if (!Array.isArray(value) || value.length !== 3) fail(key, `must be three numbers [x, y, z] in metres, got ${JSON.stringify(value)}`);
    return value.map((v, k) => number(`${key}[${k}]`, v, { min: -LIMIT, max: LIMIT }));
  };
  return { number, point };
}

/** A flight's "track": a file, or { file, height, speed, lookAhead, line }. */
function parseTrack(track, fail, number) {
  const spec = typeof track === 'string' ? { file: track } : track;
  if (spec === null || typeof spec !== 'object' || Array.isArray(spec)) fail('"track"', 'must be a file path or { "file": path, "height", "speed", "lookAhead", "line" }');
  for (const field of Object.keys(spec)) if (!['file', 'height', 'speed', 'lookAhead', 'line'].includes(field)) fail(`"track".${field}`, 'is not a track key (file, height, speed, lookAhead, line)');
  if (typeof spec.file !== 'string' || spec.file === '') fail('"track".file', 'must be a file path or an http(s) URL');
  const speed = spec.speed === undefined ? 50 : spec.speed === 'times' ? null : number('"track".speed', spec.speed, { min: 0.1, max: 1e6 });
  return {
    file: spec.file,
    height: spec.height === undefined ? 300 : number('"track".height', spec.height, { min: 0, max: 100000 }),
    speed,
    lookAhead: spec.lookAhead === undefined ? 600 : number('"track".lookAhead', spec.lookAhead, { min: 1, max: 1e6 }),
    line: spec.line === undefined ? 1 : number('"track".line', spec.line, { min: 1, max: 1e6, integer: true }),
  };
}

/** A flight's "overlays": file paths or URLs of GPX, KML, KMZ or GeoJSON files. */
function parseOverlays(overlays, fail) {
  if (overlays === undefined) return [];
  if (!Array.isArray(overlays)) fail('"overlays"', 'must be an array of file paths or URLs');
  return overlays.map((o, i) => {
    if (typeof o !== 'string' || o === '') fail(`"overlays"[${i}]`, 'must be a file path or an http(s) URL');
    return o;
  });
}

/** A flight's "layers": [{ kind: 'image', image, worldFile, opacity, visible } | { kind: 'tiles', tiles, opacity, visible }]. */
function parseLayers(layers, fail, number) {
  if (layers === undefined) return [];
  if (!Array.isArray(layers)) fail('"layers"', 'must be an array of { "image": path } or { "tiles": template } objects');
  return layers.map((layer, i) => {
    const key = `"layers"[${i}]`;
    if (layer === null || typeof layer !== 'object' || Array.isArray(layer)) fail(key, 'must be an object { "image": path } or { "tiles": template }');
    const kind = layer.image !== undefined ? 'image' : layer.tiles !== undefined ? 'tiles' : fail(key, 'needs "image" or "tiles"');
    const allowed = kind === 'image' ? ['image', 'worldFile', 'opacity', 'visible'] : ['tiles', 'opacity', 'visible'];
    for (const field of Object.keys(layer)) if (!allowed.includes(field)) fail(`${key}.${field}`, `is not a key of ${kind === 'image' ? 'an image' : 'a tile'} layer (${allowed.join(', ')})`);
    for (const field of ['image', 'worldFile', 'tiles']) {
      if (layer[field] !== undefined && (typeof layer[field] !== 'string' || layer[field] === '')) fail(`${key}.${field}`, 'must be a file path or an http(s) URL');
    }
    if (layer.visible !== undefined && typeof layer.visible !== 'boolean') fail(`${key}.visible`, `must be true or false, got ${JSON.stringify(layer.visible)}`);
    const look = { opacity: layer.opacity === undefined ? 1 : number(`${key}.opacity`, layer.opacity, { min: 0, max: 1 }), visible: layer.visible ?? true };
    return kind === 'image' ? { kind, image: layer.image, worldFile: layer.worldFile ?? null, ...look } : { kind, tiles: layer.tiles, ...look };
  });
}

/**
 * The viewer settings (web/app/settings_table.js) of a flight: the page's defaults, the flight's values,
 * an operation budget and no time budget, no triangle cap and no auto tau (both depend on time).
 */
export function flightSettings(flight) {
  const s = flight.settings;
  return Object.assign(defaultSettings(), {
    tau: s.tau, exaggeration: s.exaggeration, budgetMs: 0, maxOperations: s.operations, maxTriangles: 0,
    autoTau: false, geomorph: s.geomorph, culling: s.culling, backfaceCulling: s.backfaceCulling,
    embedding: s.embedding, freeze: false, wireframe: false, colorByLevel: false,
    ...(s.imageOpacity !== undefined && { imageOpacity: s.imageOpacity }),
    ...(s.imageUnlit !== undefined && { imageUnlit: s.imageUnlit }),
    ...(s.contours !== undefined && { contours: s.contours }),
    ...(s.contourInterval !== undefined && { contourInterval: s.contourInterval }),
    ...(s.earth !== undefined && { earth: s.earth }),
  });
}

/** Builds a terrain's mesh for a flight: what the page does when it shows a terrain. */
export function prepareTerrain(terrain, settings) {
  terrain.resetMesh(settings.embedding);
  terrain.configure(coreSettings(settings));
}

const hermite = (p0, m0, p1, m1, h, s) => {
  const s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * h * m1;
};

/**
 * The camera of a flight at each frame, for one terrain and viewport. Every output is written
 * into arrays allocated once: a frame allocates nothing.
 */
export class FlightCamera {
  /**
   * @param {ReturnType<typeof parseFlight>} flight
   * @param {{width: number, height: number, spacingX: number, spacingY: number, minHeight: number,
   *   maxHeight: number, heightAt: (x: number, z: number) => number}} terrain
   * @param {number} width @param {number} height the viewport in device pixels
   */
  constructor(flight, terrain, width, height) {
    this.flight = flight;
    this.terrain = terrain;
    this.width = width;
    this.height = height;
    this.scale = flight.settings.exaggeration;
    this.extentX = (terrain.width - 1) * terrain.spacingX;
    this.extentZ = (terrain.height - 1) * terrain.spacingY;
    this.low = terrain.minHeight * this.scale;
    this.high = terrain.maxHeight * this.scale;
    // Tangents of every channel (position xyz, target xyz, fov) at every keyframe.
    const keys = flight.keyframes;
    const n = keys.length;
    this.values = new Float64Array(n * 7);
    keys.forEach((k, i) => this.values.set([...k.position, ...k.target, k.fov], 7 * i));
    this.tangents = new Float64Array(n * 7);
    for (let i = 0; i < n; i++) {
      const a = Math.max(0, i - 1), b = Math.min(n - 1, i + 1);
      if (a === b) continue;
      const dt = keys[b].time - keys[a].time;
      for (let c = 0; c < 7; c++) this.tangents[7 * i + c] = (this.values[7 * b + c] - this.values[7 * a + c]) / dt;
    }
    this.sample = new Float64Array(7);
    /** What hexlod_lod_set_camera gets (Terrain.setLodCamera): drawn metres, device pixels. */
    this.lod = { eye: [0, 0, 0], target: [0, 0, 0], up: [0, 1, 0], tanHalfFovY: 1, aspect: width / height,
      viewportHeight: height, near: 1, far: 2 };
    this.fovY = 1;          // radians
    this.fogDistance = 1;   // metres, for the renderer
    this.time = 0;
  }

  /** Sets the camera to frame `frame` (time frame / fps) and returns this.lod. */
  at(frame) {
    const keys = this.flight.keyframes, v = this.values, m = this.tangents, out = this.sample;
    const t = frame / this.flight.fps;
    this.time = t;
    let i = 0;
    while (i + 1 < keys.length && keys[i + 1].time <= t) i++;
    if (i + 1 >= keys.length || t <= keys[0].time) {
      const k = t <= keys[0].time ? 0 : keys.length - 1;
      for (let c = 0; c < 7; c++) out[c] = v[7 * k + c];
    } else {
      const h = keys[i + 1].time - keys[i].time, s = (t - keys[i].time) / h;
      for (let c = 0; c < 7; c++) out[c] = hermite(v[7 * i + c], m[7 * i + c], v[7 * i + 7 + c], m[7 * i + 7 + c], h, s);
    }
    const lod = this.lod, scale = this.scale;
    lod.eye[0] = out[0]; lod.eye[1] = out[1] * scale; lod.eye[2] = out[2];
    lod.target[0] = out[3]; lod.target[1] = out[4] * scale; lod.target[2] = out[5];
    const dx = lod.target[0] - lod.eye[0], dy = lod.target[1] - lod.eye[1], dz = lod.target[2] - lod.eye[2];
    const look2 = dx * dx + dy * dy + dz * dz;
    // Looking (almost) straight down, +y cannot be "up": north (-z) is the top of the screen.
    const vertical = dx * dx + dz * dz <= 1e-6 * look2;
    lod.up[0] = 0; lod.up[1] = vertical ? 0 : 1; lod.up[2] = vertical ? -1 : 0;
    this.fovY = (out[6] * Math.PI) / 180;
    lod.tanHalfFovY = Math.tan(this.fovY / 2);
    // Near and far as the page's cameras choose them (cameras/clip_planes.js): far reaches the
    // farthest corner of the data's box, near is a fraction of the height above the ground.
    const x = lod.eye[0], y = lod.eye[1], z = lod.eye[2];
    let far2 = 0;
    for (let corner = 0; corner < 8; corner++) {
      const cx = corner & 1 ? this.extentX : 0, cz = corner & 2 ? this.extentZ : 0, cy = corner & 4 ? this.high : this.low;
      const d2 = (cx - x) * (cx - x) + (cy - y) * (cy - y) + (cz - z) * (cz - z);
      if (d2 > far2) far2 = d2;
    }
    const look = Math.sqrt(look2);
    const inside = x >= 0 && z >= 0 && x <= this.extentX && z <= this.extentZ;
    const clearance = y - (inside ? this.terrain.heightAt(x, z) * scale : this.high);
    const far = Math.sqrt(far2) * 1.05 + 1;
    lod.near = Math.max(far / MAX_DEPTH_RATIO, Math.min(0.3 * Math.max(clearance, 0), 0.5 * look));
    lod.far = Math.max(far, lod.near * 10);
    this.fogDistance = Math.max(8 * look, 0.25 * Math.sqrt(this.extentX * this.extentX + this.extentZ * this.extentZ));
    return lod;
  }
}

/** The per-frame figures that must be identical on every run, page or Node. */
export const RECORD_FIELDS = ['triangles', 'vertices', 'cells', 'maxLevel', 'operations', 'splits', 'merges',
  'pendingMerges', 'converged'];

/** Per-frame figures of a flight, in arrays allocated once (a frame allocates nothing). */
export class FlightRecord {
  constructor(frames) {
    this.frames = frames;
    this.done = 0; // frames recorded
    this.hashHigh = new Uint32Array(frames);
    this.hashLow = new Uint32Array(frames);
    this.fields = Object.fromEntries(RECORD_FIELDS.map((f) => [f, new Int32Array(frames)]));
  }

  /**
   * Records the next frame, after its LOD update (`operations` is what updateLod returned). It
   * reads the figures of one core query (web/core/core.js FrameStats, the same object every frame):
   * meshHash builds a string, and this runs every frame.
   */
  record(terrain, operations) {
    const f = this.done, x = this.fields, s = terrain.query(FRAME.hash);
    x.triangles[f] = s.triangles;
    x.vertices[f] = s.vertices;
    x.cells[f] = s.cells;
    x.maxLevel[f] = s.maxLevel;
    x.operations[f] = operations;
    x.splits[f] = s.splits;
    x.merges[f] = s.merges;
    x.pendingMerges[f] = s.pendingMerges;
    x.converged[f] = s.converged ? 1 : 0;
    this.hashHigh[f] = s.hashHigh;
    this.hashLow[f] = s.hashLow;
    this.done = f + 1;
  }

  /** Frame f's figures as a plain object (hash: 16 hexadecimal digits). */
  frame(f) {
    const hex = (v) => v.toString(16).padStart(8, '0');
    const out = { frame: f, hash: hex(this.hashHigh[f]) + hex(this.hashLow[f]) };
    for (const field of RECORD_FIELDS) out[field] = this.fields[field][f];
    out.converged = out.converged === 1;
    return out;
  }

  /** Every recorded frame's figures. */
  toArray() {
    return Array.from({ length: this.done }, (_, f) => this.frame(f));
  }
}

/**
 * One frame of a flight in the core, in the order the page's frame loop calls it: the camera,
 * one budgeted LOD update, the fan stream (and the renderer's acknowledgement of its upload).
 * Node replays call this; the page makes the same calls from its frame loop (web/app/main.js).
 */
export function replayFrame(terrain, camera, record, frame, earth = FLAT_EARTH, placed = newPlacedCamera()) {
  terrain.setLodCamera(lodCameraOnEarth(camera.at(frame), earth, placed));
  const operations = terrain.updateLod();
  record.record(terrain, operations);
  terrain.updateStream();
  terrain.acknowledgeStream();
}

const newPlacedCamera = () => ({ eye: [0, 0, 0], target: [0, 0, 0], up: [0, 1, 0] });

/**
 * Replays a whole flight on a loaded terrain (Node), on the Earth as the page draws it (the
 * flight's earth setting; curved needs the field's georeference). Returns the FlightRecord.
 */
export function replayFlight(terrain, flight, georef = null) {
  const settings = flightSettings(flight);
  prepareTerrain(terrain, settings);
  const earth = settings.earth === 'flat' ? FLAT_EARTH : earthShapeOf(georef, terrain);
  terrain.setEarth(earth);
  const [w, h] = flight.viewport;
  const camera = new FlightCamera(flight, terrain, Math.round(w * flight.dpr), Math.round(h * flight.dpr));
  const record = new FlightRecord(flight.frames);
  const placed = newPlacedCamera();
  for (let f = 0; f < flight.frames; f++) replayFrame(terrain, camera, record, f, earth, placed);
  return record;
}
