// The frame pipeline: camera → core frame (paper §6: one budgeted refinement step, then the
// fan stream of §7) → upload → draw, once per requested animation frame. Everything it hands
// on from frame to frame lives in objects made once here, so a frame makes no garbage of its
// own (the figures the HUD and tests read are updated in place).
import { MORPH_FRAMES } from './settings_table.js';
import { FRAME } from '../core/core.js';
import { FLAT_EARTH } from '../geo/index.js';
import { lodCameraOnEarth, placeOnEarth } from '../cameras/on_the_earth.js';

const FRAME_LOG = 4096; // frames kept in state.frameLog while recording
const SETTLE_FRAMES = 3; // frames after tiles went in before a streamed view can be at rest
const TILE_WAIT_MS = 20; // a flight's frame looks again this often for the web map tiles it waits for
const HEIGHTS_REFRESH_MS = 2000; // while tiles keep coming, what reads heights is told this often at most
// The FrameStats figures copied into state.lod and state.mesh (plain objects a test can read).
const LOD_FIGURES = ['frame', 'pendingMerges', 'converged', 'splits', 'merges', 'updateMs', 'tau'];
const MESH_FIGURES = ['triangles', 'cells', 'vertices', 'maxLevel'];

export class FramePipeline {
  /**
   * @param {object} parts  gl, canvas, renderer, rig (the cameras), settings, view (what the
   *   renderer draws), hud, state (the published figures), det (the deterministic mode or null),
   *   urlWriter, layers (layers.js: the terrain drawn, { terrain, field, loadMs, world, tiles,
   *   streamVersion, blendsEnd }, and the sources the address bar names), onHeightsChanged() (a
   *   tiled terrain's heights changed: tiles went in), onFrame() (a frame was drawn)
   */
  constructor({ gl, canvas, renderer, rig, settings, view, hud, state, det, urlWriter, layers, onHeightsChanged, onFrame = null }) {
    Object.assign(this, { gl, canvas, renderer, rig, settings, view, hud, state, det, urlWriter, layers, onHeightsChanged, onFrame });
    this.stopped = false; // the viewer was disposed: no frame is asked for again
    this.contextLost = false;
    this.frameRequested = false;
    this.lastFrameTime = 0;
    this.lastFrameMs = 0; // CPU time of the previous frame, for the HUD
    this.timingPixel = new Uint8Array(4);
    // Made once, filled every frame.
    this.flightLodCamera = { eye: [0, 0, 0], target: [0, 0, 0], up: [0, 1, 0] };
    this.lodCamera = { eye: null, target: null, up: null, fovY: 0, aspect: 1, viewportHeight: 1, near: 0, far: 0 };
    this.timingFigures = { updateMs: 0, streamMs: 0, uploadMs: 0, drawMs: 0, frameMs: 0 };
    this.hudFrame = { terrain: null, stats: null, timing: this.timingFigures, settings, camera: null, tiles: null };
    // A tiled terrain's figures as tests read them (state.tiles), filled in place.
    this.tileFigures = { waiting: 0, settled: false, bytesFetched: 0, fileBytes: 0, heldBytes: 0, capBytes: 0, tilesEvicted: 0, tilesIn: 0, failures: [] };
    this.framesSinceTiles = 0; // frames since tiles last went into the core
    // onHeightsChanged runs once a wait for tiles is over, and at most every HEIGHTS_REFRESH_MS
    // while tiles keep coming.
    this.heightsChangedAt = 0; // when onHeightsChanged last ran
    this.heightsPending = false; // tiles went in since
    // What the HUD last showed of the stream (awaiting, and the failures list, replaced when
    // new ones come): a change is shown at once.
    this.shownAwaiting = false;
    this.shownFailures = null;
    this.eye = [0, 0, 0];
    // What tests read (state.lod, state.mesh): plain objects, filled in place.
    this.lodFigures = { frame: 0, pendingMerges: 0, converged: false, splits: 0, merges: 0, updateMs: 0, tau: 0 };
    this.meshFigures = { triangles: 0, cells: 0, vertices: 0, maxLevel: 0, bytes: 0 };
    this.render = this.render.bind(this);
    this.requestLater = () => this.request(); // the frame again a little later: a flight's frame waiting for its tiles
  }

  /** No frame is drawn any more: the viewer is disposed. */
  stop() {
    this.stopped = true;
  }

  /** While the graphics context is lost, frames draw nothing (web/app/context_loss.js). */
  setContextLost(lost) {
    this.contextLost = lost;
  }

