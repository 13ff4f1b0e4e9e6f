// ESRI ASCII grids, structure-aware: header lines (ncols, nrows, corners or centres, cellsize
// or dx/dy, NODATA_value) with wrong, odd or huge values, dropped, doubled, reordered or
// unknown lines; the values (1e999, NaN, float32 overflow, malformed numbers, no-data runs),
// too few or too many of them, a consistent new size, and line-ending and whitespace changes.
// Seeds: the fixture (250x190 with voids) and small grids written here.
import { fixture, grid } from '../fixtures.js';
import { nearSize, NUMBER_TEXTS } from '../values.js';
import { applySteps } from './steps.js';

export const extension = 'asc';

const KEYS = ['ncols', 'nrows', 'xllcorner', 'xllcenter', 'yllcorner', 'yllcenter', 'cellsize', 'dx', 'dy', 'nodata_value'];
const encoder = new TextEncoder();

function text(header, rows, eol = '\n', sep = ' ') {
  return `${header.map(([k, v]) => `${k} ${v}`.trimEnd()).join(eol)}${eol}${rows.map((r) => r.join(sep)).join(eol)}${eol}`;
}

export function seeds() {
  const out = [{ files: [{ name: 'jacksboro_voids.asc', bytes: fixture('jacksboro_voids.asc') }] }];
  const g = grid('jacksboro', 12, 9, 60, 100);
  const rows = (fmt) => Array.from({ length: g.height }, (_, y) => Array.from(g.values.subarray(y * g.width, (y + 1) * g.width), fmt));
  out.push({ files: [{ name: 'small.asc', bytes: encoder.encode(text([['ncols', 12], ['nrows', 9], ['xllcorner', -84.3],
    ['yllcorner', 36.5], ['cellsize', 1 / 1200], ['NODATA_value', -9999]], rows((v, i) => (i === 3 ? '-9999' : v.toFixed(1))))) }] });
  out.push({ files: [{ name: 'centre.asc', bytes: encoder.encode(text([['NCOLS', 12], ['NROWS', 9], ['XLLCENTER', 500000],
    ['YLLCENTER', 4000000], ['DX', 30], ['DY', 25]], rows((v) => v.toExponential(4)), '\r\n', '\t')) }] });
  return out;
}

/** Header pairs and rows of value tokens of a grid's text (the whole body kept as rows of lines). */
function parse(bytes) {
  const lines = new TextDecoder('latin1').decode(bytes).split(/\r?\n/);
  const header = [];
  let i = 0;
  for (; i < lines.length; i++) {
    if (!lines[i].trim()) continue; // the loader reads tokens: blank lines are nothing
    const [k, ...v] = lines[i].trim().split(/\s+/);
    if (!KEYS.includes(k.toLowerCase())) break;
    header.push([k, v.join(' ')]);
  }
  const rows = lines.slice(i).filter((l) => l.trim()).map((l) => l.trim().split(/\s+/));
  return { header, rows };
}

