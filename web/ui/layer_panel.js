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
    },
  };
}
