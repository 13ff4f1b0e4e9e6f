// The viewer page: loads the core and the default terrain, and wires the frame pipeline
// (frame_pipeline.js), the settings, the panel, HUD, keys, pointer readout, URL state, screenshots
// and context loss together. In test mode (test_api.js) its state is published on window.hexlod.
import { createCore } from '../core/core.js';
import { createFileIntake } from '../ui/file_intake.js';
import { TerrainRenderer } from '../render/renderer.js';
import { CameraRig } from '../cameras/rig.js';
import { createWorld } from '../cameras/ground.js';
import { frameTerrain } from '../cameras/framing.js';
import { defaultSettings, applyLodSettings, MORPH_FRAMES, SHADING_MODES } from './settings.js';
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

// The names are given, not taken from the URLs: a production build puts a content hash into
// each asset's file name, and the loader pairs a height field with its sidecar by name.
const DEFAULT_TERRAIN = [
  { name: 'globe_himalaya_2048.png', url: new URL('../../public/terrain/globe_himalaya_2048.png', import.meta.url).href },
  { name: 'globe_himalaya_2048.json', url: new URL('../../public/terrain/globe_himalaya_2048.json', import.meta.url).href },
];
const params = new URLSearchParams(location.search);
// The index layout: an indexed TRIANGLES list (the default: it drew in 0.61x the time of the
// paper's TRIANGLE_FAN with primitive restart on the same mesh, and ANGLE on Direct3D 11 and
// Metal converts fans to lists; see BENCHMARKS.md), or ?layout=fans.
const LAYOUT = params.get('layout') === 'fans' ? 'fans' : 'triangles';
// ?timing=1 waits for the GPU after drawing (a one-pixel readPixels: gl.finish does not wait in
// Chromium) so that frame figures include it; for benchmarks only, since it stalls the pipeline.
const TIMING = params.get('timing') === '1';
// ?flight=URL: the deterministic mode of regression tests (web/app/deterministic/mode.js, README).
const det = deterministicMode(params);
// Settings that change only the shading (issue 14), never the core's mesh.
const SHADING_KEYS = ['shading', 'normals', 'shadows', 'occlusion', 'sunAzimuth', 'sunElevation'];

const canvas = document.getElementById('view');
const statusBox = document.getElementById('status');
const helpBox = document.getElementById('help');

/** The page's state: 'loading' | 'ready' | 'error', and figures of the current view (window.hexlod in test mode). */
const state = { status: 'loading', frames: 0, error: null, terrain: null, triangles: 0,
  contextLost: false, contextRestores: 0, recordFrames: false, frameLog: [], cursor: null };
if (isTestMode(params) || det) window.hexlod = state; // published at once: tests wait for the status

function showStatus(message, isError = false) {
  statusBox.textContent = message;
  statusBox.classList.toggle('error', isError);
}

