// The viewer page: creates the parts (core, renderer, cameras, frame pipeline, the terrain on
// stage, the settings and their owner, panel, HUD, keys, pointer readout, URL state, screenshots,
// context loss), connects them and loads the first terrain. In test mode (test_api.js) its state
// is published on window.hexlod.
import { createCore } from '../core/core.js';
import { createFileIntake } from '../ui/file_intake.js';
import { TerrainRenderer } from '../render/renderer.js';
import { createImageStage, imageFigures, layerFigures } from './image_stage.js';
import { createWebTileStage } from './web_tile_stage.js';
import { createOverlayStage } from './overlay_stage.js';
import { createOverlayTracks } from './overlay_tracks.js';
import { installOverlayPointer } from './overlay_pointer.js';
import { createOverlayPanel } from '../ui/overlay_panel.js';
import { createLayerPanel } from '../ui/layer_panel.js';
import { createAttribution } from '../ui/attribution.js';
import { CameraRig } from '../cameras/rig.js';
import { defaultSettings, SETTINGS, IMAGE_FOLDER } from './settings_table.js';
import { createView } from './view_state.js';
import { createControlsPanel } from '../ui/controls_panel.js';
import { Hud } from '../ui/hud.js';
import { installPointerReadout } from '../ui/pointer_readout.js';
import { parseUrlState, UrlWriter } from './url_state.js';
import { screenshotTaker } from './screenshot.js';
import { recoverLostContext } from './context_loss.js';
import { deterministicMode } from './deterministic/mode.js';
import { FramePipeline } from './frame_pipeline.js';
import { isTestMode, installTestApi } from './test_api.js';
import { installKeys } from './keys.js';
import { SettingsOwner } from './settings_owner.js';
import { TerrainStage } from './terrain_stage.js';
import { settingEffects } from './setting_effects.js';
import { installMeasuring } from './measuring.js';
import { createSettingChanges } from './setting_changes.js';
import { openFirstTerrain } from './first_terrain.js';
import { Layers } from './layers.js';
import { setCrsSource } from '../geo/index.js';
import { fetchCrsDefinition } from './crs_source.js';

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
  setCrsSource(fetchCrsDefinition); // EPSG definitions, fetched when a file names a code
  const urlState = parseUrlState(location.search);
  const settings = Object.assign(defaultSettings(), urlState.settings);
  if (det) Object.assign(settings, (await det.load(), det.settings)); // the flight's settings win
  const renderer = new TerrainRenderer(gl, { normalTile: () => settings.normalTile, imageTile: () => settings.imageTile });
  const view = createView(settings);
  const urlWriter = new UrlWriter();
  const layers = new Layers(); // what is shown: the terrain, its image layers, its overlays
  const requestRender = () => pipeline.request();
  const hud = new Hud(document.getElementById('hud'), true); // one summary line on every screen: I unfolds it
  layers.onChange((shown, part) => hud.showLayers(shown, part));
  const rig = new CameraRig(requestRender);
  rig.cameras.walk.eyeHeight = settings.eyeHeight;
  const cameraMode = { mode: rig.mode }; // the panel's view of the rig
  const syncPanel = () => { cameraMode.mode = rig.mode; panel.refresh(); };
  const pipeline = new FramePipeline({ gl, canvas, renderer, rig, settings, view, hud, state, det, urlWriter, layers,
    onHeightsChanged: () => measure.heightsChanged() });
  const stage = new TerrainStage({ canvas, renderer, rig, settings, layers, pipeline, state, det, syncPanel, requestRender,
    onShown: (terrain) => { owner.adopt('cellSize', terrain.spacingX); panel.setCellSizeRange(terrain.spacingX); } });
  const owner = new SettingsOwner(settings, settingEffects(stage,
    { rescaleMeasure: (k) => measure.rescale(k), showSpacing: (terrain) => intake.showSpacing(terrain) }));
  const images = createImageStage({ renderer, layers, showStatus, requestRender });
  layers.onChange((shown, part) => {
    if (part !== 'images') return;
    state.image = imageFigures(images.current, hud);
    layerPanel.show(shown);
    attribution.show(shown);
  });
  state.image = null;
  Object.defineProperty(state, 'imageLayers', { get: () => layerFigures(layers), enumerable: true }); // for tests
  Object.defineProperty(state, 'images', { value: images, enumerable: false }); // for tests: drape and remove
  Object.defineProperty(state, 'layers', { value: layers, enumerable: false }); // for tests: what is shown
  const { change, syncView, showContourNote } = createSettingChanges({ settings, view, renderer, rig, owner, state,
    showStatus, syncPanel, requestRender });
  const attribution = createAttribution(document.getElementById('attribution'));
  const screenshot = screenshotTaker({ gl, rig, renderer, view, state, layers, attribution, requestRender });
  const saveScreenshot = (scale) => screenshot(scale).catch((error) => showStatus(error.message, true));
  const toggleHelp = () => { helpBox.hidden = !helpBox.hidden; };
  const resetView = () => { if (stage.current) stage.frameDefault(); syncPanel(); requestRender(); };
  const panel = createControlsPanel(document.getElementById('panel'), settings, SETTINGS, {
    camera: cameraMode, onChange: change,
    actions: { 'screenshot 1× (P)': () => saveScreenshot(1), 'screenshot 2×': () => saveScreenshot(2),
      'reset view (R)': resetView, 'measure (M)': () => measure.toggle(), 'help (H)': toggleHelp },
  });
  const webTiles = createWebTileStage({ gl, layers, images, showStatus, requestRender, deterministic: det !== null });
  const overlays = createOverlayStage({ renderer, layers, showStatus, requestRender });
  layers.onChange((shown, part) => {
    if (part !== 'terrain') return;
    webTiles.terrainChanged();
    overlays.terrainChanged();
  });
  Object.defineProperty(state, 'overlays', { value: overlays, enumerable: false }); // for tests: add, restyle, remove
  const layerPanel = createLayerPanel(panel.folder(IMAGE_FOLDER), images, { addTiles: (text) => webTiles.addFrom(text) });
  syncView();
  document.getElementById('help-close').onclick = toggleHelp;
  // Drop, file picker, ?src=, ?image=, progress, RAW size dialog and error display (file_intake.js).
  // A new terrain takes the image away: it belonged to the old ground.
  const intake = createFileIntake({ core, state, settings, layers, defaultUrlTimeoutS: SETTINGS.urlTimeout.default,
    show: (loaded, from) => { images.removeFiles(); measure.clear(); stage.show(loaded, from); },
    showStatus, setCellSize: (metres) => change('cellSize', metres), drape: (image, sidecars, options) => images.drape(image, sidecars, options),
    addOverlay: (file, options) => overlays.add(file, options) });
  if (window.hexlod === state) {
    installTestApi(state, { gl, core, rig, settings, view, requestRender, setSetting: change, screenshot, urlWriter,
      terrain: () => stage.current?.terrain, setLayout: (layout) => change('layout', layout), openUrl: (url) => intake.openUrl(url) });
  }
  // The flight drives the camera, and adds its image layers before its first frame.
  const flightLayer = async (layer, image, sidecars) => {
    const { kind, opacity, visible } = layer;
    if (kind === 'tiles') webTiles.add(layer.tiles, { opacity, visible, throwRefusal: true });
    else await images.drape(image, sidecars, { throwRefusal: true, opacity, visible });
  };
  if (det) det.install(state, canvas, gl, requestRender, flightLayer, (url) => overlays.addUrl(url, { throwRefusal: true }));
  else rig.attach(canvas);
  installKeys({ settings, setSetting: change, setCamera: (mode) => change('camera', mode), toggleHelp,
    closeHelp: () => { helpBox.hidden = true; }, toggleHud: () => hud.setCollapsed(!hud.collapsed),
    screenshot: () => saveScreenshot(1), resetView: () => stage.current && resetView() });
  window.addEventListener('resize', requestRender);
  // The measuring tool (M): profile, distance and area of a line clicked on the terrain.
  const measure = installMeasuring({ canvas, rig, settings, stage, renderer, urlWriter, requestRender, state });
  installPointerReadout(canvas, { rig, settings, terrain: () => stage.current,
    onCursor: (pick) => { state.cursor = pick; hud.setCursor(pick); },
    onOrbit: () => { syncPanel(); requestRender(); }, measuring: () => measure.active });
  // Overlays: their legend in the panel, the feature under the pointer, a track's profile and a flight along it.
  const overlayFolder = panel.folder(`${IMAGE_FOLDER}/overlays (GPX, KML, GeoJSON)`); // inside the layers' folder: the panel stays short
  const tracks = createOverlayTracks({ measure, rig, settings, folder: overlayFolder, showStatus, requestRender, syncPanel });
  const overlayPanel = createOverlayPanel(overlayFolder, overlays, { profile: (layer) => tracks.profileOf(layer), flyAlong: (layer) => tracks.flyAlong(layer) });
  layers.onChange((shown, part) => {
    if (part !== 'overlays') return;
    overlayPanel.show(shown);
    tracks.overlaysChanged(shown.overlays);
  });
  overlayPanel.show(layers);
  const overlayPointer = installOverlayPointer(canvas, { rig, settings, terrain: () => stage.current, layers,
    tip: document.getElementById('overlay-tip'), measuring: () => measure.active,
    showTrack: (layer, feature, path) => tracks.showProfile(layer, feature, path) });
  measure.lineAt = (x, y) => overlayPointer.lineAt(x, y);
  Object.defineProperty(state, 'tracks', { value: tracks, enumerable: false }); // for tests: profile, fly along
  recoverLostContext(canvas, { pipeline, renderer, stage, images, layers, state, showStatus, requestRender });
  await openFirstTerrain({ urlState, intake, stage, rig, measure, det, state, statusBox, openingStatus: OPENING_STATUS,
    showStatus, showContourNote, syncPanel, addTiles: (text) => webTiles.addFrom(text), addOverlayUrl: (url) => overlays.addUrl(url) });
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
