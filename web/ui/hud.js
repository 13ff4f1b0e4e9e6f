// The heads-up display: what the terrain is, how fast the frames go, what the LOD did, and
// what lies under the pointer. Redrawn a few times a second, not every frame: the mesh
// census and the achieved error are passes over the cells.
import { FRAME } from '../core/core.js';

const REFRESH_MS = 250;
// The census (cell kinds and the achieved screen error) is a pass over every cell in view
// (about 9 ms on 270k triangles in WASM): once a second keeps it from showing up as a hitch.
const CENSUS_REFRESH_MS = 1000;
const FPS_WINDOW = 30; // frames averaged for fps

const number = (n) => Math.round(n).toLocaleString('en');
const MB = 2 ** 20;
const megabytes = (bytes) => (bytes >= 10 * MB ? (bytes / MB).toFixed(0) : (bytes / MB).toFixed(1));
const metres = (m) => (Math.abs(m) >= 10000 ? `${(m / 1000).toFixed(2)} km` : `${m.toFixed(1)} m`);

export class Hud {
  /**
   * @param {HTMLElement} element
   * @param {boolean} collapsed start as one summary line (the full figures behind the toggle, or I)
   */
  constructor(element, collapsed) {
    this.element = element;
    this.toggleButton = document.createElement('button');
    this.toggleButton.type = 'button';
    this.toggleButton.className = 'hud-toggle';
    this.toggleButton.onclick = () => this.setCollapsed(!this.collapsed);
    this.summary = document.createElement('div');
    this.info = document.createElement('div');
    this.figures = document.createElement('div');
    this.layerLines = document.createElement('div'); // the layers over the terrain
    this.cursor = document.createElement('div');
    this.tiles = document.createElement('div'); // a streamed terrain's tiles: shown folded or not
    this.tiles.className = 'hud-tiles';
    this.tiles.hidden = true;
    this.summary.className = 'hud-summary';
    this.info.className = this.figures.className = 'hud-more';
    this.layerLines.className = 'hud-image';
    this.layerLines.hidden = true;
    element.append(this.toggleButton, this.summary, this.tiles, this.info, this.layerLines, this.figures, this.cursor);
    this.setCollapsed(collapsed);
    // rAF timestamps of the last FPS_WINDOW frames, a ring made once (tick runs every frame).
    this.frameTimes = new Float64Array(FPS_WINDOW);
    this.frameCount = 0; // frames ticked in all; the newest is at (frameCount - 1) % FPS_WINDOW
    this.lastRefresh = -Infinity;
    this.lastCensus = -Infinity;
    this.errorPx = -1;
    this.kinds = { full: 0, semi: 0, boundarySemi: 0 };
    this.values = null;   // the figures last shown, for tests (window.hexlod.hud)
  }

  /** Folds the HUD to one summary line, or unfolds every figure. */
  setCollapsed(collapsed) {
    this.collapsed = collapsed;
    this.element.classList.toggle('collapsed', collapsed);
    this.toggleButton.textContent = collapsed ? '▸' : '▾';
    this.toggleButton.title = collapsed ? 'show every figure (I)' : 'fold to one line (I)';
    this.toggleButton.setAttribute('aria-expanded', String(!collapsed));
  }

  /**
   * Describes what the layer list (app/layers.js) shows, after `part` of it changed: the terrain
   * ('terrain': a new one, or its scale), or the layers over it ('images', 'overlays').
   */
  showLayers(layers, part) {
    if (part === 'terrain' && layers.ground) {
      const { field, terrain, loadMs } = layers.ground;
      this.setTerrain(field, terrain, loadMs);
    }
    if (part !== 'terrain') {
      // One line a layer over the terrain, bottom first, as its stage describes it.
      const lines = [...layers.images, ...layers.overlays].map((layer) => layer.description);
      this.layerLines.hidden = lines.length === 0;
      this.layerLines.textContent = lines.join('\n');
    }
  }

  /** The terrain's description, once per load and when its scale changes. */
  setTerrain(field, terrain, loadMs) {
    this.lastErrorRefresh = -Infinity; // the error of the old terrain means nothing now
    const spacing = field.spacingFromFile ? '' : ' (assumed: the file has none)';
    this.terrainName = field.source;
    this.tiles.hidden = !field.tiled;
    this.tiles.textContent = '';
    this.info.textContent = [
      `${field.source}  ${terrain.width} × ${terrain.height} ${field.sampleType}` +
        (field.cropped ? ` (the data of a sparse ${field.cropped.width} × ${field.cropped.height})` : '') +
        (field.tiled ? `, streamed: ${field.levels} levels of ${field.tileWidth} × ${field.tileHeight} tiles` +
          `${field.fileBytes ? ` in ${megabytes(field.fileBytes)} MB` : ''}` : ''),
      `spacing ${terrain.spacingX.toFixed(1)} × ${terrain.spacingY.toFixed(1)} m${spacing}, ` +
        `heights ${terrain.minHeight.toFixed(0)} … ${terrain.maxHeight.toFixed(0)} m${field.tiled ? ' (so far)' : ''}, ` +
        `${field.tiled ? 'opened' : 'loaded'} in ${loadMs.toFixed(0)} ms`,
    ].join('\n');
  }

  /** A frame was drawn at rAF time `now` (ms). */
  tick(now) {
    this.frameTimes[this.frameCount % FPS_WINDOW] = now;
    this.frameCount += 1;
  }

