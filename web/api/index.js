// hexlod's JS API for other people's pages: createViewer(element, options) puts a viewer into
// an element and resolves to its handle once the first terrain is shown. Any number of viewers
// may share a page; each has its own WebAssembly core and WebGL context, freed by dispose().
// Settings go by the settings table's keys (web/app/settings_table.js), as in the panel and the
// address bar: tau, budgetMs, exaggeration, shading, contours, ... Types: types/index.d.ts.
import { mountViewer, newState } from '../app/viewer.js';
import { SETTINGS } from '../app/settings_table.js';
import { checkSettingValue, describe } from './arguments.js';
import { ViewerHandle, EVENTS } from './viewer_handle.js';
import { ensureStyles } from './styles.js';

export { SETTINGS, EVENTS };
export const VERSION = '0.2.0';

// createViewer's own options; every other key is a setting.
const OPTIONS = new Set(['src', 'image', 'images', 'overlays', 'ui', 'on']);

/**
 * A viewer inside `element`, on the default terrain unless `options.src` names another.
 * @param {HTMLElement} element  the viewer fills it (give it a size; at least 300 px high otherwise)
 * @param {object} [options]  src (a URL), image or images (URLs to drape), overlays (URLs of
 *   GPX, KML, GeoJSON), ui (false: a bare canvas), on ({ loaded, frame, error, pick } handlers,
 *   attached before the first terrain loads), and settings by their keys (tau: 1, budgetMs: 4, ...)
 * @returns {Promise<ViewerHandle>}
 * @throws {TypeError|RangeError} at once, for an argument that is not what it should be
 */
export async function createViewer(element, options = {}) {
  if (typeof HTMLElement === 'undefined' || !(element instanceof HTMLElement)) {
    throw new TypeError(`createViewer: the first argument must be an HTML element, not ${describe(element)}`);
  }
  if (options === null || typeof options !== 'object') throw new TypeError(`createViewer: options must be an object, not ${describe(options)}`);
  const settings = checkSettings(options);
  const urls = (key, value) => {
    const list = value === undefined ? [] : Array.isArray(value) ? value : [value];
    for (const url of list) if (typeof url !== 'string' || url === '') throw new TypeError(`createViewer: ${key} must be a URL string, not ${describe(url)}`);
    return list;
  };
  const src = options.src === undefined || options.src === null ? null : urls('src', options.src)[0];
  const images = [...urls('image', options.image), ...urls('images', options.images)];
  const overlays = urls('overlays', options.overlays);
  if (options.ui !== undefined && typeof options.ui !== 'boolean') throw new TypeError(`createViewer: ui must be true or false, not ${describe(options.ui)}`);
  if (element.querySelector('.hexlod') || element.classList.contains('hexlod')) {
    throw new TypeError('createViewer: this element already holds a viewer; dispose() it first');
  }
  ensureStyles();
  const root = document.createElement('div');
  element.append(root);
  const handle = new ViewerHandle(root);
  for (const [type, handler] of Object.entries(options.on ?? {})) handle.on(type, handler);
  try {
    await mountViewer(root, { settings, src, images, overlays, ui: options.ui ?? true,
      emit: (type, detail) => handle.emit(type, detail), state: newState(), assembled: (parts) => handle.attach(parts) });
  } catch (error) {
    handle.dispose();
    root.remove();
    throw error;
  }
  return handle;
}

/** The settings among `options`, each checked: a TypeError for a wrong kind, a RangeError for a value out of range. */
export function checkSettings(options, caller = 'createViewer') {
  const settings = {};
  for (const [key, value] of Object.entries(options)) {
    if (OPTIONS.has(key)) continue;
    settings[key] = checkSettingValue(key, value, caller);
  }
  return settings;
}
