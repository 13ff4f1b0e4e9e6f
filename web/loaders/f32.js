// Raw float32 height fields: NAME.f32 (little-endian metres, row-major,
// width*height values, no header) described by its NAME.json sidecar.

import { HeightfieldError, DEFAULT_MAX_SAMPLES, allocateSamples, checkSize } from './common.js';

const LITTLE_ENDIAN_HOST = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

/**
 * Copies a .f32 file into a Float32Array from allocate().
 *
 * @param {Uint8Array} bytes the .f32 file (any byteOffset; no alignment needed)
 * @param {string} name its file name, for messages
 * @param {import('./sidecar.js').Sidecar} sidecar the parsed NAME.json (width and height required)
 * @param {(sampleType: 'f32', width: number, height: number) => Float32Array} allocate called once,
 *   after the sizes have been checked
 * @param {{ maxSamples?: number }} [options]
 * @returns {{ width: number, height: number, sampleType: 'f32', samples: Float32Array }} heights in
 *   metres; NaN samples are no-data
 * @throws {HeightfieldError} on a size mismatch or an infinite sample
 */
export function decodeF32(bytes, name, sidecar, allocate, options = {}) {
  const maxSamples = options.maxSamples ?? DEFAULT_MAX_SAMPLES;
  const fail = (problem) => { throw new HeightfieldError(name, problem); };
  if (bytes.length === 0) fail('empty file');
  const { width, height } = sidecar;
  if (width === undefined || height === undefined) {
    throw new HeightfieldError(sidecar.name, `${width === undefined ? 'width' : 'height'} missing (needed to read ${name})`);
  }
  checkSize(sidecar.name, width, height, maxSamples);
  const count = width * height;
  if (bytes.length !== count * 4) {
    fail(`size ${bytes.length} bytes does not match ${width}x${height} float32 samples (${count * 4} bytes) from ${sidecar.name}`);
  }

  const samples = allocateSamples(allocate, 'f32', width, height);
  if (LITTLE_ENDIAN_HOST) {
    // One byte copy from the file into the destination: works whatever the
    // alignment of bytes.byteOffset, which a Float32Array view would need.
    new Uint8Array(samples.buffer, samples.byteOffset, count * 4).set(bytes);
  } else {
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.length);
    for (let i = 0; i < count; i++) samples[i] = view.getFloat32(i * 4, true);
  }

  // NaN marks no-data; an infinity is damage.
  for (let i = 0; i < count; i++) {
    const v = samples[i];
    if (v === Infinity || v === -Infinity) {
      fail(`sample at row ${Math.floor(i / width)}, column ${i % width} is ${v} (expected finite metres or NaN)`);
    }
  }
  return { width, height, sampleType: 'f32', samples };
}
