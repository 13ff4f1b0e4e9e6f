// RAW / R16 (16-bit little-endian samples, no header), structure-aware: the size the caller
// gives (width/height options as a page dialog or the CLI pass them: negative, fractional,
// NaN, huge, strings), the NAME.json sidecar's width, height, min and max, the file length
// (odd, one sample off, square or not), and the name (.r16, .raw). Seeds: the two fixtures
// (one needs its size from the options, one is square) and a small one written here.
import { fixtureFile, grid, quantise } from '../fixtures.js';
import { mutateSidecar, sidecarEntries } from './sidecar.js';
import { applySteps } from './steps.js';

export const extension = 'r16';

export function seeds() {
  const g = grid('volcano', 20, 10, 30, 20);
  const { q } = quantise(g.values, 65535);
  const bytes = new Uint8Array(q.length * 2);
  q.forEach((v, i) => { bytes[2 * i] = v & 255; bytes[2 * i + 1] = v >> 8; });
  return [
    { files: [fixtureFile('volcano.r16'), fixtureFile('volcano.json')], options: { width: 87, height: 61 } },
    { files: [fixtureFile('canyon.r16'), fixtureFile('canyon.json')] },
    { files: [{ name: 'small.raw', bytes }, { name: 'small.json', bytes: new TextEncoder().encode('{"width": 20, "height": 10, "min": 95, "max": 195}') }] },
  ];
}

const SIZE_VALUES = [0, 1, -1, -87, -61, 87.5, 0.5, NaN, Infinity, -Infinity, 1e9, 2 ** 31, 2 ** 32 + 1, 2 ** 53 + 2, '87', '', null, true, [87], {}];

const STEPS = [
  [4, function sizeOption(s, r) {
    const key = r.pick(['width', 'height']);
    if (r.chance(0.2)) { delete s.options[key]; return `no ${key} option`; }
    s.options[key] = r.chance(0.3) && s.count ? r.pick([-s.count, s.count, -1, 1]) : r.pick(SIZE_VALUES);
    return `option ${key} ${typeof s.options[key] === 'number' ? s.options[key] : JSON.stringify(s.options[key])}`;
  }],
  [1, function negativePair(s, r) {
    // Negative factors whose product is the file's sample count: only a sign check stops them.
    const w = s.options.width ?? 87, h = s.options.height ?? 61;
    s.options = { width: -Math.abs(w), height: -Math.abs(h) };
    if (r.chance(0.5)) { s.options = {}; s.sidecar = new TextEncoder().encode(`{"width": ${-Math.abs(w)}, "height": ${-Math.abs(h)}}`); }
    return `size ${-Math.abs(w)}x${-Math.abs(h)}`;
  }],
  [4, function sidecar(s, r) {
    if (r.chance(0.15)) { s.sidecar = null; return 'no sidecar'; }
    const [bytes, how] = mutateSidecar(s.sidecar ?? new TextEncoder().encode('{}'), r);
    s.sidecar = bytes;
    return how;
  }],
  [3, function length(s, r) {
    const n = s.bytes.length;
    const to = r.pick([n - 1, n + 1, n - 2, n + 2, r.int(n), 2, 0, n * 2, 256 * 256 * 2]);
    const out = new Uint8Array(Math.max(0, to));
    out.set(s.bytes.subarray(0, out.length));
    s.bytes = out;
    return `length ${out.length}`;
  }],
  [1, function rename(s, r) { s.name = r.pick(['x.r16', 'x.raw', 'X.R16', 'x.RAW']); return `named ${s.name}`; }],
];

export function mutate(seed, random) {
  const [main, side] = seed.files;
  const s = { name: main.name, bytes: main.bytes, sidecar: side?.bytes ?? null, options: { ...seed.options }, count: main.bytes.length / 2 };
  const how = applySteps(s, random, STEPS);
  const files = [{ name: s.name, bytes: s.bytes }];
  if (s.sidecar) files.push({ name: s.name.replace(/\.[^.]*$/, '.json'), bytes: s.sidecar });
  return { files, options: s.options, how, invalid: mustRefuseFiles(files) };
}

/** Why the file must be refused, when that is sure: an odd length holds no 16-bit samples. */
export function mustRefuseFiles(files) {
  return files[0].bytes.length % 2 ? `odd length ${files[0].bytes.length}: not 16-bit samples` : null;
}

/** The size the caller and the sidecar give (or the square the length makes), when whole and positive. */
export function declaredSize(files, options) {
  const side = Object.fromEntries(files[1] ? sidecarEntries(files[1].bytes).map(([k, v]) => [k, JSON.parse(v)]) : []);
  const count = files[0].bytes.length / 2;
  let w = options.width ?? side.width, h = options.height ?? side.height;
  if (w === undefined && h === undefined) w = h = Math.sqrt(count);
  else if (w === undefined) w = count / h;
  else if (h === undefined) h = count / w;
  return Number.isInteger(w) && Number.isInteger(h) && w > 0 && h > 0 ? { width: w, height: h } : null;
}
