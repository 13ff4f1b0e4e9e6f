// Glue between the loaders (web/loaders) and the core (web/core/core.js): the file's samples are
// decoded straight into a terrain's WASM buffer at their native depth, then scaled and prepared.
// Runs in the browser and in Node.
import { loadHeightfield, HeightfieldError } from './index.js';
import { extensionOf } from './common.js';
import { CoreError } from '../core/core.js';

const BYTES = { u8: 1, u16: 2, i16: 2, f32: 4 };
const RELIEF_RATIO = 0.05; // height range / extent of a guessed spacing

/**
 * Loads files into a new core terrain.
 * @param {import('../core/core.js').HexlodCore} core
 * @param {Array<{name: string, bytes: Uint8Array}>} files one height field (with its sidecar), or
 *   the tiles of one mosaic (see loadHeightfield)
 * @param {{spacing?: {x: number, y: number}, guessSpacing?: boolean, width?: number, height?: number, encoding?: string,
 *   onProgress?: (fraction: number, phase: string) => void}} [options] spacing: metres between
 *   columns and rows to use instead of the file's (field still reports the file's); width,
 *   height, encoding, onProgress: see loadHeightfield; guessSpacing: when neither the file nor
 *   `spacing` gives one, pick a spacing from the relief instead of 1 m (the page does)
 * @returns {Promise<{terrain: import('../core/core.js').Terrain, field: object, missing: number, loadMs: number}>}
 *   field is the loader's metadata (its `samples` view is dropped: it may be detached later);
 *   missing counts the no-data samples that were filled.
 * @throws HeightfieldError for a bad file (including one too big for the core's memory),
 *   CoreError when the core fails otherwise. Nothing is left allocated in the core on failure.
 */
export async function loadTerrain(core, files, options = {}) {
  const start = performance.now();
  let terrain = null;
  let profile = null; // a single row or column, decoded aside, then widened (see widenProfile)
  // Whose problem a refusal by the core is: the file's, or every tile's of a mosaic.
  const main = files.filter((f) => extensionOf(f?.name ?? '') !== 'json').map((f) => f?.name ?? '').join(' + ');
  try {
    const field = await loadHeightfield(files, {
      width: options.width,
      height: options.height,
      encoding: options.encoding,
      onProgress: options.onProgress,
      allocate(sampleType, width, height) {
        try {
          terrain = core.createTerrain(Math.max(width, 2), Math.max(height, 2), sampleType);
        } catch (error) {
          const mb = Math.round((width * height * BYTES[sampleType]) / 2 ** 20);
          const problem = /memory|address space/.test(error.message)
            ? `too big for memory: ${width}x${height} ${sampleType} samples need ${mb} MB` : error.message.replace(/^[^:]*: /, '');
          throw new HeightfieldError(main, problem);
        }
        if (width > 1 && height > 1) return terrain.samples();
        profile = new (terrain.samples().constructor)(width * height);
        return profile;
      },
      reacquire: () => profile ?? terrain.samples(),
    });
    if (profile) widenProfile(terrain, profile, field);
    // The core has the last word on a field's scale and heights (a spacing of 1e-300 m, heights
    // beyond 1e9 m): its refusal is this file's problem, said with its name.
    const missing = field.missing + fileProblem(main, () => {
      terrain.setScale(options.spacing ? { ...field, spacingX: options.spacing.x, spacingY: options.spacing.y } : field);
      return terrain.prepare();
    });
    if (options.guessSpacing && !field.spacingFromFile && !options.spacing) guessSpacing(terrain, field);
    const { samples, ...metadata } = field;
    return { terrain, field: metadata, missing, loadMs: performance.now() - start };
  } catch (error) {
    terrain?.destroy();
    throw error;
  }
}

/**
 * No spacing anywhere (file, sidecar, caller): sets one that makes the relief a twentieth of the
 * extent, a plausible landscape, rather than 1 m, which turns any real DEM into needles. Call on
 * a prepared terrain before its mesh exists (setting the scale again then costs nothing).
 */
export function guessSpacing(terrain, field) {
  const relief = terrain.maxHeight - terrain.minHeight;
  const guess = relief > 0 ? relief / (RELIEF_RATIO * (Math.max(terrain.width, terrain.height) - 1)) : 1;
  field.spacingX = field.spacingY = Number(guess.toPrecision(3));
  terrain.setScale(field);
}

/** Runs a core call on a file's data; a CoreError becomes a HeightfieldError naming the file. */
function fileProblem(name, step) {
  try {
    return step();
  } catch (error) {
    if (error instanceof CoreError) throw new HeightfieldError(name, error.message);
    throw error;
  }
}

/**
 * A file of one row or one column (a profile) has no area to mesh: it is shown as a ribbon two
 * samples wide, the profile repeated, as wide as one sample spacing along it.
 */
function widenProfile(terrain, profile, field) {
  const samples = terrain.samples();
  const oneRow = field.height === 1;
  for (let k = 0; k < profile.length; ++k) {
    if (oneRow) {
      samples[k] = samples[terrain.width + k] = profile[k];
    } else {
      samples[2 * k] = samples[2 * k + 1] = profile[k];
    }
  }
  if (oneRow) field.spacingY = field.spacingX;
  else field.spacingX = field.spacingY;
}
