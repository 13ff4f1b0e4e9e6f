// The one owner of the viewer's settings. The panel, the keys, the test API and a new terrain
// all change a setting through set(): it checks the value against the settings table
// (settings_table.js: ranges, choices, switches), applies it (to the core, the cameras, the view), and when
// either fails it puts the previous value back, so the panel, the URL and the core never hold
// a value that was refused.
import { checkSetting } from './settings_table.js';

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
    const next = checkSetting(key, value);
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
