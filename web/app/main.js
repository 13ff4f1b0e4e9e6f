// The viewer page: one viewer (viewer.js) filling the window, reading and writing the address
// bar, taking keys and drops anywhere on the page, and publishing its state for tests.
import { mountViewer, newState } from './viewer.js';

mountViewer(document.querySelector('.hexlod-page'), { page: true, state: newState() })
  .catch((error) => console.error(error));
