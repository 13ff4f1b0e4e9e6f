// The pixel tolerance of a flight's captures (the "tolerance" key of a flight file), read by
// `hexlod regress` when it compares a capture with its reference; the page ignores it. The knobs
// are pixelmatch's and Playwright's toHaveScreenshot's, so users of those tools know them:
//   "tolerance": {
//     "threshold": 0.004,          per pixel: pixelmatch's perceptual (YIQ) colour distance, 0..1,
//                                  above which a pixel differs (0: any change differs)
//     "maxDiffPixels": 0,          differing pixels a capture may have ...
//     "maxDiffPixelRatio": 0.002,  ... or this share of its pixels, whichever allows more
//     "antialiasing": "ignore",    "ignore" pixels that pixelmatch finds anti-aliased, or "count" them
//     "masks": [[x, y, w, h]],     rectangles in CSS pixels from the top left, left out of the comparison
//     "captures": { "20": { ... } }  per captured frame: the same keys; its masks add to the flight's
//   }
// The default threshold, 0.004, lets a change of one level (of 255) in every channel pass, and
// catches two levels of red or green: see the README for what it catches, measured.

export const DEFAULT_TOLERANCE = Object.freeze({
  threshold: 0.004,
  maxDiffPixels: 0,
  maxDiffPixelRatio: 0.002,
  antialiasing: 'ignore',
  masks: Object.freeze([]),
});

/** What --strict compares with: any change of any pixel outside the masks fails. */
export const STRICT_TOLERANCE = Object.freeze({ threshold: 0, maxDiffPixels: 0, maxDiffPixelRatio: 0, antialiasing: 'count' });

const KEYS = ['threshold', 'maxDiffPixels', 'maxDiffPixelRatio', 'antialiasing', 'masks'];
const MAX_SIDE = 4096; // CSS pixels: the largest flight viewport

/**
 * Checks one level of a tolerance object (the flight's or a capture's) and returns the keys it
 * sets. `fail(key, why)` throws.
 */
function parseLevel(json, label, fail, allowCaptures) {
  if (json === null || typeof json !== 'object' || Array.isArray(json)) fail(label, 'must be an object');
  const known = allowCaptures ? [...KEYS, 'captures'] : KEYS;
  const out = {};
  for (const [key, value] of Object.entries(json)) {
    const name = `${label}."${key}"`;
    if (!known.includes(key)) fail(name, `is not a tolerance key (${known.join(', ')})`);
    if (key === 'captures') continue;
    if (key === 'antialiasing') {
      if (value !== 'ignore' && value !== 'count') fail(name, `must be "ignore" or "count", got ${JSON.stringify(value)}`);
      out.antialiasing = value;
    } else if (key === 'masks') {
      if (!Array.isArray(value)) fail(name, 'must be an array of rectangles [x, y, width, height] in CSS pixels');
      out.masks = value.map((rect, i) => {
        const ok = Array.isArray(rect) && rect.length === 4 && rect.every((v) => typeof v === 'number' && Number.isFinite(v) && v >= 0 && v <= MAX_SIDE)
          && rect[2] > 0 && rect[3] > 0;
        if (!ok) fail(`${name}[${i}]`, `must be [x, y, width, height] in CSS pixels, 0 to ${MAX_SIDE}, with a positive width and height, got ${JSON.stringify(rect)}`);
        return rect.slice();
      });
    } else {
      const integer = key === 'maxDiffPixels';
      const max = key === 'maxDiffPixels' ? MAX_SIDE * MAX_SIDE * 16 : 1;
      if (typeof value !== 'number' || !Number.isFinite(value) || value < 0 || value > max || (integer && !Number.isInteger(value))) {
        fail(name, `must be ${integer ? 'an integer' : 'a number'} from 0 to ${max}, got ${JSON.stringify(value)}`);
      }
      out[key] = value;
    }
  }
  return out;
}

/**
 * Checks a flight's "tolerance" value (undefined: none given).
 * @param {unknown} json
 * @param {number[]} captures the flight's captured frames (a per-capture entry must name one)
 * @param {(key: string, why: string) => never} fail throws the flight's error for a key
 * @returns {{flight: object, captures: Record<number, object>}} the keys each level sets
 */
export function parseTolerance(json, captures, fail) {
  if (json === undefined) return { flight: {}, captures: {} };
  const flight = parseLevel(json, '"tolerance"', fail, true);
  const perCapture = {};
  if (json.captures !== undefined) {
    const label = '"tolerance"."captures"';
    if (json.captures === null || typeof json.captures !== 'object' || Array.isArray(json.captures)) {
      fail(label, 'must be an object whose keys are captured frame numbers');
    }
    for (const [key, value] of Object.entries(json.captures)) {
      const frame = Number(key);
      if (!/^\d+$/.test(key) || !captures.includes(frame)) fail(`${label}."${key}"`, `must name a captured frame (${captures.join(', ')})`);
      perCapture[frame] = parseLevel(value, `${label}."${key}"`, fail, false);
    }
  }
  return { flight, captures: perCapture };
}

/**
 * The tolerance of one capture: the defaults (or strict), the flight's keys, the capture's keys,
 * then the command line's. Masks add up; every other key is replaced by the later level.
 * @param {{flight: object, captures: Record<number, object>}} parsed parseTolerance's result
 * @param {number} frame
 * @param {{strict?: boolean, threshold?: number, maxDiffPixels?: number, maxDiffPixelRatio?: number,
 *   masks?: number[][]}} overrides from the command line
 */
export function toleranceFor(parsed, frame, overrides = {}) {
  const levels = [parsed.flight, parsed.captures[frame] ?? {}];
  const result = { ...DEFAULT_TOLERANCE, masks: [] };
  for (const level of levels) {
    for (const [key, value] of Object.entries(level)) {
      if (key === 'masks') result.masks.push(...value);
      else result[key] = value;
    }
  }
  if (overrides.strict) Object.assign(result, STRICT_TOLERANCE);
  for (const key of ['threshold', 'maxDiffPixels', 'maxDiffPixelRatio']) {
    if (overrides[key] !== undefined) result[key] = overrides[key];
  }
  if (overrides.masks) result.masks.push(...overrides.masks);
  return result;
}
