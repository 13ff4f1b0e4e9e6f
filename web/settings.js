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
};

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