  /** Asks for a frame (at most one is pending). */
  request() {
    if (this.frameRequested || this.stopped) return;
    this.frameRequested = true;
    requestAnimationFrame(this.render);
  }

  /** One frame at `now` (ms, from requestAnimationFrame). */
  render(now) {
    this.frameRequested = false;
    if (this.contextLost || this.stopped) return;
    const { det, canvas, rig, state } = this;
    if (det && !det.beginFrame()) return; // deterministic: only the frames asked for
    const frameStart = performance.now();
    const seconds = now - this.lastFrameTime < 200 ? (now - this.lastFrameTime) / 1000 : 1 / 60;
    this.lastFrameTime = now;
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
    placeOnEarth(camera, this.layers.ground?.earth ?? FLAT_EARTH);
    const timing = this.timingFigures;
    timing.updateMs = timing.streamMs = timing.uploadMs = 0;
    // Web map tile layers choose the tiles this view needs (cheap while it stays the same). A
    // flight's frame waits until they are all there: its pixels must not depend on the network.
    const images = this.layers.images;
    let waiting = false;
    for (let k = 0; k < images.length; k++) {
      if (!images[k].visible || !images[k].update) continue;
      images[k].update(camera, width, height);
      if (det && !images[k].settled) waiting = true;
    }
    if (waiting) {
      setTimeout(this.requestLater, TILE_WAIT_MS);
      return;
    }
    const shown = this.layers.ground;
    if (shown) this.updateTerrain(shown, camera, width, height, now);
    const drawStart = performance.now();
    this.renderer.draw(camera, width, height, this.view, this.layers);
    if (this.settings.timing) this.gl.readPixels(0, 0, 1, 1, this.gl.RGBA, this.gl.UNSIGNED_BYTE, this.timingPixel); // waits for the draw
    timing.drawMs = performance.now() - drawStart;
    this.lastFrameMs = timing.frameMs = performance.now() - frameStart;
    if (state.recordFrames && state.frameLog.length < FRAME_LOG) { // tests and benchmarks only
      state.frameLog.push({ time: now, lodMs: timing.updateMs, streamMs: timing.streamMs, uploadMs: timing.uploadMs,
        drawMs: timing.drawMs, cpuMs: performance.now() - frameStart });
    }
    state.frames += 1;
    if (det) det.endFrame();
    if (this.onFrame && shown) this.onFrame(); // frames of a terrain, not the sky before the first one
    if (moving) this.request();
    if (shown && !det) this.urlWriter.write(this.settings, camera, this.layers.source, this.layers.layerUrls, this.layers.overlayUrls);
  }

