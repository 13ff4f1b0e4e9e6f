// The viewer page: loads the core and the default terrain, draws it, and lets the user drop
// another height field. State for headless tests is published on window.hexlod.
import { createCore, RESTART_INDEX, STREAM_VERTEX_WORDS } from './core.js';
import { createFileIntake } from './file_intake.js';
import { TerrainRenderer } from './renderer.js';
import { OrbitCamera, attachOrbitControls } from './camera.js';

const DEFAULT_TERRAIN = [
  new URL('../public/terrain/globe_himalaya_2048.png', import.meta.url).href,
  new URL('../public/terrain/globe_himalaya_2048.json', import.meta.url).href,
];
const VERTICAL_EXAGGERATION = 2;
const TAU_PX = 1;          // screen-space error tolerance, device pixels
const FRAME_BUDGET_MS = 4; // LOD update time per frame
const MORPH_FRAMES = 8;    // geomorph blends (paper §7), frames
const params = new URLSearchParams(location.search);
// The index layout: an indexed TRIANGLES list (the default: it drew in 0.61x the time of the
// paper's TRIANGLE_FAN with primitive restart on the same mesh, and ANGLE on Direct3D and
// Metal rewrites fans on the CPU; see BENCHMARKS.md), or ?layout=fans.
const LAYOUT = params.get('layout') === 'fans' ? 'fans' : 'triangles';
// ?timing=1 waits for the GPU after drawing (a one-pixel readPixels: gl.finish does not wait in
// Chromium) so that frame figures include it; for benchmarks only, since it stalls the pipeline.
const TIMING = params.get('timing') === '1';
const timingPixel = new Uint8Array(4);

const canvas = document.getElementById('view');
const hud = document.getElementById('hud');
const statusBox = document.getElementById('status');

/** What headless tests read: 'loading' | 'ready' | 'error', and figures of the current view. */
const state = (window.hexlod = { status: 'loading', frames: 0, error: null, terrain: null, triangles: 0 });

function showStatus(message, isError = false) {
  statusBox.textContent = message;
  statusBox.classList.toggle('error', isError);
}

/**
 * Where the relief is: the centroid of the drawn vertices weighted by the square of their
 * height above the lowest point, so a view opens on the mountains rather than the plain.
 * Heights in the stream are unscaled; the result is in drawn (exaggerated) metres.
 */
function reliefCentroid({ vertices, indices }, lowest, verticalScale) {
  let x = 0, y = 0, z = 0, total = 0;
  for (const v of indices) {
    if (v === RESTART_INDEX) continue;
    const k = v * STREAM_VERTEX_WORDS;
    const w = (vertices[k + 1] - lowest) ** 2;
    x += vertices[k] * w;
    y += vertices[k + 1] * w;
    z += vertices[k + 2] * w;
    total += w;
  }
  if (total === 0) return [vertices[0], vertices[1] * verticalScale, vertices[2]];
  return [x / total, (y / total) * verticalScale, z / total];
}

async function fetchFiles(urls) {
  return Promise.all(urls.map(async (url) => {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`cannot fetch ${url}: HTTP ${response.status}`);
    const name = decodeURIComponent(new URL(url, location.href).pathname.split('/').pop());
    return { name, bytes: new Uint8Array(await response.arrayBuffer()) };
  }));
}

