// The viewer page: creates the parts (core, renderer, cameras, frame pipeline, the terrain on
// stage, the settings and their owner, panel, HUD, keys, pointer readout, URL state, screenshots,
// context loss), connects them and loads the first terrain. In test mode (test_api.js) its state
// is published on window.hexlod.
import { createCore } from '../core/core.js';
import { createFileIntake } from '../ui/file_intake.js';
import { TerrainRenderer } from '../render/renderer.js';
import { createImageStage } from './image_stage.js';
import { CameraRig } from '../cameras/rig.js';
import { defaultSettings, SETTINGS } from './settings_table.js';
import { createView, deriveView } from './view_state.js';
import { createControlsPanel } from '../ui/controls_panel.js';
import { Hud } from '../ui/hud.js';
import { installPointerReadout } from '../ui/pointer_readout.js';
import { parseUrlState, applyCameraState, UrlWriter } from './url_state.js';
import { captureView, download } from './screenshot.js';
import { handleContextLoss } from './context_loss.js';
import { deterministicMode } from './deterministic/mode.js';
import { FramePipeline } from './frame_pipeline.js';
import { isTestMode, installTestApi } from './test_api.js';
import { installKeys } from './keys.js';
import { SettingsOwner } from './settings_owner.js';
import { TerrainStage } from './terrain_stage.js';
import { settingEffects } from './setting_effects.js';
import { installMeasuring } from './measuring.js';

// The names are given, not taken from the URLs: a production build puts a content hash into
// each asset's file name, and the loader pairs a height field with its sidecar by name.
const DEFAULT_TERRAIN = [
  { name: 'globe_himalaya_2048.png', url: new URL('../../public/terrain/globe_himalaya_2048.png', import.meta.url).href },
  { name: 'globe_himalaya_2048.json', url: new URL('../../public/terrain/globe_himalaya_2048.json', import.meta.url).href },
];
const REMOVE_IMAGE = 'remove image';
const params = new URLSearchParams(location.search);
// ?flight=URL: the deterministic mode of regression tests (web/app/deterministic/mode.js, README).
const det = deterministicMode(params);

const canvas = document.getElementById('view');
const statusBox = document.getElementById('status');
const helpBox = document.getElementById('help');
const OPENING_STATUS = statusBox.textContent; // index.html's "Loading…", shown before any script runs

/** The page's state: 'loading' | 'ready' | 'error', and figures of the current view (window.hexlod in test mode). */
const state = { status: 'loading', frames: 0, error: null, terrain: null, triangles: 0,
  contextLost: false, contextRestores: 0, recordFrames: false, frameLog: [], cursor: null };
if (isTestMode(params) || det) window.hexlod = state; // published at once: tests wait for the status

function showStatus(message, isError = false) {
  statusBox.textContent = message;
  statusBox.classList.toggle('error', isError);
}

