// RAW / R16 height fields: 16-bit unsigned little-endian samples, row-major, no header (as
// terrain editors export them). The file does not say its size: a square one is inferred,
// otherwise width and height come from the caller (a dialog, CLI flags) or a NAME.json sidecar.

import { HeightfieldError, DEFAULT_MAX_SAMPLES, checkSize } from './common.js';
import { shown } from '../geo/index.js';
import { SampleSink } from './pacing.js';
import { copyRows } from './copy_rows.js';

/** Thrown when only the user can say the size; the page asks, the CLI names its flags. */
export class SizeNeededError extends HeightfieldError {
  constructor(file, problem, samples) {
    super(file, problem);
    this.needsSize = true;
    this.samples = samples; // samples the file holds, for the dialog
  }
}

/**
 * @param {Uint8Array} bytes
 * @param {string} name
 * @param {Function} allocate
 * @param {{ width?: number, height?: number, sidecar?: import('./sidecar.js').Sidecar,
 *   maxSamples?: number, onProgress?: Function, reacquire?: Function }} options
 * @returns {Promise<{ width, height, sampleType: 'u16', samples: Uint16Array, heightScale, heightOffset }>}
 */
export async function decodeRaw(bytes, name, allocate, options = {}) {
  const fail = (problem) => { throw new HeightfieldError(name, problem); };
  const sidecar = options.sidecar;
  if (bytes.length % 2 !== 0) fail(`odd length ${bytes.length} bytes: not 16-bit samples`);
  const count = bytes.length / 2;
  let width = options.width ?? sidecar?.width;
  let height = options.height ?? sidecar?.height;
  // A size the caller gives (the page's dialog, the CLI, the JS API) is checked before it is
  // used to work out the other one: a height of -1 must not turn into a width of -count.
  for (const [what, v] of [['width', width], ['height', height]]) {
    if (v !== undefined && !(Number.isInteger(v) && v > 0)) {
      throw new SizeNeededError(name, `${what} ${shown(v)} is not a positive whole number`, count);
    }
  }
  if (width === undefined && height === undefined) {
    const side = Math.round(Math.sqrt(count));
    if (side * side !== count) {
      throw new SizeNeededError(name, `${count} samples do not make a square: give its width and height`, count);
    }
    width = height = side;
  } else if (width === undefined) {
    width = count / height;
  } else if (height === undefined) {
    height = count / width;
  }
  if (!Number.isInteger(width) || !Number.isInteger(height) || width * height !== count) {
    throw new SizeNeededError(name,
      `size ${width}x${height} does not fit ${count} 16-bit samples (${bytes.length} bytes)`, count);
  }
  checkSize(name, width, height, options.maxSamples ?? DEFAULT_MAX_SAMPLES);

  // RAW carries no units: a sidecar's min/max spread 0..65535 over them, else raw units.
  const ranged = sidecar && sidecar.min !== undefined;
  const sink = new SampleSink(allocate, 'u16', width, height, options);
  await copyRows(bytes, 0, sink, width, height, true);
  return {
    width, height, sampleType: 'u16', samples: sink.samples,
    heightScale: ranged ? (sidecar.max - sidecar.min) / 65535 : 1,
    heightOffset: ranged ? sidecar.min : 0,
  };
}
