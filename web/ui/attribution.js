// The credits the web map tile layers on screen ask for ("© OpenStreetMap contributors"), in a
// corner of the page and at the bottom of every screenshot (app/screenshot.js): a service's
// terms usually require both.

/**
 * @param {HTMLElement} element the page's #attribution
 * @returns {{ show(layers: import('../app/layers.js').Layers): void, readonly text: string }}
 */
export function createAttribution(element) {
  let text = '';
  return {
    /** The visible layers' attributions, bottom first, each once. */
    show(layers) {
      const credits = layers.images.filter((layer) => layer.visible && layer.attribution).map((layer) => layer.attribution);
      text = [...new Set(credits)].join(' | ');
      element.textContent = text;
      element.hidden = text === '';
    },
    /** What the corner shows now ('' for nothing). */
    get text() {
      return text;
    },
  };
}
