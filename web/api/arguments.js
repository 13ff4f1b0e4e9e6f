// How the JS API checks what it is given: a TypeError for the wrong kind of value, a RangeError
// for one out of range, each naming the call and the argument.
import { SETTINGS, checkSetting } from '../app/settings_table.js';

/** One setting's value as the API takes it (numbers as numbers, switches as booleans), or a thrown TypeError or RangeError. */
export function checkSettingValue(key, value, caller) {
  const s = SETTINGS[key];
  if (!s) throw new TypeError(`${caller}: unknown option '${key}' (settings: ${Object.keys(SETTINGS).join(', ')})`);
  const kind = typeof s.default;
  if (!s.parse && !s.positive && kind !== typeof value) throw new TypeError(`${caller}: ${key} must be a ${kind}, not ${describe(value)}`);
  const checked = checkSetting(key, value);
  if (checked instanceof Error) throw new RangeError(`${caller}: ${checked.message}`);
  return checked;
}

/** A value as a message names it. */
export function describe(value) {
  if (value === null) return 'null';
  if (Array.isArray(value)) return 'an array';
  if (typeof value === 'string') return `the string '${value.length > 40 ? `${value.slice(0, 40)}…` : value}'`;
  if (typeof value === 'object') return value.constructor?.name ? `a ${value.constructor.name}` : 'an object';
  return `${typeof value} ${String(value)}`;
}
