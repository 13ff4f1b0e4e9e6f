// The control panel (lil-gui): every setting with a panel place in the settings table it is
// given (web/app/settings_table.js), in the table's order and folders, then the camera, screenshots
// and help. The panel only edits the settings object and reports which key changed; the page
// applies it.
import GUI from 'lil-gui';
import { CAMERA_MODES } from '../cameras/rig.js';

// The folders open at first (the terrain has the view: only the controls used most).
const OPEN_FOLDERS = new Set(['Level of detail']);

/**
 * @param {HTMLElement} container
 * @param {object} settings the page's settings (edited in place)
 * @param {Record<string, object>} table the settings table: each setting's panel place, choices and range
 * @param {{camera: {mode: string}, onChange: (key: string, value: any) => void,
 *   actions: Record<string, () => void>, folderActions?: Record<string, Record<string, () => void>>}} hooks
 *   actions: buttons, label -> function; folderActions: buttons in a settings folder, path -> label -> function;
 *   small: the viewer is phone-sized (the panel starts folded); injectStyles: lil-gui adds its own stylesheet
 * @returns {{gui: GUI, refresh: () => void, setCellSizeRange: (metres: number) => void,
 *   enableAction: (label: string, enabled: boolean) => void, folder: (path: string) => GUI}}
 */
export function createControlsPanel(container, settings, table, { camera, onChange, actions, folderActions = {}, small = false, injectStyles = false }) {
  // On the page its stylesheet is imported by public/style.css: the Content-Security-Policy
  // refuses the <style> element lil-gui would inject. In someone else's page lil-gui adds it.
  const gui = new GUI({ container, title: 'Controls', injectStyles });
  gui.add(camera, 'mode', CAMERA_MODES).name('camera (1 2 3)').onChange((value) => onChange('camera', value));

  const folders = new Map(); // 'Level of detail/budgets and culling' -> its lil-gui folder
  const folderOf = (path) => {
    if (!folders.has(path)) {
      const slash = path.lastIndexOf('/');
      const parent = slash < 0 ? gui : folderOf(path.slice(0, slash));
      const folder = parent.addFolder(path.slice(slash + 1));
      if (!OPEN_FOLDERS.has(path)) folder.close();
      folders.set(path, folder);
    }
    return folders.get(path);
  };
  const controllers = {};
  for (const [key, s] of Object.entries(table)) {
    if (!s.panel) continue;
    const [path, label] = s.panel, folder = folderOf(path);
    const changed = (value) => onChange(key, value);
    let controller;
    if (s.choices) controller = folder.add(settings, key, s.choices);
    else if (s.positive) controller = folder.add(settings, key, 0.01, 1e6); // its range follows the terrain
    else if (typeof s.default === 'number') controller = folder.add(settings, key, s.min, s.max, s.step);
    else controller = folder.add(settings, key);
    controller.name(label);
    // A typed value is applied once typed (a cell size rebuilds the mesh; a half-typed interval
    // is no interval), others as they move.
    if (s.positive || s.parse) controller.onFinishChange(changed);
    else controller.onChange(changed);
    controllers[key] = controller;
  }
  const cellSize = controllers.cellSize;
  const buttons = {};
  for (const [path, list] of Object.entries(folderActions)) {
    for (const [label, action] of Object.entries(list)) buttons[label] = folderOf(path).add({ [label]: action }, label);
  }

  const tools = gui.addFolder('Screenshot, reset, help').close();
  for (const [label, action] of Object.entries(actions)) tools.add({ [label]: action }, label);

  // Small screens: start folded, the view matters more than the panel.
  if (small) gui.close();

  return {
    gui,
    /** Shows values that changed elsewhere (keys, URL, a new terrain). */
    refresh() {
      for (const c of gui.controllersRecursive()) c.updateDisplay();
    },
    /** A folder's button greys out while it has nothing to act on. */
    enableAction(label, enabled) {
      buttons[label].enable(enabled);
    },
    /** The folder at `path` ('Image layers'), for parts that add controls of their own. */
    folder(path) {
      return folderOf(path);
    },
    /** The cell size slider's range around a terrain's spacing. */
    setCellSizeRange(metres) {
      cellSize.min(metres / 100).max(metres * 100).step(metres / 1000);
      cellSize.updateDisplay();
    },
  };
}
