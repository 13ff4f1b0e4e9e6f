// The viewer page inside an <iframe> of a host page that cannot bundle the package: it answers
// the host's postMessage commands with the JS API (web/api/viewer_handle.js) and tells the host
// its events.
//   host → viewer  { hexlod: COMMAND, id, args: [...] }
//   viewer → host  { hexlod: 'reply', id, result } or { hexlod: 'reply', id, error: 'TypeError: …' }
//                  { hexlod: 'event', type: 'loaded' | 'error' | 'pick', detail }
// Commands: open, drape, addOverlay (URLs), set (key, value), settings, terrain, flyTo (view,
// options), camera, reset, screenshot (options; the reply is a PNG Blob). Only the window that
// holds the frame is answered.

const COMMANDS = {
  open: (viewer, url) => viewer.open(url),
  drape: (viewer, url) => viewer.drape(url),
  addOverlay: (viewer, url) => viewer.addOverlay(url),
  set: (viewer, key, value) => { viewer.set(key, value); return viewer.settings[key]; },
  settings: (viewer) => viewer.settings,
  terrain: (viewer) => viewer.terrain,
  flyTo: (viewer, view, options) => viewer.camera.flyTo(view, options),
  camera: (viewer) => viewer.camera.get(),
  reset: (viewer) => viewer.camera.reset(),
  screenshot: (viewer, options) => viewer.screenshot(options),
};
const EVENTS = ['loaded', 'error', 'pick'];

/**
 * Answers the host of the frame, when there is one.
 * @param {import('../api/viewer_handle.js').ViewerHandle} viewer
 * @param {import('./viewer_dom.js').ViewerDom} dom
 */
export function answerHost(viewer, dom) {
  const host = window.parent;
  if (host === window) return;
  for (const type of EVENTS) viewer.on(type, (detail) => host.postMessage({ hexlod: 'event', type, detail: plain(detail) }, '*'));
  dom.on(window, 'message', async (event) => {
    if (event.source !== host || typeof event.data?.hexlod !== 'string') return;
    const { hexlod: command, id = null, args = [] } = event.data;
    const reply = (answer) => host.postMessage({ hexlod: 'reply', id, ...answer }, event.origin === 'null' ? '*' : event.origin);
    if (!Object.hasOwn(COMMANDS, command)) {
      reply({ error: `RangeError: unknown command '${command}' (${Object.keys(COMMANDS).join(', ')})` });
      return;
    }
    try {
      if (!Array.isArray(args)) throw new TypeError('args must be an array');
      reply({ result: plain(await COMMANDS[command](viewer, ...args)) });
    } catch (error) {
      reply({ error: `${error.name}: ${error.message}` });
    }
  });
}

/** What can cross to the host: data (a Blob crosses as it is), not functions. */
function plain(value) {
  if (value === undefined || value === null || value instanceof Blob) return value ?? null;
  return JSON.parse(JSON.stringify(value));
}