  /**
   * Shows the figures of the frame just drawn (at most every REFRESH_MS, unless `force`).
   * @param {{terrain: object, stats: import('../core/core.js').FrameStats, timing: object, settings: object,
   *   camera: object, tiles: import('../tiles/tiled_terrain.js').TiledTerrain|null, tilesAwaiting: boolean}} f
   *   tiles: a tiled terrain's, whose figures are shown; tilesAwaiting: tiles are awaited or
   *   just went in, so the error is provisional
   */
  update(f, now, force = false) {
    if (!force && now - this.lastRefresh < REFRESH_MS) return;
    this.lastRefresh = now;
    const { terrain, timing, settings, camera } = f;
    const { updateMs, triangles, vertices, splits, merges, tau, converged, memoryBytes } = f.stats;
    if (force || now - this.lastCensus >= CENSUS_REFRESH_MS) {
      const census = terrain.query(FRAME.census); // the terrain's one figures object: read what it says now
      this.kinds.full = census.fullHexagons;
      this.kinds.semi = census.semiHexagons;
      this.kinds.boundarySemi = census.boundarySemiHexagons;
      this.errorPx = census.achievedErrorPx;
      this.lastCensus = now;
    }
    const kinds = this.kinds;
    const error = this.errorPx;
    const kept = Math.min(this.frameCount, FPS_WINDOW), times = this.frameTimes;
    const newest = times[(this.frameCount - 1) % FPS_WINDOW], oldest = times[(this.frameCount - kept) % FPS_WINDOW];
    const span = kept > 1 ? newest - oldest : 0;
    const fps = span > 0 && now - newest < 1000 ? ((kept - 1) * 1000) / span : 0;
    const tiles = f.tiles ?? null;
    // A tiled terrain holds only the tiles in, not width x height samples.
    const fieldBytes = tiles ? tiles.heldBytes : terrain.sampleBytes;
    const meshBytes = memoryBytes, coreBytes = meshBytes + fieldBytes;
    // Measured against the samples in so far: finer tiles still to come may show more error.
    const provisional = tiles !== null && f.tilesAwaiting === true;
    const errorText = error < 0 ? 'n/a' : `${error.toFixed(2)} px${provisional ? ' (provisional)' : ''}`;
    this.values = { fps, frameMs: timing.frameMs ?? 0, updateMs, triangles,
      full: kinds.full, semi: kinds.semi, boundarySemi: kinds.boundarySemi, vertices,
      splits, merges, coreMB: coreBytes / 2 ** 20,
      bytesPerTriangle: triangles ? meshBytes / triangles : 0, screenErrorPx: error, tau, errorProvisional: provisional,
      tiles: tiles ? this.showTiles(tiles, provisional) : null };
    const v = this.values;
    this.figures.textContent = [
      `${camera.mode} camera   ${fps > 0 ? `${fps.toFixed(0)} fps` : 'idle'}   frame ${v.frameMs.toFixed(1)} ms   ` +
        `LOD ${v.updateMs.toFixed(1)} ms${settings.freeze ? ' (frozen)' : converged ? '' : ', refining…'}`,
      `${number(v.triangles)} triangles   hexagons: ${number(v.full)} full, ${number(v.semi + v.boundarySemi)} semi ` +
        `(${number(v.boundarySemi)} on the boundary)   ${number(v.vertices)} vertices`,
      `last frame: ${number(v.splits)} splits, ${number(v.merges)} merges`,
      `core ${v.coreMB.toFixed(1)} MB (${tiles ? 'tiles' : 'field'} ${(fieldBytes / MB).toFixed(1)} MB), ` +
        `mesh ${v.bytesPerTriangle.toFixed(0)} B/triangle`,
      `screen error ${errorText} (τ ${v.tau.toFixed(2)} px)   ×${settings.exaggeration} vertical`,
    ].join('\n');
    this.summary.textContent = `${this.terrainName ?? ''}   ${fps > 0 ? `${fps.toFixed(0)} fps` : 'idle'}   ` +
      `${number(v.triangles)} triangles   error ${errorText}`;
  }

  /** The tiles' line: tiles awaited and bytes fetched, and the last failures; returns it. */
  showTiles(tiles, awaiting) {
    const { waiting, bytesFetched, fileBytes, failures } = tiles;
    const fetched = `${megabytes(bytesFetched)}${fileBytes ? ` of ${megabytes(fileBytes)}` : ''} MB fetched`;
    let text = waiting > 0 ? `waiting for ${number(waiting)} tile${waiting === 1 ? '' : 's'} · ${fetched}`
      : awaiting ? `taking in tiles · ${fetched}` : `${failures.length ? 'no tiles awaited' : 'all tiles in view loaded'} · ${fetched}`;
    if (failures.length > 0) {
      const first = failures[0];
      text += ` · ${failures.length} tile${failures.length === 1 ? '' : 's'} failed (${first.kind}): ${first.message}`;
    }
    this.tiles.textContent = text;
    this.tiles.classList.toggle('error', failures.length > 0);
    return text;
  }

  /**
   * The cursor readout: a picked ground point (picking.js) or null; its `place` (the real
   * coordinates, or 'local metres (no CRS)') goes on a line of its own.
   */
  setCursor(pick) {
    this.cursor.textContent = pick
      ? `cursor  x ${metres(pick.x)}  z ${metres(pick.z)}  height ${pick.height.toFixed(1)} m  slope ${pick.slopeDeg.toFixed(1)}°` +
        (pick.place ? `\n        ${pick.place}` : '')
      : 'cursor  —';
  }
}
