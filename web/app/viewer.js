// One viewer: creates the parts (core, renderer, cameras, frame pipeline, the terrain on stage,
// the settings and their owner, panel, HUD, keys, pointer readout, URL state, screenshots,
// context loss) inside its root element, connects them and loads the first terrain. The page
// (main.js) is one viewer filling the window, reading and writing the address bar; createViewer()
// (web/api/) puts viewers into other pages, any number of them, each with its own core and GL
// context, and hands back what its handle needs (viewer_handle.js). In test mode (test_api.js)
// the page's state is published on window.hexlod.
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
import { VIEWER_MARKUP } from './viewer_markup.js';
import { ViewerDom } from './viewer_dom.js';

/**
 * Builds a viewer inside `root` (its markup replaces what `root` holds) and opens its first
 * terrain. Resolves once that terrain is shown; a failure (no WebGL2, the first terrain does
 * not load) rejects, with the status line saying why.
 * @param {HTMLElement} root  the viewer's element; it gets the class "hexlod"
 * @param {{ page?: boolean, settings?: object, src?: string|null, images?: string[], overlays?: string[],
 *   ui?: boolean, emit?: (type: string, detail: object) => void, state?: object }} [options]
 *   page: the viewer is the page (the address bar, window keys and drops, the test API, flights);
 *   settings: checked values by the settings table's keys, over the defaults (and, on the page,
 *   the address bar's); src, images, overlays: what it opens first (the page reads them from the
 *   address bar); ui: false for a bare canvas (no panel, HUD, file bar or drops); emit: where
 *   its events go ('loaded', 'frame', 'error', 'pick'); state: the object its figures go into;
 *   assembled(parts): the parts, before the first terrain loads (a handle's events need them)
 * @returns {Promise<object>} the parts the viewer's handle drives
 */
export async function mountViewer(root, { page = false, settings: given = {}, src = null, images: imageUrls = [],
  overlays: overlayUrls = [], ui = true, emit = () => {}, state = newState(), assembled = () => {} } = {}) {
  root.classList.add('hexlod');
  root.classList.toggle('hexlod-bare', !ui);
  root.innerHTML = VIEWER_MARKUP;
  const dom = new ViewerDom(root, { page });
  const canvas = dom.byId('view'), statusBox = dom.byId('status'), helpBox = dom.byId('help');
  const openingStatus = statusBox.textContent; // "Loading…", until the first terrain is shown
  const params = page ? new URLSearchParams(location.search) : new URLSearchParams();
  // ?flight=URL: the deterministic mode of regression tests (web/app/deterministic/mode.js, README).
  const det = page ? deterministicMode(params) : null;
  if (page && (isTestMode(params) || det)) window.hexlod = state; // published at once: tests wait for the status

  const showStatus = (message, isError = false) => {
    statusBox.textContent = message;
    statusBox.classList.toggle('error', isError);
    if (isError && message) emit('error', { message });
  };

  try {
    const gl = canvas.getContext('webgl2', { antialias: true });
    if (!gl) throw new Error('this browser has no WebGL2');
    const core = await createCore();
    setCrsSource(fetchCrsDefinition); // EPSG definitions, fetched when a file names a code
    const urlState = page ? parseUrlState(location.search) : { settings: {}, camera: null, src, layers: imageUrls.map((url) => ({ kind: 'image', url })),
      overlays: overlayUrls, measure: null, errors: [] };
    const settings = Object.assign(defaultSettings(), given, urlState.settings);
    if (det) Object.assign(settings, (await det.load(), det.settings)); // the flight's settings win
    const parts = assemble({ dom, gl, core, settings, urlState, det, state, page, ui, showStatus, emit, helpBox });
    assembled(parts);
    await openFirstTerrain({ urlState, intake: parts.intake, stage: parts.stage, rig: parts.rig, measure: parts.measure, det, state,
      statusBox, openingStatus, showStatus, showContourNote: parts.showContourNote, syncPanel: parts.syncPanel,
      addTiles: (text) => parts.webTiles.addFrom(text), addOverlayUrl: (url) => parts.overlays.addUrl(url) });
    parts.requestRender();
    state.status = 'ready';
    return parts;
  } catch (error) {
    state.status = 'error';
    state.error = error.message;
    showStatus(error.message, true);
    det?.fail(error.message);
    dom.dispose();
    throw error;
  }
}

/** The viewer's state: 'loading' | 'ready' | 'error', and figures of the current view (window.hexlod in test mode). */
export function newState() {
  return { status: 'loading', frames: 0, error: null, terrain: null, triangles: 0,
    contextLost: false, contextRestores: 0, recordFrames: false, frameLog: [], cursor: null };
}