  // The core's part of a frame for the terrain `current` and its upload (the frame figures go to the HUD and state).
  updateTerrain(current, camera, width, height, now) {
    const { det, settings, view, renderer, state } = this;
    const { terrain } = current;
    // The stream keeps the mesh's normals only while they are drawn (32 bytes a vertex saved).
    const noNormals = !renderer.usesMeshNormals(view);
    if (terrain.settings.noNormals !== noNormals) terrain.configure({ noNormals });
    state.streamNormals = !noNormals;
    // §6: one budgeted refinement step for the current camera, then the fans (§7), in one core
    // call. Frozen: the mesh stays as it is while the camera moves (to look at it from outside).
    const frozen = settings.freeze;
    const lodStart = performance.now();
    const stats = frozen ? terrain.frame(null, FRAME.stream)
      : terrain.frame(det ? this.drawnFlightCamera(det.lodCamera) : this.lodCameraOf(camera, height), FRAME.all);
    const coreMs = performance.now() - lodStart;
    if (det && !frozen) det.afterLod(terrain, stats.operations);
    current.world.version += 1; // the drawn surface may have moved: the walk floor is asked anew
    if (camera.mode === 'walk') {
      camera.settle(); // stand on the surface as it is drawn in this frame
      camera.update(width / height);
      placeOnEarth(camera, current.earth ?? FLAT_EARTH);
    }
    const uploadStart = performance.now();
    if (stats.version !== current.streamVersion) current.blendsEnd = stats.frame + MORPH_FRAMES; // new blends run
    current.streamVersion = stats.version;
    state.uploadBytes = renderer.upload(terrain, stats, view.layout);
    state.streamBytes = renderer.streamBytes;
    if (view.colorByLevel || view.outline) renderer.setLevelView(terrain.levelView(view.outline));
    const timing = this.timingFigures;
    timing.updateMs = frozen ? 0 : stats.updateMs;
    timing.streamMs = Math.max(0, coreMs - timing.updateMs); // the core call's time beyond the update: the stream
    timing.uploadMs = performance.now() - uploadStart;
    timing.frameMs = this.lastFrameMs;
    view.frame = stats.frame;
    this.publish(stats);
    if (!frozen && (!stats.converged || stats.frame < current.blendsEnd)) this.request();
    const tiles = current.tiles ?? null;
    // After the frame's update: the tiles it wants are asked for, those that came go in. Frames
    // go on while tiles are awaited, so they show without input, and for SETTLE_FRAMES after
    // tiles went in: the next frame's stream step takes their heights, the one after refines on
    // them and may want finer tiles, so the wait is over only then.
    let awaiting = false;
    if (tiles) {
      const arrived = tiles.tick();
      this.framesSinceTiles = arrived > 0 ? 0 : this.framesSinceTiles + 1;
      awaiting = tiles.waiting > 0 || this.framesSinceTiles < SETTLE_FRAMES;
      if (awaiting) this.request();
      if (arrived > 0) this.heightsPending = true;
      if (this.heightsPending && (!awaiting || now - this.heightsChangedAt > HEIGHTS_REFRESH_MS)) {
        this.heightsPending = false;
        this.heightsChangedAt = now;
        this.onHeightsChanged();
      }
    }
    const hud = this.hud, figures = this.hudFrame;
    figures.terrain = terrain;
    figures.stats = stats;
    figures.camera = camera;
    figures.tiles = tiles;
    figures.tilesAwaiting = awaiting;
    hud.tick(now);
    // Tiles awaited or not, and failures, show at once (the last frame of a wait is not throttled away).
    const failures = tiles ? tiles.failures : null;
    hud.update(figures, now, awaiting !== this.shownAwaiting || failures !== this.shownFailures);
    this.shownAwaiting = awaiting;
    this.shownFailures = failures;
    if (tiles) this.publishTiles(tiles, awaiting);
    state.hud = hud.values;
    const eye = this.eye;
    eye[0] = camera.position[0], eye[1] = camera.position[1], eye[2] = camera.position[2];
    state.eye = eye;
  }

  /** A new terrain is shown: until its first frame, nothing has converged and nothing is drawn. */
  forgetFigures() {
    this.framesSinceTiles = 0;
    this.lodFigures.converged = false;
    this.meshFigures.triangles = 0;
    this.state.converged = false;
    this.state.triangles = 0;
  }

  // The frame's figures as tests read them, in objects made once.
  publish(stats) {
    const { state } = this, lod = this.lodFigures, mesh = this.meshFigures;
    for (let k = 0; k < LOD_FIGURES.length; k++) lod[LOD_FIGURES[k]] = stats[LOD_FIGURES[k]];
    for (let k = 0; k < MESH_FIGURES.length; k++) mesh[MESH_FIGURES[k]] = stats[MESH_FIGURES[k]];
    mesh.bytes = stats.memoryBytes;
    state.triangles = mesh.triangles;
    state.mesh = mesh;
    state.converged = lod.converged;
    state.lod = lod;
    state.timing = this.timingFigures;
  }

  // A tiled terrain's figures as tests read them (state.tiles).
  publishTiles(tiles, awaiting) {
    const s = this.tileFigures;
    s.waiting = tiles.waiting;
    s.settled = !awaiting;
    s.bytesFetched = tiles.bytesFetched;
    s.fileBytes = tiles.fileBytes;
    s.heldBytes = tiles.heldBytes;
    s.capBytes = tiles.capBytes;
    s.tilesEvicted = tiles.tilesEvicted;
    s.tilesIn = tiles.tilesIn;
    s.failures = tiles.failures;
    this.state.tiles = s;
  }

  // A scripted flight's camera as the core takes it, placed on the Earth from the flight's own
  // doubles, as `hexlod regress` places it in Node (flight.js replayFlight).
  drawnFlightCamera(flight) {
    return lodCameraOnEarth(flight, this.layers.ground?.earth ?? FLAT_EARTH, this.flightLodCamera);
  }

  // The camera as the core takes it, in the object made once.
  lodCameraOf(camera, height) {
    const c = this.lodCamera;
    // Where the renderer draws from (on_the_earth.js: the drawn frame, the surface's up).
    c.eye = camera.drawnPosition;
    c.target = camera.drawnTarget;
    c.up = camera.drawnUp;
    c.fovY = camera.fovY;
    c.aspect = camera.aspect;
    c.viewportHeight = height;
    c.near = camera.near;
    c.far = camera.far;
    return c;
  }
}
