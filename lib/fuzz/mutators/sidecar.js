// The NAME.json sidecar beside a height field: its fields (width, height, min, max, cell sizes,
// nodata) set to wrong types and out-of-range values, fields dropped or added, and the JSON
// itself broken. The text is written by hand so that values JSON.stringify cannot make
// (1e999, 9007199254740993) reach the parser as they would in a user's file.
import { JSON_VALUES } from '../values.js';

const FIELDS = ['width', 'height', 'min', 'max', 'cell_size_m', 'cell_size_x_m', 'cell_size_y_m', 'nodata'];
const encoder = new TextEncoder();

/** Sidecar text from [key, raw JSON value text] pairs. */
export function sidecarText(entries) {
  return `{${entries.map(([k, v]) => `${JSON.stringify(k)}: ${v}`).join(', ')}}`;
}

/** [key, raw value text] pairs of a sidecar's JSON object ([] when it is not one). */
export function sidecarEntries(bytes) {
  try {
    const json = JSON.parse(new TextDecoder().decode(bytes));
    if (json && typeof json === 'object' && !Array.isArray(json)) return Object.entries(json).map(([k, v]) => [k, JSON.stringify(v)]);
  } catch { /* a broken sidecar has no fields to keep */ }
  return [];
}

/**
 * @param {Uint8Array} bytes the sidecar
 * @param {import('../random.js').Random} random
 * @returns {[Uint8Array, string]}
 */
export function mutateSidecar(bytes, random) {
  const entries = sidecarEntries(bytes);
  const kind = random.weighted([[6, 'value'], [2, 'drop'], [1, 'add'], [1, 'duplicate'], [2, 'syntax'], [1, 'not an object']]);
  if (kind === 'value' || (kind === 'drop' && !entries.length)) {
    const key = random.chance(0.8) ? random.pick(FIELDS) : random.pick(entries)?.[0] ?? 'width';
    const value = random.pick(JSON_VALUES);
    const i = entries.findIndex(([k]) => k === key);
    if (i >= 0) entries[i] = [key, value]; else entries.push([key, value]);
    return [encoder.encode(sidecarText(entries)), `sidecar ${key}: ${value}`];
  }
  if (kind === 'drop') {
    const [key] = entries.splice(random.int(entries.length), 1)[0];
    return [encoder.encode(sidecarText(entries)), `sidecar without ${key}`];
  }
  if (kind === 'add') {
    entries.push([random.pick(['crs', 'bounds', '__proto__', 'constructor', 'licence']), random.pick(JSON_VALUES)]);
    return [encoder.encode(sidecarText(entries)), `sidecar with ${entries[entries.length - 1][0]}`];
  }
  if (kind === 'duplicate' && entries.length) {
    const [key] = random.pick(entries);
    entries.push([key, random.pick(JSON_VALUES)]);
    return [encoder.encode(sidecarText(entries)), `sidecar with ${key} twice`];
  }
  if (kind === 'not an object') {
    const text = random.pick(['[]', 'null', '"width"', '87', 'true', '[{"width": 87}]', '']);
    return [encoder.encode(text), `sidecar is ${JSON.stringify(text)}`];
  }
  const text = sidecarText(entries);
  const at = random.int(text.length + 1);
  const broken = random.pick([
    text.slice(0, at), text.slice(0, at) + text.slice(at + 1), `${text.slice(0, -1)},}`, `\ufeff${text}`, `${text}}`,
    text.replace(/"/g, "'"), text.replace(/: /g, ':NaN'),
  ]);
  return [encoder.encode(broken), 'sidecar JSON broken'];
}
