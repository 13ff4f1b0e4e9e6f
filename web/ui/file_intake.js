// How height-field files reach the page: drag & drop, the file picker, ?src=URL. Shows a
// progress bar and a Cancel button for loads slower than a blink, asks for the size of a RAW
// file that does not say it, and shows a bad file's message while the current terrain, camera
// and settings stay. One load at a time (load_sequence.js): opening a file cancels the load in
// flight, so a late answer never replaces what the user opened since. URLs are fetched within
// the settings' time limit and size cap (url_fetch.js), with a NAME.json sidecar from beside
// the data when its server has one.
// The page (main.js) hands in `show` (switch to a loaded terrain) and gets `openUrl`/`openLinks`.
import { loadTerrain } from '../loaders/terrain_source.js';
import { ACCEPT_EXTENSIONS, ACCEPTED } from '../loaders/index.js';
import { extensionOf, baseNameOf } from '../loaders/common.js';
import { LoadSequence } from './load_sequence.js';
import { fetchLimited, formatMB, LimitError } from './url_fetch.js';
import { dropRoles, IMAGE_EXTENSIONS } from '../imagery/drop_roles.js';
import { ImageError } from '../imagery/image_error.js';
import { worldFileCandidates } from '../geo/index.js';
import { detectPngEncoding, hasPngSignature } from '../loaders/png.js';
import { isTiffName, shouldOpenTiled, openTiled, afterTilesFailed } from './tiled_open.js';

// The PNG colours menu: 'image' drapes a colour PNG; an encoding makes it heights.
const PNG_CHOICE = { auto: 'auto', image: 'image', 'terrain-rgb': 'height', terrarium: 'height' };
const PROGRESS_AFTER_MS = 100; // slower than a blink: show the bar
const HEAD_BYTES = 64 * 1024; // of each opened file, to tell height fields from images
const MB = 2 ** 20;

/** Metres as the spacing field shows them: six significant digits, no trailing zeros. */
const formatMetres = (metres) => String(Number(metres.toPrecision(6)));

/** Looks at a height field's or an image's answer before its body is read: an error, or a page, is neither. */
function acceptFile(response) {
  if (!response.ok) throw new Error(`HTTP ${response.status}`);
  // A server's "not found" page often comes back as 200 text/html; no height field is HTML.
  if (/text\/html/.test(response.headers.get('content-type') ?? '')) throw new Error('the server sent an HTML page');
  return true;
}

/** A sidecar is read when the server has one: a JSON answer, not its "not found" page. */
const acceptSidecar = (response) => response.ok && /json/.test(response.headers.get('content-type') ?? '');

/** A world file likewise: any answer but an error or a page (servers call .jgw many things). */
const acceptWorldFile = (response) => response.ok && !/text\/html/.test(response.headers.get('content-type') ?? '');

/**
 * @param {{ core: import('../core/core.js').HexlodCore, state: object, settings: object,
 *   show: (loaded: object, source: string|null) => void,
 *   showStatus: (message: string, isError?: boolean) => void, setCellSize: (metres: number) => boolean,
 *   currentSpacing: () => {spacingX: number, spacingY: number}, defaultUrlTimeoutS: number }} page
 *   settings: the page's (urlTimeout in seconds and urlMaxMB, read at each URL load); show: the
 *   loaded terrain and the URL it came from (null for a file); setCellSize: the panel's cell
 *   size setting (east-west metres; north-south keeps its ratio), false when refused (the page
 *   shows why); currentSpacing: the terrain on screen's; drape(image, worldFile, url): drapes an
 *   image ({ name, blob }) on the terrain on screen (app/image_stage.js), null when refused;
 *   defaultUrlTimeoutS: the time limit of the page's own files (the setting's default)
 * @returns {{ openUrl, openImageUrl, openLinks, idle: () => Promise<void>, showSpacing: (terrain: object, assumed?: boolean) => void }}
 *   openUrl, openImageUrl and openLinks resolve to 'shown', 'failed' (the status line says why) or
 *   'cancelled' (by the Cancel button, or by a file opened meanwhile)
 */
