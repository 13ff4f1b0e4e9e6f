// The viewer's settings in one table: each one's default, range or choices, URL key, place in
// the panel and effect. The panel (web/ui/controls_panel.js), the URL state (url_state.js), the
// settings owner (settings_owner.js) and the page's wiring (main.js) read it; none keeps a list
// of its own. tests/node/settings_table.test.js checks the core's defaults against it.
//
// effect: what applying a new value touches (main.js has one handler per effect):
//   core      the terrain's core settings (one configure() call, coreSettings below)
//   heights   the vertical exaggeration: the core, the cameras' heights and the world
//   camera    the cameras only
//   view      what the renderer draws (deriveView in view_state.js); no core call
//   mesh      the hexagon mesh is rebuilt (embedding)
//   ground    the field's spacing: the scale, the mesh and the cameras' ground positions
//   tiles     the tiled terrain's tile cache (its cap in bytes)
//   earth     the surface the terrain is drawn on: the core, the renderer and the cameras
//   nodata    how no-data is drawn: the view, and how a tiled terrain fills its voids
//   none      read where it is used (the freeze switch, limits of the next URL load)
// core: the setting's hexlod_settings field (Terrain.configure's camelCase name) and how the
// value maps to it. parse: a typed value's reader (throws why it is refused). coreDiffers: why
// the page's default is not the core's (a test holds both the equal and the differing ones to
// what the table says).

import { parseContourInterval } from '../measure/contour_levels.js';

/** Shading modes of the terrain (web/render/renderer.js SHADING_MODES), the first the default. */
export const SHADING_MODES = ['natural', 'hypsometric', 'slope', 'hillshade', 'plain'];
/** Where per-pixel normals come from: the full-resolution field (default) or the mesh (paper §7). */
export const NORMAL_SOURCES = ['field', 'mesh'];
/** Index layouts: an indexed TRIANGLES list (drew in 0.68x the time of TRIANGLE_FAN with
 * primitive restart on the same mesh, and ANGLE on Direct3D 11 and Metal converts fans to lists;
 * see BENCHMARKS.md), or the paper's fans. */
export const LAYOUTS = ['triangles', 'fans'];
/** What a georeferenced terrain is drawn on, the first the default. */
export const EARTH_SHAPES = ['curved', 'flat'];
/** What no-data samples become, the first the default: filled from the samples around them
 * (web/loaders/nodata.js), or holes through which the plain ground beyond shows. */
export const NODATA_MODES = ['filled', 'holes'];
/** Frames a geomorph blend takes (paper §7) when geomorphing is on. */
export const MORPH_FRAMES = 8;

const LOD = 'Level of detail', MORE = 'Level of detail/budgets and culling', VIEW = 'View', SHADING = 'Shading';
const MESH = 'Mesh', URLS = 'Loading from a URL';
export const IMAGE_FOLDER = 'Image layers';
const IMAGE = IMAGE_FOLDER;

