// The keyboard shortcuts of the viewer (the help box lists them); keys typed into a field are
// the field's.
import { CAMERA_MODES, isTyping } from '../cameras/rig.js';

const TOGGLES = { l: 'colorByLevel', o: 'wireframe', f: 'freeze' };

/**
 * @param {import('./viewer_dom.js').ViewerDom} dom  where keys are taken
 * @param {object} actions  setSetting(key, value), setCamera(mode), toggleHelp(), closeHelp(),
 *   toggleHud(), screenshot(), resetView(), and settings (read for the toggles)
 */
export function installKeys(dom, { settings, setSetting, setCamera, toggleHelp, closeHelp, toggleHud, screenshot, resetView }) {
  dom.on(dom.keyTarget, 'keydown', (e) => {
    if (isTyping(e) || e.ctrlKey || e.metaKey || e.altKey) return;
    const key = e.key.toLowerCase();
    if (TOGGLES[key]) setSetting(TOGGLES[key], !settings[TOGGLES[key]]);
    else if (['1', '2', '3'].includes(key)) setCamera(CAMERA_MODES[Number(key) - 1]);
    else if (key === 'h' || key === '?') toggleHelp();
    else if (key === 'i') toggleHud();
    else if (key === 'escape') closeHelp();
    else if (key === 'p') screenshot();
    else if (key === 'r') resetView();
  });
}