/** Creates the parts, connects them and loads the first terrain. */
async function main() {
  const gl = canvas.getContext('webgl2', { antialias: true });
  if (!gl) throw new Error('this browser has no WebGL2');
  const core = await createCore();
  const urlState = parseUrlState(location.search);
  const settings = Object.assign(defaultSettings(), urlState.settings);
  if (det) Object.assign(settings, (await det.load(), det.settings)); // the flight's settings win
  const renderer = new TerrainRenderer(gl, { normalTile: () => settings.normalTile, imageTile: () => settings.imageTile });
  const view = createView(settings);
  const urlWriter = new UrlWriter();
  const requestRender = () => pipeline.request();
  // The HUD opens as one summary line on every screen, so the terrain has the view (I unfolds it).
  const hud = new Hud(document.getElementById('hud'), true);
  const rig = new CameraRig(requestRender);
  rig.cameras.walk.eyeHeight = settings.eyeHeight;
  const cameraMode = { mode: rig.mode }; // the panel's view of the rig
  const pipeline = new FramePipeline({ gl, canvas, renderer, rig, settings, view, hud, state, det, urlWriter,
    source: () => stage.source, imageSource: () => images.url });
  const syncPanel = () => { cameraMode.mode = rig.mode; stage.panel?.refresh(); };
  const stage = new TerrainStage({ canvas, renderer, rig, settings, pipeline, hud, state, det, syncPanel, requestRender });
  const owner = stage.owner = new SettingsOwner(settings, settingEffects(stage));
  // The draped image (image_stage.js), described by the HUD; the panel's Remove acts on it.
  const images = createImageStage({ renderer, stage, showStatus, requestRender, onChange: (image) => {
    hud.setImage(image);
    stage.panel.enableAction(REMOVE_IMAGE, image !== null);
    state.image = image && { name: image.name, width: image.width, height: image.height, metresPerPixel: image.metresPerPixel,
      coverage: image.placement.coverage, how: image.placement.how, gpuBytes: image.gpuBytes, hud: hud.image.textContent };
  } });
  state.image = null;
  Object.defineProperty(state, 'images', { value: images, enumerable: false }); // for tests: drape and remove

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

  /** The contours' note (a widened interval, a coarser or streamed field) in the status line, while they are on. */
  const showContourNote = () => { if (settings.contours) showStatus(renderer.contourNote(view)); };

  /**
   * A setting changed (panel, key, test): through its owner, which keeps the old value when it
   * fails. False when it failed (the status says why).
   */
  function onSetting(key, value) {
    let applied = true;
    try {
      if (key === 'camera') rig.setMode(value); // the camera is the rig's, not a setting
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

  async function screenshot(scale) {
    const camera = rig.active;
    const blob = await captureView(gl, scale, (width, height) => {
      camera.update(width / height);
      renderer.draw(camera, width, height, view);
    });
    const name = `hexlod-${(state.terrain?.name ?? 'view').replace(/\.[^.]*$/, '')}-${scale}x.png`;
    download(blob, name);
    requestRender();
    return name;
  }

  const toggleHelp = () => { helpBox.hidden = !helpBox.hidden; };
  const resetView = () => { if (stage.current) stage.frameDefault(); syncPanel(); requestRender(); };
  stage.panel = createControlsPanel(document.getElementById('panel'), settings, SETTINGS, {
    camera: cameraMode,
    onChange: onSetting,
    folderActions: { Image: { [REMOVE_IMAGE]: () => images.remove() } },
    actions: {
      'screenshot 1× (P)': () => screenshot(1).catch((e) => showStatus(e.message, true)),
      'screenshot 2×': () => screenshot(2).catch((e) => showStatus(e.message, true)),
      'reset view (R)': () => resetView(),
      'measure (M)': () => measure.toggle(),
      'help (H)': toggleHelp,
    },
  });
  stage.panel.enableAction(REMOVE_IMAGE, false);
  syncView();
  document.getElementById('help-close').onclick = toggleHelp;

  // Drop, file picker, ?src=, ?image=, progress, RAW size dialog and error display (file_intake.js).
  // A new terrain takes the image away: it belonged to the old ground.
  const intake = stage.intake = createFileIntake({ core, state, settings, defaultUrlTimeoutS: SETTINGS.urlTimeout.default,
    show: (loaded, from) => { images.remove(); measure.clear(); stage.show(loaded, from); },
    showStatus, setCellSize: (metres) => onSetting('cellSize', metres), currentSpacing: () => stage.current.terrain,
    drape: (image, world, url) => images.drape(image, world, { url }) });

  const setSetting = (key, value) => onSetting(key, value);
  if (window.hexlod === state) {
    installTestApi(state, { gl, core, rig, settings, view, requestRender, setSetting, screenshot, urlWriter,
      terrain: () => stage.current?.terrain, setLayout: (layout) => setSetting('layout', layout), openUrl: (url) => intake.openUrl(url) });
  }
  // The flight drives the camera, and drapes its image, if it names one, before its first frame.
  if (det) det.install(state, canvas, gl, requestRender, (image, world) => images.drape(image, world, { throwRefusal: true }));
  else rig.attach(canvas);
  installKeys({ settings, setSetting, setCamera: (mode) => onSetting('camera', mode), toggleHelp,
    closeHelp: () => { helpBox.hidden = true; }, toggleHud: () => hud.setCollapsed(!hud.collapsed),
    screenshot: () => screenshot(1).catch((error) => showStatus(error.message, true)), resetView: () => stage.current && resetView() });
  window.addEventListener('resize', requestRender);
  // The measuring tool (M): profile, distance and area of a line clicked on the terrain.
  const measure = installMeasuring({ canvas, rig, settings, stage, renderer, urlWriter, requestRender, state });
  pipeline.onHeightsChanged = () => measure.heightsChanged(); // a tiled terrain's finer tiles came

  installPointerReadout(canvas, { rig, settings, terrain: () => stage.current,
    onCursor: (pick) => { state.cursor = pick; hud.setCursor(pick); },
    onOrbit: () => { syncPanel(); requestRender(); }, measuring: () => measure.active });

  handleContextLoss(canvas, {
    onLost() {
      pipeline.contextLost = state.contextLost = true;
      showStatus('The graphics context was lost; waiting for it to come back…', true);
    },
    onRestored() {
      renderer.createGlObjects(); // the old GL objects died with the context
      renderer.invalidate();
      const world = stage.current?.world;
      if (world) renderer.setShading(world.low, world.high, world.extentX, world.extentZ);
      pipeline.contextLost = state.contextLost = false;
      state.contextRestores += 1;
      showStatus('');
      images.restore().catch((error) => showStatus(error.message, true));
      requestRender();
    },
  });

  // ?src=URL opens that file instead of the default terrain. A file the user opens meanwhile
  // cancels it; the default terrain loads when, once every load has ended, none is on screen
  // (the src failed or was cancelled: its message stays in the status line).
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
  if (statusBox.textContent === OPENING_STATUS) showStatus('');
  if (statusBox.textContent === '') showContourNote();
  if (urlState.image && !det) await intake.openImageUrl(urlState.image);
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
  requestRender();
  state.status = 'ready';
}

main().catch((error) => {
  state.status = 'error';
  state.error = error.message;
  showStatus(error.message, true);
  det?.fail(error.message);
  console.error(error);
});