export const SETTINGS = {
  tau: { default: 1, min: 0.25, max: 16, step: 0.05, url: 'tau', panel: [LOD, 'error τ (px)'], effect: 'core',
    core: ['tauPx', (v) => v] },
  budgetMs: { default: 4, min: 0.5, max: 50, step: 0.5, url: 'budget', panel: [LOD, 'frame budget (ms)'], effect: 'core',
    core: ['budgetMs', (v) => v], coreDiffers: 'the core has no time limit; the page keeps frames smooth' },
  freeze: { default: false, panel: [LOD, 'freeze LOD (F)'], effect: 'none' }, // keep the mesh while the camera moves
  maxOperations: { default: 0, min: 0, max: 20000, step: 10, panel: [MORE, 'operations / frame (0: any)'], effect: 'core',
    core: ['maxOperations', (v) => v] },
  maxTriangles: { default: 0, min: 0, max: 4000000, step: 1000, panel: [MORE, 'triangle cap (0: none)'], effect: 'core',
    core: ['maxTriangles', (v) => v] },
  autoTau: { default: false, panel: [MORE, 'auto τ (keeps the cap and budget)'], effect: 'core', core: ['autoTau', (v) => v] },
  geomorph: { default: true, panel: [MORE, 'geomorphing'], effect: 'core', core: ['morphFrames', (v) => (v ? MORPH_FRAMES : 0)],
    coreDiffers: 'the core does not blend unless asked; the page hides popping' },
  culling: { default: true, panel: [MORE, 'frustum culling'], effect: 'core', core: ['noFrustumCulling', (v) => !v] },
  backfaceCulling: { default: true, panel: [MORE, 'back-face culling'], effect: 'core', core: ['noBackfaceCulling', (v) => !v] },

  exaggeration: { default: 2, min: 0.1, max: 20, step: 0.1, url: 'exag', panel: [VIEW, 'vertical exaggeration'], effect: 'heights',
    core: ['verticalScale', (v) => v], coreDiffers: 'the core draws true heights; relief reads better at twice its height' },
  wireframe: { default: false, panel: [VIEW, 'wireframe: hexagons (O)'], effect: 'view' }, // the hexagon outlines
  colorByLevel: { default: false, panel: [VIEW, 'colour by level (L)'], effect: 'view' },
  // A georeferenced terrain is drawn on the curved Earth (web/geo/earth_shape.js); flat for
  // comparison. A terrain without a georeference is flat either way.
  earth: { default: EARTH_SHAPES[0], choices: EARTH_SHAPES, url: 'earth', urlIfChanged: true, panel: [VIEW, 'Earth'],
    effect: 'earth' },
  nodata: { default: NODATA_MODES[0], choices: NODATA_MODES, url: 'nodata', urlIfChanged: true, panel: [VIEW, 'no-data'],
    effect: 'nodata' },
  eyeHeight: { default: 2, min: 0.1, max: 2000, step: 0.1, panel: [VIEW, 'walk eye height (m)'], effect: 'camera' },

  shading: { default: SHADING_MODES[0], choices: SHADING_MODES, url: 'shading', urlIfChanged: true, panel: [SHADING, 'mode'],
    effect: 'view' },
  // The sun: compass azimuth (0 north, 90 east) and elevation above the horizon. Afternoon in
  // the west-south-west by default: views from the south see lit faces, and the light grazes
  // ridges from the side, so relief reads at a glance.
  sunAzimuth: { default: 250, min: 0, max: 360, step: 1, url: 'sunaz', panel: [SHADING, 'sun azimuth (°)'], effect: 'view' },
  sunElevation: { default: 25, min: 0, max: 90, step: 0.5, url: 'sunel', panel: [SHADING, 'sun elevation (°)'], effect: 'view' },
  shadows: { default: true, panel: [SHADING, 'sun shadows'], effect: 'view' },
  occlusion: { default: true, panel: [SHADING, 'ambient occlusion'], effect: 'view' }, // of the sky light
  normals: { default: NORMAL_SOURCES[0], choices: NORMAL_SOURCES, panel: [SHADING, 'normals'], effect: 'view' },

  // The draped image (web/imagery/): how much of it covers the ground colour or analysis mode,
  // and whether it is shown as it is (orthophotos carry their own shadows) or lit by the sun.
  imageOpacity: { default: 1, min: 0, max: 1, step: 0.05, url: 'imgop', urlIfChanged: true, panel: [IMAGE, 'opacity'], effect: 'view' },
  imageUnlit: { default: false, panel: [IMAGE, 'unlit (its own shadows)'], effect: 'view' },

  // Contour lines of the full-resolution field (web/render/contours/): every 5th thicker and
  // labelled; the interval in metres or 'auto' (web/measure/contour_levels.js). Under View: a
  // folder of their own made the open panel taller over the terrain of the opening view.
  contours: { default: false, url: 'contours', urlIfChanged: true, panel: [VIEW, 'contour lines'], effect: 'view' },
  contourInterval: { default: 'auto', parse: parseContourInterval, url: 'cint', urlIfChanged: true,
    panel: [VIEW, 'contour interval (m or auto)'], effect: 'view' },

  embedding: { default: 'exact', choices: ['exact', 'shifted'], panel: [MESH, 'embedding'], effect: 'mesh' },
  // Metres between samples; 0 until a terrain is loaded, then its slider spans around it.
  cellSize: { default: 0, positive: true, panel: [MESH, 'cell size (m)'], effect: 'ground' },
  // Not in the panel: ?layout=fans, for benchmarks of the paper's layout. In the address bar
  // only when not the default.
  layout: { default: LAYOUTS[0], choices: LAYOUTS, url: 'layout', urlIfChanged: true, effect: 'core',
    core: ['layout', (v) => v], coreDiffers: 'the core writes the paper\'s fans; lists draw faster here' },

  // Loads from a URL (?src=): give up after this long without an answer or a new byte, and
  // refuse a body larger than this (by its Content-Length before it is read, and while it
  // streams). 60 s and 1 GiB as `hexlod regress` (lib/dem_source.js): the core holds a 16385²
  // 16-bit field (512 MB), and the page holds the file beside the core's copy of it.
  urlTimeout: { default: 60, min: 1, max: 600, step: 1, url: 'timeout', urlIfChanged: true, panel: [URLS, 'URL time limit (s)'],
    effect: 'none' },
  urlMaxMB: { default: 1024, min: 1, max: 4096, step: 1, url: 'maxmb', urlIfChanged: true, panel: [URLS, 'URL size cap (MB)'],
    effect: 'none' },

  // A tiled COG (web/tiles/): the tiles' samples held at most, MB; the least recently drawn
  // go first. Also the size up to which a TIFF that cannot stream is loaded whole instead.
  tileCacheMB: { default: 512, min: 1, max: 4096, step: 1, url: 'tilecache', urlIfChanged: true, panel: [URLS, 'tile cache (MB)'],
    effect: 'tiles' },

  // Not in the panel, for tests and benchmarks. ?timing=1 waits for the GPU after drawing (a
  // one-pixel readPixels: gl.finish does not wait in Chromium) so that frame figures include it;
  // it stalls the pipeline. ?normaltile=N and ?imagetile=N make texture tiles of at most N
  // texels a side, to test the tiling on any GPU (0: the GPU's limit).
  timing: { default: false, url: 'timing', urlIfChanged: true, effect: 'none' },
  normalTile: { default: 0, parse: tileSide('normaltile', 16), url: 'normaltile', urlIfChanged: true, effect: 'none' },
  imageTile: { default: 0, parse: tileSide('imagetile', 64), url: 'imagetile', urlIfChanged: true, effect: 'none' },
};

