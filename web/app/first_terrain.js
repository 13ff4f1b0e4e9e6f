// What the page opens with: ?src=URL instead of the default terrain, then what the address
// asks of it (image layers, a camera, a measured line). A file the user opens meanwhile
// cancels the src; the default terrain loads when, once every load has ended, none is on
// screen (the src failed or was cancelled: its message stays in the status line).
import { applyCameraState } from './url_state.js';

// The names are given, not taken from the URLs: a production build puts a content hash into
// each asset's file name, and the loader pairs a height field with its sidecar by name.
const DEFAULT_TERRAIN = [
  { name: 'globe_himalaya_2048.png', url: new URL('../../public/terrain/globe_himalaya_2048.png', import.meta.url).href },
  { name: 'globe_himalaya_2048.json', url: new URL('../../public/terrain/globe_himalaya_2048.json', import.meta.url).href },
];

/**
 * @param {{ urlState: object, intake: object, stage: object, rig: object, measure: object, det: object|null,
 *   state: object, statusBox: HTMLElement, openingStatus: string, showStatus: Function, showContourNote: () => void,
 *   syncPanel: () => void, addTiles: (text: string) => Promise<object[]>, addOverlayUrl: (url: string) => Promise<object|null> }} parts
 *   addTiles: web map tile layers (?tiles=: a template, or a WMTS service); addOverlayUrl: an overlay (?overlay=)
 * @throws {Error} when the default terrain does not load, or a flight's terrain is not the one shown
 */
export async function openFirstTerrain({ urlState, intake, stage, rig, measure, det, state, statusBox, openingStatus,
  showStatus, showContourNote, syncPanel, addTiles, addOverlayUrl }) {
  const src = urlState.src;
  const outcome = src ? await intake.openUrl(src) : null;
  if (det && src && outcome !== 'shown') throw new Error(state.error ?? `${src}: loading cancelled`); // a flight is meaningless over another terrain
  await intake.idle();
  while (!stage.current) {
    if (await intake.openLinks(DEFAULT_TERRAIN) === 'failed') throw new Error(`the default terrain did not load: ${state.error}`);
    await intake.idle(); // a file dropped meanwhile cancelled the default: shown, or failed (then the default again)
  }
  // The default terrain loads quietly (a failed src's message stays over it), so the page's own
  // opening message is taken away here, and only that one.
  if (statusBox.textContent === openingStatus) showStatus('');
  if (statusBox.textContent === '') showContourNote();
  for (const { kind, url } of det ? [] : urlState.layers) {
    if (kind === 'image') await intake.openImageUrl(url);
    else await addTiles(url);
  }
  for (const url of det ? [] : urlState.overlays) await addOverlayUrl(url);
  if (urlState.camera && !det) {
    applyCameraState(rig, urlState.camera);
    if (rig.mode === 'walk') rig.active.settle();
    syncPanel();
  }
  if (urlState.measure) {
    const restored = measure.restore(urlState.measure);
    if (restored.error) {
      urlState.errors.push(`measure: ${restored.error}`);
      measure.setActive(false);
    }
  }
  if (urlState.errors.length) {
    state.error = urlState.errors.join('; ');
    showStatus(`${state.error} (defaults used)`, true);
  }
}
