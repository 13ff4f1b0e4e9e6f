// Contour levels: the interval a user types (or 'auto') and the levels it draws over a height
// range. Pure JS: the page's overlay, regression flights and Node tests read it.

/** Every majorEvery-th level (a multiple of interval * majorEvery) is drawn thicker and labelled. */
export const MAJOR_EVERY = 5;
/** What 'auto' aims at: about this many lines over the field's height range. */
const AUTO_LINES = 28;

/**
 * The interval as typed: a positive number of metres, or 'auto'.
 * @param {string|number} text
 * @returns {number|'auto'}
 * @throws Error saying what is allowed
 */
export function parseContourInterval(text) {
  const typed = String(text).trim();
  if (typed.toLowerCase() === 'auto') return 'auto';
  const allowed = 'a positive number of metres or auto';
  // Number('') is 0 and Number(' 0x10 ') is 16: only plain decimals are intervals.
  if (!/^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?$/i.test(typed)) throw new Error(`contour interval '${typed}' is not ${allowed}`);
  const value = Number(typed);
  if (!Number.isFinite(value)) throw new Error(`contour interval ${typed} is too large: it must be ${allowed}`);
  if (value <= 0) throw new Error(`contour interval ${typed} must be ${allowed}`);
  return value;
}

/** The 1-2-5 values (1, 2, 5, 10, 20, ...) around x: the largest at most x and the next. */
function niceAround(x) {
  const decade = 10 ** Math.floor(Math.log10(x));
  const steps = [1, 2, 5, 10].map((m) => m * decade);
  let k = 0;
  while (k + 1 < steps.length && steps[k + 1] <= x * (1 + 1e-12)) k += 1;
  return [steps[k], k + 1 < steps.length ? steps[k + 1] : steps[k] * 2];
}

/** The smallest 1-2-5 value at least x. */
function niceAtLeast(x) {
  const [below, above] = niceAround(x);
  return below >= x * (1 - 1e-12) ? below : above;
}

/** Levels from minHeight to maxHeight at this interval (multiples of it). */
export function countLevels(interval, minHeight, maxHeight) {
  return Math.max(0, Math.floor(maxHeight / interval + 1e-9) - Math.ceil(minHeight / interval - 1e-9) + 1);
}

/**
 * The contour levels to draw over [minHeight, maxHeight] metres.
 * @param {number|'auto'} interval metres, or 'auto': a 1-2-5 value giving about 20 to 40 lines
 * @param {number} maxLines more would be a grey smear: the interval is widened to a 1-2-5 value
 * @returns {{interval: number, majorEvery: number, major: number, widened: boolean, lines: number, message: string}}
 *   major: the height step of the labelled lines; message: what the page says when widened ('' otherwise)
 */
export function contourLevels(interval, minHeight, maxHeight, maxLines = 500) {
  const low = Math.min(minHeight, maxHeight), high = Math.max(minHeight, maxHeight);
  const range = high - low;
  let chosen;
  if (interval === 'auto') {
    if (!(range > 0)) chosen = 1;
    else {
      // Of the two 1-2-5 values around range / AUTO_LINES, the one whose count is nearer AUTO_LINES.
      const [a, b] = niceAround(range / AUTO_LINES);
      chosen = Math.abs(Math.log(range / a / AUTO_LINES)) <= Math.abs(Math.log(range / b / AUTO_LINES)) ? a : b;
    }
  } else {
    if (!(typeof interval === 'number' && Number.isFinite(interval) && interval > 0)) {
      throw new Error(`contour interval ${interval} must be a positive number of metres or auto`);
    }
    chosen = interval;
  }
  let widened = false, message = '';
  const given = countLevels(chosen, low, high);
  if (given > maxLines) {
    let wide = niceAtLeast(Math.max(chosen, range / maxLines));
    while (countLevels(wide, low, high) > maxLines) wide = niceAtLeast(wide * 1.5);
    message = `contour interval ${chosen} m would draw ${given} lines; widened to ${wide} m (at most ${maxLines} lines)`;
    chosen = wide;
    widened = true;
  }
  return { interval: chosen, majorEvery: MAJOR_EVERY, major: chosen * MAJOR_EVERY, widened,
    lines: countLevels(chosen, low, high), message };
}