/** Creates the parts and connects them. */
function assemble({ dom, gl, core, settings, urlState, det, state, page, ui, showStatus, emit, helpBox }) {
  const canvas = dom.byId('view');
  const renderer = new TerrainRenderer(gl, { normalTile: () => settings.normalTile, imageTile: () => settings.imageTile });
  const view = createView(settings);
  const urlWriter = new UrlWriter({ addressBar: page });
  const layers = new Layers(); // what is shown: the terrain, its image layers, its overlays
  const requestRender = () => pipeline.request();
  const hud = new Hud(dom.byId('hud'), true); // one summary line on every screen: I unfolds it
  layers.onChange((shown, part) => hud.showLayers(shown, part));
  const rig = new CameraRig(requestRender);
  rig.cameras.walk.eyeHeight = settings.eyeHeight;
  const cameraMode = { mode: rig.mode }; // the panel's view of the rig
  const syncPanel = () => { cameraMode.mode = rig.mode; panel.refresh(); };
  const pipeline = new FramePipeline({ gl, canvas, renderer, rig, settings, view, hud, state, det, urlWriter, layers,
    onHeightsChanged: () => measure.heightsChanged(), onFrame: () => emit('frame', state) });
  const stage = new TerrainStage({ dom, canvas, renderer, rig, settings, layers, pipeline, state, det, syncPanel, requestRender,
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
  const attribution = createAttribution(dom.byId('attribution'));
  const screenshot = screenshotTaker({ gl, rig, renderer, view, state, layers, attribution, requestRender });
  const saveScreenshot = (scale) => screenshot(scale).catch((error) => showStatus(error.message, true));
  const toggleHelp = () => { helpBox.hidden = !helpBox.hidden; };
  const resetView = () => { if (stage.current) stage.frameDefault(); syncPanel(); requestRender(); };
  const panel = createControlsPanel(dom.byId('panel'), settings, SETTINGS, {
    camera: cameraMode, onChange: change, small: dom.isSmall(), injectStyles: !page,
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
  dom.byId('help-close').onclick = toggleHelp;
  // Drop, file picker, ?src=, ?image=, progress, RAW size dialog and error display (file_intake.js).
  // A new terrain takes the image away: it belonged to the old ground.
  const intake = createFileIntake({ dom, core, state, settings, layers, defaultUrlTimeoutS: SETTINGS.urlTimeout.default, drops: ui,
    show: (loaded, from) => {
      if (dom.disposed) { // the viewer went while this terrain loaded
        loaded.tiles?.close();
        loaded.terrain.destroy();
        return;
      }
      images.removeFiles();
      measure.clear();
      stage.show(loaded, from);
      emit('loaded', { terrain: state.terrain });
    },
    showStatus, setCellSize: (metres) => change('cellSize', metres), drape: (image, sidecars, options) => images.drape(image, sidecars, options),
    addOverlay: (file, options) => overlays.add(file, options) });
  if (page && window.hexlod === state) {
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
  else rig.attach(canvas, dom);
  installKeys(dom, { settings, setSetting: change, setCamera: (mode) => change('camera', mode), toggleHelp,
    closeHelp: () => { helpBox.hidden = true; }, toggleHud: () => hud.setCollapsed(!hud.collapsed),
    screenshot: () => saveScreenshot(1), resetView: () => stage.current && resetView() });
  dom.onResize(requestRender);
  // The measuring tool (M): profile, distance and area of a line clicked on the terrain.
  const measure = installMeasuring({ dom, canvas, rig, settings, stage, renderer, urlWriter, requestRender, state });
  installPointerReadout(canvas, { rig, settings, terrain: () => stage.current,
    onCursor: (pick) => { state.cursor = pick; hud.setCursor(pick); },
    onPick: (pick) => emit('pick', pick),
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
    tip: dom.byId('overlay-tip'), measuring: () => measure.active,
    showTrack: (layer, feature, path) => tracks.showProfile(layer, feature, path) });
  measure.lineAt = (x, y) => overlayPointer.lineAt(x, y);
  Object.defineProperty(state, 'tracks', { value: tracks, enumerable: false }); // for tests: profile, fly along
  recoverLostContext(canvas, { pipeline, renderer, stage, images, layers, state, showStatus, requestRender });
  return { dom, gl, core, settings, state, view, layers, renderer, rig, pipeline, stage, images, overlays, webTiles, intake, measure, panel,
    urlWriter, screenshot, change, syncPanel, showContourNote, resetView, requestRender, showStatus };
}