/** A reader of a forced texture tile side: 0 (none) or a whole number of texels from `least`. */
function tileSide(urlKey, least) {
  return (value) => {
    const n = Number(value);
    if (value === '' || !Number.isInteger(n) || (n !== 0 && (n < least || n > 16384))) {
      throw new Error(`${urlKey}=${value} is not 0 or a whole number of texels from ${least} to 16384`);
    }
    return n;
  };
}

/** A fresh settings object with every default. */
export function defaultSettings() {
  const settings = {};
  for (const key of Object.keys(SETTINGS)) settings[key] = SETTINGS[key].default;
  return settings;
}

/**
 * The value to use for a setting, or an Error saying what is allowed: numbers within their
 * range (strings from a URL are read as numbers), choices from their list, switches on or off.
 */
export function checkSetting(key, value) {
  const s = SETTINGS[key];
  if (!s) return new Error(`there is no setting ${key}`);
  if (s.parse) {
    try {
      return s.parse(value);
    } catch (error) {
      return error;
    }
  }
  if (s.choices) return s.choices.includes(value) ? value : new Error(`${s.url ?? key} must be one of ${s.choices.join(', ')}, not ${value}`);
  if (typeof s.default === 'boolean') {
    if (typeof value === 'boolean') return value;
    // From the URL: ?contours=1 (or true; 0 or false).
    if (s.url && ['1', 'true'].includes(value)) return true;
    if (s.url && ['0', 'false'].includes(value)) return false;
    return new Error(s.url ? `${s.url} is on or off (1 or 0), not ${value}` : `${key} is on or off, not ${value}`);
  }
  if (s.positive) {
    return Number.isFinite(value) && value > 0 ? value : new Error(`the cell size must be a positive number of metres, not ${value}`);
  }
  const number = typeof value === 'number' ? value : Number(value);
  if (value === '' || !Number.isFinite(number) || number < s.min || number > s.max) {
    return new Error(`${s.url ?? key}=${value} is not a number from ${s.min} to ${s.max}`);
  }
  return number;
}

/** The settings with a URL key, as [setting, URL key] pairs. */
export const URL_KEYS = Object.keys(SETTINGS).filter((key) => SETTINGS[key].url).map((key) => [key, SETTINGS[key].url]);

/** The settings whose effect is `effect`. */
export const settingsOf = (effect) => Object.keys(SETTINGS).filter((key) => SETTINGS[key].effect === effect);

/**
 * Every core setting the page decides, as Terrain.configure takes them (one call): the table's
 * core fields, and tau mode (the page never uses the view-independent maximum error).
 */
export function coreSettings(settings) {
  const out = { maxErrorM: 0 };
  for (const key of Object.keys(SETTINGS)) {
    const core = SETTINGS[key].core;
    if (core) out[core[0]] = core[1](settings[key]);
  }
  return out;
}
