// The control panel (lil-gui): every setting of settings.js, the camera, screenshots and help.
// The panel only edits the settings object and reports which key changed; the page applies it.
import GUI from 'lil-gui';
import { RANGES, SHADING_MODES, NORMAL_SOURCES } from '../app/settings.js';
import { CAMERA_MODES } from '../cameras/rig.js';

/**
 * @param {HTMLElement} container
 * @param {object} settings the page's settings (edited in place)
 * @param {{camera: {mode: string}, onChange: (key: string, value: any) => void,
 *   actions: Record<string, () => void>}} hooks actions: buttons, label -> function
 * @returns {{gui: GUI, refresh: () => void, setCellSizeRange: (metres: number) => void}}
 */
export function createControlsPanel(container, settings, { camera, onChange, actions }) {
  // Its stylesheet is imported by public/style.css: the Content-Security-Policy refuses the
  // <style> element lil-gui would inject.
  const gui = new GUI({ container, title: 'Controls', injectStyles: false });
  const changed = (key) => (value) => onChange(key, value);
  const slider = (folder, key) => {
    const r = RANGES[key];
    return folder.add(settings, key, r.min, r.max, r.step).name(r.label).onChange(changed(key));
  };
  const toggle = (folder, key, label) => folder.add(settings, key).name(label).onChange(changed(key));

  gui.add(camera, 'mode', CAMERA_MODES).name('camera (1 2 3)').onChange(changed('camera'));

  // The terrain has the view: only the controls used most are unfolded at first.
  const lod = gui.addFolder('Level of detail');
  slider(lod, 'tau');
  slider(lod, 'budgetMs');
  toggle(lod, 'freeze', 'freeze LOD (F)');
  const more = lod.addFolder('budgets and culling').close();
  slider(more, 'maxOperations');
  slider(more, 'maxTriangles');
  toggle(more, 'autoTau', 'auto τ (keeps the cap and budget)');
  toggle(more, 'geomorph', 'geomorphing');
  toggle(more, 'culling', 'frustum culling');
  toggle(more, 'backfaceCulling', 'back-face culling');

  const view = gui.addFolder('View').close();
  slider(view, 'exaggeration');
  toggle(view, 'wireframe', 'wireframe: hexagons (O)');
  toggle(view, 'colorByLevel', 'colour by level (L)');
  slider(view, 'eyeHeight');

  const shading = gui.addFolder('Shading').close(); // folded, as View: the terrain has the view
  shading.add(settings, 'shading', SHADING_MODES).name('mode').onChange(changed('shading'));
  slider(shading, 'sunAzimuth');
  slider(shading, 'sunElevation');
  toggle(shading, 'shadows', 'sun shadows');
  toggle(shading, 'occlusion', 'ambient occlusion');
  shading.add(settings, 'normals', NORMAL_SOURCES).name('normals').onChange(changed('normals'));

  const mesh = gui.addFolder('Mesh').close();
  mesh.add(settings, 'embedding', ['exact', 'shifted']).name('embedding').onChange(changed('embedding'));
  const cellSize = mesh.add(settings, 'cellSize', 0.01, 1e6).name('cell size (m)').onFinishChange(changed('cellSize'));

  const urls = gui.addFolder('Loading from a URL').close(); // ?src=: limits of the next load
  slider(urls, 'urlTimeout');
  slider(urls, 'urlMaxMB');

  const tools = gui.addFolder('Screenshot, reset, help').close();
  for (const [label, action] of Object.entries(actions)) tools.add({ [label]: action }, label);

  // Small screens: start folded, the view matters more than the panel.
  if (window.matchMedia('(max-width: 800px), (max-height: 500px)').matches) gui.close();

  return {
    gui,
    /** Shows values that changed elsewhere (keys, URL, a new terrain). */
    refresh() {
      for (const c of gui.controllersRecursive()) c.updateDisplay();
    },
    /** The cell size slider's range around a terrain's spacing. */
    setCellSizeRange(metres) {
      cellSize.min(metres / 100).max(metres * 100).step(metres / 1000);
      cellSize.updateDisplay();
    },
  };
}
