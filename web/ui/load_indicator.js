// What a load shows while it runs: the progress bar and the Cancel button, once it takes longer
// than a blink, and the progress callbacks that drive the bar (and stop a decoder at its next
// pause once its load is cancelled).
import { formatMB } from './url_fetch.js';

const PROGRESS_AFTER_MS = 100; // slower than a blink: show the bar

/**
 * @param {{ progress: HTMLProgressElement, cancelButton: HTMLElement, state: object,
 *   showStatus: (message: string, isError?: boolean) => void }} parts
 *   state: the page's (its progress, 0..1, for tests)
 */
export function createLoadIndicator({ progress, cancelButton, state, showStatus }) {
  let timer = 0;
  state.progress = 0;
  return {
    /** A load starts: the bar (and Cancel, when `cancellable`) show if it lasts. */
    start(cancellable) {
      clearTimeout(timer);
      progress.value = 0;
      timer = setTimeout(() => { progress.hidden = false; cancelButton.hidden = !cancellable; }, PROGRESS_AFTER_MS);
    },

    hide() {
      clearTimeout(timer);
      progress.hidden = cancelButton.hidden = true;
    },

    /** The progress callback of a decode: the bar, and a stop at the next pause once `signal` aborts. */
    loadProgress(signal) {
      state.progress = 0;
      return (fraction, phase) => {
        if (signal.aborted) throw signal.reason;
        state.progress = fraction;
        progress.value = fraction;
        progress.title = phase;
      };
    },

    /** A download's progress in the status line (unless `quiet`) and the bar. */
    downloadProgress(name, quiet) {
      if (!quiet) showStatus(`Loading ${name}…`);
      let shown = '';
      return (received, total) => {
        const text = `Loading ${name}… ${formatMB(received)}${total ? ` of ${formatMB(total)}` : ''} MB`;
        if (!quiet && text !== shown) showStatus(shown = text);
        if (total) progress.value = received / total;
        else progress.removeAttribute('value'); // a bar that says "busy": the size is unknown
        progress.title = 'downloading';
      };
    },
  };
}
