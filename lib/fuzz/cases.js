// Fuzz cases: case `index` of `format` in the run with `seed` is a seed input (a fixture or
// one derived from it) changed by the format's structure-aware mutations and, now and then,
// by generic byte mutations on top. Everything comes from the case's own random stream.
import { Random } from './random.js';
import { mutateBytes } from './mutators/bytes.js';
import * as png from './mutators/png.js';
import * as tiff from './mutators/tiff.js';
import * as hgt from './mutators/hgt.js';
import * as asc from './mutators/asc.js';
import * as pgm from './mutators/pgm.js';
import * as raw from './mutators/raw.js';
import * as f32 from './mutators/f32.js';

export const FORMATS = { png, tiff, hgt, asc, pgm, raw, f32 };
export const FORMAT_NAMES = Object.keys(FORMATS);

const seedCache = new Map();
/** The seeds of a format, made once per process. */
export function seedsOf(format) {
  if (!seedCache.has(format)) seedCache.set(format, FORMATS[format].seeds());
  return seedCache.get(format);
}

/** 'png:1:4711' -> { format, seed, index } */
export function parseCaseId(id) {
  const m = /^([a-z0-9]+):(-?\d+):(\d+)$/.exec(id);
  if (!m || !FORMATS[m[1]]) throw new Error(`bad case id '${id}': expected FORMAT:SEED:INDEX with FORMAT one of ${FORMAT_NAMES.join(', ')}`);
  return { format: m[1], seed: Number(m[2]), index: Number(m[3]) };
}

/**
 * @returns {{ id: string, format: string, files: Array<{name: string, bytes: Uint8Array}>, options: object, how: string,
 *   invalid: string|null }} invalid: why the input must be refused, when a mutation knows it (a strip cut short)
 */
export function makeCase(format, seed, index) {
  const module = FORMATS[format];
  const random = Random.forCase(format, seed, index);
  const seeds = seedsOf(format);
  const base = random.weighted(seeds.map((s) => [s.weight ?? 1, s]));
  let files, options, how, invalid = null;
  if (random.chance(0.02)) {
    // The seed itself now and then: valid input must keep loading.
    ({ files, options, how } = { files: base.files, options: { ...base.options }, how: ['seed as it is'] });
  } else if (random.chance(0.1)) {
    ({ files, options } = { files: base.files, options: { ...base.options } });
    how = [];
  } else {
    ({ files, options, how, invalid = null } = module.mutate(base, random, seeds));
  }
  if (how.length === 0 || random.chance(0.25)) {
    // Mostly the height field, sometimes its sidecar.
    const k = files.length > 1 && random.chance(0.2) ? 1 : 0;
    const others = seeds.map((s) => s.files[k]?.bytes).filter(Boolean);
    const [bytes, what] = mutateBytes(files[k].bytes, random, others);
    files = files.map((f, i) => (i === k ? { name: f.name, bytes } : f));
    how.push(`${k ? 'sidecar ' : ''}${what}`);
    // Bytes changed blindly may make a file whole again: claims that come from a mutation step
    // are dropped, those a format can make from the bytes alone are made again.
    invalid = module.mustRefuseFiles?.(files, options) ?? null;
  }
  return { id: `${format}:${seed}:${index}`, format, files, options, how: how.join('; '), invalid };
}
