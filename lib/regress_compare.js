// Comparisons of `hexlod regress`: a flight's per-frame figures against the reference's (every
// frame that differs, field by field), the flight's own settings against those the reference
// recorded (so a mismatch can name its cause, "tau 1 → 2"), and captured images with pixelmatch's
// perceptual measure under a tolerance (web/app/deterministic/tolerance.js), masks, and the drift
// that stays below it (share of pixels changed at all, mean change).
import { writeFileSync } from 'node:fs';
import { encode, decode } from 'fast-png';
import pixelmatch from 'pixelmatch';
import { RECORD_FIELDS } from '../web/app/deterministic/flight.js';

const FIELDS = ['hash', ...RECORD_FIELDS];

/**
 * Every frame whose figures differ between two runs of a flight.
 * @param {object[]} expected @param {object[]} actual per-frame figures (FlightRecord.toArray())
 * @returns {{expectedFrames: number, actualFrames: number,
 *   frames: {frame: number, fields: Record<string, [unknown, unknown]>}[]}}
 *   fields maps each differing figure to [expected, actual]
 */
export function compareStats(expected, actual) {
  const frames = [];
  for (let f = 0; f < Math.min(expected.length, actual.length); f++) {
    const fields = {};
    for (const key of FIELDS) if (expected[f][key] !== actual[f][key]) fields[key] = [expected[f][key], actual[f][key]];
    if (Object.keys(fields).length) frames.push({ frame: f, fields });
  }
  return { expectedFrames: expected.length, actualFrames: actual.length, frames };
}

/** True when compareStats found no difference. */
export const statsMatch = (diff) => diff.frames.length === 0 && diff.expectedFrames === diff.actualFrames;

/** One frame's difference, e.g. 'frame 4: triangles 26668 → 26702' or 'frame 4: hash only'. */
function frameLine({ frame, fields }) {
  const counts = Object.entries(fields).filter(([key]) => key !== 'hash').map(([key, [a, b]]) => `${key} ${a} → ${b}`);
  return `frame ${frame}: ${counts.length ? counts.slice(0, 3).join(', ') : 'the mesh (hash), same counts'}`;
}

/** A frame's difference in brief: its triangles before → after, or which figures differ. */
function briefFrame({ frame, fields }) {
  if (fields.triangles) return `frame ${frame}: triangles ${fields.triangles[0]} → ${fields.triangles[1]}`;
  return `frame ${frame}: ${Object.keys(fields).join(', ')}`;
}

/**
 * A stats difference as one short phrase: how many frames differ, the first and the last with
 * their triangles before → after. `what`: who holds the expected figures ('the reference', 'Node').
 */
export function describeStats(diff, what) {
  const parts = [];
  if (diff.expectedFrames !== diff.actualFrames) parts.push(`${diff.actualFrames} frames, ${what} has ${diff.expectedFrames}`);
  const n = diff.frames.length;
  if (n) {
    const ends = n === 1 ? briefFrame(diff.frames[0]) : `${briefFrame(diff.frames[0])} … ${briefFrame(diff.frames[n - 1])}`;
    parts.push(`${n} of ${Math.min(diff.expectedFrames, diff.actualFrames)} frames differ from ${what} (${ends})`);
  }
  return parts.join('; ');
}

/** Every differing frame, one line each (for summary.txt). */
export const statsLines = (diff) => diff.frames.map(frameLine);

const SETTING_LABELS = { tau: 'tau', exaggeration: 'exaggeration', operations: 'operations', geomorph: 'geomorph',
  culling: 'culling', backfaceCulling: 'backfaceCulling', embedding: 'embedding' };
const list = (values) => values.join(', ');
const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);
/** "a.tif (0.5), tiles host/{z}/{x}/{y}.png (hidden)", or "none". */
const layerList = (layers) => (layers?.length ? layers.map((l) => `${l.image ?? `tiles ${l.tiles}`}${l.visible ? '' : ' (hidden)'}${l.opacity === 1 ? '' : ` (${l.opacity})`}`).join(', ') : 'none');

/**
 * What a reference records of a flight and its height field: everything that decides its
 * figures and pixels (not its tolerance, which only judges them).
 */
export function flightRecordOf(flight, dem) {
  const { fps, frames, viewport, dpr, settings, captures, keyframes, layers, overlays = [], track = null } = flight;
  // The layers only when there are some, and one plain image as "image" and "worldFile":
  // references of flights without layers, or with one image, stay as they were.
  const [first] = layers;
  const oneImage = layers.length === 1 && first.kind === 'image' && first.opacity === 1 && first.visible;
  const draped = oneImage ? { image: first.image, worldFile: first.worldFile } : layers.length > 0 ? { layers } : {};
  // A track and overlays only when there are some, likewise.
  const drawn = { ...(overlays.length > 0 && { overlays }), ...(track && { track }) };
  return { spec: { fps, frames, viewport, dpr, settings, captures, keyframes, ...draped, ...drawn }, dem: { name: dem.name, bytes: dem.size, sha256: dem.sha256 } };
}

