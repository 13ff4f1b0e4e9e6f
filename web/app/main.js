// The viewer page: one viewer (viewer.js) filling the window, reading and writing the address
// bar, taking keys and drops anywhere on the page, and publishing its state for tests. In an
// <iframe> it answers the host page's postMessage commands (embed_messages.js); ?ui=0 shows the
// terrain alone, without the panel, the figures and the file bar.
import { mountViewer, newState } from './viewer.js';
import { ViewerHandle } from '../api/viewer_handle.js';
import { answerHost } from './embed_messages.js';

const root = document.querySelector('.hexlod-page');
const viewer = new ViewerHandle(root);
const ui = new URLSearchParams(location.search).get('ui') !== '0';
mountViewer(root, { page: true, ui, state: newState(), emit: (type, detail) => viewer.emit(type, detail),
  assembled: (parts) => { viewer.attach(parts); answerHost(viewer, parts.dom); } })
  .catch((error) => console.error(error));
