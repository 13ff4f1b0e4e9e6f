// The image layers in the panel: one folder a layer, top first as they lie on the terrain, each
// with its visibility, opacity, place in the order and removal; and a field that adds a web
// map tile layer from a template. Made again whenever the layers change (app/layers.js); it
// only asks the image stage (app/image_stage.js) to act.

/**
 * @param {import('lil-gui').GUI} folder the panel's image folder
 * @param {{ setVisible(id, visible): boolean, setOpacity(id, opacity): void, move(id, step): void, remove(id): void }} stage
 * @param {{ addTiles?: (text: string) => void }} [hooks] addTiles: web map tile layers from the field (a template, or a WMTS service's address)
 */
export function createLayerPanel(folder, stage, { addTiles } = {}) {
  if (addTiles) {
    const field = { tiles: '' };
    const controller = folder.add(field, 'tiles').name('add tiles (template or WMTS)');
    controller.onFinishChange((text) => {
      if (text.trim() === '') return;
      addTiles(text.trim());
      field.tiles = '';
      controller.updateDisplay();
    });
  }
  let rows = [];
  return {
    /** Lists the layers of `layers` (the page's layer list). */
    show(layers) {
      const focus = focusInRows(rows);
      for (const row of rows) row.destroy();
      rows = [...layers.images].reverse().map((layer) => {
        const row = folder.addFolder(`${layer.kind === 'tiles' ? 'tiles' : 'image'}: ${layer.name}`);
        const model = { visible: layer.visible, opacity: layer.opacity };
        const visible = row.add(model, 'visible').onChange((on) => {
          if (!stage.setVisible(layer.id, on)) {
            model.visible = layer.visible;
            visible.updateDisplay();
          }
        });
        row.add(model, 'opacity', 0, 1, 0.05).onChange((value) => stage.setOpacity(layer.id, value));
        row.add({ up: () => stage.move(layer.id, 1) }, 'up').name('move up');
        row.add({ down: () => stage.move(layer.id, -1) }, 'down').name('move down');
        row.add({ remove: () => stage.remove(layer.id) }, 'remove').name('remove layer');
        row.domElement.dataset.layerId = String(layer.id);
        return row;
      });
      if (focus) restoreFocus(rows, focus, folder);
    },
  };
}

const FOCUSABLE = 'input, button, select, [tabindex="0"]';

/** Where the keyboard's focus is among the rows, if it is: the layer's id, the row's place and the control's place in it. */
function focusInRows(rows) {
  const active = document.activeElement;
  const place = rows.findIndex((row) => row.domElement.contains(active));
  if (place < 0) return null;
  const row = rows[place].domElement;
  return { layerId: row.dataset.layerId, place, control: [...row.querySelectorAll(FOCUSABLE)].indexOf(active) };
}

/**
 * The rows are made anew on every change, so a person who moved, hid or removed a layer with the
 * keyboard would find the focus thrown back to the page's start: it goes back to the same control
 * of the same layer, or, when that layer is gone, to the row now in its place, or the folder.
 */
function restoreFocus(rows, focus, folder) {
  const same = rows.find((row) => row.domElement.dataset.layerId === focus.layerId);
  const row = same ?? rows[Math.min(focus.place, rows.length - 1)];
  const controls = row ? [...row.domElement.querySelectorAll(FOCUSABLE)] : [];
  const target = same ? controls[focus.control] : controls[0];
  (target ?? folder.domElement.querySelector(FOCUSABLE))?.focus();
}
