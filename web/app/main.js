// The viewer page: loads the core and the default terrain, runs the frame loop (cameras, LOD
// update, fan stream, upload, draw), and wires the panel, HUD, URL state, screenshots and
// context loss to it. State for headless tests is published on window.hexlod.
import { createCore } from '../core.js';
import { createFileIntake } from '../ui/file_intake.js';
import { TerrainRenderer } from '../render/renderer.js';
import { CameraRig, CAMERA_MODES, isTyping } from '../cameras/rig.js';
import { createWorld } from '../cameras/ground.js';
import { frameTerrain } from '../cameras/framing.js';
import { defaultSettings, applyLodSettings, MORPH_FRAMES, SHADING_MODES } from './settings.js';
import { createControlsPanel } from '../ui/controls_panel.js';
import { Hud } from '../ui/hud.js';
import { pickGround } from '../cameras/picking.js';
import { parseUrlState, applyCameraState, UrlWriter } from './url_state.js';
import { captureView, download } from './screenshot.js';
import { handleContextLoss } from './context_loss.js';
import { deterministicMode } from './deterministic/mode.js';

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
const timingPixel = new Uint8Array(4);
const FRAME_LOG = 4096; // frames kept in window.hexlod.frameLog while recording
// ?flight=URL: the deterministic mode of regression tests (web/app/deterministic/mode.js, README).
const det = deterministicMode(params);
// Settings that change only the shading (issue 14), never the core's mesh.
const SHADING_KEYS = ['shading', 'normals', 'shadows', 'occlusion', 'sunAzimuth', 'sunElevation'];

const canvas = document.getElementById('view');
const statusBox = document.getElementById('status');
const helpBox = document.getElementById('help');

/** What headless tests read: 'loading' | 'ready' | 'error', and figures of the current view. */
const state = (window.hexlod = { status: 'loading', frames: 0, error: null, terrain: null, triangles: 0,
  contextLost: false, contextRestores: 0, recordFrames: false, frameLog: [], cursor: null });

function showStatus(message, isError = false) {
  statusBox.textContent = message;
  statusBox.classList.toggle('error', isError);
}