export function createFileIntake({ core, state, settings, show, showStatus, setCellSize, currentSpacing,
  defaultUrlTimeoutS, drape = async () => null }) {
  const $ = (id) => document.getElementById(id);
  const picker = $('file-input'), progress = $('load-progress'), encodingSelect = $('png-encoding');
  const cancelButton = $('load-cancel');
  const spacingInput = $('spacing-input'), spacingForm = $('spacing-form'), spacingRatio = $('spacing-ratio');
  const rawDialog = $('raw-dialog'), rawForm = $('raw-form');
  state.loading = false;
  state.progress = 0;

  // The progress bar and the Cancel button, shown when a load takes longer than a blink.
  let indicatorTimer = 0;
  const indicator = {
    start(cancellable) {
      clearTimeout(indicatorTimer);
      progress.value = 0;
      indicatorTimer = setTimeout(() => { progress.hidden = false; cancelButton.hidden = !cancellable; }, PROGRESS_AFTER_MS);
    },
    hide() {
      clearTimeout(indicatorTimer);
      progress.hidden = cancelButton.hidden = true;
    },
  };
  const loads = new LoadSequence((busy) => {
    state.loading = busy;
    if (!busy) indicator.hide();
  });
  cancelButton.onclick = () => loads.cancel();

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

  /** A load that was aborted: says so when the user cancelled it (a newer load speaks for itself). */
  function cancelled(signal, name) {
    if (signal.reason?.byUser) showStatus(`${name}: loading cancelled`);
    return 'cancelled';
  }

  function failed(message) {
    state.error = message;
    showStatus(message, true);
    console.warn(`hexlod: ${message}`);
    return 'failed';
  }

  /**
   * Decodes files into a new terrain and shows it, unless `signal` aborts first (the decoder
   * stops at its next pause). On failure the current terrain stays and the message shows.
   * `quiet`: the status line is left as it is (the default terrain under a failed src's message).
   */
  async function decode(files, options, signal, source, quiet) {
    const names = files.map((f) => f.name).join(' + ');
    if (!quiet) showStatus(`Loading ${names}…`);
    const onProgress = loadProgress(signal);
    try {
      const loaded = await loadTerrain(core, files, { ...options, encoding: encodingSelect.value === 'image' ? 'auto' : encodingSelect.value, onProgress, guessSpacing: true });
      if (signal.aborted) {
        loaded.terrain.destroy();
        return cancelled(signal, names);
      }
      showSpacing(loaded.terrain, !loaded.field.spacingFromFile); // first: the opening view is framed below the file bar as it will be
      show(loaded, source);
      if (!quiet) {
        state.error = null;
        showStatus('');
      }
      return 'shown';
    } catch (error) {
      if (signal.aborted) return cancelled(signal, names);
      if (error.needsSize && !options.width) {
        indicator.hide();
        const size = await askRawSize(error.file, error.samples, signal);
        if (signal.aborted) return cancelled(signal, names);
        if (size) {
          indicator.start(true);
          return decode(files, { ...options, ...size }, signal, source, quiet);
        }
      }
      return failed(error.message);
    }
  }

  /** The progress callback of a load: the bar, and a stop at the next pause once `signal` aborts. */
  function loadProgress(signal) {
    state.progress = 0;
    return (fraction, phase) => {
      if (signal.aborted) throw signal.reason;
      state.progress = fraction;
      progress.value = fraction;
      progress.title = phase;
    };
  }

  /**
   * Opens a COG (a URL or a File) as a tiled terrain and shows it once its coarsest level is
   * in; the tiles the view needs follow frame by frame. Throws the stream's errors (TileError).
   */
  async function openTiles(input, name, signal, source) {
    showStatus(`Opening ${name}…`);
    const loaded = await openTiled(core, input, { name, capBytes: settings.tileCacheMB * MB, signal, onProgress: loadProgress(signal) });
    if (signal.aborted) {
      loaded.tiles.close();
      loaded.terrain.destroy();
      return cancelled(signal, name);
    }
    showSpacing(loaded.terrain, !loaded.field.spacingFromFile); // before show() frames the view under the bar
    show(loaded, source);
    state.error = null;
    showStatus('');
    return 'shown';
  }

  /** ?src= of a TIFF: tile by tile when the server honours Range and the file is tiled; else as afterTilesFailed says. */
  async function openUrlAsTiles(url, name, links, limits, signal) {
    try {
      return await openTiles(url, name, signal, url);
    } catch (error) {
      if (signal.aborted) return cancelled(signal, name);
      const next = afterTilesFailed(error, name, settings.tileCacheMB * MB);
      if (next.failed) return failed(next.failed);
      const { maxBytes, advice } = next.whole;
      return fetchAndDecode(links, { ...limits, maxBytes: Math.min(limits.maxBytes, maxBytes) }, signal, url, false,
        (e) => (e instanceof LimitError && /size cap/.test(e.message) ? `${name}: ${e.message}, ${advice}` : null));
    }
  }

  /** Shows a download's progress in the status line (unless `quiet`) and the bar. */
  function downloadProgress(name, quiet) {
    if (!quiet) showStatus(`Loading ${name}…`);
    let shown = '';
    return (received, total) => {
      const text = `Loading ${name}… ${formatMB(received)}${total ? ` of ${formatMB(total)}` : ''} MB`;
      if (!quiet && text !== shown) showStatus(shown = text);
      if (total) progress.value = received / total;
      else progress.removeAttribute('value'); // a bar that says "busy": the size is unknown
      progress.title = 'downloading';
    };
  }

  /** Where a fetch failed, for the status line. */
  const fetchFailure = (name, url, error) =>
    `${name}: cannot fetch ${url} (${error.message}${error instanceof LimitError ? '; the limits are under Controls › Loading from a URL' : ''})`;

  /**
   * Fetches [{ name, url, optional }] within `limits` ({ timeoutMs, maxBytes }) and decodes
   * them: the first is the height field, an optional one (the sidecar) is left out when its
   * server has none. `explain(error)`: a message of the caller's for a failed fetch, or null.
   */
  async function fetchAndDecode(links, limits, signal, source, quiet, explain = () => null) {
    const name = links[0].name;
    const onBytes = downloadProgress(name, quiet);
    const files = [];
    for (const link of links) {
      try {
        const bytes = await fetchLimited(link.url, link.optional ? { ...limits, signal, accept: acceptSidecar }
          : { ...limits, signal, accept: acceptFile, onBytes });
        if (bytes) files.push({ name: link.name, bytes });
      } catch (error) {
        if (signal.aborted) return cancelled(signal, name);
        if (!link.optional) return failed(explain(error) ?? fetchFailure(link.name, link.url, error));
        // A sidecar that cannot be read is one the server does not have: the file opens without it.
      }
    }
    return decode(files, {}, signal, source, quiet);
  }

  /**
   * Opens dropped or picked files (File objects) as one load: the height field (with its
   * sidecar), or the tiles of a mosaic (several .hgt or GeoTIFF height fields, web/loaders/mosaic.js),
   * is read and decoded, then the image (with its world file) is draped on it; an image
   * alone is draped on the terrain on screen (web/imagery/drop_roles.js says which is which).
   * A colour PNG opened alone is a height field when its first row reads as heights, else an image.
   */
  function openPicked(list) {
    const picked = [...list];
    return loads.run(async (signal) => {
      indicator.start(true);
      const names = picked.map((f) => f.name).join(' + ');
      showStatus(`Loading ${names}…`);
      const heads = await Promise.all(picked.map(async (file) => ({ name: file.name, head: new Uint8Array(await file.slice(0, HEAD_BYTES).arrayBuffer()) })));
      // A colour PNG's first row is read only when the roles need it (it alone, 8-bit colour by
      // its header); the bytes read then are the ones decoded.
      const heightPng = new Set(), read = new Map();
      const [only] = heads;
      if (picked.length === 1 && encodingSelect.value === 'auto' && hasPngSignature(only.head) && only.head[24] === 8 && [2, 3, 6].includes(only.head[25])) {
        read.set(0, new Uint8Array(await picked[0].arrayBuffer()));
        if (await detectPngEncoding(read.get(0), only.name)) heightPng.add(only.name);
      }
      let roles;
      try {
        roles = dropRoles(heads, { pngAsImage: PNG_CHOICE[encodingSelect.value], colourPngIsHeight: (f) => heightPng.has(f.name) });
      } catch (error) {
        if (!(error instanceof ImageError)) throw error;
        return failed(error.message);
      }
      const image = roles.image === null ? null : { name: picked[roles.image].name, blob: picked[roles.image] };
      // A lone COG streams from the File (read by slices, never whole); any other height field loads whole.
      if (picked.length === 1 && roles.field.length === 1 && image === null
        && await shouldOpenTiled(picked[0], only.head, settings.tileCacheMB * MB)) {
        if (signal.aborted) return cancelled(signal, names);
        try {
          return await openTiles(picked[0], names, signal, null);
        } catch (error) {
          return signal.aborted ? cancelled(signal, names) : failed(`${names}: cannot stream it (${error.message})`);
        }
      }
      const world = roles.worldFile === null ? null : { name: picked[roles.worldFile].name, blob: picked[roles.worldFile] };
      if (roles.field.length > 0) {
        const files = await Promise.all(roles.field.map(async (i) => ({ name: picked[i].name, bytes: read.get(i) ?? new Uint8Array(await picked[i].arrayBuffer()) })));
        if (signal.aborted) return cancelled(signal, names);
        const outcome = await decode(files, {}, signal, null, false);
        if (outcome !== 'shown') return outcome;
      }
      if (!image || signal.aborted) return 'shown';
      return (await drape(image, world)) ? 'shown' : 'failed';
    });
  }

  /**
   * Drapes the image at `url` (?image=) on the terrain on screen, with its world file from
   * beside it when its server has one (x.jgw, x.jpgw or x.wld for x.jpg).
   */
  function openImageUrl(url) {
    return loads.run(async (signal) => {
      indicator.start(true);
      let imageUrl, name;
      try {
        imageUrl = new URL(url, location.href);
        name = decodeURIComponent(imageUrl.pathname.split('/').pop()) || 'image';
      } catch (error) {
        return failed(`image=${url}: not a URL to fetch (${error.message})`);
      }
      const limits = { timeoutMs: settings.urlTimeout * 1000, maxBytes: settings.urlMaxMB * MB, signal };
      let bytes;
      try {
        bytes = await fetchLimited(imageUrl, { ...limits, accept: acceptFile, onBytes: downloadProgress(name, false) });
      } catch (error) {
        return signal.aborted ? cancelled(signal, name) : failed(fetchFailure(name, url, error));
      }
      let world = null;
      if (!/\.tiff?$/i.test(name)) {
        const segment = imageUrl.pathname.split('/').pop();
        for (const candidate of worldFileCandidates(segment)) {
          const worldUrl = new URL(`./${candidate}`, imageUrl);
          const text = await fetchLimited(worldUrl, { ...limits, maxBytes: MB, accept: acceptWorldFile }).catch(() => null);
          if (signal.aborted) return cancelled(signal, name);
          if (text) { world = { name: decodeURIComponent(candidate), blob: new Blob([text]) }; break; }
        }
      }
      if (signal.aborted) return cancelled(signal, name);
      return (await drape({ name, blob: new Blob([bytes]) }, world, url)) ? 'shown' : 'failed';
    });
  }

  /**
   * Opens a height field at `url` (?src=) with its NAME.json sidecar from beside it (resolved
   * against the data's URL: a file on another server has its sidecar there, not on the page's).
   */
  function openUrl(url) {
    return loads.run((signal) => {
      indicator.start(true);
      let dataUrl, segment, name;
      try {
        dataUrl = new URL(url, location.href);
        segment = dataUrl.pathname.split('/').pop(); // percent-encoded, as the URL has it
        name = decodeURIComponent(segment) || 'download';
      } catch (error) {
        return failed(`src=${url}: not a URL to fetch (${error.message})`);
      }
      const links = [{ name, url }];
      if (extensionOf(name) !== 'json') {
        // './' keeps a name with a colon from reading as a URL scheme.
        links.push({ name: `${baseNameOf(name)}.json`, url: new URL(`./${baseNameOf(segment)}.json`, dataUrl).href, optional: true });
      }
      const limits = { timeoutMs: settings.urlTimeout * 1000, maxBytes: settings.urlMaxMB * MB };
      if (isTiffName(name)) return openUrlAsTiles(url, name, links, limits, signal);
      return fetchAndDecode(links, limits, signal, url, false);
    });
  }

  /**
   * Opens files fetched from [{ name, url }] (the default terrain), with no status line of its
   * own unless it fails, and no Cancel button: the page needs a terrain. The page's own files:
   * the default time limit, and no size cap (the user's is for theirs).
   */
  function openLinks(links) {
    return loads.run((signal) => {
      indicator.start(false);
      return fetchAndDecode(links, { timeoutMs: defaultUrlTimeoutS * 1000, maxBytes: Infinity }, signal, null, true);
    });
  }

  /** Asks the width and height of a RAW file of `samples` samples; null when cancelled (or the load is). */
  function askRawSize(name, samples, signal) {
    $('raw-name').textContent = `${name} holds ${samples.toLocaleString('en')} 16-bit samples.`;
    const width = $('raw-width'), height = $('raw-height');
    width.value = '';
    height.value = '';
    width.oninput = () => { if (samples % Number(width.value) === 0) height.value = samples / Number(width.value); };
    return new Promise((resolve) => {
      const answer = (size) => {
        signal.removeEventListener('abort', onAbort);
        rawDialog.close();
        resolve(size);
      };
      const onAbort = () => answer(null);
      rawForm.onsubmit = (e) => {
        e.preventDefault();
        answer({ width: Number(width.value), height: Number(height.value) });
      };
      $('raw-cancel').onclick = () => answer(null);
      signal.addEventListener('abort', onAbort);
      rawDialog.showModal();
    });
  }

  window.addEventListener('dragover', (e) => {
    e.preventDefault();
    document.body.classList.add('dragging');
  });
  window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
  window.addEventListener('drop', async (e) => {
    e.preventDefault();
    document.body.classList.remove('dragging');
    const dropped = e.dataTransfer?.files ?? [];
    if (dropped.length) await openPicked(dropped);
  });
  picker.accept = [...ACCEPT_EXTENSIONS, ...IMAGE_EXTENSIONS].join(',');
  $('open-button').title = `Open a height field (${ACCEPTED}), an image to drape on it (PNG, JPEG, WebP, GeoTIFF, with its world file), or both`;
  $('open-button').onclick = () => picker.click();
  picker.onchange = () => {
    if (picker.files.length) openPicked(picker.files); // takes the list at once: it is emptied next
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
  return { openUrl, openImageUrl, openLinks, idle: () => loads.idle(), showSpacing };
}
