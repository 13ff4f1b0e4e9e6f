// A viewer filling the page on the default terrain, without the panel, the figures or the file bar.
import { createViewer } from 'hexlod';

const element = /** @type {HTMLElement} */ (document.getElementById('terrain'));
const viewer = await createViewer(element, { ui: false, tau: 1, budgetMs: 4 });
viewer.on('error', ({ message }) => console.warn(`hexlod: ${message}`));
console.log(`showing ${viewer.terrain?.name}: ${viewer.terrain?.width} × ${viewer.terrain?.height} samples`);
Object.assign(window, { viewer, createViewer }); // for the console
