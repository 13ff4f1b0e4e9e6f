// <hexlod-viewer>: the viewer as an HTML element (import 'hexlod/element').
//   <hexlod-viewer src="dem.tif" image="photo.jpg" tau="2" ui="false"></hexlod-viewer>
// Its attributes are src, image, ui and every setting by its address-bar name (tau, budget, exag,
// shading, contours, cint, ...: web/app/settings_table.js), read as the address bar reads them.
// Changing one applies it live. Its `viewer` property is the createViewer() handle once the
// first terrain is shown (`ready` resolves to it); its events come as DOM events on the element:
// hexlod-loaded, hexlod-error, hexlod-pick (detail: the API's), and hexlod-ready.
import { createViewer } from './index.js';
import { URL_KEYS, checkSetting } from '../app/settings_table.js';

const SETTING_OF_ATTRIBUTE = new Map(URL_KEYS.map(([key, name]) => [name, key]));
const OFF = new Set(['false', '0', 'off', 'no']);

export class HexlodViewerElement extends HTMLElement {
  static get observedAttributes() {
    return ['src', 'image', 'ui', ...SETTING_OF_ATTRIBUTE.keys()];
  }

  constructor() {
    super();
    this.viewer = null;
    this.starting = null;
    this.ready = new Promise((resolve, reject) => { this.settle = { resolve, reject }; });
    this.ready.catch(() => {}); // a failure is told by hexlod-error too; an unawaited ready must not be an unhandled rejection
  }

  connectedCallback() {
    if (this.viewer || this.starting) return;
    const options = { ui: !OFF.has((this.getAttribute('ui') ?? 'true').toLowerCase()), on: this.forwarders() };
    if (this.hasAttribute('src')) options.src = this.getAttribute('src');
    if (this.hasAttribute('image')) options.image = this.getAttribute('image');
    const refused = [];
    for (const [name, key] of SETTING_OF_ATTRIBUTE) {
      if (!this.hasAttribute(name)) continue;
      const value = checkSetting(key, this.getAttribute(name));
      if (value instanceof Error) refused.push(value.message);
      else options[key] = value;
    }
    this.starting = createViewer(this, options).then((viewer) => {
      this.viewer = viewer;
      this.starting = null;
      for (const message of refused) this.tell('error', { message: `${message} (the default is used)` });
      this.tell('ready', { viewer });
      this.settle.resolve(viewer);
      return viewer;
    }, (error) => {
      this.starting = null;
      this.tell('error', { message: error.message });
      this.settle.reject(error);
    });
  }

  disconnectedCallback() {
    // Moved within the page (removed and put back at once) keeps its viewer.
    queueMicrotask(() => {
      if (this.isConnected) return;
      this.viewer?.dispose();
      this.viewer = null;
    });
  }

  attributeChangedCallback(name, old, value) {
    const viewer = this.viewer;
    if (!viewer || old === value || value === null) return; // before the first terrain: read when it starts
    const failed = (error) => this.tell('error', { message: error.message });
    if (name === 'src') viewer.open(value).catch(failed);
    else if (name === 'image') viewer.drape(value).catch(failed);
    else if (name === 'ui') viewer.root.classList.toggle('hexlod-bare', OFF.has(value.toLowerCase()));
    else {
      const key = SETTING_OF_ATTRIBUTE.get(name);
      const checked = checkSetting(key, value);
      if (checked instanceof Error) failed(checked);
      else {
        try {
          viewer.set(key, checked);
        } catch (error) {
          failed(error);
        }
      }
    }
  }

  /** The API's events, told as DOM events on the element. */
  forwarders() {
    const forward = (type) => (detail) => this.tell(type, detail);
    return { loaded: forward('loaded'), error: forward('error'), pick: forward('pick') };
  }

  tell(type, detail) {
    this.dispatchEvent(new CustomEvent(`hexlod-${type}`, { detail, bubbles: true }));
  }
}

if (!customElements.get('hexlod-viewer')) customElements.define('hexlod-viewer', HexlodViewerElement);