const STEPS = [
  [6, function headerValue(g, r) {
    const present = g.header.map(([k]) => k);
    const key = r.chance(0.7) && present.length ? r.pick(present) : r.pick(KEYS);
    const i = g.header.findIndex(([k]) => k.toLowerCase() === key.toLowerCase());
    const old = Number(g.header[i]?.[1] ?? 12);
    const value = /^n(cols|rows)$/i.test(key) && r.chance(0.6)
      ? String(r.pick([nearSize(r, old), -old, old + 0.5, 1e9, 2 ** 31, 46341, 1e15, 2 ** 53 + 1]))
      : r.pick([...NUMBER_TEXTS, '0.0001', '1e-300', '-30', '1e300']);
    if (i >= 0) g.header[i] = [g.header[i][0], value]; else g.header.splice(r.int(g.header.length + 1), 0, [key, value]);
    return `${key} ${value}`;
  }],
  [3, function headerLine(g, r) {
    const op = r.pick(['drop', 'duplicate', 'move', 'case', 'unknown', 'no value', 'extra token']);
    const i = r.int(g.header.length);
    if (!g.header.length) return null;
    if (op === 'drop') g.header.splice(i, 1);
    else if (op === 'duplicate') g.header.splice(r.int(g.header.length), 0, [g.header[i][0], r.pick(NUMBER_TEXTS)]);
    else if (op === 'move') g.header.splice(r.int(g.header.length), 0, g.header.splice(i, 1)[0]);
    else if (op === 'case') g.header[i] = [r.pick([g.header[i][0].toUpperCase(), g.header[i][0].toLowerCase(), 'nCoLs']), g.header[i][1]];
    else if (op === 'unknown') g.header.splice(i, 0, [r.pick(['byteorder', 'foo', '#', 'ncols2', 'cellsize_x']), 'x']);
    else if (op === 'no value') g.header[i] = [g.header[i][0], ''];
    else g.header[i] = [g.header[i][0], `${g.header[i][1]} 7`];
    return `header line ${op}`;
  }],
  [3, function resize(g, r) {
    // A new size with exactly that many values: shapes the loader must accept.
    const w = r.pick([1, 2, 3, r.range(1, 40), r.range(1, 300)]), h = r.pick([1, 2, 3, r.range(1, 40), r.range(1, 300)]);
    const nodata = g.header.find(([k]) => k.toLowerCase() === 'nodata_value')?.[1] ?? '-9999';
    const base = r.range(-500, 9000);
    g.rows = Array.from({ length: h }, () => Array.from({ length: w }, () => (r.chance(0.05) ? nodata : String(base + r.range(-50, 50)))));
    for (const [key, value] of [['ncols', w], ['nrows', h]]) {
      const i = g.header.findIndex(([k]) => k.toLowerCase() === key);
      if (i >= 0) g.header[i] = [g.header[i][0], String(value)]; else g.header.unshift([key, String(value)]);
    }
    return `resized to ${w}x${h} with matching values`;
  }],
  [5, function valuesBad(g, r) {
    if (!g.rows.length) return null;
    const value = r.pick([...NUMBER_TEXTS, '1e999', '3.5e38', 'NaN']);
    const k = r.weighted([[6, 1], [2, r.range(2, 20)], [1, 1000]]);
    for (let n = 0; n < k; n++) {
      const y = r.int(g.rows.length);
      g.rows[y] = g.rows[y].slice();
      g.rows[y][r.int(g.rows[y].length)] = value;
    }
    return `${k} values ${JSON.stringify(value)}`;
  }],
  [2, function noData(g, r) {
    const nodata = g.header.find(([k]) => k.toLowerCase() === 'nodata_value')?.[1] ?? '-9999';
    const op = r.pick(['all', 'all but one', 'a row', 'a column']);
    const x = r.int(g.rows[0]?.length ?? 1), y = r.int(g.rows.length);
    g.rows = g.rows.map((row, j) => row.map((v, i) => (op === 'all' || (op === 'all but one' && (i !== x || j !== y)) ||
      (op === 'a row' && j === y) || (op === 'a column' && i === x) ? nodata : v)));
    return `no-data: ${op}`;
  }],
  [3, function count(g, r) {
    const op = r.pick(['fewer', 'more', 'row short', 'row long', 'many more', 'none']);
    if (!g.rows.length) return null;
    const y = r.int(g.rows.length);
    if (op === 'fewer') g.rows = g.rows.slice(0, y);
    else if (op === 'more') g.rows = [...g.rows, ['1', '2']];
    else if (op === 'row short') g.rows[y] = g.rows[y].slice(0, -1);
    else if (op === 'row long') g.rows[y] = [...g.rows[y], '5'];
    else if (op === 'many more') g.rows = [...g.rows, ...Array.from({ length: 2000 }, () => ['0', '0', '0', '0', '0', '0', '0', '0'])];
    else g.rows = [];
    return `values: ${op}`;
  }],
  [2, function layout(g, r) {
    g.eol = r.pick(['\r\n', '\r', '\n\n', ' ', '\t\n']);
    g.sep = r.pick([' ', '\t', '  ', ',', ' \u00a0', '\0']);
    return `line ends ${JSON.stringify(g.eol)}, separators ${JSON.stringify(g.sep)}`;
  }],
];

