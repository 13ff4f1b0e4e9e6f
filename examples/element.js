// <hexlod-viewer>: attributes set what it shows, and changing one applies it live.
import 'hexlod/element';

const element = /** @type {import('hexlod/element').HexlodViewerElement} */ (document.getElementById('terrain'));
element.addEventListener('hexlod-loaded', (event) => {
  const { terrain } = /** @type {CustomEvent} */ (event).detail;
  console.log(`showing ${terrain.name}`);
});
const viewer = await element.ready;
Object.assign(window, { viewer }); // for the console
