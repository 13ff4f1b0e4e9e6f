// The viewer's settings: one table of ranges and defaults, shared by the control panel (its
// sliders) and the URL state (its validation), so the two never disagree.

/** Ranges of the numeric settings; `url` names the ones a shared link carries. */
export const RANGES = {
  tau: { min: 0.25, max: 16, step: 0.05, value: 1, label: 'error τ (px)', url: 'tau' },
  budgetMs: { min: 0.5, max: 50, step: 0.5, value: 4, label: 'frame budget (ms)', url: 'budget' },
  maxOperations: { min: 0, max: 20000, step: 10, value: 0, label: 'operations / frame (0: any)' },
  maxTriangles: { min: 0, max: 4000000, step: 1000, value: 0, label: 'triangle cap (0: none)' },
  exaggeration: { min: 0.1, max: 20, step: 0.1, value: 2, label: 'vertical exaggeration', url: 'exag' },
  eyeHeight: { min: 0.1, max: 2000, step: 0.1, value: 2, label: 'walk eye height (m)' },
  // The sun (issue 14): compass azimuth (0 north, 90 east) and elevation above the horizon.
  // Afternoon in the west-south-west by default: views from the south see lit faces, and the
  // light grazes ridges from the side, so relief reads at a glance.
  sunAzimuth: { min: 0, max: 360, step: 1, value: 250, label: 'sun azimuth (°)', url: 'sunaz' },
  sunElevation: { min: 0, max: 90, step: 0.5, value: 25, label: 'sun elevation (°)', url: 'sunel' },
  // Loads from a URL (?src=, issue 29): give up after this long without an answer or a new byte,
  // and refuse a body larger than this (by its Content-Length before it is read, and while it
  // streams). 60 s and 1 GiB as `hexlod regress` (bin/dem_source.js): the core holds a 16385²
  // 16-bit field (512 MB), and the page holds the file beside the core's copy of it.
  // `urlIfChanged`: in the address bar only when not the default.
  urlTimeout: { min: 1, max: 600, step: 1, value: 60, label: 'URL time limit (s)', url: 'timeout', urlIfChanged: true },
  urlMaxMB: { min: 1, max: 4096, step: 1, value: 1024, label: 'URL size cap (MB)', url: 'maxmb', urlIfChanged: true },
};

/** Shading modes of the terrain (web/render/renderer.js SHADING_MODES), the first the default. */
export const SHADING_MODES = ['natural', 'hypsometric', 'slope', 'hillshade', 'plain'];
/** Where per-pixel normals come from: the full-resolution field (default) or the mesh (paper §7). */
export const NORMAL_SOURCES = ['field', 'mesh'];

/** Frames a geomorph blend takes (paper §7) when geomorphing is on. */
export const MORPH_FRAMES = 8;

/** A fresh settings object with every default. */
export function defaultSettings() {
  const settings = Object.fromEntries(Object.entries(RANGES).map(([key, r]) => [key, r.value]));
  return Object.assign(settings, {
    autoTau: false,
    wireframe: false,   // the hexagon outlines
    colorByLevel: false,
    freeze: false,      // keep the mesh while the camera moves
    geomorph: true,
    culling: true,      // frustum culling
    backfaceCulling: true,
    embedding: 'exact',
    cellSize: 0,        // metres between samples; 0 until a terrain is loaded
    shading: SHADING_MODES[0],
    normals: NORMAL_SOURCES[0],
    shadows: true,      // the sun's terrain shadows
    occlusion: true,    // ambient occlusion of the sky light
  });
}

/**
 * Checks a numeric setting against its range: the number, or an Error saying what is allowed.
 * @param {keyof RANGES} key
 */
export function checkSetting(key, value) {
  const r = RANGES[key];
  const number = typeof value === 'number' ? value : Number(value);
  if (value === '' || !Number.isFinite(number) || number < r.min || number > r.max) {
    return new Error(`${r.url ?? key}=${value} is not a number from ${r.min} to ${r.max}`);
  }
  return number;
}

/** Gives the terrain's refiner every LOD setting (on load, and after a mesh rebuild). */
export function applyLodSettings(terrain, settings) {
  terrain.setLodVerticalScale(settings.exaggeration);
  terrain.setLodTolerance(settings.tau);
  terrain.setLodBudget(settings.budgetMs, settings.maxOperations);
  terrain.setLodLimits(settings.maxTriangles, settings.autoTau);
  terrain.setLodCulling(settings.culling);
  terrain.setLodBackfaceCulling(settings.backfaceCulling);
  terrain.setMorphFrames(settings.geomorph ? MORPH_FRAMES : 0);
}
