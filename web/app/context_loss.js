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

/**
 * The page's recovery: the frame loop stops drawing while the context is lost; when it comes
 * back the renderer makes its GL objects anew, the shading and the draped image are made again
 * from what the page kept, and a frame is asked for.
 */
export function recoverLostContext(canvas, { pipeline, renderer, stage, images, layers, state, showStatus, requestRender }) {
  handleContextLoss(canvas, {
    onLost() {
      pipeline.setContextLost(true);
      state.contextLost = true;
      showStatus('The graphics context was lost; waiting for it to come back…', true);
    },
    onRestored() {
      renderer.createGlObjects(); // the old GL objects died with the context
      for (const overlay of layers.overlays) overlay.createGlObjects(renderer.gl);
      renderer.invalidate();
      const world = stage.current?.world;
      if (world) renderer.setShading(world.low, world.high, world.extentX, world.extentZ);
      pipeline.setContextLost(false);
      state.contextLost = false;
      state.contextRestores += 1;
      showStatus('');
      images.restore().catch((error) => showStatus(error.message, true));
      requestRender();
    },
  });
}
