// A setting changed (panel, key, test): through its owner (settings_owner.js), which keeps the
// old value when applying it fails; then the view follows the settings, the panel shows them and
// a frame is asked for. The camera is the rig's, not a setting, and is changed here too.
import { deriveView } from './view_state.js';

/**
 * @param {{ settings: object, view: object, renderer: object, rig: object, owner: object, state: object,
 *   showStatus: (message: string, isError?: boolean) => void, syncPanel: () => void, requestRender: () => void }} parts
 * @returns {{ change: (key: string, value: any) => boolean, syncView: () => void, showContourNote: () => void }}
 *   change: false when the value was refused (the status line says why)
 */
export function createSettingChanges({ settings, view, renderer, rig, owner, state, showStatus, syncPanel, requestRender }) {
  /** The view follows the settings: the draw state, the sun, and the shading's figures for tests. */
  function syncView() {
    deriveView(settings, view);
    renderer.setSun(view.sunAzimuth, view.sunElevation);
    state.shadingTimes = renderer.fieldTextures.times;
    // For tests: the normal texture's tiles. Not enumerable: it holds the terrain and through it
    // the WASM heap, which a test's evaluate(() => window.hexlod) would try to copy whole.
    Object.defineProperty(state, 'fieldTextures', { value: renderer.fieldTextures, enumerable: false, configurable: true });
    state.contours = renderer.contours.info; // the interval in force, its message, the labels drawn
  }

  /** The contours' note (a widened interval, a coarser or tiled field) in the status line, while they are on. */
  const showContourNote = () => { if (settings.contours) showStatus(renderer.contourNote(view)); };

  function change(key, value) {
    let applied = true;
    try {
      if (key === 'camera') rig.setMode(value);
      else owner.set(key, value);
      showStatus('');
    } catch (error) {
      showStatus(error.message, true);
      applied = false;
    }
    syncView();
    if (applied && (key === 'contours' || key === 'contourInterval')) showContourNote();
    syncPanel();
    requestRender();
    return applied;
  }

  return { change, syncView, showContourNote };
}
