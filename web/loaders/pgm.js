// Binary PGM (P5) height fields: a text header "P5 width height maxval" (with # comments),
// one whitespace byte, then samples: 1 byte each when maxval < 256, else 2 bytes big-endian.

import { HeightfieldError, DEFAULT_MAX_SAMPLES, checkSize } from './common.js';
import { SampleSink } from './pacing.js';
import { copyRows } from './copy_rows.js';

/** True when bytes start like a PGM (P2 or P5 and whitespace). */
export function hasPgmSignature(bytes) {
  return bytes.length >= 3 && bytes[0] === 0x50 && (bytes[1] === 0x35 || bytes[1] === 0x32) && isSpace(bytes[2]);
}

function isSpace(c) {
  return c === 0x20 || c === 0x09 || c === 0x0a || c === 0x0d || c === 0x0b || c === 0x0c;
}

/**
 * @param {Uint8Array} bytes
 * @param {string} name
 * @param {Function} allocate
 * @param {{ sidecar?: import('./sidecar.js').Sidecar, maxSamples?: number, onProgress?: Function,
 *   reacquire?: Function }} options the sidecar's min/max (metres) map 0..maxval, else raw units
 */
export async function decodePgm(bytes, name, allocate, options = {}) {
  const fail = (problem) => { throw new HeightfieldError(name, problem); };
  if (bytes.length < 2 || bytes[0] !== 0x50 || bytes[1] < 0x31 || bytes[1] > 0x37) fail('not a PGM file (it must start with P5)');
  if (bytes[1] === 0x32) fail('unsupported PGM: ASCII (P2); save it as binary PGM (P5)');
  if (bytes[1] !== 0x35) fail(`not a grayscale PGM (magic P${String.fromCharCode(bytes[1])}; expected P5)`);

  // Three decimal fields, separated by whitespace and comments.
  let pos = 2;
  const field = (what) => {
    for (;;) {
      while (pos < bytes.length && isSpace(bytes[pos])) pos++;
      if (bytes[pos] !== 0x23) break; // '#': comment to the end of the line
      while (pos < bytes.length && bytes[pos] !== 0x0a && bytes[pos] !== 0x0d) pos++;
    }
    if (pos >= bytes.length) fail(`truncated: header ends before its ${what}`);
    let value = 0, digits = 0;
    while (pos < bytes.length && bytes[pos] >= 0x30 && bytes[pos] <= 0x39 && digits < 12) {
      value = value * 10 + (bytes[pos++] - 0x30);
      digits++;
    }
    if (digits === 0 || (pos < bytes.length && !isSpace(bytes[pos]))) fail(`bad header: ${what} is not a number`);
    return value;
  };
  const width = field('width'), height = field('height'), maxval = field('maxval');
  if (pos >= bytes.length) fail('truncated: no sample data after the header');
  pos++; // the single whitespace byte before the samples
  checkSize(name, width, height, options.maxSamples ?? DEFAULT_MAX_SAMPLES);
  if (maxval < 1 || maxval > 65535) fail(`bad header: maxval ${maxval} (must be 1..65535)`);
  const sidecar = options.sidecar;
  if (sidecar && ((sidecar.width ?? width) !== width || (sidecar.height ?? height) !== height)) {
    fail(`size ${width}x${height} does not match ${sidecar.width ?? '?'}x${sidecar.height ?? '?'} from ${sidecar.name}`);
  }

  const bytesPerSample = maxval < 256 ? 1 : 2;
  const needed = width * height * bytesPerSample;
  if (bytes.length - pos < needed) {
    fail(`truncated: ${bytes.length - pos} bytes of samples, ${needed} needed for ${width}x${height} at ${8 * bytesPerSample} bits`);
  }
  const ranged = sidecar && sidecar.min !== undefined;
  const sampleType = bytesPerSample === 1 ? 'u8' : 'u16';
  const sink = new SampleSink(allocate, sampleType, width, height, options);
  await copyRows(bytes, pos, sink, width, height, false);
  return {
    width, height, sampleType, samples: sink.samples,
    heightScale: ranged ? (sidecar.max - sidecar.min) / maxval : 1,
    heightOffset: ranged ? sidecar.min : 0,
  };
}
