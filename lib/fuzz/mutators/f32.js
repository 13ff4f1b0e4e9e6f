// Raw float32 fields (.f32 with the NAME.json sidecar that gives width and height),
// structure-aware: the values (NaN voids, all NaN, infinities, float32 extremes, denormals,
// signalling NaNs), the length (a few bytes or samples off), and the sidecar (size fields that
// are negative, fractional, huge, strings; a wrong shape with the right sample count).
// Seeds: the fixture pair and sidecars written here for the other reference grids.
import { fixtureFile, fixture, demFile } from '../fixtures.js';
import { mutateSidecar, sidecarEntries, sidecarText } from './sidecar.js';
import { applySteps } from './steps.js';

export const extension = 'f32';

const encoder = new TextEncoder();

export function seeds() {
  const sidecar = (name, w, h) => ({ name: `${name}.json`, bytes: encoder.encode(`{"width": ${w}, "height": ${h}, "cell_size_m": 30}`) });
  const small = new Float32Array(80).map((_, i) => 100 + (i % 10) * 3 - Math.floor(i / 10));
  small[5] = small[6] = NaN;
  return [
    { files: [fixtureFile('jacksboro.f32'), fixtureFile('jacksboro.json')] },
    { files: [{ name: 'everest.f32', bytes: fixture('everest.f32') }, sidecar('everest', 200, 200)] },
    { files: [{ name: 'volcano.f32', bytes: fixture('volcano.f32') }, sidecar('volcano', 87, 61)] },
    { files: [{ name: 'small.f32', bytes: new Uint8Array(small.buffer) }, sidecar('small', 10, 8)] },
    // The real DEMs, whose sidecars carry many more fields; the larger ones less often.
    ...[['volcano_maungawhau', 1], ['jacksboro_fault', 0.5], ['grandcanyon_512', 0.25]]
      .map(([name, weight]) => ({ files: [demFile(`${name}.f32`), demFile(`${name}.json`)], weight })),
  ];
}

const SPECIALS = [NaN, Infinity, -Infinity, 3.4028234663852886e38, -3.4028234663852886e38, 1e-45, -0, 1e30, -1e30];

const STEPS = [
  [5, function samples(s, r) {
    const out = s.bytes.slice();
    const view = new DataView(out.buffer);
    const n = out.length >> 2;
    if (n === 0) return null; // shorter than one sample: nothing to change
    const op = r.pick(['special', 'special', 'all NaN', 'all but one NaN', 'bits']);
    if (op === 'special') {
      const v = r.pick(SPECIALS);
      for (let k = r.weighted([[5, 1], [2, 50], [1, n]]); k > 0; k--) view.setFloat32(4 * r.int(n), v, true);
      s.bytes = out;
      return `samples ${v}`;
    }
    if (op === 'bits') {
      const bits = r.pick([0x7f800001, 0xffffffff, 0x7fc00000, 0x00000001, 0x80000000]);
      for (let k = r.range(1, 20); k > 0; k--) view.setUint32(4 * r.int(n), bits, true);
      s.bytes = out;
      return `samples 0x${bits.toString(16)}`;
    }
    const keep = op === 'all NaN' ? -1 : r.int(n);
    for (let i = 0; i < n; i++) if (i !== keep) view.setFloat32(4 * i, NaN, true);
    s.bytes = out;
    return op;
  }],
  [3, function length(s, r) {
    const n = s.bytes.length;
    const to = r.pick([n - 1, n + 1, n - 4, n + 4, n - 3, r.int(n), 4, n * 2]);
    const out = new Uint8Array(Math.max(0, to));
    out.set(s.bytes.subarray(0, out.length));
    s.bytes = out;
    return `length ${out.length}`;
  }],
  [3, function sidecar(s, r) {
    const [bytes, how] = mutateSidecar(s.sidecar, r);
    s.sidecar = bytes;
    return how;
  }],
  [2, function shape(s, r) {
    // The right number of samples in the wrong shape, a profile, or negative factors.
    const count = s.bytes.length >> 2;
    const entries = sidecarEntries(s.sidecar).filter(([k]) => k !== 'width' && k !== 'height');
    const [w, h] = r.pick([[count, 1], [1, count], [-1, -count], [count / 2, 2], [2, count / 2], [count / 3, 3]]);
    s.sidecar = encoder.encode(sidecarText([['width', String(w)], ['height', String(h)], ...entries]));
    return `sidecar size ${w}x${h}`;
  }],
];

/** Why the pair must be refused, when that is sure: no sidecar, no whole size in it, a length that does not match it, an infinite sample. */
export function mustRefuseFiles(files) {
  if (files.length < 2) return 'its sidecar is missing';
  const size = declaredSize(files);
  if (!size) return 'its sidecar gives no whole positive size';
  if (files[0].bytes.length !== size.width * size.height * 4) return `${files[0].bytes.length} bytes do not hold ${size.width}x${size.height} float32 samples`;
  const b = files[0].bytes;
  const samples = new Float32Array(b.buffer.slice(b.byteOffset, b.byteOffset + b.length));
  const i = samples.findIndex((v) => v === Infinity || v === -Infinity);
  return i >= 0 ? `sample ${i} is ${samples[i]}` : null;
}

export function mutate(seed, random) {
  const [main, side] = seed.files;
  const s = { bytes: main.bytes, sidecar: side.bytes };
  const how = applySteps(s, random, STEPS);
  const files = [{ name: main.name, bytes: s.bytes }];
  if (random.chance(0.97)) files.push({ name: side.name, bytes: s.sidecar });
  return { files, options: {}, how, invalid: mustRefuseFiles(files) };
}

export function declaredSize(files) {
  // The last of duplicated keys wins, as in JSON.parse.
  const side = Object.fromEntries(files[1] ? sidecarEntries(files[1].bytes).map(([k, v]) => [k, JSON.parse(v)]) : []);
  return Number.isInteger(side.width) && Number.isInteger(side.height) && side.width > 0 && side.height > 0
    ? { width: side.width, height: side.height } : null;
}
