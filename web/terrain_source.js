// Glue between the loaders (web/loaders) and the core (web/core.js): the file's samples are
// decoded straight into a terrain's WASM buffer at their native depth, then scaled and prepared.
// Runs in the browser and in Node.
import { loadHeightfield } from './loaders/index.js';

/**
 * Loads files into a new core terrain.
 * @param {import('./core.js').HexlodCore} core
 * @param {Array<{name: string, bytes: Uint8Array}>} files one height field (with its sidecar)
 * @param {{spacing?: {x: number, y: number}}} [options] spacing: metres between columns and rows
 *   to use instead of the file's (field still reports the file's)
 * @returns {Promise<{terrain: import('./core.js').Terrain, field: object, missing: number, loadMs: number}>}
 *   field is the loader's metadata (its `samples` view is dropped: it may be detached later).
 * @throws HeightfieldError for a bad file, CoreError when the core cannot hold it. Nothing is
 *   left allocated in the core on failure.
 */
export async function loadTerrain(core, files, options = {}) {
  const start = performance.now();
  let terrain = null;
  try {
    const field = await loadHeightfield(files, {
      allocate(sampleType, width, height) {
        terrain = core.createTerrain(width, height, sampleType);
        return terrain.samples();
      },
    });
    terrain.setScale(options.spacing ? { ...field, spacingX: options.spacing.x, spacingY: options.spacing.y } : field);
    const missing = terrain.prepare();
    const { samples, ...metadata } = field;
    return { terrain, field: metadata, missing, loadMs: performance.now() - start };
  } catch (error) {
    terrain?.destroy();
    throw error;
  }
}
