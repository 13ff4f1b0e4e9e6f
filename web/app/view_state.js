// What the renderer draws, derived from the settings in one place: deriveView writes every
// field that follows from a setting (the exaggeration, the geomorph length, the shading), so no
// caller pushes a setting into the view by hand. The frame pipeline adds the blends' clock.
import { MORPH_FRAMES } from './settings_table.js';

/** The view object, made once; the renderer reads it every frame. */
export function createView(settings) {
  const view = { frame: 0, hideTerrain: false, terrainMask: false }; // the clock (frame_pipeline.js); tests hide the terrain or draw it alone
  return deriveView(settings, view);
}

/** Writes the view's settings-derived fields from `settings`, in place (no allocation). */
export function deriveView(settings, view) {
  view.colorByLevel = settings.colorByLevel;
  view.outline = settings.wireframe;
  view.morphFrames = settings.geomorph ? MORPH_FRAMES : 0;
  view.verticalScale = settings.exaggeration;
  view.layout = settings.layout;
  view.shading = settings.shading;
  view.imageOpacity = settings.imageOpacity;
  view.imageUnlit = settings.imageUnlit;
  view.normals = settings.normals;
  view.shadows = settings.shadows;
  view.occlusion = settings.occlusion;
  view.sunAzimuth = settings.sunAzimuth;
  view.sunElevation = settings.sunElevation;
  view.contours = settings.contours;
  view.contourInterval = settings.contourInterval;
  view.nodata = settings.nodata;
  return view;
}
