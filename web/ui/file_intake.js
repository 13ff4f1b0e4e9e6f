// How height-field files reach the page: drag & drop, the file picker, ?src=URL. Shows a
// progress bar for loads slower than a blink, asks for the size of a RAW file that does not
// say it, and shows a bad file's message while the current terrain, camera and settings stay.
// The page (main.js) hands in `show` (switch to a loaded terrain) and gets `open`/`openUrl`.
import { loadTerrain } from '../loaders/terrain_source.js';
import { ACCEPT_EXTENSIONS, ACCEPTED } from '../loaders/index.js';
import { extensionOf, baseNameOf } from '../loaders/common.js';

const PROGRESS_AFTER_MS = 100; // slower than a blink: show the bar

/** Metres as the spacing field shows them: six significant digits, no trailing zeros. */
const formatMetres = (metres) => String(Number(metres.toPrecision(6)));

/**
 * @param {{ core: import('../core/core.js').HexlodCore, state: object, show: (loaded: object) => void,
 *   showStatus: (message: string, isError?: boolean) => void, setCellSize: (metres: number) => boolean,
 *   currentSpacing: () => {spacingX: number, spacingY: number} }} page
 *   setCellSize: the panel's cell size setting (east-west metres; north-south keeps its ratio),
 *   false when refused (the page shows why); currentSpacing: the terrain on screen's
 * @returns {{ open: (files: Array<{name: string, bytes: Uint8Array}>, options?: object) => Promise<boolean>,
 *   openUrl: (url: string) => Promise<boolean>, showSpacing: (terrain: object, assumed?: boolean) => void }}
 */