/** A value the loader must read: a decimal number that float32 holds. */
const GOOD_VALUE = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;
const goodValue = (t) => GOOD_VALUE.test(t) && Number.isFinite(Math.fround(Number(t)));

/**
 * Why the grid must be refused, when that is sure: its header is plain (known keys, finite
 * numbers, a whole positive size) and the values are too few or too many, or one is no number
 * float32 holds. Only rows a mutation touched are scanned (the seeds' values are good).
 */
function mustRefuse(g, seedRows) {
  const h = {};
  for (const [k, v] of g.header) {
    if (!KEYS.includes(k.toLowerCase()) || !/^\S+$/.test(v) || !Number.isFinite(Number(v))) return null;
    h[k.toLowerCase()] = Number(v);
  }
  if (!(h.ncols > 0 && h.nrows > 0 && Number.isInteger(h.ncols) && Number.isInteger(h.nrows))) return null;
  // An empty token (a value replaced by '') is written as two spaces: no value at all.
  const count = g.rows.reduce((s, row) => s + row.filter((t) => t !== '').length, 0);
  if (count !== h.ncols * h.nrows) return `it has ${count} values for ${h.ncols}x${h.nrows}`;
  if (![' ', '\t', '  '].includes(g.sep) && g.rows.some((row) => row.filter((t) => t !== '').length > 1)) return `its values are separated by ${JSON.stringify(g.sep)}`;
  const seedSet = new Set(seedRows);
  for (const row of g.rows) {
    if (seedSet.has(row)) continue;
    const bad = row.find((t) => t !== '' && !goodValue(t));
    if (bad !== undefined) return `a value is ${JSON.stringify(bad)}`;
  }
  return null;
}

export function mutate(seed, random) {
  seed.parsed ??= parse(seed.files[0].bytes);
  const g = { header: seed.parsed.header.map((p) => p.slice()), rows: seed.parsed.rows.slice(), eol: '\n', sep: ' ' };
  const how = applySteps(g, random, STEPS);
  return { files: [{ name: seed.files[0].name, bytes: encoder.encode(text(g.header, g.rows, g.eol, g.sep)) }], options: {}, how,
    invalid: mustRefuse(g, seed.parsed.rows) };
}

/** Rows as the minimiser's parts: the grid is written back with nrows counting the rows left. */
export function split(bytes) {
  const g = parse(bytes);
  if (!g.header.some(([k]) => k.toLowerCase() === 'nrows')) return null;
  return {
    parts: g.rows.map((row) => encoder.encode(row.join(' '))),
    join: (parts) => {
      const rows = parts.filter(Boolean).map((p) => new TextDecoder('latin1').decode(p).split(' '));
      const header = g.header.map(([k, v]) => [k, k.toLowerCase() === 'nrows' ? String(rows.length) : v]);
      return encoder.encode(text(header, rows));
    },
    shrinkInside: false,
  };
}

/** The same claim from the bytes alone (after byte mutations, and for the minimiser). */
export function mustRefuseFiles(files) {
  const g = parse(files[0].bytes);
  const text = new TextDecoder('latin1').decode(files[0].bytes);
  // Separators other than spaces, tabs and line ends glue values into one token.
  return mustRefuse({ ...g, sep: /[^ \t\r\n\S]/.test(text) ? '?' : ' ' }, []);
}

/** ncols x nrows as the header says them (the last line of each wins, as in the loader). */
export function declaredSize(files) {
  const header = {};
  const tokens = new TextDecoder('latin1').decode(files[0].bytes.subarray(0, 4096)).split(/[ \t\r\n]+/).filter(Boolean);
  for (let i = 0; i + 1 < tokens.length && KEYS.includes(tokens[i].toLowerCase()); i += 2) header[tokens[i].toLowerCase()] = Number(tokens[i + 1]);
  return Number.isInteger(header.ncols) && Number.isInteger(header.nrows) ? { width: header.ncols, height: header.nrows } : null;
}
