// The page's own buttons fly the camera; a click on the ground says where it is.
import { createViewer } from 'hexlod';

const $ = (/** @type {string} */ id) => /** @type {HTMLElement} */ (document.getElementById(id));
const viewer = await createViewer($('terrain'), { ui: false });
const terrain = viewer.terrain;
if (!terrain) throw new Error('no terrain');
// Metres: x east from the first sample, y up, z south (rows).
const width = (terrain.width - 1) * terrain.spacingX, depth = (terrain.height - 1) * terrain.spacingY;
const centre = [width / 2, terrain.minHeight, depth / 2];
$('overview').onclick = () => viewer.camera.flyTo({ target: centre, position: [width / 2, terrain.maxHeight * 6, depth * 1.1] }, { seconds: 2 });
$('low').onclick = () => viewer.camera.flyTo({ target: centre, position: [width * 0.3, terrain.maxHeight * 2.5, depth * 0.7] }, { seconds: 3 });
$('reset').onclick = () => viewer.camera.reset();
viewer.on('pick', (pick) => {
  $('where').textContent = `${Math.round(pick.height)} m${pick.place ? ` at ${pick.place}` : ''}`;
});
Object.assign(window, { viewer }); // for the console
