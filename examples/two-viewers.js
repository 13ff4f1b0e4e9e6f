// Two viewers side by side, each with its own core, settings and camera.
import { createViewer } from 'hexlod';

const left = /** @type {HTMLElement} */ (document.getElementById('left'));
const right = /** @type {HTMLElement} */ (document.getElementById('right'));
const [natural, hypsometric] = await Promise.all([
  createViewer(left, { tau: 1 }),
  createViewer(right, { tau: 2, shading: 'hypsometric', ui: false }),
]);
Object.assign(window, { viewers: [natural, hypsometric] }); // for the console
