// Shared pieces of the height-field loaders: the error type, size limits and
// the call to the caller's allocate(). Plain ES module (browser and Node).
import { shown } from '../geo/index.js';

/**
 * Thrown for every bad input file. `message` is one line, "<file>: <problem>".
 */
export class HeightfieldError extends Error {
  /**
   * @param {string} file name of the offending file ('' when no single file is to blame)
   * @param {string} problem what is wrong, e.g. 'empty file'
   */
  constructor(file, problem) {
    super(file ? `${file}: ${problem}` : problem);
    this.name = 'HeightfieldError';
    this.file = file;
    this.problem = problem;
  }
}

/**
 * Default limit on width*height: 32769^2 (~1.07e9 samples, 2 GiB at u16), the
 * next 2^n+1 size above 16385^2. Beyond that a 32-bit WebAssembly heap is hopeless.
 */
export const DEFAULT_MAX_SAMPLES = 32769 * 32769;

/** sampleType -> typed array constructor. */
export const SAMPLE_ARRAYS = {
  u8: Uint8Array,
  u16: Uint16Array,
  i16: Int16Array,
  f32: Float32Array,
};

/** Default allocate(): a fresh JS typed array. */
export function defaultAllocate(sampleType, width, height) {
  return new SAMPLE_ARRAYS[sampleType](width * height);
}

/**
 * Throws HeightfieldError unless width x height is a sane size: two positive integers whose
 * product is at most maxSamples. Called before anything is allocated, on every size a file,
 * a sidecar or the caller declares (a negative, fractional or NaN size would otherwise reach
 * allocate() as a RangeError or a degenerate field).
 */
export function checkSize(file, width, height, maxSamples) {
  const declared = `declared size ${shown(width)}x${shown(height)}`;
  for (const [what, v] of [['width', width], ['height', height]]) {
    if (v === 0) throw new HeightfieldError(file, `zero ${what} (${declared})`);
    if (!Number.isInteger(v) || v < 0) {
      throw new HeightfieldError(file, `${what} ${shown(v)} is not a positive whole number (${declared})`);
    }
  }
  if (width * height > maxSamples) {
    throw new HeightfieldError(file,
      `${declared} is absurd (${width * height} samples; limit ${maxSamples})`);
  }
}


/**
 * Calls allocate exactly once and checks that it kept its side of the contract.
 * A wrong return value is a programming error in the caller, not a bad file,
 * so that is a plain Error; errors thrown by allocate itself pass through.
 */
export function allocateSamples(allocate, sampleType, width, height) {
  const Ctor = SAMPLE_ARRAYS[sampleType];
  const samples = allocate(sampleType, width, height);
  if (!(samples instanceof Ctor) || samples.length !== width * height) {
    const got = samples && samples.constructor ? `${samples.constructor.name}(${samples.length})` : String(samples);
    throw new Error(`allocate('${sampleType}', ${width}, ${height}) returned ${got}; expected a ${Ctor.name} of ${width * height} elements`);
  }
  return samples;
}

/** Best guess at what a file that is not what its name says really holds, for error messages. */
export function describeContent(bytes) {
  const b = bytes;
  const starts = (...sig) => sig.every((v, i) => b[i] === v);
  if (starts(0xff, 0xd8, 0xff)) return 'JPEG data';
  if (starts(0x47, 0x49, 0x46, 0x38)) return 'GIF data';
  if (starts(0x49, 0x49, 0x2a, 0x00) || starts(0x4d, 0x4d, 0x00, 0x2a)) return 'TIFF data';
  if (starts(0x1f, 0x8b)) return 'gzip data';
  if (starts(0x50, 0x4b, 0x03, 0x04)) return 'ZIP data';
  if (starts(0x89, 0x50, 0x4e, 0x47)) return 'PNG data';
  const n = Math.min(b.length, 256);
  let printable = 0;
  for (let i = 0; i < n; i++) {
    const c = b[i];
    if ((c >= 0x20 && c < 0x7f) || c === 9 || c === 10 || c === 13 || c >= 0x80) printable++;
  }
  if (n > 0 && printable === n) return 'text';
  return null;
}

/** Lower-cased extension without the dot ('' if none). */
export function extensionOf(name) {
  const slash = Math.max(name.lastIndexOf('/'), name.lastIndexOf('\\'));
  const dot = name.lastIndexOf('.');
  return dot > slash + 1 ? name.slice(dot + 1).toLowerCase() : '';
}

/** Name without its extension ('dir/x.png' -> 'dir/x'). */
export function baseNameOf(name) {
  const ext = extensionOf(name);
  return ext ? name.slice(0, name.length - ext.length - 1) : name;
}

/** Name of a file without its directories ('a/b/N27E086.hgt' -> 'N27E086.hgt'). */
export function fileNameOf(name) {
  return name.slice(Math.max(name.lastIndexOf('/'), name.lastIndexOf('\\')) + 1);
}