async function main() {
  const gl = canvas.getContext('webgl2', { antialias: true });
  if (!gl) throw new Error('this browser has no WebGL2');
  const core = await createCore();
  const renderer = new TerrainRenderer(gl);
  const settings = defaultSettings();
  const urlState = parseUrlState(location.search);
  Object.assign(settings, urlState.settings);
  if (SHADING_MODES.includes(params.get('shading'))) settings.shading = params.get('shading'); // issue 14
  if (det) Object.assign(settings, (await det.load(), det.settings)); // the flight's settings win
  const urlWriter = new UrlWriter();
  let pipeline = null; // made below, once the cameras and the HUD exist
  const requestRender = () => pipeline.request();
  let source = null;         // the data's URL, while the terrain on screen came from one (the address bar's src)
  let current = null;        // { terrain, field, loadMs, world, streamVersion, blendsEnd }
  const view = { colorByLevel: false, outline: false, frame: 0, morphFrames: MORPH_FRAMES, verticalScale: settings.exaggeration,
    layout: LAYOUT, hideTerrain: false };
  // The HUD opens as one summary line on every screen, so the terrain has the view (I unfolds it).
  const hud = new Hud(document.getElementById('hud'), true);
  const rig = new CameraRig(requestRender);
  rig.cameras.walk.eyeHeight = settings.eyeHeight;
  const cameraMode = { mode: rig.mode }; // the panel's view of the rig

  function syncView() {
    view.colorByLevel = settings.colorByLevel;
    view.outline = settings.wireframe;
    view.morphFrames = settings.geomorph ? MORPH_FRAMES : 0;
    view.verticalScale = settings.exaggeration;
    syncShading();
  }

  // Shading (issue 14): the mode, the normals' source, shadows, occlusion and the sun.
  function syncShading() {
    Object.assign(view, { shading: settings.shading, normals: settings.normals, shadows: settings.shadows,
      occlusion: settings.occlusion });
    renderer.setSun(settings.sunAzimuth, settings.sunElevation);
    state.shadingTimes = renderer.fieldTextures.times;
    // For tests: the normal texture's tiles. Not enumerable: it holds the terrain and through it
    // the WASM heap, which a test's evaluate(() => window.hexlod) would try to copy whole.
    Object.defineProperty(state, 'fieldTextures', { value: renderer.fieldTextures, enumerable: false, configurable: true });
  }

  pipeline = new FramePipeline({ gl, canvas, renderer, rig, settings, view, hud, state, det, timing: TIMING, urlWriter,
    source: () => source });

  /** Heights and extent of the world in drawn metres, for the cameras (ground.js). */
  function makeWorld(loaded) {
    const { terrain } = loaded;
    const s = settings.exaggeration;
    const extent = { extentX: (terrain.width - 1) * terrain.spacingX, extentZ: (terrain.height - 1) * terrain.spacingY,
      low: terrain.minHeight * s, high: terrain.maxHeight * s };
    loaded.world = createWorld(terrain, extent, () => settings.exaggeration, () => 0.5 * rig.cameras.walk.eyeHeight);
    rig.setWorld(loaded.world);
    renderer.setShading(extent.low, extent.high, extent.extentX, extent.extentZ);
    if (renderer.fieldTextures.terrain !== terrain || renderer.fieldTextures.spacing !== terrain.spacingX) {
      renderer.setField(terrain, loaded.field); // issue 14: normals, shadows, occlusion from the field
    }
  }

  /** The opening view (framing.js): the field, or its region of most relief, in view from above. */
  function frameDefault(loaded) {
    const orbit = rig.cameras.orbit;
    const width = Math.max(canvas.clientWidth, 1), height = Math.max(canvas.clientHeight, 1);
    // The file bar along the top and the HUD along the bottom: the terrain opens between them.
    const bar = document.getElementById('intake').getBoundingClientRect(), hudBox = document.getElementById('hud').getBoundingClientRect();
    const covered = {
      top: bar.height > 0 ? Math.min(bar.bottom / height, 0.3) : 0,
      bottom: hudBox.height > 0 ? Math.min((height - hudBox.top) / height, 0.3) : 0,
    };
    frameTerrain(loaded.terrain, loaded.world, orbit, settings.exaggeration, width / height, covered);
    rig.active = orbit;
  }

  /** Shows a loaded terrain; `from`: the URL it came from, null for a file (no URL to share). */
  function show(loaded, from) {
    const { terrain, field } = loaded;
    source = from;
    terrain.resetMesh(settings.embedding);
    applyLodSettings(terrain, settings);
    terrain.setStreamLayout(view.layout);
    current?.terrain.destroy();
    current = pipeline.current = loaded;
    makeWorld(loaded);
    frameDefault(loaded);
    renderer.invalidate();
    owner.adopt('cellSize', terrain.spacingX);
    panel.setCellSizeRange(terrain.spacingX);
    pipeline.forgetFigures(); // the last terrain's "converged" and triangles do not describe this one
    state.terrain = { name: field.source, width: terrain.width, height: terrain.height,
      minHeight: terrain.minHeight, maxHeight: terrain.maxHeight };
    hud.setTerrain(field, terrain, loaded.loadMs);
    syncPanel();
    det?.setTerrain(terrain);
    requestRender();
  }

  /** Scales the cameras' heights when the exaggeration changes from `from` to `to`. */
  function rescaleHeights(from, to) {
    const k = to / from;
    rig.cameras.orbit.target[1] *= k;
    rig.cameras.fly.position[1] *= k;
    rig.cameras.walk.position[1] *= k;
  }

  /** Lifts the active camera out of the ground after the ground's heights changed. */
  function keepCamerasAboveGround() {
    const camera = rig.active, margin = current.world.spacing * 0.05;
    if (camera.mode === 'walk') camera.settle();
    else camera.keepAboveGround(camera.mode === 'orbit' ? Math.max(margin, 0.01 * camera.distance) : margin);
  }

  /** Scales the cameras' ground positions when the cell size changes by `k`. */
  function rescaleGround(k) {
    for (const p of [rig.cameras.orbit.target, rig.cameras.fly.position, rig.cameras.walk.position]) {
      p[0] *= k;
      p[2] *= k;
    }
    rig.cameras.orbit.distance *= k;
  }

  /** Applies a setting that SettingsOwner checked (to the core, the cameras or the view); throws when it cannot. */
  function applySetting(key, value, previous) {
    const terrain = current?.terrain;
    if (key === 'eyeHeight') rig.cameras.walk.eyeHeight = value;
    else if (key === 'exaggeration') {
      rescaleHeights(previous, value);
      if (terrain) {
        terrain.setLodVerticalScale(value); // no mesh rebuild: the shader scales heights
        makeWorld(current);
        keepCamerasAboveGround(); // taller hills may now stand where the eye is
      }
    } else if (key === 'embedding' && terrain) {
      terrain.resetMesh(value);
      applyLodSettings(terrain, settings);
      terrain.setStreamLayout(view.layout);
      renderer.invalidate();
    } else if (key === 'cellSize' && terrain) {
      const k = value / terrain.spacingX;
      terrain.setScale({ ...current.field, spacingX: value, spacingY: terrain.spacingY * k }); // the value as typed, rows in ratio
      rescaleGround(k);
      makeWorld(current);
      keepCamerasAboveGround();
      renderer.invalidate();
      hud.setTerrain(current.field, terrain, current.loadMs);
      intake.showSpacing(terrain);
    } else if (terrain && !['wireframe', 'colorByLevel', 'freeze', 'urlTimeout', 'urlMaxMB', ...SHADING_KEYS].includes(key)) {
      applyLodSettings(terrain, settings);
    }
  }
  const owner = new SettingsOwner(settings, applySetting);

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
    syncPanel();
    requestRender();
    return applied;
  }

  function syncPanel() {
    cameraMode.mode = rig.mode;
    panel?.refresh();
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
  const panel = createControlsPanel(document.getElementById('panel'), settings, {
    camera: cameraMode,
    onChange: onSetting,
    actions: {
      'screenshot 1× (P)': () => screenshot(1).catch((e) => showStatus(e.message, true)),
      'screenshot 2×': () => screenshot(2).catch((e) => showStatus(e.message, true)),
      'reset view (R)': () => resetView(),
      'help (H)': toggleHelp,
    },
  });
  syncView();
  document.getElementById('help-close').onclick = toggleHelp;

  // Drop, file picker, ?src=, progress, RAW size dialog and error display (file_intake.js).
  const intake = createFileIntake({ core, state, settings, show, showStatus, setCellSize: (metres) => onSetting('cellSize', metres),
    currentSpacing: () => current.terrain });

  const setSetting = (key, value) => onSetting(key, value);
  const resetView = () => { if (current) frameDefault(current); syncPanel(); requestRender(); };
  if (window.hexlod === state) {
    installTestApi(state, { gl, core, rig, settings, view, requestRender, setSetting, screenshot, urlWriter,
      terrain: () => current?.terrain,
      setLayout: (layout) => { view.layout = layout; current?.terrain.setStreamLayout(layout); requestRender(); } });
  }
  if (det) det.install(state, canvas, gl, requestRender); // the flight drives the camera
  else rig.attach(canvas);
  installKeys({ settings, setSetting, setCamera: (mode) => onSetting('camera', mode), toggleHelp,
    closeHelp: () => { helpBox.hidden = true; }, toggleHud: () => hud.setCollapsed(!hud.collapsed),
    screenshot: () => screenshot(1).catch((error) => showStatus(error.message, true)), resetView: () => current && resetView() });
  window.addEventListener('resize', requestRender);

  installPointerReadout(canvas, { rig, settings, terrain: () => current,
    onCursor: (pick) => { state.cursor = pick; hud.setCursor(pick); },
    onOrbit: () => { syncPanel(); requestRender(); } });

  handleContextLoss(canvas, {
    onLost() {
      pipeline.contextLost = state.contextLost = true;
      showStatus('The graphics context was lost; waiting for it to come back…', true);
    },
    onRestored() {
      renderer.createGlObjects(); // the old GL objects died with the context
      renderer.invalidate();
      if (current) renderer.setShading(current.world.low, current.world.high, current.world.extentX, current.world.extentZ);
      pipeline.contextLost = state.contextLost = false;
      state.contextRestores += 1;
      showStatus('');
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
  while (!current) {
    if (await intake.openLinks(DEFAULT_TERRAIN) === 'failed') throw new Error(`the default terrain did not load: ${state.error}`);
    await intake.idle(); // a file dropped meanwhile cancelled the default: shown, or failed (then the default again)
  }
  if (urlState.camera && !det) {
    applyCameraState(rig, urlState.camera);
    if (rig.mode === 'walk') rig.active.settle();
    syncPanel();
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
