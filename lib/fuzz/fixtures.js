// The project's format fixtures (tests/fixtures/formats, made by scripts/make_format_fixtures.js)
// as the fuzzer's seeds, and their float32 reference grids, from which the format modules
// write further small seeds (other bit depths, byte orders, layouts) with writers of their own.
import { readFileSync } from 'node:fs';

const DIR = new URL('../../tests/fixtures/formats/', import.meta.url);
const DEMS = new URL('../../tests/fixtures/', import.meta.url);

/** Sizes of the reference grids (<name>.f32, float32 metres, row-major). */
const GRIDS = { everest: [200, 200], jacksboro: [250, 190], canyon: [192, 192], etopo: [240, 120], volcano: [87, 61] };

/** The bytes of a fixture file. */
export function fixture(name) {
  return new Uint8Array(readFileSync(new URL(name, DIR)));
}

/** A file entry { name, bytes } of a fixture. */
export function fixtureFile(name) {
  return { name, bytes: fixture(name) };
}

/** A file entry of the real DEMs in tests/fixtures (PNG, .f32 and their .json sidecars). */
export function demFile(name) {
  return { name, bytes: new Uint8Array(readFileSync(new URL(name, DEMS))) };
}

/**
 * A crop of a reference grid.
 * @returns {{ width: number, height: number, values: Float32Array }} metres; NaN marks voids
 */
export function grid(name, width, height, x0 = 0, y0 = 0) {
  const [w] = GRIDS[name];
  const bytes = fixture(`${name}.f32`);
  const all = new Float32Array(bytes.buffer, bytes.byteOffset, bytes.length / 4);
  const values = new Float32Array(width * height);
  for (let y = 0; y < height; y++) values.set(all.subarray((y0 + y) * w + x0, (y0 + y) * w + x0 + width), y * width);
  return { width, height, values };
}

/** Values scaled to 0..top (whole numbers) and the range in metres they span. */
export function quantise(values, top) {
  let min = Infinity, max = -Infinity;
  for (const v of values) if (!Number.isNaN(v)) { min = Math.min(min, v); max = Math.max(max, v); }
  const q = Array.from(values, (v) => (Number.isNaN(v) ? 0 : Math.round(((v - min) / (max - min || 1)) * top)));
  return { q, min, max };
}
