// WebGL context loss (the GPU reset, the driver updated, the tab was evicted): the page keeps
// the core's state, waits for the context to come back, rebuilds the renderer's GL objects
// and uploads the whole stream again, without a reload.

/**
 * @param {HTMLCanvasElement} canvas
 * @param {{onLost: () => void, onRestored: () => void}} hooks
 */
export function handleContextLoss(canvas, { onLost, onRestored }) {
  canvas.addEventListener('webglcontextlost', (e) => {
    e.preventDefault(); // tells the browser we will restore: without it no restored event comes
    onLost();
  });
  canvas.addEventListener('webglcontextrestored', () => onRestored());
}