/** Fetches [{ name, url }] as the { name, bytes } files the loaders take. */
async function fetchFiles(files) {
  return Promise.all(files.map(async ({ name, url }) => {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`cannot fetch ${url}: HTTP ${response.status}`);
    return { name, bytes: new Uint8Array(await response.arrayBuffer()) };
  }));
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
  let source = null;         // the data's URL, while the terrain on screen came from one
  let pendingSource = null;  // the URL being opened
  let current = null;        // { terrain, field, loadMs, world, streamVersion, blendsEnd }
  let frameRequested = false;
  let contextLost = false;
  let lastFrameTime = 0;
  let lastFrameMs = 0; // CPU time of the previous frame, for the HUD
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

  function render(now) {
    frameRequested = false;
    if (contextLost) return;
    if (det && !det.beginFrame()) return; // deterministic: only the frames asked for
    const frameStart = performance.now();
    const seconds = now - lastFrameTime < 200 ? (now - lastFrameTime) / 1000 : 1 / 60;
    lastFrameTime = now;
    const moving = rig.step(seconds);
    const dpr = window.devicePixelRatio || 1;
    const width = det ? det.width : Math.max(1, Math.round(canvas.clientWidth * dpr));
    const height = det ? det.height : Math.max(1, Math.round(canvas.clientHeight * dpr));
    if (canvas.width !== width || canvas.height !== height) {
      canvas.width = width;
      canvas.height = height;
    }
    const camera = det ? det.camera : rig.active;
    camera.update(width / height);
    let lodMs = 0, streamMs = 0, uploadMs = 0;
    if (current) {
      // §6: one budgeted refinement step per frame for the current camera, then the fans.
      // Frozen: the mesh stays as it is while the camera moves (to look at it from outside).
      const { terrain } = current;
      if (!settings.freeze) {
        terrain.setLodCamera(det ? det.lodCamera : { eye: camera.position, target: camera.target, fovY: camera.fovY,
          aspect: camera.aspect, viewportHeight: height, near: camera.near, far: camera.far });
        const operations = terrain.updateLod();
        if (det) det.afterLod(terrain, operations);
      }
      const lod = terrain.lodStats();
      lodMs = settings.freeze ? 0 : lod.updateMs;
      const streamStart = performance.now();
      terrain.setStreamNormals(renderer.usesMeshNormals(view));
      state.streamNormals = terrain.streamNormals;
      const version = terrain.updateStream();
      current.world.version += 1; // the drawn surface may have moved: the walk floor is asked anew
      if (camera.mode === 'walk') {
        camera.settle(); // stand on the surface as it is drawn in this frame
        camera.update(width / height);
      }
      const uploadStart = performance.now();
      streamMs = uploadStart - streamStart;
      if (version !== current.streamVersion) current.blendsEnd = lod.frame + MORPH_FRAMES; // new blends run
      current.streamVersion = version;
      state.uploadBytes = renderer.upload(terrain, view.layout);
      state.streamBytes = renderer.streamBytes;
      if (view.colorByLevel || view.outline) renderer.setLevelView(terrain.levelView(view.outline));
      uploadMs = performance.now() - uploadStart;
      view.frame = lod.frame;
      const stats = terrain.meshStats();
      state.triangles = stats.triangles;
      state.mesh = stats;
      state.converged = lod.converged;
      state.lod = lod;
      state.timing = { updateMs: lod.updateMs, streamMs, uploadMs, frameMs: lastFrameMs };
      if (!settings.freeze && (!lod.converged || lod.frame < current.blendsEnd)) requestRender();
      hud.tick(now);
      hud.update({ terrain, lod, stats, timing: state.timing, settings, camera }, now);
      state.hud = hud.values;
      state.eye = Array.from(camera.position);
    }
    const drawStart = performance.now();
    renderer.draw(camera, width, height, view);
    if (TIMING) gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, timingPixel); // waits for the draw
    const drawMs = performance.now() - drawStart;
    lastFrameMs = performance.now() - frameStart;
    if (state.timing) Object.assign(state.timing, { drawMs, frameMs: performance.now() - frameStart });
    if (state.recordFrames && state.frameLog.length < FRAME_LOG) {
      state.frameLog.push({ time: now, lodMs, streamMs, uploadMs, drawMs, cpuMs: performance.now() - frameStart });
    }
    state.frames += 1;
    if (det) det.endFrame();
    if (moving) requestRender();
    if (current && !det) urlWriter.write({ settings, camera, src: source });
  }

  function requestRender() {
    if (!frameRequested) {
      frameRequested = true;
      requestAnimationFrame(render);
    }
  }

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

  function show(loaded) {
    const { terrain, field } = loaded;
    source = pendingSource; // a dropped or picked file has no URL to share
    terrain.resetMesh(settings.embedding);
    applyLodSettings(terrain, settings);
    terrain.setStreamLayout(view.layout);
    current?.terrain.destroy();
    current = loaded;
    makeWorld(loaded);
    frameDefault(loaded);
    renderer.invalidate();
    settings.cellSize = terrain.spacingX;
    panel.setCellSizeRange(terrain.spacingX);
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

  /** A setting changed (panel, key or URL): apply it to the core, the cameras or the view. */
  function onSetting(key, value) {
    const terrain = current?.terrain;
    try {
      if (key === 'camera') rig.setMode(value);
      else if (key === 'eyeHeight') rig.cameras.walk.eyeHeight = value;
      else if (key === 'exaggeration') {
        rescaleHeights(view.verticalScale, value);
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
        if (!(k > 0) || !Number.isFinite(k)) throw new Error(`cell size ${value} m is not a positive number`);
        terrain.setScale({ ...current.field, spacingX: terrain.spacingX * k, spacingY: terrain.spacingY * k });
        rescaleGround(k);
        makeWorld(current);
        keepCamerasAboveGround();
        renderer.invalidate();
        hud.setTerrain(current.field, terrain, current.loadMs);
      } else if (terrain && !['wireframe', 'colorByLevel', 'freeze', ...SHADING_KEYS].includes(key)) {
        applyLodSettings(terrain, settings);
      }
      showStatus('');
    } catch (error) {
      showStatus(error.message, true);
    }
    syncView();
    syncPanel();
    requestRender();
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
      'reset view (R)': () => { if (current) frameDefault(current); syncPanel(); requestRender(); },
      'help (H)': toggleHelp,
    },
  });
  syncView();
  document.getElementById('help-close').onclick = toggleHelp;

  // Drop, file picker, ?src=, progress, RAW size dialog and error display (file_intake.js).
  const intake = createFileIntake({ core, state, show, showStatus });

  // For headless tests and benchmarks: drive the camera, ask for frames, read GL errors.
  Object.assign(state, { rig, settings, view, requestRender, setSetting: (key, value) => { settings[key] = value; onSetting(key, value); },
    glError: () => gl.getError(), screenshot, terrainObject: () => current?.terrain, flushUrl: () => urlWriter.flush() });
  Object.defineProperty(state, 'camera', { get: () => rig.active, enumerable: true });
  if (det) det.install(state, canvas, gl, requestRender); // the flight drives the camera
  else rig.attach(canvas);
  // For benchmarks: the same mesh drawn with the other index layout ('fans' | 'triangles').
  state.setLayout = (layout) => {
    view.layout = layout;
    current?.terrain.setStreamLayout(layout);
    requestRender();
  };
  window.addEventListener('keydown', (e) => {
    if (isTyping(e) || e.ctrlKey || e.metaKey || e.altKey) return;
    const toggles = { l: 'colorByLevel', o: 'wireframe', f: 'freeze' };
    const key = e.key.toLowerCase();
    if (toggles[key]) state.setSetting(toggles[key], !settings[toggles[key]]);
    else if (['1', '2', '3'].includes(key)) onSetting('camera', CAMERA_MODES[Number(key) - 1]);
    else if (key === 'h' || key === '?') toggleHelp();
    else if (key === 'i') hud.setCollapsed(!hud.collapsed);
    else if (key === 'escape') helpBox.hidden = true;
    else if (key === 'p') screenshot(1).catch((error) => showStatus(error.message, true));
    else if (key === 'r' && current) { frameDefault(current); syncPanel(); requestRender(); }
  });
  window.addEventListener('resize', requestRender);

  // The cursor readout: the ground under the mouse, at most every 50 ms.
  let lastPick = 0;
  canvas.addEventListener('pointermove', (e) => {
    if (!current || e.pointerType === 'touch' || e.timeStamp - lastPick < 50) return;
    lastPick = e.timeStamp;
    const rect = canvas.getBoundingClientRect();
    state.cursor = pickGround(rig.active, e.clientX - rect.left, e.clientY - rect.top, rect.width, rect.height,
      current.terrain, current.world, settings.exaggeration);
    hud.setCursor(state.cursor);
  });
  // A double click orbits around the point under the pointer.
  canvas.addEventListener('dblclick', (e) => {
    if (!current) return;
    const rect = canvas.getBoundingClientRect();
    const pick = pickGround(rig.active, e.clientX - rect.left, e.clientY - rect.top, rect.width, rect.height,
      current.terrain, current.world, settings.exaggeration);
    if (!pick) return;
    if (rig.mode !== 'orbit') rig.setMode('orbit');
    rig.cameras.orbit.lookAround(pick.x, pick.height * settings.exaggeration, pick.z);
    syncPanel();
    requestRender();
  });

  handleContextLoss(canvas, {
    onLost() {
      contextLost = state.contextLost = true;
      showStatus('The graphics context was lost; waiting for it to come back…', true);
    },
    onRestored() {
      renderer.createGlObjects(); // the old GL objects died with the context
      renderer.invalidate();
      if (current) renderer.setShading(current.world.low, current.world.high, current.world.extentX, current.world.extentZ);
      contextLost = state.contextLost = false;
      state.contextRestores += 1;
      showStatus('');
      requestRender();
    },
  });

  // ?src=URL opens that file instead of the default terrain (which still loads if it fails).
  const src = urlState.src;
  pendingSource = src;
  const opened = src && await intake.openUrl(src);
  pendingSource = null;
  if (!opened && det && src) throw new Error(state.error); // a flight is meaningless over another terrain
  if (!opened) {
    const error = state.error;
    await intake.open(await fetchFiles(DEFAULT_TERRAIN));
    if (error) { state.error = error; showStatus(error, true); }
  }
  if (!current) throw new Error(`the default terrain did not load: ${state.error}`);
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