/**
 * How a flight and its height field differ from what the reference recorded, one phrase per
 * change ('tau 1 → 2', 'viewport 320x180 → 400x225'), or [] when they are the same (or the
 * reference records nothing to compare with).
 */
export function flightChanges(reference, current) {
  const changes = [];
  const was = reference.spec, now = current.spec;
  if (!was) return changes; // made by an older hexlod: judge() says so
  for (const key of Object.keys({ ...was.settings, ...now.settings })) {
    if (!same(was.settings[key], now.settings[key])) changes.push(`${SETTING_LABELS[key] ?? key} ${was.settings[key]} → ${now.settings[key]}`);
  }
  if (!same(was.viewport, now.viewport)) changes.push(`viewport ${was.viewport.join('x')} → ${now.viewport.join('x')}`);
  for (const key of ['dpr', 'fps', 'frames']) if (was[key] !== now[key]) changes.push(`${key} ${was[key]} → ${now[key]}`);
  for (const key of ['image', 'worldFile']) {
    if ((was[key] ?? null) !== (now[key] ?? null)) changes.push(`${key} ${was[key] ?? 'none'} → ${now[key] ?? 'none'}`);
  }
  if (!same(was.layers ?? null, now.layers ?? null)) changes.push(`layers ${layerList(was.layers)} → ${layerList(now.layers)}`);
  if (!same(was.captures, now.captures)) changes.push(`captures ${list(was.captures)} → ${list(now.captures)}`);
  if (was.keyframes.length !== now.keyframes.length) {
    changes.push(`keyframes ${was.keyframes.length} → ${now.keyframes.length}`);
  } else {
    was.keyframes.forEach((k, i) => {
      for (const key of ['time', 'position', 'target', 'fov']) {
        if (!same(k[key], now.keyframes[i][key])) changes.push(`keyframe ${i} ${key} ${JSON.stringify(k[key])} → ${JSON.stringify(now.keyframes[i][key])}`);
      }
    });
  }
  const a = typeof reference.dem === 'object' ? reference.dem : { name: reference.dem };
  const b = current.dem;
  if (a.name !== b.name) changes.push(`height field ${a.name} → ${b.name}`);
  else if (a.sha256 && a.sha256 !== b.sha256) changes.push(`height field ${a.name}: its content changed (sha256 ${a.sha256.slice(0, 8)} → ${b.sha256.slice(0, 8)})`);
  return changes;
}

/** Reads an 8-bit RGB(A) PNG as {width, height, rgb}. */
export function readPng(bytes) {
  const image = decode(bytes);
  if (image.depth !== 8 || image.channels < 3) throw new Error(`expected an 8-bit RGB PNG, got ${image.depth}-bit with ${image.channels} channels`);
  const rgb = new Uint8Array(image.width * image.height * 3);
  for (let k = 0, j = 0; j < rgb.length; k += image.channels, j += 3) {
    rgb[j] = image.data[k];
    rgb[j + 1] = image.data[k + 1];
    rgb[j + 2] = image.data[k + 2];
  }
  return { width: image.width, height: image.height, rgb };
}

export function writePng(path, { width, height, rgb }) {
  writeFileSync(path, encode({ width, height, data: rgb, channels: 3, depth: 8 }));
}

/** RGB -> RGBA (opaque), as pixelmatch reads. */
function rgba({ width, height, rgb }) {
  const out = new Uint8Array(width * height * 4);
  for (let p = 0; p < width * height; p++) {
    out[4 * p] = rgb[3 * p];
    out[4 * p + 1] = rgb[3 * p + 1];
    out[4 * p + 2] = rgb[3 * p + 2];
    out[4 * p + 3] = 255;
  }
  return out;
}

/** A mask per pixel (1: left out) from rectangles in CSS pixels, rounded outwards to device pixels. */
function maskOf(rects, dpr, width, height) {
  const mask = new Uint8Array(width * height);
  for (const [x, y, w, h] of rects) {
    const x0 = Math.max(0, Math.floor(x * dpr)), x1 = Math.min(width, Math.ceil((x + w) * dpr));
    const y0 = Math.max(0, Math.floor(y * dpr)), y1 = Math.min(height, Math.ceil((y + h) * dpr));
    for (let row = y0; row < y1; row++) mask.fill(1, row * width + x0, row * width + Math.max(x0, x1));
  }
  return mask;
}

