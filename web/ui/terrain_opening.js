// The end of every load, whatever brought the file: decode it into a new terrain (or open a COG
// tile by tile) and show it, or say why not while the terrain on screen stays. Also the two
// other outcomes a load can have: failed (the message in the status line) and cancelled.
import { loadTerrain } from '../loaders/terrain_source.js';
import { openTiled } from './tiled_open.js';
import { askRawSize } from './raw_size_dialog.js';

const MB = 2 ** 20;

/**
 * @param {{ core: import('../core/core.js').HexlodCore, state: object, settings: object,
 *   show: (loaded: object, source: string|null) => void, showStatus: (message: string, isError?: boolean) => void,
 *   indicator: ReturnType<import('./load_indicator.js').createLoadIndicator>,
 *   showSpacing: (terrain: object, assumed?: boolean) => void, encoding: () => string }} page
 *   encoding: the PNG colours menu's value ('auto', 'image', 'terrain-rgb', 'terrarium')
 * @returns each resolves to a load's outcome: 'shown', 'failed' (the status line says why) or
 *   'cancelled'
 */
export function createTerrainOpening({ dom, core, state, settings, show, showStatus, indicator, showSpacing, encoding }) {
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

  /** Shows what a load made, unless it was cancelled meanwhile. */
  function shown(loaded, source, signal, name, quiet) {
    if (signal.aborted) {
      loaded.tiles?.close();
      loaded.terrain.destroy();
      return cancelled(signal, name);
    }
    showSpacing(loaded.terrain, !loaded.field.spacingFromFile); // first: the opening view is framed below the file bar as it will be
    show(loaded, source);
    if (!quiet) {
      state.error = null;
      showStatus(loaded.field.notes?.join(' · ') ?? ''); // what its .prj or .aux.xml could not give
    }
    return 'shown';
  }

  /**
   * Decodes files ([{ name, bytes }]) into a new terrain and shows it, unless `signal` aborts
   * first (the decoder stops at its next pause). A RAW file without its size asks for it.
   * `quiet`: the status line is left as it is (the default terrain under a failed src's message).
   */
  async function decode(files, options, signal, source, quiet) {
    const names = files.map((f) => f.name).join(' + ');
    if (!quiet) showStatus(`Loading ${names}…`);
    try {
      const loaded = await loadTerrain(core, files, { ...options, encoding: encoding() === 'image' ? 'auto' : encoding(),
        onProgress: indicator.loadProgress(signal), guessSpacing: true });
      return shown(loaded, source, signal, names, quiet);
    } catch (error) {
      if (signal.aborted) return cancelled(signal, names);
      if (error.needsSize && !options.width) {
        indicator.hide();
        const size = await askRawSize(dom, error.file, error.samples, signal);
        if (signal.aborted) return cancelled(signal, names);
        if (size) {
          indicator.start(true);
          return decode(files, { ...options, ...size }, signal, source, quiet);
        }
      }
      return failed(error.message);
    }
  }

  /**
   * Opens a COG (a URL or a File) as a tiled terrain and shows it once its coarsest level is
   * in; the tiles the view needs follow frame by frame. Throws the tiles' errors (TileError).
   */
  async function openTiles(input, name, signal, source) {
    showStatus(`Opening ${name}…`);
    const loaded = await openTiled(core, input, { name, capBytes: settings.tileCacheMB * MB, signal,
      onProgress: indicator.loadProgress(signal) });
    return shown(loaded, source, signal, name, false);
  }

  return { decode, openTiles, failed, cancelled };
}
