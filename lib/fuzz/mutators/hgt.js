// SRTM .hgt tiles, structure-aware: the file size (one or two bytes off, the other tile size,
// cut anywhere), the tile name that gives the latitude (hemispheres, out-of-range degrees,
// case, folders, malformed names), voids (-32768) in blocks, rows or everywhere, and extreme
// heights. Seeds: a 1201x1201 tile (3") and, rarely, a 3601x3601 one (1", 26 MB), both written
// here from the Everest fixture, since SRTM has no small form.
import { grid } from '../fixtures.js';
import { applySteps } from './steps.js';

export const extension = 'hgt';

const VOID = -32768;

function tile(side) {
  const g = grid('everest', 200, 200);
  const bytes = new Uint8Array(side * side * 2);
  const view = new DataView(bytes.buffer);
  for (let y = 0; y < side; y++) {
    for (let x = 0; x < side; x++) view.setInt16(2 * (y * side + x), Math.round(g.values[Math.floor((y * 200) / side) * 200 + Math.floor((x * 200) / side)]), false);
  }
  return bytes;
}

export function seeds() {
  return [
    { files: [{ name: 'N27E086.hgt', bytes: tile(1201) }] },
    { files: [{ name: 'N27E086.hgt', bytes: tile(3601) }], weight: 0.003 }, // 26 MB: a case costs ~1 s
  ];
}

const NAMES = ['N27E086.hgt', 'S33W070.hgt', 'n00e000.hgt', 'N90E000.hgt', 'S90W180.hgt', 'N91E000.hgt', 'S99W999.hgt',
  'X27E086.hgt', 'N27E086.HGT', 'dir/N27E086.hgt', 'a\\S12W077.hgt', 'tile.hgt', 'N2E86.hgt', 'N27E086_x.hgt', '.hgt',
  'N27E086.SRTMGL1.hgt', 'N27E086.hgt.hgt', 'N-1E000.hgt', 'N89E179.hgt'];

const STEPS = [
  [4, function size(t, r) {
    const n = t.bytes.length;
    const to = r.pick([n - 1, n + 1, n - 2, n + 2, 1201 * 1201 * 2, 3601 * 3601 * 2 - 2, 1200 * 1200 * 2, 1201 * 1200 * 2,
      r.int(n), 2, 0, 1201 * 1201 * 2 + 3601 * 3601 * 2]);
    const out = new Uint8Array(Math.max(0, to));
    out.set(t.bytes.subarray(0, out.length));
    t.bytes = out;
    return `size ${out.length} bytes`;
  }],
  [4, function name(t, r) { t.name = r.pick(NAMES); return `named ${t.name}`; }],
  [4, function voids(t, r) {
    const side = Math.round(Math.sqrt(t.bytes.length / 2));
    const view = new DataView(t.bytes.buffer, t.bytes.byteOffset, t.bytes.length);
    const op = r.pick(['block', 'row', 'column', 'all', 'all but one', 'scattered']);
    const set = (i) => { if (2 * i + 1 < t.bytes.length) view.setInt16(2 * i, VOID, false); };
    if (op === 'block') { const x0 = r.int(side), y0 = r.int(side), s = r.range(1, 300); for (let y = y0; y < Math.min(side, y0 + s); y++) for (let x = x0; x < Math.min(side, x0 + s); x++) set(y * side + x); }
    else if (op === 'row') { const y = r.int(side); for (let x = 0; x < side; x++) set(y * side + x); }
    else if (op === 'column') { const x = r.int(side); for (let y = 0; y < side; y++) set(y * side + x); }
    else if (op === 'all' || op === 'all but one') { const keep = op === 'all' ? -1 : r.int(side * side); for (let i = 0; i < side * side; i++) if (i !== keep) set(i); }
    else for (let k = r.range(1, 1000); k > 0; k--) set(r.int(side * side));
    return `voids: ${op}`;
  }],
  [2, function extremes(t, r) {
    const view = new DataView(t.bytes.buffer, t.bytes.byteOffset, t.bytes.length);
    const v = r.pick([32767, -32767, 0, -1, 9000, -12000]);
    if (t.bytes.length < 2) return null;
    for (let k = r.range(1, 100); k > 0; k--) { const i = r.int(t.bytes.length >> 1); view.setInt16(2 * i, v, false); }
    return `heights ${v}`;
  }],
];

export function mutate(seed, random) {
  const t = { name: seed.files[0].name, bytes: seed.files[0].bytes.slice() };
  const how = applySteps(t, random, STEPS);
  const files = [{ name: t.name, bytes: t.bytes }];
  return { files, options: {}, how, invalid: mustRefuseFiles(files) };
}

/** Why a tile must be refused, when that is sure: its length is no tile's. */
export function mustRefuseFiles(files) {
  return declaredSize(files) ? null : `${files[0].bytes.length} bytes is no tile size`;
}

export function declaredSize(files) {
  const side = [1201, 3601].find((s) => s * s * 2 === files[0].bytes.length);
  return side ? { width: side, height: side } : null;
}
