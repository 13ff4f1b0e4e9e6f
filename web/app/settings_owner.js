// The one owner of the viewer's settings. The panel, the keys, the test API and a new terrain
// all change a setting through set(): it checks the value (numbers against their ranges,
// choices against their lists), applies it (to the core, the cameras, the view), and when
// either fails it puts the previous value back, so the panel, the URL and the core never hold
// a value that was refused.
import { RANGES, SHADING_MODES, NORMAL_SOURCES, checkSetting } from './settings.js';

const CHOICES = { shading: SHADING_MODES, normals: NORMAL_SOURCES, embedding: ['exact', 'shifted'] };

/** The value to use, or an Error that says what is allowed. */
function checked(key, value, previous) {
  if (RANGES[key]) return checkSetting(key, value);
  if (CHOICES[key]) return CHOICES[key].includes(value) ? value : new Error(`${key} must be one of ${CHOICES[key].join(', ')}, not ${value}`);
  if (key === 'cellSize') {
    return Number.isFinite(value) && value > 0 ? value : new Error(`the cell size must be a positive number of metres, not ${value}`);
  }
  if (typeof previous === 'boolean') return typeof value === 'boolean' ? value : new Error(`${key} is on or off, not ${value}`);
  return new Error(`there is no setting ${key}`);
}

export class SettingsOwner {
  /**
   * @param {object} values the settings object (the panel edits it in place, then calls set)
   * @param {(key: string, value: any, previous: any) => void} apply throws when it cannot apply
   */
  constructor(values, apply) {
    this.values = values;
    this.apply = apply;
    this.applied = { ...values }; // what is in effect
  }

  /** Checks and applies a new value; on failure keeps the previous one and throws why. */
  set(key, value) {
    const previous = this.applied[key];
    const next = checked(key, value, previous);
    if (next instanceof Error) {
      this.values[key] = previous;
      throw next;
    }
    this.values[key] = next;
    try {
      this.apply(key, next, previous);
    } catch (error) {
      this.values[key] = previous;
      throw error;
    }
    this.applied[key] = next;
  }

  /** A value that is already in effect (e.g. a new terrain's cell size): recorded, not applied. */
  adopt(key, value) {
    this.values[key] = value;
    this.applied[key] = value;
  }
}