export function createFileIntake({ core, state, show, showStatus, setCellSize, currentSpacing }) {
  const $ = (id) => document.getElementById(id);
  const picker = $('file-input'), progress = $('load-progress'), encodingSelect = $('png-encoding');
  const spacingInput = $('spacing-input'), spacingForm = $('spacing-form'), spacingRatio = $('spacing-ratio');
  const rawDialog = $('raw-dialog'), rawForm = $('raw-form');
  state.loading = false;
  state.progress = 0;

  /**
   * The terrain's spacing in the field: east-west metres, and north-south beside it when the
   * cells are not square (the two scale together, as the panel's cell size does). `assumed`: a
   * guess (the file said nothing), outlined until the user sets one here or in the panel.
   */
  function showSpacing(terrain, assumed = false) {
    spacingForm.classList.toggle('assumed', assumed);
    spacingInput.value = formatMetres(terrain.spacingX);
    const square = Math.abs(terrain.spacingY - terrain.spacingX) <= 1e-9 * terrain.spacingX;
    spacingRatio.hidden = square;
    spacingRatio.textContent = square ? '' : `(${formatMetres(terrain.spacingY)} m north–south)`;
    spacingInput.title = square ? 'metres between samples' : 'metres between columns (east–west); rows scale with them';
  }

  /** Loads files into a new terrain; on failure the current one stays and the message shows. */
  async function open(files, options = {}) {
    if (state.loading) {
      showStatus('Still loading the previous file…', true);
      return false;
    }
    const names = files.map((f) => f.name).join(' + ');
    state.loading = true;
    state.progress = 0;
    showStatus(`Loading ${names}…`);
    const timer = setTimeout(() => { progress.hidden = false; }, PROGRESS_AFTER_MS);
    const onProgress = (fraction, phase) => {
      state.progress = fraction;
      progress.value = fraction;
      progress.title = phase;
    };
    const encoding = encodingSelect.value;
    try {
      const loaded = await loadTerrain(core, files, { ...options, encoding, onProgress, guessSpacing: true });
      show(loaded);
      showSpacing(loaded.terrain, !loaded.field.spacingFromFile);
      state.error = null;
      showStatus('');
      return true;
    } catch (error) {
      if (error.needsSize && !options.width) {
        clearTimeout(timer);
        progress.hidden = true;
        const size = await askRawSize(error.file, error.samples);
        state.loading = false;
        if (size) return open(files, { ...options, ...size });
      }
      state.error = error.message;
      showStatus(error.message, true);
      console.warn(`hexlod: ${error.message}`);
      return false;
    } finally {
      clearTimeout(timer);
      progress.hidden = true;
      state.loading = false;
    }
  }

  /** Asks the width and height of a RAW file of `samples` samples; null when cancelled. */
  function askRawSize(name, samples) {
    $('raw-name').textContent = `${name} holds ${samples.toLocaleString('en')} 16-bit samples.`;
    const width = $('raw-width'), height = $('raw-height');
    width.value = '';
    height.value = '';
    width.oninput = () => { if (samples % Number(width.value) === 0) height.value = samples / Number(width.value); };
    return new Promise((resolve) => {
      rawForm.onsubmit = (e) => {
        e.preventDefault();
        rawDialog.close();
        resolve({ width: Number(width.value), height: Number(height.value) });
      };
      $('raw-cancel').onclick = () => { rawDialog.close(); resolve(null); };
      rawDialog.showModal();
    });
  }

  /** Fetches a height field (and its NAME.json sidecar, when the server has one) and opens it. */
  async function openUrl(url) {
    const name = decodeURIComponent(new URL(url, location.href).pathname.split('/').pop() || 'download');
    try {
      const response = await fetch(url);
      if (!response.ok) throw new Error(`HTTP ${response.status}`);
      // A server's "not found" page often comes back as 200 text/html; no height field is HTML.
      if (/text\/html/.test(response.headers.get('content-type') ?? '')) throw new Error('the server sent an HTML page');
      const files = [{ name, bytes: new Uint8Array(await response.arrayBuffer()) }];
      if (extensionOf(name) !== 'json') {
        const sidecarUrl = new URL(`${baseNameOf(new URL(url, location.href).pathname)}.json`, location.href);
        const sidecar = await fetch(sidecarUrl).catch(() => null);
        if (sidecar?.ok && /json/.test(sidecar.headers.get('content-type') ?? '')) {
          files.push({ name: `${baseNameOf(name)}.json`, bytes: new Uint8Array(await sidecar.arrayBuffer()) });
        }
      }
      return await open(files);
    } catch (error) {
      const message = `${name}: cannot fetch ${url} (${error.message})`;
      state.error = message;
      showStatus(message, true);
      return false;
    }
  }

  const readFiles = (list) => Promise.all([...list].map(async (file) => ({ name: file.name, bytes: new Uint8Array(await file.arrayBuffer()) })));

  window.addEventListener('dragover', (e) => {
    e.preventDefault();
    document.body.classList.add('dragging');
  });
  window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
  window.addEventListener('drop', async (e) => {
    e.preventDefault();
    document.body.classList.remove('dragging');
    const dropped = e.dataTransfer?.files ?? [];
    if (dropped.length) await open(await readFiles(dropped));
  });
  picker.accept = ACCEPT_EXTENSIONS.join(',');
  $('open-button').title = `Open a height field: ${ACCEPTED}`;
  $('open-button').onclick = () => picker.click();
  picker.onchange = async () => {
    if (picker.files.length) await open(await readFiles(picker.files));
    picker.value = '';
  };
  // The same setting as the panel's cell size (the form is novalidate: our message, not the
  // browser's bubble, says what is wrong): the terrain is scaled in place (no reload) and
  // the cameras with it; a bad value leaves both, and the page says why. (This form used to
  // reload the file with square cells, so Apply on a field with 806.9 x 926 m cells squashed it.)
  spacingForm.onsubmit = (e) => {
    e.preventDefault();
    if (state.loading || !state.terrain) return;
    // '' also for text that is not a number, which Number() would read as 0.
    const text = spacingInput.value.trim();
    if (text === '') showStatus('spacing: type the metres between samples, a positive number', true);
    else if (setCellSize(Number(text))) return; // main.js shows the new spacing
    spacingInput.value = formatMetres(currentSpacing().spacingX); // what is in effect again
  };
  return { open, openUrl, showSpacing };
}
