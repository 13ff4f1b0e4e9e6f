// The overlays' legend in the panel: one folder an overlay, top first as they are drawn, each
// with its colour, visibility, line width, how its lines are drawn (as the file says, on the
// ground, at their own altitude, with a curtain), its tracks' profile and flight, and removal.
// Made again whenever the overlays change (app/layers.js); it only asks the overlay stage
// (app/overlay_stage.js) and the page's hooks to act.

const ALTITUDES = { 'as the file says': 'file', 'on the ground': 'clamp', 'at its altitude': 'absolute' };

/**
 * @param {import('lil-gui').GUI} folder the panel's overlay folder
 * @param {object} stage app/overlay_stage.js
 * @param {{ profile: (layer: object) => void, flyAlong: (layer: object) => void }} hooks
 *   profile: the first line of the overlay in the measuring panel; flyAlong: the camera along it
 */
export function createOverlayPanel(folder, stage, { profile, flyAlong }) {
  let rows = [];
  const empty = folder.add({ note: 'drop a GPX, KML, KMZ or GeoJSON file' }, 'note').name('overlays').disable();
  return {
    /** Lists the overlays of `layers` (the page's layer list). */
    show(layers) {
      for (const row of rows) row.destroy();
      const files = layers.overlays.filter((layer) => layer.kind === 'overlay'); // not other kinds drawn over the terrain
      empty.show(files.length === 0);
      rows = [...files].reverse().map((layer) => {
        const row = folder.addFolder(`overlay: ${layer.name}`);
        const model = { visible: layer.visible, color: layer.color, width: layer.halfWidth * 2,
          altitude: layer.altitude, curtain: layer.curtain };
        row.add(model, 'visible').onChange((visible) => stage.setStyle(layer, { visible }));
        row.addColor(model, 'color').onChange((color) => stage.setStyle(layer, { color }));
        row.add(model, 'width', 1, 12, 0.5).name('width (px)').onFinishChange((width) => stage.setStyle(layer, { halfWidth: width / 2 }));
        const hasLines = layer.overlay.features.some((f) => f.kind !== 'point');
        if (hasLines) {
          row.add(model, 'altitude', ALTITUDES).name('lines').onChange((altitude) => stage.setAltitude(layer, { altitude }));
          row.add(model, 'curtain').name('curtain (lines aloft)').onChange((curtain) => stage.setAltitude(layer, { curtain }));
        }
        if (layer.overlay.features.some((f) => f.kind === 'line')) {
          row.add({ profile: () => profile(layer) }, 'profile').name('profile of its track');
          row.add({ fly: () => flyAlong(layer) }, 'fly').name('fly along');
        }
        row.add({ remove: () => stage.remove(layer) }, 'remove').name('remove overlay');
        row.domElement.dataset.overlayId = String(layer.id);
        row.domElement.style.setProperty('--overlay-color', layer.color);
        row.domElement.classList.add('overlay-row');
        return row;
      });
    },
  };
}
