// Node side of the core: reads the .wasm from the build and hands it to web/core.js (the
// ES module build cannot locate its .wasm in Node by itself; see build.sh).
import { readFileSync, existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { createCore } from '../web/core.js';

export const wasmPath = fileURLToPath(new URL('../build/wasm/hexlod_core.wasm', import.meta.url));

/** Instantiates the WASM core in Node. Throws a clear error when it was not built. */
export async function createNodeCore() {
  if (!existsSync(wasmPath)) {
    throw new Error(`the WebAssembly core is not built (${wasmPath} is missing): run ./build.sh`);
  }
  return createCore({ wasmBinary: readFileSync(wasmPath) });
}