const RED = [255, 0, 0], YELLOW = [255, 255, 0], ORANGE = [255, 150, 0], MASKED = [70, 110, 200];

/**
 * Compares a capture with its reference under a tolerance. The diff image marks pixels that
 * differ red, anti-aliased ones pixelmatch left out yellow, pixels changed below the threshold
 * orange, masked regions blue; the rest is the reference in faint grey.
 * @param {{width, height, rgb}} reference @param {{width, height, rgb}} actual
 * @param {ReturnType<import('../web/app/deterministic/tolerance.js').toleranceFor>} tolerance
 * @param {number} dpr device pixels per CSS pixel (masks are in CSS pixels)
 */
export function compareImages(reference, actual, tolerance, dpr = 1) {
  if (reference.width !== actual.width || reference.height !== actual.height) {
    return { sizeMismatch: `${actual.width}x${actual.height}, the reference is ${reference.width}x${reference.height}` };
  }
  const { width, height } = reference;
  const mask = maskOf(tolerance.masks, dpr, width, height);
  const a = rgba(reference), b = rgba(actual);
  let masked = 0, changed = 0, deltaSum = 0, maxDelta = 0;
  for (let p = 0; p < width * height; p++) {
    const k = 4 * p;
    if (mask[p]) {
      masked += 1;
      b[k] = a[k]; b[k + 1] = a[k + 1]; b[k + 2] = a[k + 2]; // equal: pixelmatch passes over it
      continue;
    }
    const delta = Math.max(Math.abs(a[k] - b[k]), Math.abs(a[k + 1] - b[k + 1]), Math.abs(a[k + 2] - b[k + 2]));
    if (delta) changed += 1;
    deltaSum += delta;
    if (delta > maxDelta) maxDelta = delta;
  }
  const output = new Uint8Array(width * height * 4);
  const differing = pixelmatch(a, b, output, width, height, {
    threshold: tolerance.threshold, includeAA: tolerance.antialiasing === 'count', alpha: 0.15,
    diffColor: RED, aaColor: YELLOW,
  });
  const diff = new Uint8Array(width * height * 3);
  let antialiased = 0;
  for (let p = 0; p < width * height; p++) {
    const k = 4 * p;
    let colour = [output[k], output[k + 1], output[k + 2]];
    const isRed = colour[0] === 255 && colour[1] === 0 && colour[2] === 0;
    const isYellow = colour[0] === 255 && colour[1] === 255 && colour[2] === 0;
    if (isYellow) antialiased += 1;
    if (mask[p]) colour = MASKED;
    else if (!isRed && !isYellow && (a[k] !== b[k] || a[k + 1] !== b[k + 1] || a[k + 2] !== b[k + 2])) colour = ORANGE;
    diff.set(colour, 3 * p);
  }
  const compared = width * height - masked;
  const allowed = Math.max(tolerance.maxDiffPixels, Math.floor(tolerance.maxDiffPixelRatio * compared));
  return {
    compared, masked, differing, allowed, antialiased, changed, maxDelta,
    share: compared ? differing / compared : 0,
    changedShare: compared ? changed / compared : 0,
    meanChange: compared ? deltaSum / compared : 0,
    passed: differing <= allowed,
    diff: { width, height, rgb: diff },
  };
}

const percent = (share) => `${(100 * share).toFixed(share && share < 0.0001 ? 4 : share < 0.01 ? 3 : 2)} %`;

/** A failed capture in brief, e.g. '13.60 % of pixels differ (0.200 % allowed)'. */
export function briefImage(result) {
  return `${percent(result.share)} of pixels differ (${percent(result.compared ? result.allowed / result.compared : 0)} allowed)`;
}

/** A capture's comparison in words, e.g. '12.30 % of pixels differ (allowed 0.200 %); 32.36 % changed at all, mean change 0.668, largest 4'. */
export function describeImage(result, tolerance) {
  const allowedShare = result.compared ? result.allowed / result.compared : 0;
  const drift = result.changed
    ? `${percent(result.changedShare)} changed at all, mean change ${result.meanChange.toFixed(3)}, largest ${result.maxDelta} of 255`
    : 'identical';
  const masked = result.masked ? `, ${result.masked} pixels masked` : '';
  if (!result.passed) {
    return `${result.differing} pixels (${percent(result.share)}) differ beyond threshold ${tolerance.threshold}, ` +
      `${result.allowed} (${percent(allowedShare)}) allowed; ${drift}${masked}`;
  }
  return `${drift}${result.differing ? `; ${result.differing} pixels beyond threshold ${tolerance.threshold}, ${result.allowed} allowed` : ''}${masked}`;
}
