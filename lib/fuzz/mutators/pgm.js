// Binary PGM (P5), structure-aware: the magic, the width, height and maxval fields (zero,
// negative, fractional, too many digits, huge), comments and whitespace between them, the
// single whitespace byte before the samples, sample data too short or too long, a consistent
// new size and depth, and the NAME.json sidecar (height range, size). Seeds: the two fixtures
// (16-bit and 8-bit with sidecars) and small ones written here.
import { fixtureFile, grid, quantise } from '../fixtures.js';
import { nearSize } from '../values.js';
import { mutateSidecar } from './sidecar.js';
import { applySteps } from './steps.js';

export const extension = 'pgm';

const encoder = new TextEncoder();

function pgm({ magic = 'P5', fields, separators, data }) {
  const head = encoder.encode(`${magic}${separators[0]}${fields[0]}${separators[1]}${fields[1]}${separators[2]}${fields[2]}${separators[3]}`);
  const out = new Uint8Array(head.length + data.length);
  out.set(head);
  out.set(data, head.length);
  return out;
}

function samples(q, maxval) {
  if (maxval < 256) return Uint8Array.from(q);
  const out = new Uint8Array(q.length * 2);
  q.forEach((v, i) => { out[2 * i] = v >> 8; out[2 * i + 1] = v & 255; });
  return out;
}

export function seeds() {
  const out = [
    { files: [fixtureFile('everest.pgm'), fixtureFile('everest.json')] },
    { files: [fixtureFile('jacksboro_8bit.pgm'), fixtureFile('jacksboro_8bit.json')] },
  ];
  const g = grid('everest', 16, 12, 30, 150);
  for (const maxval of [100, 1000]) {
    const { q } = quantise(g.values, maxval);
    out.push({ files: [{ name: `small${maxval}.pgm`, bytes: pgm({ fields: [16, 12, maxval], separators: ['\n# made by the fuzzer\n', ' ', '\n', '\n'], data: samples(q, maxval) }) }] });
  }
  return out;
}

/** Magic, fields, separators and data of a PGM (null when the header cannot be walked). */
function parse(bytes) {
  const head = new TextDecoder('latin1').decode(bytes.subarray(0, 512));
  const m = /^(P.)((?:\s|#[^\n]*\n)+)(\S+)((?:\s|#[^\n]*\n)+)(\S+)((?:\s|#[^\n]*\n)+)(\d+)(\s)/.exec(head);
  if (!m) return null;
  return { magic: m[1], fields: [m[3], m[5], m[7]], separators: [m[2], m[4], m[6], m[8]], data: bytes.subarray(m[0].length) };
}

const STEPS = [
  [2, function magic(p, r) { p.magic = r.pick(['P2', 'P6', 'P1', 'P7', 'p5', 'P5#', 'P55', 'P', 'PF']); return `magic ${p.magic}`; }],
  [7, function field(p, r) {
    const i = r.int(3);
    p.fields[i] = r.pick([String(nearSize(r, Number(p.fields[i]) || 16)), '0', '-1', '1.5', '1e3', '+5', '0000000000001',
      '99999999999999', 'abc', '', '65535', '65536', '256', '255', '4294967297', '46341']);
    return `${['width', 'height', 'maxval'][i]} ${JSON.stringify(p.fields[i])}`;
  }],
  [3, function separator(p, r) {
    const i = r.int(4);
    p.separators[i] = r.pick(['', ' ', '\t', '\r\n', '\n#', '#', '# comment\r', '\n# a\n# b\n', '\v', '\f', '\0', '  \n  ']);
    return `separator ${i} ${JSON.stringify(p.separators[i])}`;
  }],
  [3, function resize(p, r) {
    const w = r.pick([1, 2, r.range(1, 40), r.range(1, 300)]), h = r.pick([1, 2, r.range(1, 40), r.range(1, 300)]);
    const maxval = r.pick([1, 255, 256, 1000, 65535]);
    p.fields = [String(w), String(h), String(maxval)];
    p.data = Uint8Array.from({ length: w * h * (maxval < 256 ? 1 : 2) }, () => r.int(256));
    return `resized to ${w}x${h} maxval ${maxval} with matching data`;
  }],
  [3, function data(p, r) {
    const op = r.pick(['cut', 'extend', 'empty', 'one short']);
    if (op === 'cut') p.data = p.data.slice(0, r.int(p.data.length));
    else if (op === 'one short') p.data = p.data.slice(0, Math.max(0, p.data.length - 1));
    else if (op === 'empty') p.data = new Uint8Array(0);
    else { const d = new Uint8Array(p.data.length + r.smallLength()); d.set(p.data); p.data = d; }
    return `data ${op}`;
  }],
  [2, function sidecar(p, r) {
    if (r.chance(0.2)) { p.sidecar = null; return 'no sidecar'; }
    const [bytes, how] = mutateSidecar(p.sidecar ?? encoder.encode('{"min": 100, "max": 900}'), r);
    p.sidecar = bytes;
    return how;
  }],
];

/** Why the file must be refused, when that is sure: a plain P5 header whose samples are too few. */
function mustRefuse(p) {
  const [w, h, maxval] = p.fields.map((f) => (/^\d{1,12}$/.test(f) ? Number(f) : NaN));
  const plain = p.separators.slice(0, 3).every((s) => /^[ \t\r\n]+$/.test(s)) && /^[ \t\r\n]$/.test(p.separators[3]);
  if (p.magic !== 'P5' || !plain || !(w > 0 && h > 0 && maxval > 0 && maxval < 65536)) return null;
  const needed = w * h * (maxval < 256 ? 1 : 2);
  return p.data.length < needed ? `${p.data.length} bytes of samples, ${needed} needed` : null;
}

export function mutate(seed, random) {
  const [main, side] = seed.files;
  seed.parsed ??= parse(main.bytes);
  const p = { ...seed.parsed, fields: seed.parsed.fields.slice(), separators: seed.parsed.separators.slice(), sidecar: side?.bytes ?? null };
  const how = applySteps(p, random, STEPS);
  const files = [{ name: main.name, bytes: pgm(p) }];
  if (p.sidecar) files.push({ name: main.name.replace(/\.pgm$/, '.json'), bytes: p.sidecar });
  return { files, options: {}, how, invalid: mustRefuse(p) };
}

/** The same claim from the bytes alone. */
export function mustRefuseFiles(files) {
  const p = parse(files[0].bytes);
  return p && mustRefuse(p);
}

/** Width x height of the header, when it is a plain P5 header. */
export function declaredSize(files) {
  const p = parse(files[0].bytes);
  const [w, h] = (p?.fields ?? []).map((f) => (/^\d{1,12}$/.test(f) ? Number(f) : NaN));
  return p && p.magic === 'P5' && Number.isInteger(w) && Number.isInteger(h) ? { width: w, height: h } : null;
}
