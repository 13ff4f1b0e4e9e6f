// Node side of the core: the diagnostics build (build/wasm-diag: the product core plus the
// functions of src/api/hexlod_diagnostics.h, for the CLI, its tests and benchmarks), its .wasm
// read from the build and handed to web/core/core.js (the ES module build cannot locate its .wasm in
// Node by itself; see build.sh). The page loads the product build, build/wasm.
import { readFileSync, existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { createCore } from '../web/core/core.js';

/** Whether hexlod runs from a checkout (the core's source is there) or from an installed package (its build only). */
export const inCheckout = () => existsSync(fileURLToPath(new URL('../src/api/hexlod.h', import.meta.url)));

export const wasmPath = fileURLToPath(new URL('../build/wasm-diag/hexlod_core.wasm', import.meta.url));
export const factoryPath = new URL('../build/wasm-diag/hexlod_core.mjs', import.meta.url);

/** Instantiates the WASM core (diagnostics build) in Node. Throws a clear error when it was not built. */
export async function createNodeCore() {
  if (!existsSync(wasmPath) || !existsSync(fileURLToPath(factoryPath))) {
    throw new Error(`the WebAssembly core is not built (${wasmPath} is missing): ${inCheckout() ? 'run ./build.sh wasm' : 'reinstall the hexlod package'}`);
  }
  const { default: factory } = await import(factoryPath.href);
  return createCore({ wasmBinary: readFileSync(wasmPath), factory });
}