async function main() {
  const gl = canvas.getContext('webgl2', { antialias: true });
  if (!gl) throw new Error('this browser has no WebGL2');
  const core = await createCore();
  const renderer = new TerrainRenderer(gl);
  const camera = new OrbitCamera();
  let current = null; // { terrain, field, loadMs }
  let frameRequested = false;
  const view = { colorByLevel: false, outline: false, frame: 0, morphFrames: MORPH_FRAMES, verticalScale: VERTICAL_EXAGGERATION,
    layout: LAYOUT };
  const lodLine = document.createElement('div');

  function render() {
    frameRequested = false;
    const frameStart = performance.now();
    const dpr = window.devicePixelRatio || 1;
    const width = Math.max(1, Math.round(canvas.clientWidth * dpr));
    const height = Math.max(1, Math.round(canvas.clientHeight * dpr));
    if (canvas.width !== width || canvas.height !== height) {
      canvas.width = width;
      canvas.height = height;
    }
    camera.update(width / height);
    if (current) {
      // §6: one budgeted refinement step per frame for the current camera, then the fans.
      const { terrain } = current;
      terrain.setLodCamera({ eye: camera.position, target: camera.target, fovY: camera.fovY, aspect: camera.aspect,
        viewportHeight: height, near: camera.near, far: camera.far });
      if (!state.frozen) terrain.updateLod(); // frozen: keep the mesh (benchmarks, inspection)
      const lod = terrain.lodStats();
      const streamStart = performance.now();
      const version = terrain.updateStream();
      const uploadStart = performance.now();
      if (version !== current.streamVersion) current.blendsEnd = lod.frame + MORPH_FRAMES; // new blends run
      current.streamVersion = version;
      state.uploadBytes = renderer.upload(terrain, view.layout);
      state.streamBytes = renderer.streamBytes;
      if (view.colorByLevel || view.outline) renderer.setLevelView(terrain.levelView(view.outline));
      state.timing = { updateMs: lod.updateMs, streamMs: uploadStart - streamStart, uploadMs: performance.now() - uploadStart };
      view.frame = lod.frame;
      const stats = terrain.meshStats();
      state.triangles = stats.triangles;
      state.mesh = stats;
      state.converged = lod.converged;
      lodLine.textContent = `LOD: ${stats.triangles.toLocaleString('en')} triangles, ${stats.cells.toLocaleString('en')} cells, ` +
        `update ${lod.updateMs.toFixed(1)} ms (${lod.splits} splits, ${lod.merges} merges)${lod.converged ? '' : ', refining…'}`;
      if (!lod.converged || lod.frame < current.blendsEnd) requestRender();
    }
    const drawStart = performance.now();
    renderer.draw(camera, width, height, view);
    if (TIMING) gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, timingPixel); // waits for the draw
    if (state.timing) Object.assign(state.timing, { drawMs: performance.now() - drawStart, frameMs: performance.now() - frameStart });
    state.frames += 1;
  }

  function requestRender() {
    if (!frameRequested) {
      frameRequested = true;
      requestAnimationFrame(render);
    }
  }

  function show(loaded) {
    const { terrain, field } = loaded;
    loaded.extentX = (terrain.width - 1) * field.spacingX;
    loaded.extentZ = (terrain.height - 1) * field.spacingY;
    loaded.low = terrain.minHeight * VERTICAL_EXAGGERATION;
    loaded.high = terrain.maxHeight * VERTICAL_EXAGGERATION;
    terrain.resetMesh('exact');
    terrain.setLodVerticalScale(VERTICAL_EXAGGERATION);
    terrain.setLodTolerance(TAU_PX);
    terrain.setLodBudget(FRAME_BUDGET_MS, 0);
    terrain.setMorphFrames(MORPH_FRAMES);
    terrain.setStreamLayout(view.layout);
    terrain.updateStream();
    const focus = reliefCentroid(terrain.stream(), terrain.minHeight, VERTICAL_EXAGGERATION);
    camera.frame(focus[0], focus[1], focus[2], Math.hypot(loaded.extentX, loaded.extentZ));
    current?.terrain.destroy();
    current = loaded;
    renderer.invalidate();
    renderer.setShading(loaded.low, loaded.high, loaded.extentX, loaded.extentZ);
    state.terrain = { name: field.source, width: terrain.width, height: terrain.height,
      minHeight: terrain.minHeight, maxHeight: terrain.maxHeight };
    const spacing = field.spacingFromFile ? '' : ' (assumed: the file has none)';
    hud.textContent = [
      `${field.source}  ${terrain.width} × ${terrain.height} ${field.sampleType}`,
      `spacing ${field.spacingX.toFixed(1)} × ${field.spacingY.toFixed(1)} m${spacing}`,
      `heights ${terrain.minHeight.toFixed(0)} … ${terrain.maxHeight.toFixed(0)} m, loaded in ${loaded.loadMs.toFixed(0)} ms`,
      `τ ${TAU_PX} px, budget ${FRAME_BUDGET_MS} ms/frame, vertical ×${VERTICAL_EXAGGERATION}`,
      'L: colour by level   O: hexagon outlines',
    ].join('\n');
    hud.appendChild(lodLine);
    requestRender();
  }

  // Drop, file picker, ?src=, progress, RAW size dialog and error display (file_intake.js).
  const intake = createFileIntake({ core, state, show, showStatus });

  // For headless tests and benchmarks: drive the camera, ask for frames, read GL errors.
  Object.assign(state, { camera, requestRender, glError: () => gl.getError() });
  // For benchmarks: the same mesh drawn with the other index layout ('fans' | 'triangles').
  state.setLayout = (layout) => {
    view.layout = layout;
    current?.terrain.setStreamLayout(layout);
    requestRender();
  };
  attachOrbitControls(canvas, camera, requestRender);
  window.addEventListener('keydown', (e) => {
    if (e.key === 'l' || e.key === 'L') view.colorByLevel = !view.colorByLevel;
    else if (e.key === 'o' || e.key === 'O') view.outline = !view.outline;
    else return;
    requestRender();
  });
  window.addEventListener('resize', requestRender);

  // ?src=URL opens that file instead of the default terrain (which still loads if it fails).
  const src = new URLSearchParams(location.search).get('src');
  if (!(src && await intake.openUrl(src))) {
    const error = state.error;
    await intake.open(await fetchFiles(DEFAULT_TERRAIN));
    if (error) { state.error = error; showStatus(error, true); }
  }
  if (!current) throw new Error(`the default terrain did not load: ${state.error}`);
  state.status = 'ready';
}

main().catch((error) => {
  state.status = 'error';
  state.error = error.message;
  showStatus(error.message, true);
  console.error(error);
});
