// How files reach the page: dropped or picked (drop_target.js, picked_files.js), or from URLs
// (url_opening.js), each load ending the same way (terrain_opening.js). One load at a time
// (load_sequence.js): opening a file cancels the load in flight, so a late answer never
// replaces what the user opened since. A load slower than a blink shows a progress bar and a
// Cancel button (load_indicator.js); a bad file's message shows while the current terrain,
// camera and settings stay.
import { LoadSequence } from './load_sequence.js';
import { createLoadIndicator } from './load_indicator.js';
import { installSpacingField } from './spacing_field.js';
import { createTerrainOpening } from './terrain_opening.js';
import { createUrlOpening } from './url_opening.js';
import { pickedFilesOpener } from './picked_files.js';
import { installDropTarget } from './drop_target.js';

/**
 * @param {{ core: import('../core/core.js').HexlodCore, state: object, settings: object,
 *   layers: import('../app/layers.js').Layers, show: (loaded: object, source: string|null) => void,
 *   showStatus: (message: string, isError?: boolean) => void, setCellSize: (metres: number) => boolean,
 *   drape: (image: object, sidecars: { worldFile, prj, auxXml }, options?: { url?: string, throwRefusal?: boolean }) => Promise<object|null>,
 *   defaultUrlTimeoutS: number }} page
 *   settings: the page's (read at each load); layers: what is shown (a drop replaces its terrain
 *   or adds an image layer over it); show: the loaded terrain and the URL it came from (null for
 *   a file); setCellSize: the panel's cell size setting, false when refused; drape: an image
 *   ({ name, blob }) onto the terrain on screen (app/image_stage.js), null when refused;
 *   addOverlay: a GPX, KML, KMZ or GeoJSON file ({ name, bytes }) over it (app/overlay_stage.js);
 *   defaultUrlTimeoutS: the time limit of the page's own files
 * @returns {{ openUrl, openImageUrl, openLinks, openFiles, idle: () => Promise<void>, showSpacing: (terrain: object, assumed?: boolean) => void }}
 *   openUrl, openImageUrl, openLinks and openFiles (files as if dropped together) resolve to 'shown', 'failed' (the status line says why) or
 *   'cancelled' (by the Cancel button, or by a file opened meanwhile)
 */
export function createFileIntake({ dom, drops = true, core, state, settings, layers, show, showStatus, setCellSize, drape, addOverlay, defaultUrlTimeoutS }) {
  const $ = (id) => dom.byId(id);
  const encodingSelect = $('png-encoding'), encoding = () => encodingSelect.value;
  state.loading = false;
  const indicator = createLoadIndicator({ progress: $('load-progress'), cancelButton: $('load-cancel'), state, showStatus });
  const loads = new LoadSequence((busy) => {
    state.loading = busy;
    if (!busy) indicator.hide();
  });
  $('load-cancel').onclick = () => loads.cancel();
  const showSpacing = installSpacingField({ dom, state, layers, showStatus, setCellSize });
  const opening = createTerrainOpening({ dom, core, state, settings, show, showStatus, indicator, showSpacing, encoding });
  const urls = createUrlOpening({ loads, indicator, settings, opening, drape, defaultUrlTimeoutS });
  const openFiles = pickedFilesOpener({ loads, indicator, settings, layers, opening, drape, addOverlay, showStatus, encoding });
  installDropTarget(dom, openFiles, showStatus, drops);
  return { ...urls, openFiles, idle: () => loads.idle(), showSpacing };
}
